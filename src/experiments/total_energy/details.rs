//! The details of the total-energy experiment, declared once ([`DetailTable`]): each
//! load's ratios at full resolution and at the lowest magnifications and `S~` over each
//! increment window, then the headline's drift, improvement, overestimate and shortfall,
//! then the statistics over the loads.
//!
//! The keys depend on the scene only; most labels quote a measured number (the measured
//! contact area, a step of the sweeps, `p~0`), so each is read with its value from the
//! statistics ([`DetailTable::row_labelled`]), and Persson's `S(a_r)` of a window at the
//! original theory's area at the load found ([`Declared::persson_from`]).
//!
//! [`Declared::persson_from`]: crate::experiments::declared::Declared::persson_from

use super::stats::{
    area_corrected_deviation, corrected_worst, numerator_cv_log_ratio, original_area, overestimate,
    ratio, AtFullResolution, EnergyStats, Load, Theory, HIGH_LOADS_FROM,
};
use super::EnergyScene;
use crate::experiments::declared::DetailTable;
use crate::experiments::keys::{DetailKey, Tag};
use crate::stats::Estimate;

/// The table of the statistics of the total energy.
type Table<'s> = DetailTable<'s, EnergyStats>;

/// The keys of a load's details: both theories' ratios at full resolution, the corrected
/// one's at the lowest magnification, and `S~` over window `w`.
fn original_key(a: f64) -> DetailKey {
    DetailKey::new("original").at(Tag::ContactArea, a)
}
fn corrected_key(a: f64) -> DetailKey {
    DetailKey::new("corrected").at(Tag::ContactArea, a)
}
fn corrected_start_key(a: f64) -> DetailKey {
    DetailKey::new("corrected_start").at(Tag::ContactArea, a)
}
fn s_tilde_key(a: f64, w: usize) -> DetailKey {
    DetailKey::new("s_tilde")
        .at(Tag::ContactArea, a)
        .at(Tag::Window, w as f64)
}

/// The key of the corrected ratio at the load nearest `p~0 = 0.1` at the lowest
/// magnification, and at the step nearest each of [`NEAR_P01_ZETAS`] ([`near_p01_key`]).
const NEAR_P01_START: &str = "corrected_start_p0.1";
const NEAR_P01_ZETAS: [f64; 2] = [2.0, 4.0];
fn near_p01_key(zeta: f64) -> DetailKey {
    DetailKey::new("corrected")
        .at(Tag::Pressure, 0.1)
        .at(Tag::Zeta, zeta)
}
/// E_exa / E_c of a load at the step nearest zeta = 2 and 4 (the caption's "low
/// magnification" beyond zeta = 1).
fn corrected_at_key(a: f64, zeta: f64) -> DetailKey {
    corrected_key(a).at(Tag::Zeta, zeta)
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

/// Declares the details of every load, those at the lowest magnifications, the
/// headline's and those over the loads (the resolutions' apart).
pub fn declare<'s>(t: &mut Table<'s>, scene: &'s EnergyScene) {
    for &a in &scene.contact_areas {
        declare_load(t, scene, a);
    }
    declare_low_magnification(t, &scene.contact_areas);
    declare_headline(t, scene.headline_contact_area);
    declare_across_loads(t, scene);
}

/// Declares the details of load `a` (Persson: 1): both theories' ratios at full
/// resolution, the corrected one's at the lowest magnification, and `S~` averaged over
/// each window of single-shell increments (Persson: `S(a_r)` of eq. gamma at the original
/// theory's area at the window's last step).
fn declare_load(t: &mut Table<'_>, scene: &EnergyScene, a: f64) {
    let full = move |s: &EnergyStats| AtFullResolution::of(&s.load(a), s.end());
    t.row_labelled(original_key(a), move |s| {
        let full = full(s);
        let name = format!(
            "E_exa / E_P (S = 1) at full resolution, a_r = {a} ({:.4} measured)",
            full.area.value
        );
        Some((name, full.original))
    })
    .persson(1.0);
    t.row_labelled(corrected_key(a), move |s| {
        let full = full(s);
        let name = format!(
            "E_exa / E_c (S of eq. gamma) at full resolution, a_r = {a} ({:.4} measured)",
            full.area.value
        );
        Some((name, full.corrected))
    })
    .persson(1.0);
    t.row_labelled(corrected_start_key(a), move |s| {
        let load = s.load(a);
        let name = format!(
            "E_exa / E_c at the lowest magnification, zeta = {:.3}, a_r = {a} at full \
             resolution (p~0 = p0 / E* g_bar = {:.4}, g_bar at full resolution)",
            s.zetas[0],
            p_tilde(&load)
        );
        Some((name, ratio(&load, 0, Theory::Corrected)))
    })
    .persson(1.0);
    let correction = scene.correction;
    for w in 0..scene.increments_at.len() {
        t.row_labelled(s_tilde_key(a, w), move |s| {
            let window = s.windows.get(w)?;
            let last = *window.last().expect("non-empty window");
            let name = format!(
                "S~ over {} single-shell increments from zeta = {:.3} to {:.3}, \
                 a_r = {a} at full resolution (Persson: S(a_r) of eq. gamma)",
                window.len() - 1,
                s.zetas[window[0]],
                s.zetas[last],
            );
            Some((name, s.load(a).mean(|r| r.window_mean(&r.windows[w]))))
        })
        .persson_from(move |s| {
            let last = *s.windows.get(w)?.last()?;
            Some(correction.factor(original_area(&s.load(a), last).value))
        });
    }
}

/// `p~0 = p0 / E* g_bar` of a load, averaged over its realizations.
fn p_tilde(load: &Load) -> f64 {
    load.mean(|r| r.p0).value
}

/// Of the loads `contact_areas`, the one whose `p~0` is nearest 0.1 (the first of equals).
fn near_p01<'a>(s: &'a EnergyStats, contact_areas: &[f64]) -> Option<Load<'a>> {
    s.loads(contact_areas).into_iter().min_by(|a, b| {
        (p_tilde(a) - 0.1)
            .abs()
            .total_cmp(&(p_tilde(b) - 0.1).abs())
    })
}

/// Declares `E_exa / E_c` at the lowest magnifications (Persson: 1): at each load, at the
/// steps nearest the first octaves; and at the load whose `p~0` is nearest 0.1 (the
/// caption of fig. E_vs_zeta), at the first step and those octaves.
fn declare_low_magnification<'s>(t: &mut Table<'s>, contact_areas: &'s [f64]) {
    for &a in contact_areas {
        for z in NEAR_P01_ZETAS {
            t.row_labelled(corrected_at_key(a, z), move |s| {
                let k = nearest_step(&s.zetas, z)?;
                let name = format!(
                    "E_exa / E_c at zeta = {:.3}, a_r = {a} at full resolution",
                    s.zetas[k]
                );
                Some((name, ratio(&s.load(a), k, Theory::Corrected)))
            })
            .persson(1.0);
        }
    }
    // The caption of fig. E_vs_zeta speaks of p~0 = 0.1: the load nearest to it, on any
    // scene (the key does not depend on the scene's loads).
    t.row_labelled(NEAR_P01_START, move |s| {
        let near = near_p01(s, contact_areas)?;
        let name = format!(
            "E_exa / E_c at the lowest magnification, zeta = {:.3}, at the load whose \
             p~0 at full resolution is nearest 0.1 (a_r = {}, p~0 = {:.4})",
            s.zetas[0],
            near.contact_area,
            p_tilde(&near)
        );
        Some((name, ratio(&near, 0, Theory::Corrected)))
    })
    .persson(1.0);
    // "Low magnification" read over the first octaves too: the step nearest zeta = 2
    // and 4.
    for z in NEAR_P01_ZETAS {
        t.row_labelled(near_p01_key(z), move |s| {
            let near = near_p01(s, contact_areas)?;
            let k = nearest_step(&s.zetas, z)?;
            let name = format!(
                "E_exa / E_c at zeta = {:.3}, at the load whose p~0 at full resolution \
                 is nearest 0.1 (a_r = {})",
                s.zetas[k], near.contact_area
            );
            Some((name, ratio(&near, k, Theory::Corrected)))
        })
        .persson(1.0);
    }
}

/// Declares the corrected theory at the headline load `headline`: the drift of `E_exa /
/// E_c` over the magnifications, how much closer it is than Persson's original, how its
/// deviation grows at the lowest load, its overestimate and the measurement's shortfall.
fn declare_headline(t: &mut Table<'_>, headline: f64) {
    t.row_labelled(CORRECTED_HEADLINE_DRIFT, |s| {
        let name = format!(
            "change of E_exa / E_c at the headline load from zeta = {:.3} to {:.3}",
            s.zetas[s.headline.quarter],
            s.zetas[s.end()]
        );
        Some((name, s.headline.drift))
    })
    .persson(0.0);
    t.row_labelled(IMPROVEMENT_HEADLINE, |s| {
        let name = format!(
            "|E_exa / E_P - 1| - |E_exa / E_c - 1| at the headline load (a_r = {:.3}): how \
             much closer the corrected theory is",
            s.headline.head.area.value
        );
        Some((name, s.headline.improvement()))
    });
    t.row_labelled(DEVIATION_GROWTH_LOW_LOAD, |s| {
        let name = format!(
            "|E_exa / E_c - 1| at the lowest load (a_r = {:.4}) less that at the headline \
             load",
            s.headline.low.area.value
        );
        Some((name, s.headline.growth()))
    });
    t.row_labelled(OVERESTIMATE_HEADLINE, move |s| {
        let name = format!(
            "E_c / E_exa - 1 at full resolution at the headline load (a_r = {:.3}): the \
             corrected theory's overestimate of the total energy",
            s.headline.head.area.value
        );
        Some((name, overestimate(&s.load(headline), s.end())))
    })
    .persson(0.0);
    t.row_labelled(SHORTFALL_HEADLINE, |s| {
        let head = &s.headline.head;
        let name = format!(
            "1 - E_exa / E_c at full resolution at the headline load (a_r = {:.3}): the \
             measurement's shortfall against the corrected theory",
            head.area.value
        );
        let shortfall = Estimate::new(1.0 - head.corrected.value, head.corrected.std_error);
        Some((name, shortfall))
    })
    .persson(0.0);
}

/// Declares, over the loads: the corrected theory's worst deviation at the high loads (at
/// full resolution), the noise of the measured energy's increments against the theory's
/// at the headline load, and the measured contact area against the corrected theory's.
fn declare_across_loads<'s>(t: &mut Table<'s>, scene: &'s EnergyScene) {
    let (areas, headline) = (&scene.contact_areas, scene.headline_contact_area);
    t.row(
        CORRECTED_WORST_HIGH,
        format!(
            "E_exa / E_c - 1 at full resolution of largest magnitude over the loads \
             with a_r >= {HIGH_LOADS_FROM}"
        ),
        move |s| corrected_worst(&s.loads(areas), s.end()),
    )
    .persson(0.0);
    t.row_labelled(NUMERATOR_CV_LOG_RATIO, move |s| {
        let name = format!(
            "ln of CV(increments of E_exa) / CV(increments of E_P) over each window's \
             single-shell steps, mean over windows and realizations at the headline load \
             (a_r = {:.3})",
            s.headline.head.area.value
        );
        Some((name, numerator_cv_log_ratio(&s.load(headline))))
    });
    t.row(
        AREA_CORRECTED_DEVIATION,
        "|measured a_r / corrected theory's a_r - 1| at full resolution, largest over \
         the loads",
        move |s| area_corrected_deviation(&s.loads(areas), s.end()),
    )
    .persson(0.0);
}
