//! The statistics of the one-step flux: the headline from the steps of every realization
//! (means over realizations), then its findings (details, the guard, golden values); the
//! rows of the sensitivity study, and the waterfall's statistics.

use std::collections::BTreeMap;

use super::study::sensitivity::{SensitivityRow, StudyJob, StudyResult};
use super::study::waterfall::{WaterfallResult, WaterfallStats};
use super::{net_flow_residual, FluxJob, FluxOutput, FluxResult, FluxScene};
use crate::experiments::contact_change::net_over_gross;
use crate::experiments::declared::DetailTable;
use crate::experiments::Guard;
use crate::stats::{round_sig, Decision, Estimate};

/// The keys of the details ([`crate::experiments::Experiment::detail_table`]).
const FLUX_IN: &str = "flux_in";
const FLUX_OUT: &str = "flux_out";
const NET_OVER_GROSS: &str = "net_over_gross";
const NET_FLOW: &str = "net_flow";
const NET_FLOW_RESIDUAL: &str = "net_flow_residual";
const CONTACT_AREA_BEFORE: &str = "contact_area_before";
const CONTACT_AREA_AFTER: &str = "contact_area_after";

/// The statistics of the steps, means over realizations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepStats {
    /// Fraction of the nominal area entering contact.
    pub flux_in: Estimate,
    /// Fraction of the nominal area leaving contact.
    pub flux_out: Estimate,
    /// `flux_in / flux_out`, per realization: the headline.
    pub ratio: Estimate,
    /// The net flux over the mean one-way flux, per realization.
    pub net: Estimate,
    /// The net flow to non-contact, `flux_out - flux_in`.
    pub net_flow: Estimate,
    /// The net-flow identity's residual ([`net_flow_residual`]), per realization.
    pub net_flow_residual: Estimate,
    /// The contact area before the step.
    pub a_before: Estimate,
    /// The contact area after it.
    pub a_after: Estimate,
}

impl StepStats {
    /// The statistics of the realizations' steps.
    pub fn of(results: &[(u64, FluxResult)]) -> Self {
        let over = |f: fn(&FluxResult) -> f64| {
            Estimate::mean_of(&results.iter().map(|(_, r)| f(r)).collect::<Vec<_>>())
        };
        Self {
            flux_in: over(|r| r.flux_in),
            flux_out: over(|r| r.flux_out),
            // Per realization, so that the error bar holds the realizations' spread.
            ratio: over(|r| r.flux_in / r.flux_out.max(f64::MIN_POSITIVE)),
            net: over(|r| net_over_gross(r.flux_in, r.flux_out)),
            net_flow: over(|r| r.flux_out - r.flux_in),
            net_flow_residual: over(|r| {
                net_flow_residual(r.a_r_old, r.a_r_new, r.flux_in, r.flux_out)
            }),
            a_before: over(|r| r.a_r_old),
            a_after: over(|r| r.a_r_new),
        }
    }
}

/// The net-flow identity on a grid of `n` points a side, a guard of the counting (never
/// part of a verdict): `(out - in) + (a_r after - a_r before)` within half a point, its
/// mean and its error bar, as it must be for any two sets of points in contact.
pub fn identity_guard(n: usize, s: &StepStats) -> Guard {
    let half_point = 0.5 / (n as f64).powi(2);
    let e = s.net_flow_residual;
    let holds = e.value.abs() < half_point && (!e.has_error() || e.std_error < half_point);
    Guard::new(
        "net_flow_identity",
        "net flow to non-contact equals the fall of a_r over the step (the points in contact \
         after it are those before, plus those that entered, less those that left)",
        Decision::from_bool(holds),
        format!(
            "residual {} of A0 (half a point: {half_point:.1e})",
            e.text(1.0, 9, "")
        ),
    )
}

/// The fluxes, the net flux, the net-flow identity, and the contact area before and after.
pub fn rows(t: &mut DetailTable<'_, FluxStats>) {
    t.always(
        FLUX_IN,
        "fraction of the nominal area entering contact",
        |s: &FluxStats| s.steps.flux_in,
    );
    t.always(
        FLUX_OUT,
        "fraction of the nominal area leaving contact",
        |s: &FluxStats| s.steps.flux_out,
    );
    t.always(
        NET_OVER_GROSS,
        "net flux over the mean one-way flux, |out - in| / ((out + in) / 2)",
        |s: &FluxStats| s.steps.net,
    );
    t.always(
        NET_FLOW,
        "net flow to non-contact, flux_out - flux_in, fraction of the nominal area",
        |s: &FluxStats| s.steps.net_flow,
    );
    t.always(
        NET_FLOW_RESIDUAL,
        "net-flow identity at fixed load: (flux_out - flux_in) + (a_r after - a_r before), \
         zero up to rounding",
        |s: &FluxStats| s.steps.net_flow_residual,
    );
    t.always(CONTACT_AREA_BEFORE, "a_r at zeta", |s: &FluxStats| {
        s.steps.a_before
    });
    t.always(
        CONTACT_AREA_AFTER,
        "a_r at zeta + dzeta",
        |s: &FluxStats| s.steps.a_after,
    );
}

/// The golden values: the headline ratio and both fluxes.
pub fn golden(s: &StepStats) -> BTreeMap<String, f64> {
    [
        ("ratio", s.ratio),
        ("flux_in", s.flux_in),
        ("flux_out", s.flux_out),
    ]
    .map(|(key, e)| (key.to_string(), round_sig(e.value, 2)))
    .into()
}

/// The statistics of the one-step flux: the headline steps', and the sensitivity study's
/// rows.
#[derive(Debug, Clone)]
pub struct FluxStats {
    /// The steps of the scene's realizations.
    pub steps: StepStats,
    /// The steps' results, by seed.
    pub results: Vec<(u64, FluxResult)>,
    /// The rows of the sensitivity study (none without one).
    pub rows: Vec<SensitivityRow>,
    /// The waterfall's statistics over its realizations (none without a waterfall).
    pub waterfall: Option<WaterfallStats>,
}

impl FluxStats {
    /// The statistics of every job's output.
    pub fn of(scene: &FluxScene, outputs: &[(FluxJob, FluxOutput)]) -> Self {
        let results: Vec<(u64, FluxResult)> = outputs
            .iter()
            .filter_map(|(j, r)| match (j, r) {
                (FluxJob::Step(s), FluxOutput::Step(r)) => Some((*s, r.clone())),
                _ => None,
            })
            .collect();
        let study: Vec<(&StudyJob, &StudyResult)> = outputs
            .iter()
            .filter_map(|(j, r)| match (j, r) {
                (FluxJob::Study(j), FluxOutput::Study(r)) => Some((j, r)),
                _ => None,
            })
            .collect();
        let waterfalls: Vec<&WaterfallResult> = outputs
            .iter()
            .filter_map(|(_, r)| match r {
                FluxOutput::Waterfall(w) => Some(w),
                _ => None,
            })
            .collect();
        Self {
            steps: StepStats::of(&results),
            rows: scene.sensitivity.as_ref().map_or_else(Vec::new, |plan| {
                plan.conclude(scene.relative_step(), &study)
            }),
            results,
            waterfall: WaterfallStats::of(&waterfalls),
        }
    }
}
