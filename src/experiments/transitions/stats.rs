//! The statistics of the transitions, as pure functions of the binned walkers: the moment
//! analysis of one bin (Appendix), region means over bins, estimates over realizations,
//! the ensemble row of every bin, and the statistics the paper's side remarks need: how
//! well the mirror Gaussian with a bin's moments fits the bin's stored transition histogram
//! (total-variation distance), the bin's own width against its half width and against the
//! broadening, the walkers lost against Persson's drift-free loss, and the share of walkers
//! below the mean contact pressure in bins of negative drift.

use std::f64::consts::SQRT_2;

use statrs::function::erf::erfc;

use super::{BinSums, DistanceResult, TransitionResult, TransitionScene};
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

/// The mean over realizations of `f` of each result, over the realizations where it has a
/// value.
pub fn mean_where(
    results: &[(u64, TransitionResult)],
    f: impl Fn(&TransitionResult) -> Option<f64>,
) -> Estimate {
    Estimate::mean_of(&results.iter().filter_map(|(_, r)| f(r)).collect::<Vec<_>>())
}

/// One analysed bin of a realization with its sums.
#[derive(Debug, Clone, Copy)]
pub struct AnalysedBin<'a> {
    /// Bin index.
    pub bin: usize,
    /// The bin's sums.
    pub sums: &'a BinSums,
    /// Its moment analysis.
    pub analysis: BinAnalysis,
}

impl AnalysedBin<'_> {
    /// `dp_n`, the standard deviation of the old pressures in the bin, in units of `unit`.
    pub fn own_width(&self, unit: f64) -> f64 {
        let b = self.sums;
        let mean = b.old / b.count;
        (b.old2 / b.count - mean * mean).max(0.0).sqrt() / unit
    }
}

/// Per realization: the analysed bins but the last (which collects the rest), in order of
/// pressure.
pub fn analysed_bins<'a>(scene: &TransitionScene, r: &'a TransitionResult) -> Vec<AnalysedBin<'a>> {
    analyse_all(scene, r)
        .into_iter()
        .enumerate()
        .take(scene.bins - 1)
        .filter_map(|(bin, a)| {
            a.map(|analysis| AnalysedBin {
                bin,
                sums: &r.bins[bin],
                analysis,
            })
        })
        .collect()
}

/// The mass of the mirror Gaussian of eq. (transitionFinal) with parameter `p_mean = p'`
/// and width `width = Dp_n` in each column of a row of the transition histogram, all
/// pressures in one unit: column 0 the mass absorbed at `p = 0`, `erfc(p' / (sqrt2 Dp_n))`;
/// column `k >= 1` the new pressures in `[(k - 1) w, k w)`, `w = bin_width`, the last column
/// open above, each `[Phi((b - p')/Dp_n) - Phi((a - p')/Dp_n)] - [Phi((b + p')/Dp_n) -
/// Phi((a + p')/Dp_n)]`. A width of 0 puts all the mass in the column of `p'`.
///
/// # Panics
///
/// If `columns < 2`.
pub fn mirror_gaussian_columns(
    p_mean: f64,
    width: f64,
    bin_width: f64,
    columns: usize,
) -> Vec<f64> {
    assert!(columns >= 2, "a histogram row of {columns} columns");
    let mut g = vec![0.0; columns];
    if width <= 0.0 {
        let k = if p_mean > 0.0 {
            ((p_mean / bin_width).floor() as usize + 1).min(columns - 1)
        } else {
            0
        };
        g[k] = 1.0;
        return g;
    }
    // Phi((x - p')/Dp) - Phi((x + p')/Dp), with x = infinity giving 0.
    let image = |x: f64| {
        if x.is_infinite() {
            0.0
        } else {
            let phi = |y: f64| 0.5 * erfc(-y / (SQRT_2 * width));
            phi(x - p_mean) - phi(x + p_mean)
        }
    };
    g[0] = erfc(p_mean / (SQRT_2 * width));
    for (k, gk) in g.iter_mut().enumerate().skip(1) {
        let a = (k - 1) as f64 * bin_width;
        let b = if k + 1 == columns {
            f64::INFINITY
        } else {
            k as f64 * bin_width
        };
        *gk = image(b) - image(a);
    }
    g
}

/// The total-variation distance `1/2 sum_k |counts_k / walkers - g_k|` between a row of the
/// transition histogram (`walkers` in all) and the masses `g` of a distribution over the
/// same columns.
pub fn total_variation(counts: &[u32], walkers: f64, g: &[f64]) -> f64 {
    0.5 * counts
        .iter()
        .zip(g)
        .map(|(&c, &gk)| (f64::from(c) / walkers - gk).abs())
        .sum::<f64>()
}

/// How well the mirror Gaussian with a bin's moments describes its transitions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BinFit {
    /// Bin index.
    pub bin: usize,
    /// Suited for the moment analysis (mean above the broadening).
    pub suited: bool,
    /// Total-variation distance between the bin's transition histogram and the mirror
    /// Gaussian with parameter `p' = <p>_{n,new}` and width `Dp_n`.
    pub distance: f64,
}

/// Per realization: the fit of every analysed bin but the last, in order of pressure.
pub fn bin_fits(scene: &TransitionScene, r: &TransitionResult) -> Vec<BinFit> {
    let unit = r.p0 / r.a_r_old;
    analysed_bins(scene, r)
        .into_iter()
        .map(|a| {
            let row = &r.histogram[a.bin + 1];
            let g = mirror_gaussian_columns(
                a.sums.new / a.sums.count / unit,
                a.analysis.width,
                scene.bin_width,
                row.len(),
            );
            BinFit {
                bin: a.bin,
                suited: a.analysis.suited,
                distance: total_variation(row, a.sums.count, &g),
            }
        })
        .collect()
}

/// The mean distance of the unsuited bins minus that of the suited bins (each an
/// unweighted mean over bins); `None` without bins of either kind.
pub fn unsuited_minus_suited(fits: &[BinFit]) -> Option<f64> {
    let mean = |suited: bool| {
        let d: Vec<f64> = fits
            .iter()
            .filter(|f| f.suited == suited)
            .map(|f| f.distance)
            .collect();
        (!d.is_empty()).then(|| d.iter().sum::<f64>() / d.len() as f64)
    };
    Some(mean(false)? - mean(true)?)
}

/// The distance of the lowest unsuited bin minus that of the highest; `None` with fewer
/// than two unsuited bins.
pub fn lowest_minus_top_unsuited(fits: &[BinFit]) -> Option<f64> {
    let mut unsuited = fits.iter().filter(|f| !f.suited);
    let lowest = unsuited.next()?;
    let top = unsuited.next_back()?;
    Some(lowest.distance - top.distance)
}

/// Per realization: the mean over analysed bins of `dp_n / (w / 2)`, the spread of the old
/// pressures in a bin over the bin's half width (a flat density gives `1/sqrt3`).
pub fn bin_spread_over_half_width(scene: &TransitionScene, r: &TransitionResult) -> Option<f64> {
    let unit = r.p0 / r.a_r_old;
    let bins = analysed_bins(scene, r);
    let spread: f64 = bins
        .iter()
        .map(|a| a.own_width(unit) / (scene.bin_width / 2.0))
        .sum();
    (!bins.is_empty()).then(|| spread / bins.len() as f64)
}

/// Per realization: the mean over suited bins (of non-zero broadening) of `dp_n^2 /
/// Dp_n^2`, the share of the new distribution's width that the bin's own width makes up,
/// i.e. the relative change of `D_n` its correction makes.
pub fn bin_broadening_share(scene: &TransitionScene, r: &TransitionResult) -> Option<f64> {
    let unit = r.p0 / r.a_r_old;
    let shares: Vec<f64> = analysed_bins(scene, r)
        .iter()
        .filter(|a| a.analysis.suited && a.analysis.width > 0.0)
        .map(|a| (a.own_width(unit) / a.analysis.width).powi(2))
        .collect();
    (!shares.is_empty()).then(|| shares.iter().sum::<f64>() / shares.len() as f64)
}

/// Per realization: the walkers that left contact over the step, over the number
/// Persson's drift-free mirror Gaussian of width `Dp^2 = D_P dzeta` absorbs at `p = 0`,
/// `sum_n count_n erfc(pbar_n / sqrt(2 D_P dzeta))`, `pbar_n` the bin's mean old pressure
/// standing in for its walkers', over every bin with walkers (the last included). `None`
/// when Persson's loss is 0.
pub fn lost_over_persson(scene: &TransitionScene, r: &TransitionResult) -> Option<f64> {
    let scale = (2.0 * r.d_persson * scene.dzeta).sqrt();
    let (lost, persson) = r
        .bins
        .iter()
        .filter(|b| b.count > 0.0)
        .fold((0.0, 0.0), |(l, p), b| {
            (l + b.lost, p + b.count * erfc(b.old / b.count / scale))
        });
    (persson > 0.0).then(|| lost / persson)
}

/// Per realization: the share of the walkers of the lowest analysed bin that left contact
/// over the step, less the share of the walkers at `p >= high` (units of `p0 / a_r`) that
/// did (walker-weighted over those bins). `None` without both.
pub fn lost_lowest_minus_high(
    scene: &TransitionScene,
    r: &TransitionResult,
    high: f64,
) -> Option<f64> {
    let bins = analysed_bins(scene, r);
    let lowest = bins.first()?.analysis.lost;
    let (lost, walkers) = bins
        .iter()
        .map(|a| a.analysis)
        .filter(|a| a.mean_old >= high)
        .fold((0.0, 0.0), |(l, w), a| {
            (l + a.lost * a.walkers, w + a.walkers)
        });
    (walkers > 0.0).then(|| lowest - lost / walkers)
}

/// Per realization: the share of the walkers in the analysed bins whose mean lies below
/// the broadening (unsuited for the moment analysis) that left contact over the step.
/// `None` without such bins.
pub fn lost_unsuited(scene: &TransitionScene, r: &TransitionResult) -> Option<f64> {
    let (lost, walkers) = analysed_bins(scene, r)
        .iter()
        .map(|a| a.analysis)
        .filter(|a| !a.suited)
        .fold((0.0, 0.0), |(l, w), a| {
            (l + a.lost * a.walkers, w + a.walkers)
        });
    (walkers > 0.0).then(|| lost / walkers)
}

/// The mean contact pressure `p0 / a_r` in its own units: the bins below it are those the
/// paper's count of drifting walkers speaks of (tex 676-677).
pub const MEAN_CONTACT_PRESSURE: f64 = 1.0;

/// Per realization: over the analysed bins with mean pressure below
/// [`MEAN_CONTACT_PRESSURE`], the share of walkers in bins of negative drift. `None`
/// without such bins.
pub fn share_walkers_negative_drift(scene: &TransitionScene, r: &TransitionResult) -> Option<f64> {
    let (negative, all) = analysed_bins(scene, r)
        .iter()
        .map(|a| a.analysis)
        .filter(|a| a.mean_old < MEAN_CONTACT_PRESSURE)
        .fold((0.0, 0.0), |(n, w), a| {
            (
                n + if a.drift < 0.0 { a.walkers } else { 0.0 },
                w + a.walkers,
            )
        });
    (all > 0.0).then(|| negative / all)
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

/// One realization's mean distance to the nearest point out of contact (grid spacings)
/// of the walkers in the bins wholly below `low_pressure` and of those in the bins from
/// `high_pressure` up (`None` where either holds no walker).
pub fn contact_line_distances(scene: &TransitionScene, d: &DistanceResult) -> Option<(f64, f64)> {
    let w = scene.bin_width;
    let low_end = ((scene.low_pressure / w) + 1e-9).floor() as usize;
    let high_from = ((scene.high_pressure / w) - 1e-9).ceil() as usize;
    let mean = |bins: &[(f64, f64)]| {
        let (n, sum) = bins.iter().fold((0.0, 0.0), |(n, s), b| (n + b.0, s + b.1));
        (n > 0.0).then(|| sum / n)
    };
    let low = mean(&d.bins[..low_end.min(d.bins.len())])?;
    let high = mean(&d.bins[high_from.min(d.bins.len())..])?;
    Some((low, high))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_line_distances_average_the_walkers_of_whole_bins() {
        // Bins of 0.25 p0/a_r: below 0.5 are bins 0 and 1, from 1.0 up bins 4 to 7.
        let scene = super::super::synthetic_scene(8, 0.25);
        let mut bins = vec![(0.0, 0.0); 8];
        bins[0] = (2.0, 2.0);
        bins[1] = (2.0, 4.0);
        bins[2] = (5.0, 50.0); // between the regions: not read
        bins[5] = (1.0, 9.0);
        bins[7] = (3.0, 15.0);
        let d = DistanceResult {
            p0: 0.1,
            a_r: 0.3,
            bins,
            max_residual: 0.0,
        };
        assert_eq!(contact_line_distances(&scene, &d), Some((1.5, 6.0)));
        let empty = DistanceResult {
            bins: vec![(0.0, 0.0); 8],
            ..d
        };
        assert_eq!(contact_line_distances(&scene, &empty), None);
    }

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

    use super::super::{synthetic, synthetic_scene};

    #[test]
    fn the_mirror_gaussian_columns_hold_all_the_mass_and_its_absorbed_part() {
        let g = mirror_gaussian_columns(0.3, 0.2, 0.1, 8);
        let total: f64 = g.iter().sum();
        assert!((total - 1.0).abs() < 1e-12, "{total}");
        assert_eq!(g[0], erfc(0.3 / (SQRT_2 * 0.2)));
        assert!(g.iter().all(|&m| m >= 0.0), "{g:?}");
        // Far from p = 0 and narrow: the column of p' = 0.55, [0.5, 0.6), holds nearly all.
        let narrow = mirror_gaussian_columns(0.55, 1e-3, 0.1, 8);
        assert!((narrow[6] - 1.0).abs() < 1e-12, "{narrow:?}");
        // No width: all in the column of p'; beyond the last edge, in the last column.
        assert_eq!(mirror_gaussian_columns(0.55, 0.0, 0.1, 8)[6], 1.0);
        assert_eq!(mirror_gaussian_columns(5.0, 0.0, 0.1, 8)[7], 1.0);
    }

    #[test]
    fn total_variation_is_zero_for_the_same_and_one_for_disjoint_distributions() {
        assert_eq!(total_variation(&[1, 3, 0], 4.0, &[0.25, 0.75, 0.0]), 0.0);
        assert_eq!(total_variation(&[4, 0, 0], 4.0, &[0.0, 0.5, 0.5]), 1.0);
        assert_eq!(total_variation(&[2, 2, 0], 4.0, &[0.5, 0.0, 0.5]), 0.5);
    }

    #[test]
    fn fits_compare_unsuited_with_suited_and_the_lowest_with_the_top_unsuited() {
        let fit = |bin, suited, distance| BinFit {
            bin,
            suited,
            distance,
        };
        let fits = [
            fit(0, false, 0.5),
            fit(1, false, 0.3),
            fit(2, false, 0.1),
            fit(3, true, 0.1),
            fit(4, true, 0.2),
        ];
        let d = unsuited_minus_suited(&fits).unwrap();
        assert!((d - 0.15).abs() < 1e-12, "{d}");
        let d = lowest_minus_top_unsuited(&fits).unwrap();
        assert!((d - 0.4).abs() < 1e-12, "{d}");
        // One unsuited bin: nothing to compare it with.
        assert_eq!(lowest_minus_top_unsuited(&fits[2..]), None);
        assert_eq!(unsuited_minus_suited(&fits[3..]), None);
    }

    #[test]
    fn a_bin_that_stays_in_its_column_fits_its_mirror_gaussian() {
        // Bins of 1 (p0 = 1); bin 1 = [1, 2): walkers at 1.4 and 1.6 stay, the mirror
        // Gaussian of width 0.1 about 1.5 lies in the column [1, 2) but for 6e-7.
        let scene = synthetic_scene(4, 1.0);
        let r = synthetic(&scene, 1.0, 1.0, &[(1.4, 1.4), (1.6, 1.6)]);
        let fits = bin_fits(&scene, &r);
        assert_eq!(fits.len(), 1);
        assert_eq!((fits[0].bin, fits[0].suited), (1, true));
        assert!(fits[0].distance < 1e-5, "{}", fits[0].distance);
    }

    #[test]
    fn the_spread_of_a_bin_is_measured_against_its_half_width() {
        // Bins of 0.5 (p0 = 1): in bins 0, 1, 2 the old pressures lie 0.3 apart, dp = 0.15
        // = 0.6 half widths; the last bin (the rest, dp = 0.5) does not count.
        let scene = synthetic_scene(4, 0.5);
        let walkers = [
            (0.1, 0.0),
            (0.4, 0.2),
            (0.6, 0.7),
            (0.9, 1.0),
            (0.6, 0.7),
            (0.9, 1.0),
            (1.1, 1.1),
            (1.4, 1.4),
            (2.0, 2.0),
            (3.0, 3.0),
        ];
        let r = synthetic(&scene, 1.0, 1.0, &walkers);
        let spread = bin_spread_over_half_width(&scene, &r).unwrap();
        assert!((spread - 0.6).abs() < 1e-12, "{spread}");
        // Below p0/a_r: bin 0 (2 walkers) drifts down, bin 1 (4 walkers) up.
        let share = share_walkers_negative_drift(&scene, &r).unwrap();
        assert!((share - 1.0 / 3.0).abs() < 1e-15, "{share}");
    }

    #[test]
    fn the_broadening_share_is_the_bins_own_variance_over_the_new_one() {
        // Far above p = 0 the mirror Gaussian is a Gaussian: Dp_n^2 is the variance of the
        // new pressures. Unmoved walkers: the bin's width is all the broadening.
        let scene = synthetic_scene(2, 100.0);
        let same = synthetic(&scene, 1.0, 1.0, &[(10.0, 10.0), (10.2, 10.2)]);
        let share = bin_broadening_share(&scene, &same).unwrap();
        assert!((share - 1.0).abs() < 1e-9, "{share}");
        // New pressures twice as far apart: a quarter.
        let wider = synthetic(&scene, 1.0, 1.0, &[(10.0, 9.9), (10.2, 10.3)]);
        let share = bin_broadening_share(&scene, &wider).unwrap();
        assert!((share - 0.25).abs() < 1e-9, "{share}");
    }

    #[test]
    fn losses_are_counted_against_the_drift_free_mirror_gaussian() {
        // Four walkers at p = 1, one lost; 2 D_P dzeta = 1: Persson loses 4 erfc(1).
        let scene = synthetic_scene(4, 0.5);
        let walkers = [(1.0, 0.0), (1.0, 1.0), (1.0, 1.0), (1.0, 1.0)];
        let r = synthetic(&scene, 1.0, 1.0 / (2.0 * scene.dzeta), &walkers);
        let ratio = lost_over_persson(&scene, &r).unwrap();
        let expected = 1.0 / (4.0 * 0.157_299_207_050_285_13);
        // statrs' erfc agrees with the tabulated erfc(1) to 5e-11 relative.
        assert!(
            (ratio / expected - 1.0).abs() < 1e-9,
            "{ratio} vs {expected}"
        );
        // No broadening: Persson loses none, no ratio.
        let r = synthetic(&scene, 1.0, 0.0, &walkers);
        assert_eq!(lost_over_persson(&scene, &r), None);
    }
}
