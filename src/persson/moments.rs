//! The paper's on-the-fly moment analysis (Appendix, "On-the-fly determination of the
//! diffusion coefficient").
//!
//! Walkers that start at pressure `p'` and are broadened by `Dp_n`, with absorption at
//! `p = 0`, end in the mirror Gaussian of eq. (transitionFinal). Its first moment is `p'`
//! and its second moment is eq. (2ndMoment):
//!
//! ```text
//! <p^2> = sqrt(2/pi) p' Dp_n exp(-p'^2 / (2 Dp_n^2)) + (p'^2 + Dp_n^2) erf(p' / (sqrt2 Dp_n)).
//! ```
//!
//! Given the measured `p' = <p>` and `<p^2>` of a pressure bin at the new magnification,
//! [`width_from_moments`] inverts eq. (2ndMoment) for `Dp_n`. With
//! `sigma^2 = <p^2> / p'^2 - 1`, the closed form eq. (approxDeltaPress),
//!
//! ```text
//! Dp_n / p' ~ sigma (1 + alpha1 sigma + alpha2 sqrt(pi/8) sigma^2) / (1 + alpha2 sigma),
//! alpha1 = 0.5153, alpha2 = 0.7591,
//! ```
//!
//! exact for `sigma -> 0` (`Dp_n = p' sigma`) and `sigma -> inf`
//! (`Dp_n = p' sqrt(pi/8) sigma^2`), starts Newton's method.
//!
//! Newton works on the dimensionless excess `g(t) = <p^2>/p'^2 - 1` as a function of
//! `t = Dp_n / p'`, `x = 1 / (sqrt2 t)`:
//!
//! ```text
//! g(t) = t^2 erf(x) + sqrt(2/pi) t exp(-x^2) - erfc(x),      g'(t) = 2 t erf(x),
//! ```
//!
//! which avoids subtracting `p'^2` from `<p^2>` when `sigma` is small. The derivative
//! follows because the two terms from differentiating `x` cancel:
//! `d/dDp [sqrt(2/pi) p' Dp e^{-x^2}] = sqrt(2/pi) p' e^{-x^2} (1 + 2 x^2)` and
//! `d/dDp [(p'^2 + Dp^2) erf(x)] = 2 Dp erf(x) - sqrt(2/pi) p' e^{-x^2} (1 + 2 x^2)`, so
//! `d<p^2>/dDp_n = 2 Dp_n erf(p' / (sqrt2 Dp_n))`. `g` is increasing and convex
//! (`g'' = 2 [erf(x) - (2/sqrt(pi)) x e^{-x^2}] >= 0`), so Newton converges from any start
//! and, after its first step, from above.

use std::f64::consts::PI;

use statrs::function::erf::{erf, erfc};

use crate::error::{Error, Result};

/// `alpha1` of eq. (approxDeltaPress).
pub const ALPHA1: f64 = 0.5153;
/// `alpha2` of eq. (approxDeltaPress).
pub const ALPHA2: f64 = 0.7591;

/// Newton iterations allowed; the closed-form start leaves it 5 or fewer in practice.
const MAX_NEWTON: usize = 100;

/// Second moment of the mirror Gaussian with parameter `p_mean = p'` and width `dp = Dp_n`,
/// eq. (2ndMoment). `dp = 0` gives `p'^2`.
pub fn second_moment(p_mean: f64, dp: f64) -> f64 {
    if dp == 0.0 {
        return p_mean * p_mean;
    }
    let x = p_mean / (std::f64::consts::SQRT_2 * dp);
    (2.0 / PI).sqrt() * p_mean * dp * (-x * x).exp() + (p_mean * p_mean + dp * dp) * erf(x)
}

/// Checks `p' > 0` and finite, `<p^2>` finite with `sigma^2 = <p^2>/p'^2 - 1 >= 0`;
/// returns `sigma^2`.
fn relative_variance(p_mean: f64, second: f64) -> Result<f64> {
    if !(p_mean.is_finite() && p_mean > 0.0) {
        return Err(Error::invalid("p_mean", p_mean, "a finite number > 0"));
    }
    if !second.is_finite() {
        return Err(Error::invalid("second_moment", second, "a finite number"));
    }
    let sigma2 = second / (p_mean * p_mean) - 1.0;
    if sigma2 < 0.0 {
        return Err(Error::invalid(
            "second_moment",
            second,
            format!(">= p_mean^2 = {} (sigma^2 = {sigma2} < 0)", p_mean * p_mean),
        ));
    }
    if !sigma2.is_finite() {
        return Err(Error::invalid(
            "second_moment",
            second,
            format!("such that second_moment / p_mean^2 is finite (p_mean = {p_mean})"),
        ));
    }
    Ok(sigma2)
}

/// The closed form of eq. (approxDeltaPress) as a ratio: `Dp_n / p'` for a given `sigma`.
pub fn relative_width_estimate(sigma: f64) -> f64 {
    let s = sigma;
    s * (1.0 + ALPHA1 * s + ALPHA2 * (PI / 8.0).sqrt() * s * s) / (1.0 + ALPHA2 * s)
}

/// `Dp_n` from the closed form of eq. (approxDeltaPress) (its error against the exact
/// inversion: [`estimate_largest_error`]). Errors name `p_mean` (not finite and > 0) or `second_moment` (not finite,
/// or below `p_mean^2`).
pub fn width_estimate(p_mean: f64, second_moment: f64) -> Result<f64> {
    let sigma2 = relative_variance(p_mean, second_moment)?;
    Ok(p_mean * relative_width_estimate(sigma2.sqrt()))
}

/// The largest relative error of eq. (approxDeltaPress) against the exact inversion of
/// eq. (2ndMoment), over `Dp_n / p'` from 1e-3 to 1e3 (`points` log-spaced values): at each
/// `t`, the exact `sigma = sqrt(g(t))` goes into the closed form, whose result is set
/// against `t`. Both limits are exact (the large one approached as `1/sqrt(t)`), so the
/// largest error lies inside the range.
pub fn estimate_largest_error(points: usize) -> f64 {
    (0..points)
        .map(|k| {
            let t = 10f64.powf(-3.0 + 6.0 * k as f64 / (points - 1) as f64);
            let sigma = excess_and_slope(t).0.sqrt();
            (relative_width_estimate(sigma) / t - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

/// The relative error of eq. (approxDeltaPress) against the exact inversion of eq.
/// (2ndMoment) far into its two limits, `Dp_n / p' = 1e-6` and `1e8`, the larger of the
/// two: the paper calls the estimate exact in the limits `sigma_n -> 0` and `-> infinity`
/// (the error falls as `t` and as `t^(-1/2)`).
pub fn estimate_error_in_the_limits() -> f64 {
    [1e-6, 1e8]
        .into_iter()
        .map(|t: f64| {
            let sigma = excess_and_slope(t).0.sqrt();
            (relative_width_estimate(sigma) / t - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

/// `g(t) = <p^2>/p'^2 - 1` at `t = Dp_n / p'`, and `g'(t)` (see the module docs).
fn excess_and_slope(t: f64) -> (f64, f64) {
    let x = 1.0 / (std::f64::consts::SQRT_2 * t);
    let e = erf(x);
    let g = t * t * e + (2.0 / PI).sqrt() * t * (-x * x).exp() - erfc(x);
    (g, 2.0 * t * e)
}

/// `Dp_n` such that the mirror Gaussian with parameter `p_mean` has second moment
/// `second_moment` (eq. 2ndMoment), by Newton's method from eq. (approxDeltaPress), to
/// machine precision. Errors as in [`width_estimate`].
pub fn width_from_moments(p_mean: f64, second_moment: f64) -> Result<f64> {
    let sigma2 = relative_variance(p_mean, second_moment)?;
    if sigma2 == 0.0 {
        return Ok(0.0);
    }
    let mut t = relative_width_estimate(sigma2.sqrt());
    let mut last_step = f64::INFINITY;
    let mut iterations = 0;
    while iterations < MAX_NEWTON {
        iterations += 1;
        let (g, slope) = excess_and_slope(t);
        let step = (g - sigma2) / slope;
        let next = t - step;
        if !(next.is_finite() && next > 0.0) {
            break;
        }
        t = next;
        // After the first step Newton approaches from above with shrinking steps; stop
        // once a step is at the last bit or no longer shrinks (rounding).
        let size = step.abs();
        if size <= 2.0 * f64::EPSILON * t || size >= last_step {
            return Ok(p_mean * t);
        }
        last_step = size;
    }
    Err(Error::NotConverged {
        solver: "moment inversion (Newton)",
        reason: crate::error::Termination::BudgetExhausted,
        iterations,
        residual: (excess_and_slope(t).0 - sigma2).abs() / sigma2,
        tol: 2.0 * f64::EPSILON,
        contact_points: None,
    })
}

/// Intervals of the composite Simpson rule in [`mirror_moment_largest_error`].
const QUADRATURE_INTERVALS: usize = 2000;

/// Half the range of the quadrature in [`mirror_moment_largest_error`], in widths `Dp_n`:
/// the Gaussians' tails beyond it weigh below `e^{-72}`.
const QUADRATURE_HALF_RANGE: f64 = 12.0;

/// The first two moments of the mirror Gaussian of eq. (transitionFinal) with parameter
/// `p_mean = p'` and width `dp = Dp_n > 0`, by quadrature of its continuous part
/// `G(p - p') - G(p + p')` over `p > 0` (the delta at `p = 0` adds nothing to either):
/// the composite Simpson rule on `[max(0, p' - 12 Dp_n), p' + 12 Dp_n]`.
pub fn mirror_moments_by_quadrature(p_mean: f64, dp: f64) -> (f64, f64) {
    let lo = (p_mean - QUADRATURE_HALF_RANGE * dp).max(0.0);
    let hi = p_mean + QUADRATURE_HALF_RANGE * dp;
    let h = (hi - lo) / QUADRATURE_INTERVALS as f64;
    let norm = 1.0 / ((2.0 * PI).sqrt() * dp);
    let gauss = |x: f64| norm * (-0.5 * (x / dp).powi(2)).exp();
    let (mut first, mut second) = (0.0, 0.0);
    for k in 0..=QUADRATURE_INTERVALS {
        let p = lo + k as f64 * h;
        let weight = if k == 0 || k == QUADRATURE_INTERVALS {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let density = gauss(p - p_mean) - gauss(p + p_mean);
        first += weight * p * density;
        second += weight * p * p * density;
    }
    (first * h / 3.0, second * h / 3.0)
}

/// The largest relative error of the quadrature of the mirror Gaussian's first two moments
/// ([`mirror_moments_by_quadrature`]) against `p'` and the closed form eq. (2ndMoment)
/// ([`second_moment`]), over `Dp_n / p'` from 1e-3 to 1e3 (`points` log-spaced values, `p'
/// = 1`): the identities of the Appendix (tex 1168-1169, 1186-1200), checked to the
/// quadrature's accuracy.
pub fn mirror_moment_largest_error(points: usize) -> f64 {
    (0..points)
        .map(|k| {
            let t = 10f64.powf(-3.0 + 6.0 * k as f64 / (points - 1) as f64);
            let (first, second) = mirror_moments_by_quadrature(1.0, t);
            (first - 1.0)
                .abs()
                .max((second / second_moment(1.0, t) - 1.0).abs())
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_closed_form_errs_by_a_few_percent_at_most_and_is_exact_at_the_limits() {
        let worst = estimate_largest_error(2001);
        assert!(worst > 0.005 && worst < 0.05, "{worst}");
        // Finer sampling moves the maximum little: it is a smooth maximum inside.
        assert!((estimate_largest_error(8001) / worst - 1.0).abs() < 1e-3);
        // The limits are approached slowly at large t (the error falls as 1/sqrt(t)).
        for t in [1e-6, 1e8] {
            let sigma = excess_and_slope(t).0.sqrt();
            assert!(
                (relative_width_estimate(sigma) / t - 1.0).abs() < 1e-4,
                "{t}"
            );
        }
    }

    #[test]
    fn excess_matches_the_papers_second_moment() {
        for t in [1e-3, 0.1, 0.7, 1.0, 3.0, 100.0, 1e5] {
            let (g, _) = excess_and_slope(t);
            let direct = second_moment(1.0, t) - 1.0;
            assert!(
                (g - direct).abs() <= 1e-14 * (1.0 + direct.abs()),
                "t = {t}: {g} vs {direct}"
            );
        }
    }

    #[test]
    fn the_quadrature_reproduces_the_mirror_moments() {
        // Narrow: the mirror image is negligible, the moments those of a Gaussian.
        let (m1, m2) = mirror_moments_by_quadrature(2.0, 0.01);
        assert!((m1 - 2.0).abs() < 1e-9, "{m1}");
        assert!((m2 - (4.0 + 1e-4)).abs() < 1e-9, "{m2}");
        // At every width from 1e-3 p' to 1e3 p' the quadrature follows eq. (2ndMoment).
        let err = mirror_moment_largest_error(41);
        assert!(err < 1e-6, "{err}");
        // The mirror matters: at Dp = p' the second moment is 1.849 p'^2, not the
        // unmirrored p'^2 + Dp^2.
        let (_, m2) = mirror_moments_by_quadrature(1.0, 1.0);
        assert!((m2 / 2.0 - 1.0).abs() > 1e-2, "{m2}");
    }
}
