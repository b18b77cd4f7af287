//! Estimates with error bars: means over realizations, linear fits, verdict arithmetic.
//!
//! Every statistic a validation reports is an [`Estimate`]: a value and its standard error.
//! Ensemble averages use the spread over independent realizations (seeds), which is the
//! honest error when points within one realization are correlated.

use serde::{Deserialize, Serialize};

/// A value with its standard error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Its standard error (0 when not estimable, e.g. one sample).
    pub std_error: f64,
}

impl Estimate {
    /// An estimate.
    pub fn new(value: f64, std_error: f64) -> Self {
        Self { value, std_error }
    }

    /// Mean and standard error of the mean of independent samples (sample standard
    /// deviation over `sqrt(n)`; the error is NaN for fewer than two samples).
    pub fn mean_of(samples: &[f64]) -> Self {
        let n = samples.len();
        if n == 0 {
            return Self::new(f64::NAN, f64::NAN);
        }
        let mean = samples.iter().sum::<f64>() / n as f64;
        if n < 2 {
            return Self::new(mean, f64::NAN);
        }
        let var = samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        Self::new(mean, (var / n as f64).sqrt())
    }

    /// Ratio of a sum to a sum over realizations, `sum_i a_i / sum_i b_i`, with the
    /// delta-method standard error (each realization contributing one pair `(a_i, b_i)`).
    pub fn ratio_of_sums(pairs: &[(f64, f64)]) -> Self {
        let n = pairs.len();
        if n == 0 {
            return Self::new(f64::NAN, f64::NAN);
        }
        let sa: f64 = pairs.iter().map(|p| p.0).sum();
        let sb: f64 = pairs.iter().map(|p| p.1).sum();
        let r = sa / sb;
        if n < 2 {
            return Self::new(r, f64::NAN);
        }
        let mb = sb / n as f64;
        let var = pairs.iter().map(|(a, b)| (a - r * b).powi(2)).sum::<f64>() / (n - 1) as f64;
        Self::new(r, (var / n as f64).sqrt() / mb.abs())
    }

    /// Whether the estimate has an error bar (a finite standard error): not from one
    /// realization.
    pub fn has_error(&self) -> bool {
        self.std_error.is_finite()
    }

    /// The estimate in words, times `scale`, with `decimals` decimals and `unit` after
    /// each number: `"v +- e unit"`, or `"v unit (1 realization: no error bar)"` when the
    /// error is not known. Never prints NaN for a finite value.
    pub fn text(&self, scale: f64, decimals: usize, unit: &str) -> String {
        let v = self.value * scale;
        if self.has_error() {
            format!(
                "{v:.d$}{unit} +- {:.d$}{unit}",
                self.std_error * scale,
                d = decimals
            )
        } else {
            format!("{v:.d$}{unit} (1 realization: no error bar)", d = decimals)
        }
    }

    /// `z = (value - reference) / std_error`.
    pub fn z_score(&self, reference: f64) -> f64 {
        (self.value - reference) / self.std_error
    }
}

/// Least-squares line `y = intercept + slope x` with standard errors from the residuals.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LineFit {
    /// Intercept at `x = 0`.
    pub intercept: Estimate,
    /// Slope.
    pub slope: Estimate,
}

impl LineFit {
    /// Fits `y = a + b x` to the points (at least two distinct `x`).
    pub fn fit(x: &[f64], y: &[f64]) -> Option<Self> {
        let n = x.len();
        if n < 2 || y.len() != n {
            return None;
        }
        let nf = n as f64;
        let mx = x.iter().sum::<f64>() / nf;
        let my = y.iter().sum::<f64>() / nf;
        let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
        if sxx <= 0.0 {
            return None;
        }
        let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
        let slope = sxy / sxx;
        let intercept = my - slope * mx;
        let (se_b, se_a) = if n > 2 {
            let rss: f64 = x
                .iter()
                .zip(y)
                .map(|(a, b)| (b - intercept - slope * a).powi(2))
                .sum();
            let s2 = rss / (nf - 2.0);
            ((s2 / sxx).sqrt(), (s2 * (1.0 / nf + mx * mx / sxx)).sqrt())
        } else {
            (f64::NAN, f64::NAN)
        };
        Some(Self {
            intercept: Estimate::new(intercept, se_a),
            slope: Estimate::new(slope, se_b),
        })
    }

    /// The line at `x`.
    pub fn at(&self, x: f64) -> f64 {
        self.intercept.value + self.slope.value * x
    }
}

/// `"1 realization"` or `"n realizations"`.
pub fn realizations(n: usize) -> String {
    if n == 1 {
        "1 realization".into()
    } else {
        format!("{n} realizations")
    }
}

/// Rounds to `digits` significant digits (for golden values that must not depend on the
/// last bits of a platform's `exp` or `ln`).
pub fn round_sig(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let e = x.abs().log10().floor() as i32;
    let scale = 10f64.powi(digits - 1 - e);
    (x * scale).round() / scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_error() {
        let e = Estimate::mean_of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(e.value, 2.5);
        assert!((e.std_error - (5.0f64 / 3.0 / 4.0).sqrt()).abs() < 1e-15);
        assert!(Estimate::mean_of(&[1.0]).std_error.is_nan());
        assert!(!Estimate::mean_of(&[1.0]).has_error());
        assert_eq!(
            Estimate::mean_of(&[0.25]).text(100.0, 1, "%"),
            "25.0% (1 realization: no error bar)"
        );
        assert_eq!(Estimate::new(0.5, 0.02).text(1.0, 2, ""), "0.50 +- 0.02");
        assert_eq!(realizations(1), "1 realization");
        assert_eq!(realizations(4), "4 realizations");
    }

    #[test]
    fn ratio_of_sums_is_exact_for_proportional_pairs() {
        let r = Estimate::ratio_of_sums(&[(2.0, 1.0), (4.0, 2.0), (6.0, 3.0)]);
        assert!((r.value - 2.0).abs() < 1e-15 && r.std_error.abs() < 1e-15);
    }

    #[test]
    fn line_fit_recovers_a_line_and_its_errors() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let y: Vec<f64> = x.iter().map(|v| 1.5 - 0.5 * v).collect();
        let f = LineFit::fit(&x, &y).unwrap();
        assert!((f.slope.value + 0.5).abs() < 1e-14 && (f.intercept.value - 1.5).abs() < 1e-14);
        assert!(f.slope.std_error < 1e-14);
        let noisy = [1.0, 2.1, 2.9, 4.2, 4.8];
        let g = LineFit::fit(&x, &noisy).unwrap();
        assert!(g.slope.std_error > 0.0 && (g.slope.value - 0.97).abs() < 1e-12);
    }

    #[test]
    fn rounding() {
        assert_eq!(round_sig(0.0123456789, 4), 0.01235);
        assert_eq!(round_sig(-98765.4, 3), -98800.0);
    }
}
