//! The statistics of the total-energy experiment, as pure functions of the sweeps, and the
//! findings drawn from them as data (details, checks, golden values).
//!
//! Ensemble ratios are ratios of sums over realizations, load by load
//! ([`crate::experiments::ensemble::LoadGroup::ratio`]).

use super::keys::{
    corrected_at_key, corrected_key, corrected_start_key, near_p01_key, original_key, s_tilde_key,
    NEAR_P01_START, NEAR_P01_ZETAS,
};
use crate::experiments::keys::DetailKey;
use std::collections::BTreeMap;

use super::resolutions::ResolutionStats;
use super::{EnergyResult, EnergyScene};
use crate::experiments::ensemble::{group, LoadGroup, SeedLoad};
use crate::experiments::Detail;
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

/// The step of `zetas` nearest `z` (on a log scale).
fn nearest_step(zetas: &[f64], z: f64) -> Option<usize> {
    (0..zetas.len()).min_by(|&a, &b| {
        (zetas[a] / z)
            .ln()
            .abs()
            .total_cmp(&(zetas[b] / z).ln().abs())
    })
}

/// The keys of the headline's and the loads' other details.
const CORRECTED_HEADLINE_DRIFT: &str = "corrected_headline_drift";
const IMPROVEMENT_HEADLINE: &str = "improvement_headline";
const DEVIATION_GROWTH_LOW_LOAD: &str = "deviation_growth_low_load";
const OVERESTIMATE_HEADLINE: &str = "overestimate_headline";
const SHORTFALL_HEADLINE: &str = "shortfall_headline";
const CORRECTED_WORST_HIGH: &str = "corrected_worst_high";
const NUMERATOR_CV_LOG_RATIO: &str = "numerator_cv_log_ratio";
const AREA_CORRECTED_DEVIATION: &str = "area_corrected_deviation";
const OTHER_DETAILS: [&str; 8] = [
    CORRECTED_HEADLINE_DRIFT,
    IMPROVEMENT_HEADLINE,
    DEVIATION_GROWTH_LOW_LOAD,
    OVERESTIMATE_HEADLINE,
    SHORTFALL_HEADLINE,
    CORRECTED_WORST_HIGH,
    NUMERATOR_CV_LOG_RATIO,
    AREA_CORRECTED_DEVIATION,
];

/// The keys of every detail [`details`] can write for `scene` (the resolutions' apart).
pub fn detail_keys(scene: &EnergyScene) -> Vec<DetailKey> {
    let mut keys = Vec::new();
    for &a in &scene.contact_areas {
        keys.extend([original_key(a), corrected_key(a), corrected_start_key(a)]);
        keys.extend((0..scene.increments_at.len()).map(|w| s_tilde_key(a, w)));
        keys.extend(NEAR_P01_ZETAS.map(|z| corrected_at_key(a, z)));
    }
    keys.push(NEAR_P01_START.into());
    keys.extend(NEAR_P01_ZETAS.map(near_p01_key));
    keys.extend(OTHER_DETAILS.map(DetailKey::from));
    keys
}

/// The details of every load, then the headline's drift with magnification.
pub fn details(
    scene: &EnergyScene,
    loads: &[Load],
    zetas: &[f64],
    windows: &[Vec<usize>],
    h: &Headline,
) -> Vec<Detail> {
    let mut details: Vec<Detail> = loads
        .iter()
        .flat_map(|load| load_details(scene, load, zetas, windows))
        .collect();
    details.extend(low_magnification_details(loads, zetas));
    details.extend(headline_details(scene, loads, zetas, h));
    let headline = group(loads, scene.headline_contact_area);
    details.extend(across_loads_details(loads, zetas.len() - 1, headline, h));
    details
}

/// `E_exa / E_c` at the lowest magnifications: at each load, at the steps nearest the
/// first octaves; and at the load whose `p~0` is nearest 0.1 (the caption of fig.
/// E_vs_zeta), at the first step and those octaves.
fn low_magnification_details(loads: &[Load], zetas: &[f64]) -> Vec<Detail> {
    let mut details = Vec::new();
    for load in loads {
        for z in NEAR_P01_ZETAS {
            let Some(k) = nearest_step(zetas, z) else {
                continue;
            };
            details.push(
                Detail::new(
                    corrected_at_key(load.contact_area, z),
                    format!(
                        "E_exa / E_c at zeta = {:.3}, a_r = {} at full resolution",
                        zetas[k], load.contact_area
                    ),
                    ratio(load, k, Theory::Corrected),
                )
                .persson(1.0),
            );
        }
    }
    // The caption of fig. E_vs_zeta speaks of p~0 = 0.1: the load nearest to it, on any
    // scene (the key does not depend on the scene's loads).
    let p_tilde = |load: &Load| load.mean(|r| r.p0).value;
    if let Some(near) = loads.iter().min_by(|a, b| {
        (p_tilde(a) - 0.1)
            .abs()
            .total_cmp(&(p_tilde(b) - 0.1).abs())
    }) {
        details.push(
            Detail::new(
                NEAR_P01_START,
                format!(
                    "E_exa / E_c at the lowest magnification, zeta = {:.3}, at the load whose \
                     p~0 at full resolution is nearest 0.1 (a_r = {}, p~0 = {:.4})",
                    zetas[0],
                    near.contact_area,
                    p_tilde(near)
                ),
                ratio(near, 0, Theory::Corrected),
            )
            .persson(1.0),
        );
        // "Low magnification" read over the first octaves too: the step nearest zeta = 2
        // and 4.
        for z in NEAR_P01_ZETAS {
            let Some(k) = nearest_step(zetas, z) else {
                continue;
            };
            details.push(
                Detail::new(
                    near_p01_key(z),
                    format!(
                        "E_exa / E_c at zeta = {:.3}, at the load whose p~0 at full resolution \
                         is nearest 0.1 (a_r = {})",
                        zetas[k], near.contact_area
                    ),
                    ratio(near, k, Theory::Corrected),
                )
                .persson(1.0),
            );
        }
    }
    details
}

/// The corrected theory at the headline load: the drift of `E_exa / E_c` over the
/// magnifications, how much closer it is than Persson's original, how its deviation
/// grows at the lowest load, its overestimate and the measurement's shortfall.
fn headline_details(
    scene: &EnergyScene,
    loads: &[Load],
    zetas: &[f64],
    h: &Headline,
) -> Vec<Detail> {
    let end = zetas.len() - 1;
    let mut details = vec![
        Detail::new(
            CORRECTED_HEADLINE_DRIFT,
            format!(
                "change of E_exa / E_c at the headline load from zeta = {:.3} to {:.3}",
                zetas[h.quarter], zetas[end]
            ),
            h.drift,
        )
        .persson(0.0),
        Detail::new(
            IMPROVEMENT_HEADLINE,
            format!(
                "|E_exa / E_P - 1| - |E_exa / E_c - 1| at the headline load (a_r = {:.3}): how \
                 much closer the corrected theory is",
                h.head.area.value
            ),
            h.improvement(),
        ),
        Detail::new(
            DEVIATION_GROWTH_LOW_LOAD,
            format!(
                "|E_exa / E_c - 1| at the lowest load (a_r = {:.4}) less that at the headline \
                 load",
                h.low.area.value
            ),
            h.growth(),
        ),
    ];
    let headline = group(loads, scene.headline_contact_area);
    details.push(
        Detail::new(
            OVERESTIMATE_HEADLINE,
            format!(
                "E_c / E_exa - 1 at full resolution at the headline load (a_r = {:.3}): the \
                 corrected theory's overestimate of the total energy",
                h.head.area.value
            ),
            overestimate(headline, end),
        )
        .persson(0.0),
    );
    details.push(
        Detail::new(
            SHORTFALL_HEADLINE,
            format!(
                "1 - E_exa / E_c at full resolution at the headline load (a_r = {:.3}): the \
                 measurement's shortfall against the corrected theory",
                h.head.area.value
            ),
            Estimate::new(1.0 - h.head.corrected.value, h.head.corrected.std_error),
        )
        .persson(0.0),
    );
    details
}

/// Over the loads: the corrected theory's worst deviation at the high loads (at the last
/// step, `end`), the noise of the measured energy's increments against the theory's at the
/// `headline` load, and the measured contact area against the corrected theory's.
fn across_loads_details(loads: &[Load], end: usize, headline: &Load, h: &Headline) -> Vec<Detail> {
    let mut details = Vec::new();
    if let Some(worst) = corrected_worst(loads, end) {
        details.push(
            Detail::new(
                CORRECTED_WORST_HIGH,
                format!(
                    "E_exa / E_c - 1 at full resolution of largest magnitude over the loads \
                     with a_r >= {HIGH_LOADS_FROM}"
                ),
                worst,
            )
            .persson(0.0),
        );
    }
    details.push(Detail::new(
        NUMERATOR_CV_LOG_RATIO,
        format!(
            "ln of CV(increments of E_exa) / CV(increments of E_P) over each window's \
             single-shell steps, mean over windows and realizations at the headline load \
             (a_r = {:.3})",
            h.head.area.value
        ),
        numerator_cv_log_ratio(headline),
    ));
    if let Some(dev) = area_corrected_deviation(loads, end) {
        details.push(
            Detail::new(
                AREA_CORRECTED_DEVIATION,
                "|measured a_r / corrected theory's a_r - 1| at full resolution, largest over \
                 the loads",
                dev,
            )
            .persson(0.0),
        );
    }
    details
}

/// The details of one load: both theories' ratios at full resolution, and `S~` averaged
/// over each window of single-shell increments.
fn load_details(
    scene: &EnergyScene,
    load: &Load,
    zetas: &[f64],
    windows: &[Vec<usize>],
) -> Vec<Detail> {
    let full = AtFullResolution::of(load, zetas.len() - 1);
    let a = load.contact_area;
    let mut details = vec![
        Detail::new(
            original_key(a),
            format!(
                "E_exa / E_P (S = 1) at full resolution, a_r = {a} ({:.4} measured)",
                full.area.value
            ),
            full.original,
        )
        .persson(1.0),
        Detail::new(
            corrected_key(a),
            format!(
                "E_exa / E_c (S of eq. gamma) at full resolution, a_r = {a} ({:.4} measured)",
                full.area.value
            ),
            full.corrected,
        )
        .persson(1.0),
        Detail::new(
            corrected_start_key(a),
            format!(
                "E_exa / E_c at the lowest magnification, zeta = {:.3}, a_r = {a} at full \
                 resolution (p~0 = p0 / E* g_bar = {:.4}, g_bar at full resolution)",
                zetas[0],
                load.mean(|r| r.p0).value
            ),
            ratio(load, 0, Theory::Corrected),
        )
        .persson(1.0),
    ];
    for (w, window) in windows.iter().enumerate() {
        let s_w = load.mean(|r| r.window_mean(&r.windows[w]));
        let last = *window.last().expect("non-empty window");
        let s_p = scene.correction.factor(original_area(load, last).value);
        details.push(
            Detail::new(
                s_tilde_key(a, w),
                format!(
                    "S~ over {} single-shell increments from zeta = {:.3} to {:.3}, \
                     a_r = {a} at full resolution (Persson: S(a_r) of eq. gamma)",
                    window.len() - 1,
                    zetas[window[0]],
                    zetas[last],
                ),
                s_w,
            )
            .persson(s_p),
        );
    }
    details
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
