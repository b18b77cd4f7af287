//! Estimates with error bars: means over realizations, linear fits, the rule that
//! decides a claim about an estimate ([`decision`]), and histograms ([`histogram`]).
//!
//! Every statistic a validation reports is an [`Estimate`]: a value and its standard error.
//! Ensemble averages use the spread over independent realizations (seeds), which is the
//! honest error when points within one realization are correlated. With one realization
//! there is no spread: the standard error is NaN ("no error bar"), written as `null` in
//! JSON (serde_json's NaN) and read back as NaN ([`null_as_nan`]), and as an empty cell in
//! CSV.

pub mod decision;
pub mod histogram;

pub use decision::{decide, establish, Claim, Decision, Region};
pub use histogram::{Bins, Histogram};

use serde::{Deserialize, Deserializer, Serialize};

/// What the text of an estimate without an error bar says in place of `+- error`.
pub const NO_ERROR_BAR: &str = "no error bar with one realization";

/// A value with its standard error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The value (NaN, written `null`, when there was nothing to estimate from; NaN also
    /// when left out).
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub value: f64,
    /// Its standard error: NaN (written `null`, or left out) when there is no error bar,
    /// e.g. from one realization.
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub std_error: f64,
}

/// NaN: the value of a float an output leaves out (`#[serde(default = "nan")]`).
pub fn nan() -> f64 {
    f64::NAN
}

/// Reads a float that may be `null` (how serde_json writes NaN) as NaN: for the fields of
/// outputs that can be NaN, so that an outcome written from one realization reads back.
pub fn null_as_nan<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// [`null_as_nan`] for the values of a map.
pub fn null_as_nan_values<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<std::collections::BTreeMap<String, f64>, D::Error> {
    let map = std::collections::BTreeMap::<String, Option<f64>>::deserialize(d)?;
    Ok(map
        .into_iter()
        .map(|(k, v)| (k, v.unwrap_or(f64::NAN)))
        .collect())
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

    /// A statistic `stat` of all `n` realizations, with its jackknife standard error:
    /// `stat` is called with the realization to leave out (`None` for all of them), and
    /// the error is `sqrt((n - 1) / n sum_i (theta_i - theta_mean)^2)` over the `n`
    /// leave-one-out values `theta_i` (NaN for fewer than two realizations).
    pub fn jackknife(n: usize, stat: impl Fn(Option<usize>) -> f64) -> Self {
        let value = stat(None);
        if n < 2 {
            return Self::new(value, f64::NAN);
        }
        let theta: Vec<f64> = (0..n).map(|i| stat(Some(i))).collect();
        let mean = theta.iter().sum::<f64>() / n as f64;
        let ss = theta.iter().map(|t| (t - mean).powi(2)).sum::<f64>();
        Self::new(value, ((n - 1) as f64 / n as f64 * ss).sqrt())
    }

    /// The difference `a - b` of two independent estimates, with their combined standard
    /// error.
    pub fn difference(a: Estimate, b: Estimate) -> Self {
        Self::new(a.value - b.value, a.std_error.hypot(b.std_error))
    }

    /// Whether the estimate has an error bar (a finite standard error): not from one
    /// realization.
    pub fn has_error(&self) -> bool {
        self.std_error.is_finite()
    }

    /// The estimate in words, times `scale`, with `decimals` decimals and `unit` after
    /// each number: `"v +- e unit"`, or `"v unit (no error bar with one realization)"`
    /// when the error is not known. Never prints NaN for a finite value.
    pub fn text(&self, scale: f64, decimals: usize, unit: &str) -> String {
        let v = self.value * scale;
        if self.has_error() {
            format!(
                "{v:.d$}{unit} +- {:.d$}{unit}",
                self.std_error * scale,
                d = decimals
            )
        } else {
            format!("{v:.d$}{unit} ({NO_ERROR_BAR})", d = decimals)
        }
    }

    /// `z = (value - reference) / std_error`.
    pub fn z_score(&self, reference: f64) -> f64 {
        (self.value - reference) / self.std_error
    }

    /// The z-score against `reference` in words, `"z = 4.2 against {whom}"` (one
    /// decimal), or [`NO_ERROR_BAR`] without an error bar.
    pub fn z_text(&self, reference: f64, whom: &str) -> String {
        if self.has_error() {
            format!("z = {:.1} against {whom}", self.z_score(reference))
        } else {
            NO_ERROR_BAR.to_string()
        }
    }
}

/// The Pearson correlation of two equally long series (NaN where either is flat); its
/// square is the share of the variance of either that a line in the other explains.
pub fn pearson(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len()) as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        let (dx, dy) = (x - ma, y - mb);
        ab += dx * dy;
        aa += dx * dx;
        bb += dy * dy;
    }
    ab / (aa * bb).sqrt()
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
    fn the_jackknife_of_a_mean_is_the_standard_error_of_the_mean() {
        let x = [1.0, 2.5, 4.0, 3.0, 7.5];
        let mean_without = |leave: Option<usize>| {
            let kept: Vec<f64> = (0..x.len())
                .filter(|&i| Some(i) != leave)
                .map(|i| x[i])
                .collect();
            kept.iter().sum::<f64>() / kept.len() as f64
        };
        let j = Estimate::jackknife(x.len(), mean_without);
        let m = Estimate::mean_of(&x);
        assert!((j.value - m.value).abs() < 1e-15);
        assert!((j.std_error - m.std_error).abs() < 1e-14, "{j:?} {m:?}");
        assert!(Estimate::jackknife(1, |_| 2.0).std_error.is_nan());
    }

    #[test]
    fn mean_and_error() {
        let e = Estimate::mean_of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(e.value, 2.5);
        assert!((e.std_error - (5.0f64 / 3.0 / 4.0).sqrt()).abs() < 1e-15);
        assert!(Estimate::mean_of(&[1.0]).std_error.is_nan());
        assert!(!Estimate::mean_of(&[1.0]).has_error());
        assert_eq!(
            Estimate::mean_of(&[0.25]).text(100.0, 1, "%"),
            "25.0% (no error bar with one realization)"
        );
        assert_eq!(Estimate::new(0.5, 0.02).text(1.0, 2, ""), "0.50 +- 0.02");
        assert_eq!(
            Estimate::new(1.5, 0.1).z_text(1.0, "Persson's 1"),
            "z = 5.0 against Persson's 1"
        );
        assert_eq!(
            Estimate::mean_of(&[1.5]).z_text(1.0, "Persson's 1"),
            "no error bar with one realization"
        );
        let d = Estimate::difference(Estimate::new(1.0, 0.3), Estimate::new(0.5, 0.4));
        assert!((d.value - 0.5).abs() < 1e-15 && (d.std_error - 0.5).abs() < 1e-15);
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
    fn no_error_bar_is_written_as_null_and_read_back_as_nan() {
        let one = Estimate::mean_of(&[0.25]);
        let json = serde_json::to_string(&one).unwrap();
        assert_eq!(json, r#"{"value":0.25,"std_error":null}"#);
        let back: Estimate = serde_json::from_str(&json).unwrap();
        assert_eq!(back.value, 0.25);
        assert!(!back.has_error());
        // Left out, too; a number reads as itself.
        let absent: Estimate = serde_json::from_str(r#"{"value":0.5}"#).unwrap();
        assert!(absent.std_error.is_nan());
        let full: Estimate = serde_json::from_str(r#"{"value":0.5,"std_error":0.1}"#).unwrap();
        assert_eq!(full, Estimate::new(0.5, 0.1));
    }

    #[test]
    fn rounding() {
        assert_eq!(round_sig(0.0123456789, 4), 0.01235);
        assert_eq!(round_sig(-98765.4, 3), -98800.0);
    }
}
