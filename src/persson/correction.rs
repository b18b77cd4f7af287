//! The correction factor `S(a_r)` of the modified theory.
//!
//! Persson's later versions of the theory reduce the pressure broadening in partial contact,
//! `Dp_mod^2 = S(a_r) Dp^2`, and multiply each mode's elastic energy by the same factor.
//! Two forms are in use:
//!
//! * [`Correction::YangPersson`], paper eq. (gamma) (Yang & Persson, J. Phys.: Condens.
//!   Matter 20, 215214 (2008)): `S = gamma + (1 - gamma) a_r^2`, `gamma = 0.42`. This is the
//!   paper's form and the default.
//! * [`Correction::WangMueser`] (Wang & Müser, Lubricants 5, 7 (2017)):
//!   `S = gamma - (2/9) a_r^2 + (11/9 - gamma) a_r^4`, `gamma = 5/9`.
//!
//! Both give `S(1) = 1` (full contact is not corrected) and `S(0+) = gamma`.
//!
//! In a scene file the factor is named by its model, with `gamma` optional:
//!
//! ```toml
//! correction = { model = "wang_mueser" }
//! # or: correction = { model = "yang_persson", gamma = 0.42 }
//! ```

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// `gamma` of paper eq. (gamma).
pub const YANG_PERSSON_GAMMA: f64 = 0.42;
/// `gamma` of Wang & Müser (2017).
pub const WANG_MUESER_GAMMA: f64 = 5.0 / 9.0;

fn yang_persson_gamma() -> f64 {
    YANG_PERSSON_GAMMA
}

fn wang_mueser_gamma() -> f64 {
    WANG_MUESER_GAMMA
}

/// The correction factor `S(a_r)` of the modified theory (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Correction {
    /// `S = gamma + (1 - gamma) a_r^2`, paper eq. (gamma).
    YangPersson {
        /// `S(0+)`; 0.42 in the paper.
        #[serde(default = "yang_persson_gamma")]
        gamma: f64,
    },
    /// `S = gamma - (2/9) a_r^2 + (11/9 - gamma) a_r^4` (Wang & Müser 2017).
    WangMueser {
        /// `S(0+)`; 5/9 in Wang & Müser.
        #[serde(default = "wang_mueser_gamma")]
        gamma: f64,
    },
}

impl Default for Correction {
    /// The paper's factor, eq. (gamma) with `gamma = 0.42`.
    fn default() -> Self {
        Self::yang_persson()
    }
}

impl Correction {
    /// Paper eq. (gamma) with `gamma = 0.42`.
    pub fn yang_persson() -> Self {
        Self::YangPersson {
            gamma: YANG_PERSSON_GAMMA,
        }
    }

    /// Wang & Müser's factor with `gamma = 5/9`.
    pub fn wang_mueser() -> Self {
        Self::WangMueser {
            gamma: WANG_MUESER_GAMMA,
        }
    }

    /// `S(0+) = gamma`.
    pub fn gamma(&self) -> f64 {
        match *self {
            Self::YangPersson { gamma } | Self::WangMueser { gamma } => gamma,
        }
    }

    /// `S(a_r)` for a relative contact area `a_r` in `[0, 1]`.
    pub fn factor(&self, a_r: f64) -> f64 {
        let a2 = a_r * a_r;
        match *self {
            Self::YangPersson { gamma } => gamma + (1.0 - gamma) * a2,
            Self::WangMueser { gamma } => gamma + a2 * (-2.0 / 9.0 + (11.0 / 9.0 - gamma) * a2),
        }
    }

    /// The smallest value of `S(a_r)` over `a_r` in `[0, 1]`.
    pub fn min_factor(&self) -> f64 {
        match *self {
            Self::YangPersson { gamma } => gamma.min(1.0),
            Self::WangMueser { gamma } => {
                // S = gamma - (2/9) u + c u^2 in u = a_r^2, c = 11/9 - gamma.
                let c = 11.0 / 9.0 - gamma;
                let u = if c > 0.0 {
                    (1.0 / (9.0 * c)).min(1.0)
                } else {
                    1.0
                };
                self.factor(u.sqrt()).min(gamma).min(1.0)
            }
        }
    }

    /// Checks `gamma` in `(0, 1]` (partial contact broadens less than full contact) and
    /// `S > 0` on `[0, 1]`.
    pub fn validate(&self) -> Result<()> {
        let gamma = self.gamma();
        if !(gamma.is_finite() && gamma > 0.0 && gamma <= 1.0) {
            return Err(Error::invalid("gamma", gamma, "in (0, 1]"));
        }
        let min = self.min_factor();
        if min <= 0.0 {
            return Err(Error::invalid(
                "gamma",
                gamma,
                format!("a value for which S(a_r) > 0 on [0, 1] (min S = {min})"),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_factors_are_one_at_full_contact_and_gamma_at_zero_area() {
        for c in [Correction::yang_persson(), Correction::wang_mueser()] {
            assert!((c.factor(1.0) - 1.0).abs() <= 2e-16, "{c:?}");
            assert_eq!(c.factor(0.0), c.gamma(), "{c:?}");
        }
    }

    #[test]
    fn min_factor_is_the_minimum_over_a_fine_grid() {
        for c in [
            Correction::yang_persson(),
            Correction::wang_mueser(),
            Correction::WangMueser { gamma: 0.05 },
            Correction::WangMueser { gamma: 1.0 },
        ] {
            let sampled = (0..=100_000)
                .map(|i| c.factor(i as f64 / 100_000.0))
                .fold(f64::INFINITY, f64::min);
            assert!(c.min_factor() <= sampled + 1e-15, "{c:?}");
            assert!(c.min_factor() >= sampled - 1e-9, "{c:?}");
        }
    }

    #[test]
    fn gamma_outside_its_range_is_rejected_by_name() {
        for c in [
            Correction::YangPersson { gamma: 0.0 },
            Correction::YangPersson { gamma: 1.5 },
            Correction::YangPersson { gamma: f64::NAN },
            // gamma - 1/(81 (11/9 - gamma)) < 0: S dips below zero.
            Correction::WangMueser { gamma: 0.005 },
        ] {
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("gamma"), "{e}");
        }
        Correction::WangMueser { gamma: 0.02 }.validate().unwrap();
    }
}
