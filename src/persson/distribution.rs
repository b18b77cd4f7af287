//! Persson's pressure distribution, paper eq. (pressureDistOri).
//!
//! Starting from `Pr(p) = delta(p - p0)` on the flat interface and absorbing walkers at
//! `p = 0`, the distribution after a total broadening `Dp_tot^2` is the mirror Gaussian
//!
//! ```text
//! Pr(p > 0) = [exp(-(p - p0)^2 / (2 Dp_tot^2)) - exp(-(p + p0)^2 / (2 Dp_tot^2))]
//!             / sqrt(2 pi Dp_tot^2),
//! ```
//!
//! zero for `p < 0`, plus a delta function at `p = 0` of weight `1 - a_r`, with
//! `a_r = erf(p0 / (sqrt2 Dp_tot))`. The continuous part integrates to `a_r`, the whole to
//! one, and its mean is `p0` (the mirror image carries the absorbed walkers' load back).

use statrs::function::erf::{erf, erfc};

use crate::error::{check_positive, Error, Result};

/// The pressure distribution of eq. (pressureDistOri) for mean pressure `p0` and total
/// broadening `Dp_tot^2`.
///
/// With `Dp_tot^2 = 0` (no roughness resolved) the distribution is `delta(p - p0)`: full
/// contact, and [`density`](Self::density) is zero everywhere because all the probability
/// sits in that point mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PressureDistribution {
    p0: f64,
    dp2: f64,
}

impl PressureDistribution {
    /// The distribution for mean pressure `p0` (finite, > 0) and total broadening
    /// `dp2 = Dp_tot^2` (finite, >= 0); errors name the argument.
    ///
    /// With `p0 -> p'` and `dp2 -> Dp^2` this is also the transition probability of
    /// eq. (transitionFinal) for walkers starting at `p'`.
    pub fn new(p0: f64, dp2: f64) -> Result<Self> {
        check_positive("p0", p0)?;
        if !(dp2.is_finite() && dp2 >= 0.0) {
            return Err(Error::invalid("dp2", dp2, "a finite number >= 0"));
        }
        Ok(Self::from_validated(p0, dp2))
    }

    /// [`new`](Self::new) for arguments already checked.
    pub(super) fn from_validated(p0: f64, dp2: f64) -> Self {
        Self { p0, dp2 }
    }

    /// The mean pressure `p0`.
    pub fn p0(&self) -> f64 {
        self.p0
    }

    /// The total broadening `Dp_tot^2`.
    pub fn variance(&self) -> f64 {
        self.dp2
    }

    /// `Dp_tot`.
    pub fn width(&self) -> f64 {
        self.dp2.sqrt()
    }

    /// True when nothing is resolved yet (`Dp_tot = 0`) and `Pr(p) = delta(p - p0)`.
    pub fn is_flat(&self) -> bool {
        self.dp2 == 0.0
    }

    /// `p0 / (sqrt2 Dp_tot)`, infinite when flat.
    fn x0(&self) -> f64 {
        if self.is_flat() {
            f64::INFINITY
        } else {
            self.p0 / (2.0 * self.dp2).sqrt()
        }
    }

    /// Relative contact area `a_r = erf(p0 / (sqrt2 Dp_tot))`: the weight of `p > 0`.
    pub fn contact_area(&self) -> f64 {
        erf(self.x0())
    }

    /// `1 - a_r = erfc(p0 / (sqrt2 Dp_tot))`: the weight of the delta function at `p = 0`,
    /// computed without cancellation.
    pub fn non_contact_area(&self) -> f64 {
        erfc(self.x0())
    }

    /// The continuous part `Pr(p)` for `p > 0` (zero for `p <= 0` and when flat).
    ///
    /// Written as `exp(-(p - p0)^2 / 2V) (1 - exp(-2 p p0 / V)) / sqrt(2 pi V)` with
    /// `expm1`, so that the difference of the two Gaussians keeps full relative precision
    /// near `p = 0`.
    pub fn density(&self, p: f64) -> f64 {
        if p <= 0.0 || self.is_flat() {
            return 0.0;
        }
        let v = self.dp2;
        let d = p - self.p0;
        let mirror = -(-2.0 * p * self.p0 / v).exp_m1();
        (-d * d / (2.0 * v)).exp() * mirror / (2.0 * std::f64::consts::PI * v).sqrt()
    }

    /// Probability of a pressure `<= p`, the delta at `p = 0` included:
    /// `1 - [erf((p + p0)/(sqrt2 Dp)) - erf((p - p0)/(sqrt2 Dp))] / 2` for `p >= 0`, zero
    /// for `p < 0`. When flat, a step at `p0`.
    pub fn cdf(&self, p: f64) -> f64 {
        if p < 0.0 {
            return 0.0;
        }
        if self.is_flat() {
            return if p >= self.p0 { 1.0 } else { 0.0 };
        }
        1.0 - self.survival(p)
    }

    /// Probability of a pressure `> p` for `p >= 0`, computed with `erfc` so that the far
    /// tail keeps its relative precision: `[erfc((p - p0)/s) - erfc((p + p0)/s)] / 2`,
    /// `s = sqrt2 Dp_tot`. One for `p < 0`.
    pub fn survival(&self, p: f64) -> f64 {
        if p < 0.0 {
            return 1.0;
        }
        if self.is_flat() {
            return if p < self.p0 { 1.0 } else { 0.0 };
        }
        let s = (2.0 * self.dp2).sqrt();
        let lo = (p - self.p0) / s;
        let hi = (p + self.p0) / s;
        if lo >= 0.0 {
            0.5 * (erfc(lo) - erfc(hi))
        } else {
            // erf(hi) - erf(lo) with erf(lo) < 0: no cancellation.
            0.5 * (erf(hi) - erf(lo))
        }
    }

    /// The second moment `<p^2>` (the delta at zero contributes nothing), paper
    /// eq. (2ndMoment) with `p' = p0`, `Dp_n = Dp_tot`.
    pub fn second_moment(&self) -> f64 {
        super::moments::second_moment(self.p0, self.width())
    }
}
