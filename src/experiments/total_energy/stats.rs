//! The statistics of the total-energy experiment, as pure functions of the sweeps, and the
//! golden values drawn from them (the details are declared in `details.rs`).
//!
//! Ensemble ratios are ratios of sums over realizations, load by load
//! ([`crate::experiments::ensemble::LoadGroup::ratio`]).

use std::collections::BTreeMap;

use super::resolutions::ResolutionStats;
use super::EnergyResult;
use crate::experiments::ensemble::{by_load, group, LoadGroup, SeedLoad};
use crate::stats::{round_sig, Estimate};

/// The realizations of one load.
pub type Load<'a> = LoadGroup<'a, EnergyResult>;

/// Which theory's total energy a ratio divides by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Theory {
    /// The original theory, `E_P` (`S = 1`), eq. (elasticEnergy_h_tot).
    Original,
    /// The corrected theory, `E_c` (`S` of eq. gamma), eq. (elasticEnergy_h_tot_wS).
    Corrected,
}

impl Theory {
    /// The theory's energy at every step of a sweep.
    pub fn energy(self, r: &EnergyResult) -> &[f64] {
        match self {
            Theory::Original => &r.e_p,
            Theory::Corrected => &r.e_c,
        }
    }
}

/// `E_exa / E_theory` at step `k`: the ratio of sums over realizations.
pub fn ratio(load: &Load, k: usize, theory: Theory) -> Estimate {
    load.ratio(|r| (r.e_exa[k], theory.energy(r)[k]))
}

/// The measured contact area at step `k`, averaged over realizations.
pub fn measured_area(load: &Load, k: usize) -> Estimate {
    load.mean(|r| r.contact_area[k])
}

/// The original theory's contact area at step `k`, averaged over realizations.
pub fn original_area(load: &Load, k: usize) -> Estimate {
    load.mean(|r| r.area_original[k])
}

/// The corrected theory's contact area at step `k`, averaged over realizations.
pub fn corrected_area(load: &Load, k: usize) -> Estimate {
    load.mean(|r| r.area_corrected[k])
}

/// `S~` of the step from index `a` to index `b`, eq. (S_q_numerical): the increment of
/// `E_exa` over the increment of `E_P`, as a ratio of sums over realizations.
pub fn s_tilde(load: &Load, a: usize, b: usize) -> Estimate {
    load.ratio(|r| (r.e_exa[b] - r.e_exa[a], r.e_p[b] - r.e_p[a]))
}

/// The index of the step closest (in `ln zeta`) to a quarter of the last magnification:
/// two octaves below the end.
pub fn two_octaves_below_end(zetas: &[f64]) -> usize {
    let end = zetas.len() - 1;
    (0..end)
        .min_by(|&i, &j| {
            let d = |k: usize| (zetas[k] / zetas[end] * 4.0).ln().abs();
            d(i).total_cmp(&d(j))
        })
        .unwrap_or(0)
}

/// How `E_exa / E_c` still moves at the end of the sweep: its change from step `from` to the
/// last step, per realization, averaged.
pub fn corrected_drift(load: &Load, from: usize) -> Estimate {
    load.mean(|r| {
        let end = r.zetas.len() - 1;
        r.e_exa[end] / r.e_c[end] - r.e_exa[from] / r.e_c[from]
    })
}

/// How much more the corrected energy deviates from the measurement at a low load than at
/// the headline load: `|low - 1| - |head - 1|`, with the combined standard error.
pub fn deviation_growth(low: Estimate, head: Estimate) -> Estimate {
    Estimate::new(
        (low.value - 1.0).abs() - (head.value - 1.0).abs(),
        low.std_error.hypot(head.std_error),
    )
}

/// The corrected theory's overestimate of the total energy at step `k`:
/// `sum_r E_c / sum_r E_exa - 1`, the ratio of sums over realizations.
pub fn overestimate(load: &Load, k: usize) -> Estimate {
    let r = load.ratio(|r| (r.e_c[k], r.e_exa[k]));
    Estimate::new(r.value - 1.0, r.std_error)
}

/// Loads at or above this contact area are the high and intermediate loads of the
/// caption of fig. E_vs_ar ("very good" there).
pub const HIGH_LOADS_FROM: f64 = 0.05;

/// Of the values `E_exa / E_c` at full resolution of the loads with a contact area of at
/// least [`HIGH_LOADS_FROM`], the deviation `E_exa / E_c - 1` of largest magnitude, with its
/// standard error (none without such a load).
pub fn corrected_worst(loads: &[Load], end: usize) -> Option<Estimate> {
    loads
        .iter()
        .filter(|l| l.contact_area >= HIGH_LOADS_FROM)
        .map(|l| {
            let c = ratio(l, end, Theory::Corrected);
            Estimate::new(c.value - 1.0, c.std_error)
        })
        .max_by(|a, b| a.value.abs().total_cmp(&b.value.abs()))
}

/// The coefficient of variation (sample standard deviation over mean) of the increments
/// of `e` over the consecutive steps of `window` (NaN with fewer than two increments).
pub fn increment_cv(e: &[f64], window: &[usize]) -> f64 {
    let inc: Vec<f64> = window.windows(2).map(|p| e[p[1]] - e[p[0]]).collect();
    let n = inc.len() as f64;
    if inc.len() < 2 {
        return f64::NAN;
    }
    let mean = inc.iter().sum::<f64>() / n;
    let var = inc.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    var.sqrt() / mean
}

/// How much more the numerator of eq. (S_q_numerical) scatters than its denominator: per
/// realization and increment window, `ln[CV(increments of E_exa) / CV(increments of
/// E_P)]`; the mean over windows and realizations with its standard error.
pub fn numerator_cv_log_ratio(load: &Load) -> Estimate {
    let logs: Vec<f64> = load
        .runs
        .iter()
        .flat_map(|r| {
            r.windows
                .iter()
                .map(|w| (increment_cv(&r.e_exa, w) / increment_cv(&r.e_p, w)).ln())
        })
        .filter(|x| x.is_finite())
        .collect();
    Estimate::mean_of(&logs)
}

/// Of the loads, the largest `|sum_r a_r / sum_r a_c - 1|` at step `k`: the measured
/// contact area against the corrected theory's at the same load and magnification, with
/// its standard error (ratio of sums).
pub fn area_corrected_deviation(loads: &[Load], k: usize) -> Option<Estimate> {
    loads
        .iter()
        .map(|l| {
            let r = l.ratio(|r| (r.contact_area[k], r.area_corrected[k]));
            Estimate::new((r.value - 1.0).abs(), r.std_error)
        })
        .max_by(|a, b| a.value.total_cmp(&b.value))
}

/// A load at full resolution: the measured area and both theories' ratios.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtFullResolution {
    /// The measured contact area.
    pub area: Estimate,
    /// `E_exa / E_P`.
    pub original: Estimate,
    /// `E_exa / E_c`.
    pub corrected: Estimate,
}

impl AtFullResolution {
    /// The values of `load` at the last step, `end`.
    pub fn of(load: &Load, end: usize) -> Self {
        Self {
            area: measured_area(load, end),
            original: ratio(load, end, Theory::Original),
            corrected: ratio(load, end, Theory::Corrected),
        }
    }
}

/// The headline load and the lowest load, the statistics the findings are drawn from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Headline {
    /// The headline load at full resolution (`corrected` is the headline).
    pub head: AtFullResolution,
    /// The step two octaves below the end.
    pub quarter: usize,
    /// The change of `E_exa / E_c` at the headline load from `quarter` to the end.
    pub drift: Estimate,
    /// The lowest load at full resolution.
    pub low: AtFullResolution,
    /// Realizations at the lowest load.
    pub low_runs: usize,
}

impl Headline {
    /// The statistics of `loads` (sweeps over `zetas`) at the headline load
    /// `headline_area`.
    pub fn of(loads: &[Load], headline_area: f64, zetas: &[f64]) -> Self {
        let end = zetas.len() - 1;
        let headline = group(loads, headline_area);
        let quarter = two_octaves_below_end(zetas);
        let lowest = loads
            .iter()
            .min_by(|a, b| a.contact_area.total_cmp(&b.contact_area))
            .expect("validated non-empty");
        Self {
            head: AtFullResolution::of(headline, end),
            quarter,
            drift: corrected_drift(headline, quarter),
            low: AtFullResolution::of(lowest, end),
            low_runs: lowest.runs.len(),
        }
    }

    /// How much more the corrected energy deviates at the lowest load than at the
    /// headline load.
    pub fn growth(&self) -> Estimate {
        deviation_growth(self.low.corrected, self.head.corrected)
    }

    /// How much closer the corrected energy is to the measurement than the original, at
    /// the headline load: `|E_exa / E_P - 1| - |E_exa / E_c - 1|`.
    pub fn improvement(&self) -> Estimate {
        deviation_growth(self.head.original, self.head.corrected)
    }
}

/// The statistics of the total energy: the sweeps' steps and windows (the same in every
/// job) and the headline and lowest loads.
#[derive(Debug, Clone)]
pub struct EnergyStats {
    /// The headline's sweeps (the finer grids' apart).
    pub sweeps: Vec<(SeedLoad, EnergyResult)>,
    /// The finer grids beside the headline's.
    pub resolutions: Vec<ResolutionStats>,
    /// Magnifications of the sweeps.
    pub zetas: Vec<f64>,
    /// The increment windows, indices into `zetas`.
    pub windows: Vec<Vec<usize>>,
    /// The headline and the lowest load.
    pub headline: Headline,
}

impl EnergyStats {
    /// The index of the last step of the sweeps (full resolution).
    pub fn end(&self) -> usize {
        self.zetas.len() - 1
    }

    /// The realizations of the loads `contact_areas` among the headline's sweeps, in that
    /// order.
    pub fn loads(&self, contact_areas: &[f64]) -> Vec<Load<'_>> {
        by_load(contact_areas, &self.sweeps)
    }

    /// The realizations of load `contact_area` among the headline's sweeps.
    pub fn load(&self, contact_area: f64) -> Load<'_> {
        self.loads(&[contact_area]).remove(0)
    }
}

/// The golden values: both ratios at every load, the headline and its drift.
pub fn golden(loads: &[Load], end: usize, h: &Headline) -> BTreeMap<String, f64> {
    let mut golden = BTreeMap::new();
    for load in loads {
        let full = AtFullResolution::of(load, end);
        let a = load.contact_area;
        golden.insert(format!("original_ar{a}"), round_sig(full.original.value, 2));
        golden.insert(
            format!("corrected_ar{a}"),
            round_sig(full.corrected.value, 2),
        );
    }
    golden.insert(
        "corrected_headline".into(),
        round_sig(h.head.corrected.value, 2),
    );
    golden.insert(
        "corrected_headline_drift".into(),
        round_sig(h.drift.value, 1),
    );
    golden
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(e_exa: Vec<f64>, e_p: Vec<f64>) -> EnergyResult {
        let n = e_exa.len();
        EnergyResult {
            p0: 0.1,
            zetas: (1..=n).map(|k| k as f64).collect(),
            contact_area: vec![0.2; n],
            e_c: e_p.iter().map(|e| 0.8 * e).collect(),
            e_exa,
            e_p,
            area_original: vec![0.1; n],
            area_corrected: vec![0.3; n],
            windows: Vec::new(),
            max_residual: 0.0,
        }
    }

    #[test]
    fn s_tilde_is_the_ratio_of_increments() {
        let a = run(vec![1.0, 1.5, 2.5], vec![2.0, 3.0, 5.0]);
        let b = run(vec![2.0, 2.5, 3.0], vec![4.0, 5.0, 6.0]);
        let load = Load {
            contact_area: 0.2,
            runs: vec![&a, &b],
        };
        // (0.5 + 0.5) / (1 + 1) from step 0 to 1.
        assert_eq!(s_tilde(&load, 0, 1).value, 0.5);
        assert_eq!(a.window_mean(&[0, 1, 2]), 0.5);
        let r = ratio(&load, 2, Theory::Corrected);
        assert!((r.value - 5.5 / 8.8).abs() < 1e-15, "{r:?}");
    }

    #[test]
    fn new_statistics_follow_their_formulas() {
        let mut a = run(vec![1.0, 2.0, 5.0, 10.0], vec![2.0, 3.0, 5.0, 8.0]);
        let b = run(vec![2.0, 2.5, 3.0, 3.5], vec![4.0, 5.0, 6.0, 7.0]);
        // Increments of E_exa 1, 3, 5 (CV 2/3), of E_P 1, 2, 3 (CV 1/2).
        assert!((increment_cv(&a.e_exa, &[0, 1, 2, 3]) - 2.0 / 3.0).abs() < 1e-15);
        a.windows = vec![vec![0, 1, 2, 3]];
        let load = Load {
            contact_area: 0.2,
            runs: vec![&a],
        };
        let l = numerator_cv_log_ratio(&load);
        assert!((l.value - (4.0f64 / 3.0).ln()).abs() < 1e-14, "{l:?}");
        let both = Load {
            contact_area: 0.2,
            runs: vec![&a, &b],
        };
        // sum E_c / sum E_exa - 1 at the end: 0.8 (8 + 7) / (10 + 3.5) - 1.
        let o = overestimate(&both, 3);
        assert!((o.value - (12.0 / 13.5 - 1.0)).abs() < 1e-15, "{o:?}");
        // Measured 0.2 against corrected 0.3 at every load: |2/3 - 1|.
        let d = area_corrected_deviation(std::slice::from_ref(&both), 3).unwrap();
        assert!((d.value - 1.0 / 3.0).abs() < 1e-15, "{d:?}");
        // The load below HIGH_LOADS_FROM is left out even though it deviates more.
        let low = Load {
            contact_area: 0.01,
            runs: vec![&b],
        };
        let w = corrected_worst(&[low, both], 3).unwrap();
        assert!((w.value - (13.5 / 12.0 - 1.0)).abs() < 1e-15, "{w:?}");
    }

    #[test]
    fn the_reference_step_is_two_octaves_below_the_end() {
        let zetas = [1.0, 2.0, 3.0, 4.0, 8.0, 16.0];
        assert_eq!(two_octaves_below_end(&zetas), 3);
    }

    #[test]
    fn growth_of_the_deviation_is_signed_and_combines_errors() {
        let g = deviation_growth(Estimate::new(0.7, 0.04), Estimate::new(0.9, 0.03));
        assert!((g.value - 0.2).abs() < 1e-15 && (g.std_error - 0.05).abs() < 1e-15);
        let g = deviation_growth(Estimate::new(0.95, 0.0), Estimate::new(0.9, 0.0));
        assert!(g.value < 0.0);
    }
}
