//! From the spectrum of profiles to the spectrum of the surface: the Abel transform.
//!
//! Under isotropy the profiles' spectrum is the surface's integrated across them,
//! `C1D(q) = integral_{-inf}^{inf} C(sqrt(q^2 + q_y^2)) dq_y
//!         = 2 integral_q^inf C(k) k dk / sqrt(k^2 - q^2)` ([`project`]), an Abel transform,
//! inverted by `C(q) = -(1/pi) integral_q^inf C1D'(k) / sqrt(k^2 - q^2) dk` ([`invert`]):
//! Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017), section 2.3;
//! Persson, Tribol. Lett. 54, 99 (2014). Both integrals are taken in `k = q cosh t`, which
//! removes the square root's singularity (`dk / sqrt(k^2 - q^2) = dt`), by Simpson's rule.
//!
//! The profiles' spectrum is known in bins ([`super::spectrum`]); between bins it is
//! interpolated linearly in `ln C1D` against `ln q` ([`LogLog`]), and beyond the highest
//! bin, where the profile's cutoff ends what is known, it is extrapolated with the power
//! law fitted to the highest octave (when it falls; else the integral is truncated there).
//! A self-affine `C(q) = K q^(-2-2H)` maps to `C1D(q) = K R(H) q^(-1-2H)` with
//! `R(H) = sqrt(pi) Gamma(1/2 + H) / Gamma(1 + H)` ([`self_affine_ratio`]), exactly, both
//! ways: the tests' oracle.
//!
//! Where the conversion is uncertain ([`Uncertain`]): near the profile's cutoff, where
//! the integral leans on the extrapolated tail (the share of `C(q)` that the tail gives,
//! [`ConvertedBin::tail_share`], above [`TAIL_SHARE`]: about the top third of a decade
//! for `H = 0.8`, the top decade as `H` goes to 0); at the lowest `q`, where a bin holds
//! few modes and the window's main lobe mixes them (below [`LOW_MODES`] times the lowest
//! wavevector, or a relative error above [`RELATIVE_ERROR`]); and wherever the noise of
//! the derivative makes `C(q)` come out not positive. The error bar of `C(q)` is the
//! bins' errors propagated through the conversion (the conversion's derivative in each
//! bin, by finite differences), the bins taken as independent.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use statrs::function::gamma::gamma;

use super::spectrum::{LineBin, ProfileSpectrum};

/// Share of `C(q)` from the extrapolated tail above which a converted bin is uncertain:
/// there the spectrum's shape near the cutoff (which the tail's power law only guesses)
/// moves the result by several percent (rows of a surface band-limited at the Nyquist
/// wavevector: 4% off at a share of 1%, 10% at 3%, 30% at 7%; the line module's tests).
pub const TAIL_SHARE: f64 = 0.01;

/// Bins below this many lowest wavevectors `2 pi / L` are uncertain (the Hann window's
/// main lobe spans two modes on each side).
pub const LOW_MODES: f64 = 4.0;

/// Relative error above which a converted bin is uncertain.
pub const RELATIVE_ERROR: f64 = 0.3;

/// Simpson steps per unit of `t` (`k = q cosh t`).
const STEPS_PER_UNIT_T: f64 = 200.0;

/// How far past the cutoff the tail is integrated, in units of `1 / (1 - s)` (`s` the
/// tail's log-log slope): the tail's integrand has fallen by `e^-40` there.
const TAIL_DECAYS: f64 = 40.0;

/// `R(H) = C1D(q) q^(1+2H) / (C(q) q^(2+2H))` for a self-affine spectrum:
/// `sqrt(pi) Gamma(1/2 + H) / Gamma(1 + H)` (2 at `H = 1/2`).
pub fn self_affine_ratio(hurst: f64) -> f64 {
    std::f64::consts::PI.sqrt() * gamma(0.5 + hurst) / gamma(1.0 + hurst)
}

/// `C1D(q) = 2 integral_0^inf C(q cosh t) q cosh t dt` of an isotropic `c2d`, the
/// integral taken up to `k = k_max` (beyond which `c2d` must vanish or be negligible).
pub fn project(c2d: &dyn Fn(f64) -> f64, q: f64, k_max: f64) -> f64 {
    if q >= k_max {
        return 0.0;
    }
    let t_max = (k_max / q).acosh();
    2.0 * simpson(
        &|t: f64| {
            let k = q * t.cosh();
            c2d(k) * k
        },
        0.0,
        t_max,
    )
}

/// A positive function tabulated at increasing `q`, interpolated linearly in log-log, and
/// beyond its last node either a power law of slope `tail` or zero.
#[derive(Debug, Clone, PartialEq)]
pub struct LogLog {
    ln_q: Vec<f64>,
    ln_c: Vec<f64>,
    tail: Option<f64>,
}

impl LogLog {
    /// The table of `(q, c)` nodes (`c > 0`, `q` increasing), with the tail's slope.
    pub fn new(nodes: &[(f64, f64)], tail: Option<f64>) -> Self {
        Self {
            ln_q: nodes.iter().map(|n| n.0.ln()).collect(),
            ln_c: nodes.iter().map(|n| n.1.ln()).collect(),
            tail,
        }
    }

    /// The last node's `q`.
    pub fn top(&self) -> f64 {
        self.ln_q.last().map_or(0.0, |v| v.exp())
    }

    /// The log-log slope of the segment holding `ln_q` (the first below the first node,
    /// the tail's past the last, `None` past the last without a tail).
    fn slope_at(&self, ln_q: f64) -> Option<(usize, f64)> {
        let n = self.ln_q.len();
        if n < 2 {
            return None;
        }
        if ln_q >= self.ln_q[n - 1] {
            return self.tail.map(|s| (n - 1, s));
        }
        let i = self.ln_q.partition_point(|&x| x <= ln_q).clamp(1, n - 1) - 1;
        let s = (self.ln_c[i + 1] - self.ln_c[i]) / (self.ln_q[i + 1] - self.ln_q[i]);
        Some((i, s))
    }

    /// The value at `q`.
    pub fn at(&self, q: f64) -> f64 {
        let l = q.ln();
        match self.slope_at(l) {
            Some((i, s)) => (self.ln_c[i] + s * (l - self.ln_q[i])).exp(),
            None => 0.0,
        }
    }

    /// The derivative `dC/dq` at `q`.
    pub fn derivative(&self, q: f64) -> f64 {
        let l = q.ln();
        match self.slope_at(l) {
            Some((i, s)) => (self.ln_c[i] + s * (l - self.ln_q[i])).exp() * s / q,
            None => 0.0,
        }
    }
}

/// `C(q) = -(1/pi) integral_0^inf C1D'(q cosh t) dt` of the profiles' spectrum `c1d`.
pub fn invert(c1d: &LogLog, q: f64) -> f64 {
    let top = c1d.top();
    let t_top = if q < top { (top / q).acosh() } else { 0.0 };
    let d = |t: f64| c1d.derivative(q * t.cosh());
    let mut sum = simpson(&d, 0.0, t_top);
    if let Some(s) = c1d.tail {
        if s < 1.0 {
            sum += simpson(&d, t_top, t_top + TAIL_DECAYS / (1.0 - s));
        }
    }
    -sum / std::f64::consts::PI
}

/// Composite Simpson's rule on `[a, b]`, [`STEPS_PER_UNIT_T`] steps per unit.
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    if b <= a {
        return 0.0;
    }
    let steps = (((b - a) * STEPS_PER_UNIT_T).ceil() as usize)
        .max(64)
        .next_multiple_of(2);
    let h = (b - a) / steps as f64;
    let mut sum = f(a) + f(b);
    for k in 1..steps {
        sum += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// Why a converted bin is uncertain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Uncertain {
    /// Near the profile's cutoff: the tail beyond it gives more than [`TAIL_SHARE`].
    Cutoff,
    /// At the lowest `q`: few modes, mixed by the window, or a large error bar.
    FewModes,
    /// The conversion came out not positive (noise in the derivative).
    NotPositive,
}

/// One bin of the converted (2D, isotropic) spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ConvertedBin {
    /// `q` (1 / length).
    pub q: f64,
    /// `C(q)` (length^4).
    pub c: f64,
    /// Its standard error, the profiles' errors propagated.
    pub std_error: f64,
    /// The share of `c` from the extrapolated tail beyond the profile's cutoff.
    pub tail_share: f64,
    /// Why it is uncertain, if it is.
    pub uncertain: Option<Uncertain>,
}

/// The converted spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Converted {
    /// Bins at the profiles' bins' `q`.
    pub bins: Vec<ConvertedBin>,
    /// The log-log slope of `C1D` over the highest octave, the tail's (absent: the
    /// spectrum does not fall there, and the integral is truncated at the cutoff).
    pub tail_slope: Option<f64>,
}

impl Converted {
    /// The bins with `C(q) > 0`, as a table to interpolate.
    pub fn table(&self) -> Vec<(f64, f64)> {
        self.bins
            .iter()
            .filter(|b| b.c > 0.0)
            .map(|b| (b.q, b.c))
            .collect()
    }
}

/// The log-log slope of the bins over the highest octave, when it falls.
fn tail_slope(bins: &[LineBin]) -> Option<f64> {
    let top = bins.last()?.q;
    let (x, y): (Vec<f64>, Vec<f64>) = bins
        .iter()
        .filter(|b| b.q >= 0.5 * top && b.c > 0.0)
        .map(|b| (b.q.ln(), b.c.ln()))
        .unzip();
    let s = crate::stats::LineFit::fit(&x, &y)?.slope.value;
    (s < 0.0).then_some(s)
}

/// `C(q)` at every bin's `q` from the bins' `C1D` (and whether the tail is used).
fn convert_values(bins: &[LineBin], with_tail: bool) -> (Vec<f64>, Option<f64>) {
    let nodes: Vec<(f64, f64)> = bins
        .iter()
        .filter(|b| b.c > 0.0)
        .map(|b| (b.q, b.c))
        .collect();
    let tail = if with_tail { tail_slope(bins) } else { None };
    let table = LogLog::new(&nodes, tail);
    (bins.iter().map(|b| invert(&table, b.q)).collect(), tail)
}

/// The isotropic 2D spectrum the profiles' spectrum implies, with error bars and the
/// bins where it is uncertain (module docs).
pub fn convert(spectrum: &ProfileSpectrum) -> Converted {
    let bins = &spectrum.bins;
    let (c, tail) = convert_values(bins, true);
    let (truncated, _) = convert_values(bins, false);
    // The conversion's derivative in each bin, by a relative step of 1e-3.
    let step = 1e-3;
    let columns: Vec<Vec<f64>> = (0..bins.len())
        .into_par_iter()
        .map(|j| {
            let mut moved = bins.clone();
            moved[j].c *= 1.0 + step;
            let (c2, _) = convert_values(&moved, true);
            c2.iter()
                .zip(&c)
                .map(|(a, b)| (a - b) / (step * bins[j].c))
                .collect()
        })
        .collect();
    let q_min = 2.0 * std::f64::consts::PI / spectrum.length();
    let converted = (0..bins.len())
        .map(|i| {
            let var: f64 = (0..bins.len())
                .map(|j| (columns[j][i] * bins[j].std_error).powi(2))
                .sum();
            let std_error = var.sqrt();
            let tail_share = if c[i] > 0.0 {
                ((c[i] - truncated[i]) / c[i]).abs()
            } else {
                f64::NAN
            };
            let uncertain = if c[i].is_nan() || c[i] <= 0.0 {
                Some(Uncertain::NotPositive)
            } else if tail_share > TAIL_SHARE {
                Some(Uncertain::Cutoff)
            } else if bins[i].q < LOW_MODES * q_min || std_error > RELATIVE_ERROR * c[i] {
                Some(Uncertain::FewModes)
            } else {
                None
            };
            ConvertedBin {
                q: bins[i].q,
                c: c[i],
                std_error,
                tail_share,
                uncertain,
            }
        })
        .collect();
    Converted {
        bins: converted,
        tail_slope: tail,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_self_affine_spectrum_maps_to_its_profiles_with_the_gamma_prefactor_both_ways() {
        for hurst in [0.3, 0.5, 0.8] {
            // R(1/2) = 2 exactly (the integral of 1 / (t^2 sqrt(t^2 - 1)) from 1 is 1).
            if hurst == 0.5 {
                assert!((self_affine_ratio(0.5) - 2.0).abs() < 1e-12);
            }
            let k = 3.0;
            let c2d = |q: f64| k * q.powf(-2.0 - 2.0 * hurst);
            let r = self_affine_ratio(hurst);
            // Forward: C1D of the power law, integrated far enough that the rest is below
            // 1e-6 of it ((q / k_max)^(1+2H) is the share left out).
            for q in [0.1, 1.0, 7.0] {
                let k_max = q * 1e6f64.powf(1.0 / (1.0 + 2.0 * hurst)) * 10.0;
                let got = project(&c2d, q, k_max);
                let want = k * r * q.powf(-1.0 - 2.0 * hurst);
                assert!(
                    (got / want - 1.0).abs() < 1e-5,
                    "H {hurst} q {q}: {got} vs {want}"
                );
            }
            // Inverse: C1D tabulated on nodes with its own power-law tail gives C back.
            let nodes: Vec<(f64, f64)> = (0..40)
                .map(|i| {
                    let q = 0.01 * 10f64.powf(i as f64 / 10.0);
                    (q, k * r * q.powf(-1.0 - 2.0 * hurst))
                })
                .collect();
            let table = LogLog::new(&nodes, Some(-1.0 - 2.0 * hurst));
            for &(q, _) in nodes.iter().step_by(7) {
                let got = invert(&table, q);
                assert!((got / c2d(q) - 1.0).abs() < 1e-6, "H {hurst} q {q}: {got}");
            }
        }
    }

    #[test]
    fn truncating_at_the_cutoff_loses_the_top_of_the_spectrum_only() {
        // Without the tail, C(q) is too low near the last node and right a decade below.
        let hurst = 0.8;
        let r = self_affine_ratio(hurst);
        let nodes: Vec<(f64, f64)> = (0..31)
            .map(|i| {
                let q = 10f64.powf(i as f64 / 10.0);
                (q, r * q.powf(-1.0 - 2.0 * hurst))
            })
            .collect();
        let table = LogLog::new(&nodes, None);
        let exact = |q: f64| q.powf(-2.0 - 2.0 * hurst);
        let near = invert(&table, 800.0) / exact(800.0);
        let decade_below = invert(&table, 100.0) / exact(100.0);
        assert!(near < 0.9, "{near}");
        assert!((decade_below - 1.0).abs() < 0.01, "{decade_below}");
        // The tail gives it back.
        let tailed = LogLog::new(&nodes, Some(-1.0 - 2.0 * hurst));
        let near = invert(&tailed, 800.0) / exact(800.0);
        assert!((near - 1.0).abs() < 1e-6, "{near}");
    }
}
