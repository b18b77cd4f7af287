//! The statistics of the transitions, as pure functions of the binned walkers: the moment
//! analysis of one bin (Appendix), region means over bins, estimates over realizations,
//! and the ensemble row of every bin.

use super::{BinSums, TransitionResult, TransitionScene};
use crate::persson::moments;
use crate::stats::{Bins, Estimate};

/// The moment analysis of one bin (Appendix), in units of `p0 / a_r`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BinAnalysis {
    /// Walkers in the bin.
    pub walkers: f64,
    /// `<p>_{n, zeta}` / unit.
    pub mean_old: f64,
    /// Drift `mu_n` / unit.
    pub drift: f64,
    /// `Dp_n` / unit (width of the mirror Gaussian with the new moments).
    pub width: f64,
    /// `D_n / D_P`.
    pub ratio: f64,
    /// Mean above the broadening (the moment analysis applies).
    pub suited: bool,
    /// Fraction of walkers that left contact.
    pub lost: f64,
}

/// The moment analysis of bin `b` (`None` for fewer than two walkers, or moments no mirror
/// Gaussian has): pressures in units of `unit = p0 / a_r`, the step `dzeta`, Persson's
/// `D_P`.
pub fn analyse(b: &BinSums, unit: f64, dzeta: f64, d_persson: f64) -> Option<BinAnalysis> {
    if b.count < 2.0 {
        return None;
    }
    let mean_old = b.old / b.count;
    let own = (b.old2 / b.count - mean_old * mean_old).max(0.0);
    let p_new = b.new / b.count;
    let m2 = b.new2 / b.count;
    let width = if p_new > 0.0 && m2 > p_new * p_new {
        moments::width_from_moments(p_new, m2).ok()?
    } else {
        0.0
    };
    let d_n = (width * width - own) / dzeta;
    Some(BinAnalysis {
        walkers: b.count,
        mean_old: mean_old / unit,
        drift: (p_new - mean_old) / dzeta / unit,
        width: width / unit,
        ratio: d_n / d_persson,
        suited: mean_old > width,
        lost: b.lost / b.count,
    })
}

/// Per realization: the analysis of every bin (`None` where too few walkers).
pub fn analyse_all(scene: &TransitionScene, r: &TransitionResult) -> Vec<Option<BinAnalysis>> {
    let unit = r.p0 / r.a_r_old;
    r.bins
        .iter()
        .map(|b| {
            if b.count < scene.min_walkers as f64 {
                None
            } else {
                analyse(b, unit, scene.dzeta, r.d_persson)
            }
        })
        .collect()
}

/// Walker-weighted mean of `f` over the analysed bins passing `keep`.
pub fn region_mean(
    bins: &[Option<BinAnalysis>],
    keep: impl Fn(&BinAnalysis) -> bool,
    f: impl Fn(&BinAnalysis) -> f64,
) -> Option<f64> {
    let (mut s, mut w) = (0.0, 0.0);
    for b in bins.iter().flatten().filter(|b| keep(b)) {
        s += b.walkers * f(b);
        w += b.walkers;
    }
    (w > 0.0).then(|| s / w)
}

/// Estimate over realizations of a per-realization statistic of the analysed bins
/// (realizations without a value are skipped).
pub fn over_realizations(
    scene: &TransitionScene,
    results: &[(u64, TransitionResult)],
    f: impl Fn(&[Option<BinAnalysis>]) -> Option<f64>,
) -> Estimate {
    let samples: Vec<f64> = results
        .iter()
        .filter_map(|(_, r)| f(&analyse_all(scene, r)))
        .collect();
    Estimate::mean_of(&samples)
}

/// The mean over realizations of `f` of each result.
pub fn mean_of(
    results: &[(u64, TransitionResult)],
    f: impl Fn(&TransitionResult) -> f64,
) -> Estimate {
    Estimate::mean_of(&results.iter().map(|(_, r)| f(r)).collect::<Vec<_>>())
}

/// One bin over the realizations that analysed it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BinRow {
    /// Bin index.
    pub bin: usize,
    /// Mean old pressure, units of `p0 / a_r`.
    pub pressure: f64,
    /// Walkers over all realizations.
    pub walkers: f64,
    /// `D_n / D_P`.
    pub ratio: Estimate,
    /// Drift `mu_n`, units of `p0 / a_r` per unit `zeta`.
    pub drift: Estimate,
    /// `Dp_n`, units of `p0 / a_r`.
    pub width: f64,
    /// Fraction of walkers that left contact.
    pub lost: f64,
    /// Suited for the moment analysis in every realization that has the bin.
    pub suited: bool,
}

/// The ensemble row of every bin analysed in at least one realization (the last bin,
/// which collects the rest, left out).
pub fn bin_rows(scene: &TransitionScene, results: &[(u64, TransitionResult)]) -> Vec<BinRow> {
    let all: Vec<Vec<Option<BinAnalysis>>> =
        results.iter().map(|(_, r)| analyse_all(scene, r)).collect();
    let mut rows = Vec::new();
    for k in 0..scene.bins - 1 {
        let here: Vec<BinAnalysis> = all.iter().filter_map(|bins| bins[k]).collect();
        if here.is_empty() {
            continue;
        }
        let mean =
            |f: fn(&BinAnalysis) -> f64| Estimate::mean_of(&here.iter().map(f).collect::<Vec<_>>());
        rows.push(BinRow {
            bin: k,
            pressure: mean(|b| b.mean_old).value,
            walkers: here.iter().map(|b| b.walkers).sum(),
            ratio: mean(|b| b.ratio),
            drift: mean(|b| b.drift),
            width: mean(|b| b.width).value,
            lost: mean(|b| b.lost).value,
            suited: here.iter().all(|b| b.suited),
        });
    }
    rows
}

/// The contact pressures counted as small for the shape of `Pr(p)`, in units of
/// `p0 / a_r`: the bins that lie wholly below this.
pub const SMALL_PRESSURE: f64 = 0.2;

/// The local exponent `alpha` of `Pr(p) ~ p^alpha` at small pressure, from the old-pressure
/// histogram of one realization: the least-squares slope of `ln n_k` against
/// `ln (k + 1/2)` over the bins `k` that lie wholly below `SMALL_PRESSURE` (bin width
/// `bin_width`, in units of `p0 / a_r`). Persson's distribution, eq. (pressureDistOri),
/// vanishes linearly at `p = 0` (`alpha = 1`). `None` with fewer than two non-empty bins.
pub fn small_pressure_exponent(bins: &[BinSums], bin_width: f64) -> Option<f64> {
    if bins.len() < 2 {
        return None;
    }
    let last = Bins::linear(0.0, bin_width, bins.len()).below(SMALL_PRESSURE);
    let points: Vec<(f64, f64)> = bins
        .iter()
        .take(last)
        .enumerate()
        .filter(|(_, b)| b.count > 0.0)
        .map(|(k, b)| ((k as f64 + 0.5).ln(), b.count.ln()))
        .collect();
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(x, y), p| (x + p.0 / n, y + p.1 / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(xy, xx), p| {
        (xy + (p.0 - mx) * (p.1 - my), xx + (p.0 - mx) * (p.0 - mx))
    });
    Some(sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_small_pressure_exponent_of_a_linear_and_a_flat_histogram() {
        // Pr(p) ~ p: counts in bins of width w grow as the bins' centres, k + 1/2.
        let counted = |f: &dyn Fn(f64) -> f64| -> Vec<BinSums> {
            (0..10)
                .map(|k| BinSums {
                    count: f(k as f64 + 0.5),
                    ..BinSums::default()
                })
                .collect()
        };
        let linear = small_pressure_exponent(&counted(&|c| 100.0 * c), 0.05).unwrap();
        assert!((linear - 1.0).abs() < 1e-12, "{linear}");
        let flat = small_pressure_exponent(&counted(&|_| 7.0), 0.05).unwrap();
        assert!(flat.abs() < 1e-12, "{flat}");
        // Bins beyond SMALL_PRESSURE do not count: a spike in bin 4 (0.2 to 0.25) changes
        // nothing.
        let mut spiked = counted(&|c| c * c);
        spiked[4].count = 1e9;
        let square = small_pressure_exponent(&spiked, 0.05).unwrap();
        assert!((square - 2.0).abs() < 1e-12, "{square}");
        assert!(small_pressure_exponent(&spiked, 0.15).is_none());
    }

    fn bin(pairs: &[(f64, f64)]) -> BinSums {
        let mut b = BinSums::default();
        for &(old, new) in pairs {
            b.add(old, new);
        }
        b
    }

    #[test]
    fn a_bin_that_does_not_move_has_no_drift_and_no_diffusion() {
        let b = bin(&[(2.0, 2.0), (2.0, 2.0), (2.0, 2.0)]);
        let a = analyse(&b, 1.0, 0.5, 1.0).unwrap();
        assert_eq!((a.walkers, a.mean_old, a.drift), (3.0, 2.0, 0.0));
        assert_eq!((a.width, a.ratio, a.lost), (0.0, 0.0, 0.0));
        assert!(a.suited);
        assert!(analyse(&bin(&[(1.0, 1.0)]), 1.0, 0.5, 1.0).is_none());
    }

    #[test]
    fn drift_is_the_mean_change_per_unit_zeta_and_losses_count_at_zero() {
        // Old pressures 1 and 3 (unit 2), new 0 and 3: mean change -0.5 over dzeta 0.25,
        // in units of 2: -1; one of two walkers lost.
        let a = analyse(&bin(&[(1.0, 0.0), (3.0, 3.0)]), 2.0, 0.25, 1.0).unwrap();
        assert_eq!(a.mean_old, 1.0);
        assert_eq!(a.drift, -1.0);
        assert_eq!(a.lost, 0.5);
    }

    #[test]
    fn region_means_are_weighted_by_walkers() {
        let a = |walkers, mean_old, drift| {
            Some(BinAnalysis {
                walkers,
                mean_old,
                drift,
                width: 0.0,
                ratio: 1.0,
                suited: true,
                lost: 0.0,
            })
        };
        let bins = [a(1.0, 0.1, 4.0), None, a(3.0, 0.3, 0.0), a(5.0, 2.0, 9.0)];
        let low = region_mean(&bins, |b| b.mean_old < 1.0, |b| b.drift);
        assert_eq!(low, Some(1.0));
        assert_eq!(region_mean(&bins, |b| b.mean_old > 5.0, |b| b.drift), None);
    }
}
