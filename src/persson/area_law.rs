//! The paper's empirical contact-area law, eq. (contactArea) with the switching function
//! eq. (switching), fitted to GFMD data as a function of the reduced pressure
//! `p~0 = p0 / (E* g_bar)`:
//!
//! ```text
//! a_r = (1 - s) erf(c1 sqrt(pi) p~0) + s erf(c2 sqrt2 p~0),   s = erf^2(c2 sqrt2 p~0),
//! c1 = 1.075, c2 = 1.025.
//! ```
//!
//! At low load `a_r -> kappa p~0` with `kappa = 2 c1 = 2.15`; at high load
//! `1 - a_r -> erfc(c2 sqrt2 p~0)`, Persson's own form (`c2 = 1`) up to the small factor
//! `c2`. Persson's original theory on the same footing reads `a_r = erf(sqrt2 p~0)`, since
//! `Dp_tot = E* g_bar / 2`.

use std::f64::consts::{PI, SQRT_2};

use serde::{Deserialize, Serialize};
use statrs::function::erf::{erf, erfc};

use crate::engine::spectrum::ShellSpectrum;

/// Eq. (contactArea) with its two fit parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactAreaLaw {
    /// Low-load coefficient: `a_r ~ 2 c1 p~0`.
    pub c1: f64,
    /// High-load coefficient: `1 - a_r ~ erfc(c2 sqrt2 p~0)`.
    pub c2: f64,
}

impl Default for ContactAreaLaw {
    /// The paper's fit, [`ContactAreaLaw::PAPER`].
    fn default() -> Self {
        Self::PAPER
    }
}

impl ContactAreaLaw {
    /// `c1 = 1.075`, `c2 = 1.025`, the paper's values for `H = 0.3, 0.5, 0.8`.
    pub const PAPER: Self = Self {
        c1: 1.075,
        c2: 1.025,
    };

    /// The switching function `s(p~0) = erf^2(c2 sqrt2 p~0)`, eq. (switching).
    pub fn switching(&self, p_reduced: f64) -> f64 {
        let e = erf(self.c2 * SQRT_2 * p_reduced);
        e * e
    }

    /// `a_r(p~0)`, eq. (contactArea).
    pub fn contact_area(&self, p_reduced: f64) -> f64 {
        let s = self.switching(p_reduced);
        (1.0 - s) * erf(self.c1 * PI.sqrt() * p_reduced) + s * erf(self.c2 * SQRT_2 * p_reduced)
    }

    /// `1 - a_r(p~0)` without cancellation at high load:
    /// `(1 - s) erfc(c1 sqrt(pi) p~0) + s erfc(c2 sqrt2 p~0)` with
    /// `1 - s = erfc(y) (1 + erf(y))`, `y = c2 sqrt2 p~0`.
    pub fn non_contact_area(&self, p_reduced: f64) -> f64 {
        let y = self.c2 * SQRT_2 * p_reduced;
        let (e, ec) = (erf(y), erfc(y));
        let one_minus_s = ec * (1.0 + e);
        one_minus_s * erfc(self.c1 * PI.sqrt() * p_reduced) + e * e * ec
    }

    /// The low-load slope `kappa = lim a_r / p~0 = 2 c1`.
    pub fn kappa(&self) -> f64 {
        2.0 * self.c1
    }
}

/// Persson's original contact area as a function of the reduced pressure,
/// `a_r = erf(sqrt2 p~0)` (since `Dp_tot = E* g_bar / 2` in full contact).
pub fn persson_contact_area(p_reduced: f64) -> f64 {
    erf(SQRT_2 * p_reduced)
}

/// Reduced pressure `p~0 = p0 / (E* g_bar(zeta))`, with `g_bar(zeta)` the rms gradient of
/// the modes resolved at `zeta` ([`ShellSpectrum::rms_gradient`]). Infinite when nothing is
/// resolved.
pub fn reduced_pressure(spectrum: &ShellSpectrum, p0: f64, e_star: f64, zeta: f64) -> f64 {
    p0 / (e_star * spectrum.rms_gradient(zeta))
}
