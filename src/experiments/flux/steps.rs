//! The headline from the steps of every realization: statistics (means over
//! realizations), then findings (details, the check, golden values), then the account and
//! the map of the first realization.

use std::collections::BTreeMap;

use super::{FluxResult, FluxScene};
use crate::experiments::reentry::history::unpack_categories;
use crate::experiments::reentry::{net_over_gross, step_palette};
use crate::experiments::{Check, Criteria, Detail};
use crate::plot::Raster;
use crate::stats::{decide, round_sig, Claim, Estimate};

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
            a_before: over(|r| r.a_r_old),
            a_after: over(|r| r.a_r_new),
        }
    }
}

/// The paper's finding: points enter contact in the step.
pub fn check(criteria: &Criteria, s: &StepStats) -> Check {
    Check::new(
        "points_enter_contact",
        format!(
            "points enter contact in the step (flux in more than {} standard errors above 0)",
            criteria.significance
        ),
        decide(s.flux_in, Claim::Above(0.0), criteria.significance),
        format!("flux in = {}", s.flux_in.text(1.0, 5, "")),
    )
}

/// The fluxes, the net flux, and the contact area before and after.
pub fn details(s: &StepStats) -> Vec<Detail> {
    vec![
        Detail::new(
            "flux_in",
            "fraction of the nominal area entering contact",
            s.flux_in,
        ),
        Detail::new(
            "flux_out",
            "fraction of the nominal area leaving contact",
            s.flux_out,
        ),
        Detail::new(
            "net_over_gross",
            "net flux over the mean one-way flux, |out - in| / ((out + in) / 2)",
            s.net,
        ),
        Detail::new("contact_area_before", "a_r at zeta", s.a_before),
        Detail::new("contact_area_after", "a_r at zeta + dzeta", s.a_after),
    ]
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

/// The account, from the numbers.
pub fn account(scene: &FluxScene, s: &StepStats) -> String {
    format!(
        "{}, at the load that gives a_r = {:.3} at zeta = {}, the step to zeta = {} moves \
         {:.3}% of the nominal area into contact and {:.3}% out of it: {} points enter per \
         point that leaves, where Persson's absorbing boundary allows none. The net flux is \
         {} of the mean one-way flux; a_r goes from {:.4} to {:.4}.",
        scene.base().over(),
        s.a_before.value,
        scene.zeta,
        scene.zeta + scene.dzeta,
        100.0 * s.flux_in.value,
        100.0 * s.flux_out.value,
        s.ratio.text(1.0, 3, ""),
        s.net.text(1.0, 3, ""),
        s.a_before.value,
        s.a_after.value,
    )
}

/// The map of the first realization's step, coloured as the paper's figure.
pub fn flux_map(scene: &FluxScene, results: &[(u64, FluxResult)]) -> Option<Raster> {
    let (seed, r) = results.iter().find(|(_, r)| r.map.is_some())?;
    Some(Raster {
        name: "flux_map".into(),
        title: format!(
            "Contact changes from zeta = {} to {} (seed {seed}, a_r = {:.3})",
            scene.zeta,
            scene.zeta + scene.dzeta,
            r.a_r_old
        ),
        n: scene.n,
        pixels: unpack_categories(r.map.as_deref().unwrap_or(""), scene.n * scene.n),
        palette: step_palette(),
    })
}
