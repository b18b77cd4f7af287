//! The findings of the total-energy experiment as data (details, checks, golden values),
//! and its account, from the statistics of [`super::stats`].

use std::collections::BTreeMap;

use super::stats::{original_area, ratio, window_mean, AtFullResolution, Headline, Load, Theory};
use super::{EnergyScene, FAILS_BELOW};
use crate::experiments::{Check, Criteria, Detail};
use crate::stats::{decide, realizations, round_sig, Claim};

/// The details of every load, then the headline's drift with magnification.
pub fn details(
    scene: &EnergyScene,
    loads: &[Load],
    zetas: &[f64],
    windows: &[Vec<usize>],
    h: &Headline,
) -> Vec<Detail> {
    let end = zetas.len() - 1;
    let mut details: Vec<Detail> = loads
        .iter()
        .flat_map(|load| load_details(scene, load, zetas, windows))
        .collect();
    details.push(
        Detail::new(
            "corrected_headline_drift",
            format!(
                "change of E_exa / E_c at the headline load from zeta = {:.3} to {:.3}",
                zetas[h.quarter], zetas[end]
            ),
            h.drift,
        )
        .persson(0.0),
    );
    details.push(Detail::new(
        "improvement_headline",
        format!(
            "|E_exa / E_P - 1| - |E_exa / E_c - 1| at the headline load (a_r = {:.3}): how much \
             closer the corrected theory is",
            h.head.area.value
        ),
        h.improvement(),
    ));
    details.push(Detail::new(
        "deviation_growth_low_load",
        format!(
            "|E_exa / E_c - 1| at the lowest load (a_r = {:.4}) less that at the headline load",
            h.low.area.value
        ),
        h.growth(),
    ));
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
            format!("original_ar{a}"),
            format!(
                "E_exa / E_P (S = 1) at full resolution, a_r = {a} ({:.4} measured)",
                full.area.value
            ),
            full.original,
        )
        .persson(1.0),
        Detail::new(
            format!("corrected_ar{a}"),
            format!(
                "E_exa / E_c (S of eq. gamma) at full resolution, a_r = {a} ({:.4} measured)",
                full.area.value
            ),
            full.corrected,
        )
        .persson(1.0),
        Detail::new(
            format!("corrected_start_ar{a}"),
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
        let s_w = load.mean(|r| window_mean(r, &r.windows[w]));
        let last = *window.last().expect("non-empty window");
        let s_p = scene.correction.factor(original_area(load, last).value);
        details.push(
            Detail::new(
                format!("s_tilde_ar{a}_window{w}"),
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

/// The paper's findings: the correction brings the energy closer to the measurement, and
/// (when the lowest load is below the contact area of the paper's claim
/// [`FAILS_BELOW`]) fails there.
pub fn checks(criteria: &Criteria, h: &Headline) -> Vec<Check> {
    let (head, low) = (&h.head, &h.low);
    let mut checks = vec![Check::new(
        "correction_brings_energy_closer",
        "the correction factor brings the total energy closer to the measurement than S = 1",
        decide(h.improvement(), Claim::Above(0.0), 0.0),
        format!(
            "E_exa / E_c = {}, E_exa / E_P = {} at a_r = {:.3}",
            head.corrected.text(1.0, 3, ""),
            head.original.text(1.0, 3, ""),
            head.area.value
        ),
    )];
    let below = criteria.paper(FAILS_BELOW);
    if let Some(below) = below.filter(|&b| low.area.value < b) {
        let growth = h.growth();
        checks.push(Check::new(
            "correction_fails_at_low_load",
            format!(
                "below a_r = {below} the corrected energy deviates from the \
                 measurement more than at the headline load (by {} combined standard errors)",
                criteria.significance
            ),
            decide(growth, Claim::Above(0.0), criteria.significance),
            format!(
                "E_exa / E_c = {} at a_r = {:.4} against {} at a_r = {:.3}: |deviation| grows \
                 by {}",
                low.corrected.text(1.0, 3, ""),
                low.area.value,
                head.corrected.text(1.0, 3, ""),
                head.area.value,
                growth.text(1.0, 3, "")
            ),
        ));
    }
    checks
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

/// The account, from the numbers.
pub fn account(scene: &EnergyScene, zetas: &[f64], h: &Headline, criteria: &Criteria) -> String {
    let (head, low) = (&h.head, &h.low);
    let below = criteria.paper(FAILS_BELOW);
    let low_text = if below.is_some_and(|b| low.area.value < b) {
        format!(
            " At the lowest load (a_r = {:.4}, {}) E_exa / E_c = {}.",
            low.area.value,
            realizations(h.low_runs),
            low.corrected.text(1.0, 3, "")
        )
    } else {
        String::new()
    };
    format!(
        "{}, at the load that gives a_r = {:.3} at full resolution (zeta = {}), the \
         measured total elastic energy is {} of the corrected theory's E_c (eq. gamma) and \
         {} of the original theory's E_P: the corrected theory's energy exceeds the \
         measurement by {:+.1}% ({}), the original theory's by {:+.0}%.{} Each theory uses \
         its own a_r(p0, zeta).",
        scene.base().over(),
        head.area.value,
        round_sig(zetas[zetas.len() - 1], 4),
        head.corrected.text(1.0, 3, ""),
        head.original.text(1.0, 3, ""),
        100.0 * (1.0 / head.corrected.value - 1.0),
        head.corrected.z_text(1.0, "Persson's 1"),
        100.0 * (1.0 / head.original.value - 1.0),
        low_text,
    )
}
