//! One history of the headline scene (paper section 3.3): the sweep of every shell from
//! the flat interface to `zeta_max` at fixed load, and the counts it ends with. The
//! re-entry share of the final contact is `reentered / contact_points` (the convention of
//! [`crate::conventions`], section 6); the flux is taken over the scene's flux interval.

use serde::{Deserialize, Serialize};

use super::stats::ratio;
use super::ReentryScene;
use crate::engine::sweep::shell_steps;
use crate::error::{Error, Result};
use crate::experiments::climb::climb_job;
use crate::experiments::contact_change::{net_over_gross, pack_categories};
use crate::experiments::ensemble::SeedLoad;
use crate::experiments::history::History;
use crate::experiments::JobContext;

/// What one history sweep measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReentryResult {
    /// Load.
    pub p0: f64,
    /// Contact area at `zeta_max` from the sweep.
    pub a_r: f64,
    /// Points in contact at `zeta_max`.
    pub contact_points: u64,
    /// Of those, points that were out of contact at some step (first shell included).
    pub reentered: u64,
    /// Of those, points that left contact after the first shell and came back.
    pub reentered_after_first: u64,
    /// Fraction of the nominal area entering contact over the flux interval.
    pub flux_in: f64,
    /// Fraction of the nominal area leaving contact over the flux interval.
    pub flux_out: f64,
    /// Share of the non-contact at `flux_zeta` in contact at `flux_zeta + flux_dzeta`.
    // Serialised as "zero_bin_reentry": the stored name is kept for the committed results.
    #[serde(rename = "zero_bin_reentry")]
    pub flux_in_of_noncontact: f64,
    /// Shells added.
    pub shells: usize,
    /// Solver iterations over the sweep.
    pub iterations: u64,
    /// Wall time of the sweep (seconds, resumed runs included).
    pub wall_s: f64,
    /// Largest residual.
    pub max_residual: f64,
    /// Map categories at `zeta_max` (2 bits a point, hex), for the first seed only.
    pub map: Option<String>,
    /// Flux categories over the flux interval (2 bits a point, hex), first seed only.
    pub flux_map: Option<String>,
}

impl ReentryResult {
    /// The re-entry share: points in contact at `zeta_max` that were ever out, over the
    /// points in contact.
    pub fn share(&self) -> f64 {
        ratio(self.reentered, self.contact_points)
    }

    /// The share that left contact after the first shell and came back.
    pub fn share_after_first(&self) -> f64 {
        ratio(self.reentered_after_first, self.contact_points)
    }

    /// The share of the final contact that was out of contact at the first shell
    /// (`zeta = 1`) and in contact at every later one: `(reentered -
    /// reentered_after_first) / contact_points`, a lower bound on the final contact's share
    /// out of contact at `zeta = 1`.
    pub fn share_out_at_first(&self) -> f64 {
        ratio(
            self.reentered.saturating_sub(self.reentered_after_first),
            self.contact_points,
        )
    }

    /// The net flux over the mean one-way flux, `|out - in| / ((out + in) / 2)`.
    pub fn net_over_gross(&self) -> f64 {
        net_over_gross(self.flux_in, self.flux_out)
    }
}

/// Runs (or resumes) one history sweep.
pub(super) fn run_history(
    scene: &ReentryScene,
    job: &SeedLoad,
    ctx: &JobContext,
    keep_maps: bool,
) -> Result<ReentryResult> {
    let base = scene.base();
    let r = base.realization(job.seed)?;
    let zeta_max = r.surface.zeta_max();
    let steps = shell_steps(&r.surface, 0.0, zeta_max);
    let interval = (scene.flux_zeta, scene.flux_zeta + scene.flux_dzeta);
    let mut history = History::new(r.model.grid.points(), interval);
    let climbed = climb_job(
        &base,
        ctx,
        &r,
        job.contact_area,
        &steps,
        &mut history,
        scene.checkpoint_seconds,
    )?;
    history.close_flux();
    let flux = history.flux.as_ref().ok_or_else(|| {
        Error::invalid(
            "flux_zeta",
            scene.flux_zeta,
            format!("below zeta_max = {zeta_max}"),
        )
    })?;
    let (contact_points, reentered, reentered_after_first) = history.counts();
    // The climb ends in contact at every point that is in contact now.
    let a_r = contact_points as f64 / history.in_contact.len() as f64;
    // The checkpoints stay until the runner has stored the result (it then removes them):
    // a run killed in between still resumes from the last one.
    Ok(ReentryResult {
        p0: climbed.p0,
        a_r,
        contact_points,
        reentered,
        reentered_after_first,
        flux_in: flux.into,
        flux_out: flux.out_of,
        flux_in_of_noncontact: flux.into_of_noncontact,
        shells: steps.len(),
        iterations: climbed.iterations,
        wall_s: climbed.wall_s,
        max_residual: climbed.max_residual,
        map: keep_maps.then(|| pack_categories(&history.categories())),
        flux_map: keep_maps.then(|| pack_categories(&flux.map)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_at_first_is_the_reentered_that_never_left_after_the_first_shell() {
        let r = ReentryResult {
            p0: 0.1,
            a_r: 0.14,
            contact_points: 1000,
            reentered: 640,
            reentered_after_first: 615,
            flux_in: 0.0,
            flux_out: 0.0,
            flux_in_of_noncontact: 0.0,
            shells: 4355,
            iterations: 0,
            wall_s: 0.0,
            max_residual: 0.0,
            map: None,
            flux_map: None,
        };
        assert!((r.share_out_at_first() - 0.025).abs() < 1e-15);
        assert!((r.share() - r.share_after_first() - r.share_out_at_first()).abs() < 1e-15);
    }
}
