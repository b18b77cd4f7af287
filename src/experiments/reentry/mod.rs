//! Re-entry into contact: assumption (c), `p = 0` absorbs ([`crate::conventions`], section 6, row c; paper
//! section 3.3).
//!
//! In Persson's diffusion picture a walker that reaches `p = 0` is lost to non-contact for
//! good. Here every distinct shell `|q|^2` of a realization is added one at a time, from the
//! flat interface (every point in contact) up to `zeta_max`, at the fixed load `p0` that
//! gives the scene's contact area at `zeta_max`; each solve is warm-started from the last.
//! For every point the sweep records how often it left contact and how often it came back.
//!
//! * **Re-entry share** (the convention of [`crate::conventions`], section 6): among the points in contact at `zeta_max`, the
//!   share that was out of contact at some earlier step, the first shell (`zeta = 1`)
//!   included. Also reported: the share that left contact *after* the first shell and came
//!   back, so both readings are visible. Persson: 0. Paper (H = 0.8, 1024^2,
//!   lambda_l = 512): ~62% at a_r = 0.14, ~100% at 0.014, ~8% at 0.88.
//! * **Flux** between `flux_zeta` and `flux_zeta + flux_dzeta`: the fractions of the nominal
//!   area that enter and leave contact, the net flux over the mean one-way flux (paper,
//!   zeta 128 -> 129.5: in 0.675%, out 0.597% of A0, net ~ 0.12 of either), and the
//!   transition probability out of the `p = 0` bin, the share of non-contact that enters
//!   contact (paper: ~1% from zeta = 63 to 63.3). Persson: no flux into contact.
//! * **Contact map** at `zeta_max` coloured as the paper's re-entry figures: grey, in
//!   contact at every step; red, in contact after having been out (re-entered); white, out
//!   of contact and never back; blue, out of contact after having come back at least once.
//!
//! The climb ([`crate::experiments::climb`]) checkpoints its state, with the history of
//! every point ([`history`]), every `checkpoint_seconds`; a run killed mid-sweep resumes
//! (`--resume`) from the last checkpoint and ends with the same numbers as an
//! uninterrupted run. A run without `--resume` starts every sweep afresh.

pub mod history;

use serde::{Deserialize, Serialize};

use self::history::{pack_categories, unpack_categories, History};
use super::climb::{climb, Checkpointing};
use super::ensemble::{by_load, check_contact_areas, seed_load_jobs, LoadGroup, SeedLoad};
use super::scene::scene;
use super::{
    max_residual, Check, Conclusion, Criteria, Detail, Experiment, JobContext, Jobs, Table, Work,
};
use crate::engine::scene::check_zeta;
use crate::engine::sweep::shell_steps;
use crate::error::{check_positive, Error, Result};
use crate::plot::Raster;
use crate::stats::{realizations, round_sig, Claim, Estimate};

/// The paper's flux into contact from zeta = 128 to 129.5 (fraction of the nominal area).
pub const PAPER_FLUX_IN: f64 = 0.00675;
/// The paper's flux out of contact over the same step.
pub const PAPER_FLUX_OUT: f64 = 0.00597;
/// The paper's net flux over the mean one-way flux.
pub const PAPER_NET_OVER_GROSS: f64 = 0.12;
/// The paper's share of non-contact that enters contact from zeta = 63 to 63.3.
pub const PAPER_ZERO_BIN: f64 = 0.01;

scene! {
    /// Scene of the re-entry experiment.
    pub struct ReentryScene {
        /// Contact areas at `zeta_max` (the first is the headline).
        pub contact_areas: Vec<f64>,
        /// The paper's re-entry share at each contact area, for comparison.
        pub paper_shares: Vec<f64>,
        /// Start of the flux interval.
        pub flux_zeta: f64,
        /// Length of the flux interval.
        pub flux_dzeta: f64,
        /// Seconds between checkpoints of a sweep.
        pub checkpoint_seconds: f64,
    }
}

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
    pub zero_bin_reentry: f64,
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
        self.reentered as f64 / self.contact_points.max(1) as f64
    }

    /// The share that left contact after the first shell and came back.
    pub fn share_after_first(&self) -> f64 {
        self.reentered_after_first as f64 / self.contact_points.max(1) as f64
    }

    /// The net flux over the mean one-way flux, `|out - in| / ((out + in) / 2)`.
    pub fn net_over_gross(&self) -> f64 {
        net_over_gross(self.flux_in, self.flux_out)
    }
}

/// `|out - in| / ((out + in) / 2)`: the net flux over the mean one-way flux (0 when
/// both are 0).
pub fn net_over_gross(flux_in: f64, flux_out: f64) -> f64 {
    (flux_out - flux_in).abs() / (0.5 * (flux_out + flux_in)).max(f64::MIN_POSITIVE)
}

/// The experiment.
pub struct Reentry;

/// Runs (or resumes) one history sweep.
fn run_history(
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
    let climbed = climb(
        &base,
        ctx.solver,
        &r,
        job.contact_area,
        &steps,
        &mut history,
        Some(Checkpointing {
            dir: &ctx.state_dir,
            seconds: scene.checkpoint_seconds,
        }),
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
        zero_bin_reentry: flux.zero_bin,
        shells: steps.len(),
        iterations: climbed.iterations,
        wall_s: climbed.wall_s,
        max_residual: climbed.max_residual,
        map: keep_maps.then(|| pack_categories(&history.categories())),
        flux_map: keep_maps.then(|| pack_categories(&flux.map)),
    })
}

impl Jobs for ReentryScene {
    const FAMILY: &'static str = "reentry";
    type Job = SeedLoad;
    type JobResult = ReentryResult;

    fn validate(&self) -> Result<()> {
        let scene = self;
        scene.base().validate()?;
        check_contact_areas(&scene.contact_areas)?;
        if scene.paper_shares.len() != scene.contact_areas.len() {
            return Err(Error::invalid(
                "paper_shares",
                format!("{} values", scene.paper_shares.len()),
                format!("one per contact area ({})", scene.contact_areas.len()),
            ));
        }
        let zeta_max = scene.base().zeta_max();
        check_zeta(scene.flux_zeta, zeta_max)?;
        check_positive("flux_dzeta", scene.flux_dzeta)?;
        if scene.flux_zeta + scene.flux_dzeta > zeta_max {
            return Err(Error::invalid(
                "flux_dzeta",
                scene.flux_dzeta,
                format!("with flux_zeta + flux_dzeta <= zeta_max = {zeta_max}"),
            ));
        }
        check_positive("checkpoint_seconds", scene.checkpoint_seconds)
    }

    fn jobs(&self) -> Vec<SeedLoad> {
        seed_load_jobs(&self.contact_areas, &self.seeds)
    }

    fn work(&self, _job: &SeedLoad) -> Work {
        // The load at full resolution, then every shell from the first.
        let base = self.base();
        Work::climb(self.n, 0, base.shells(0.0, base.zeta_max()))
    }

    fn run_job(&self, job: &SeedLoad, ctx: &JobContext) -> Result<ReentryResult> {
        let keep_maps = job.seed == self.seeds[0];
        run_history(self, job, ctx, keep_maps)
    }
}

impl Experiment for Reentry {
    type Scene = ReentryScene;

    fn conclude(
        criteria: &Criteria,
        scene: &ReentryScene,
        results: &[(SeedLoad, ReentryResult)],
    ) -> Result<Conclusion> {
        let loads = by_load(&scene.contact_areas, results);
        let mut c = Conclusion {
            persson: 0.0,
            max_residual: max_residual(results, |r| r.max_residual),
            ..Default::default()
        };
        let mut shares = Vec::new();
        for (k, load) in loads.iter().enumerate() {
            let target = load.contact_area;
            let share = load.mean(ReentryResult::share);
            let after = load.mean(ReentryResult::share_after_first);
            if k == 0 {
                c.measured = Some(share);
            }
            shares.push(share);
            c.details.push(
                Detail::new(
                    format!("share_ar{target}"),
                    format!("re-entry share at a_r = {target}"),
                    share,
                )
                .persson(0.0)
                .paper(Some(scene.paper_shares[k])),
            );
            c.details.push(
                Detail::new(
                    format!("share_after_first_ar{target}"),
                    format!("share that left after zeta = 1 and came back, a_r = {target}"),
                    after,
                )
                .persson(0.0),
            );
            c.golden
                .insert(format!("share_{target}"), round_sig(share.value, 3));
            c.golden.insert(
                format!("share_after_first_{target}"),
                round_sig(after.value, 3),
            );
        }
        // Flux statistics at the headline contact area.
        let head = &loads[0];
        let flux_in = head.mean(|r| r.flux_in);
        let flux_out = head.mean(|r| r.flux_out);
        let ratio = head.mean(ReentryResult::net_over_gross);
        let zero = head.mean(|r| r.zero_bin_reentry);
        for (key, name, e, paper) in [
            (
                "flux_in",
                format!(
                    "flux into contact, zeta {} -> {} (fraction of A0)",
                    scene.flux_zeta,
                    scene.flux_zeta + scene.flux_dzeta
                ),
                flux_in,
                PAPER_FLUX_IN,
            ),
            (
                "flux_out",
                "flux out of contact (fraction of A0)".to_string(),
                flux_out,
                PAPER_FLUX_OUT,
            ),
            (
                "net_over_gross",
                "net flux / mean one-way flux".to_string(),
                ratio,
                PAPER_NET_OVER_GROSS,
            ),
            (
                "zero_bin_reentry",
                "share of non-contact entering contact (transition out of p = 0)".to_string(),
                zero,
                PAPER_ZERO_BIN,
            ),
        ] {
            c.details
                .push(Detail::new(key, name, e).persson(0.0).paper(Some(paper)));
        }
        c.golden
            .insert("flux_in".into(), round_sig(flux_in.value, 3));
        c.golden
            .insert("flux_out".into(), round_sig(flux_out.value, 3));
        let z = criteria.significance;
        c.checks.push(Check::claim(
            "flux_in_positive",
            format!("flux into contact above zero beyond {z} standard errors"),
            flux_in,
            Claim::Above(0.0),
            z,
            format!("{} of A0", flux_in.text(1.0, 5, "")),
        ));
        // The paper's ordering: lower load, more re-entry.
        let mut order: Vec<(f64, Estimate)> = scene
            .contact_areas
            .iter()
            .copied()
            .zip(shares.iter().copied())
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        c.checks.push(Check::new(
            "share_falls_with_area",
            "re-entry share falls as the contact area grows",
            order.windows(2).all(|w| w[0].1.value >= w[1].1.value),
            order
                .iter()
                .map(|(a, s)| format!("a_r {a}: {:.3}", s.value))
                .collect::<Vec<_>>()
                .join(", "),
        ));
        c.account = account(scene, results, &shares, flux_in, flux_out);
        c.rasters = maps(scene, head);
        c.tables.push(table(&criteria.name, scene, results));
        Ok(c)
    }
}

/// The account of the conclusion, from its numbers.
fn account(
    scene: &ReentryScene,
    results: &[(SeedLoad, ReentryResult)],
    shares: &[Estimate],
    flux_in: Estimate,
    flux_out: Estimate,
) -> String {
    let shells = results.first().map_or(0, |r| r.1.shells);
    let head = scene.contact_areas[0];
    format!(
        "{} ({}x{}, H = {}, lambda_l = {}, lambda_s = {}) were swept through all \
         {} shells one at a time at fixed load, from the flat interface to zeta_max = {}. \
         Of the points in contact at zeta_max, {} had been out of contact at a lower \
         magnification (paper: {}). Between zeta = {} and {}, {:.3}% of the nominal area \
         entered contact and {:.3}% left it, at a_r = {head}. A sweep took {} solver \
         iterations on average.",
        realizations(scene.seeds.len()),
        scene.n,
        scene.n,
        scene.hurst,
        scene.lambda_l,
        scene.lambda_s,
        shells,
        scene.lambda_l / scene.lambda_s,
        scene
            .contact_areas
            .iter()
            .zip(shares)
            .map(|(a, s)| format!("{} at a_r = {a}", s.text(100.0, 1, "%")))
            .collect::<Vec<_>>()
            .join(", "),
        scene
            .contact_areas
            .iter()
            .zip(&scene.paper_shares)
            .map(|(a, s)| format!("{:.0}% at {a}", 100.0 * s))
            .collect::<Vec<_>>()
            .join(", "),
        scene.flux_zeta,
        scene.flux_zeta + scene.flux_dzeta,
        100.0 * flux_in.value,
        100.0 * flux_out.value,
        results.iter().map(|r| r.1.iterations).sum::<u64>() / results.len().max(1) as u64,
    )
}

/// One row per history.
fn table(name: &str, scene: &ReentryScene, results: &[(SeedLoad, ReentryResult)]) -> Table {
    let mut table = Table::new(
        name,
        &[
            "contact_area_target",
            "seed",
            "a_r",
            "share",
            "share_after_first",
            "flux_in",
            "flux_out",
            "zero_bin_reentry",
            "shells",
            "iterations",
            "wall_s",
        ],
    );
    for &target in &scene.contact_areas {
        for (j, r) in results.iter().filter(|(j, _)| j.contact_area == target) {
            table.push(vec![
                target,
                j.seed as f64,
                r.a_r,
                r.share(),
                r.share_after_first(),
                r.flux_in,
                r.flux_out,
                r.zero_bin_reentry,
                r.shells as f64,
                r.iterations as f64,
                r.wall_s,
            ]);
        }
    }
    table
}

/// The contact map at `zeta_max` and the map of the flux interval, coloured as the
/// paper's figures, for the first seed at the headline load.
fn maps(scene: &ReentryScene, head: &LoadGroup<ReentryResult>) -> Vec<Raster> {
    let Some(r) = head.runs.iter().find(|r| r.map.is_some()) else {
        return Vec::new();
    };
    let n2 = scene.n * scene.n;
    let seed = scene.seeds[0];
    vec![
        Raster {
            name: "reentry_map".into(),
            title: format!(
                "Contact at zeta_max, a_r = {:.3} (seed {seed}): history of every point",
                r.a_r
            ),
            n: scene.n,
            pixels: unpack_categories(r.map.as_deref().unwrap_or(""), n2),
            palette: vec![
                ([150, 150, 150], "in contact throughout".into()),
                ([220, 40, 40], "in contact, re-entered".into()),
                ([255, 255, 255], "out of contact, never back".into()),
                ([40, 80, 220], "out of contact after re-entering".into()),
            ],
        },
        Raster {
            name: "flux_map".into(),
            title: format!(
                "Changes between zeta = {} and {} (seed {seed})",
                scene.flux_zeta,
                scene.flux_zeta + scene.flux_dzeta,
            ),
            n: scene.n,
            pixels: unpack_categories(r.flux_map.as_deref().unwrap_or(""), n2),
            palette: vec![
                ([150, 150, 150], "in contact at both".into()),
                ([220, 40, 40], "entered contact".into()),
                ([255, 255, 255], "out of contact at both".into()),
                ([40, 80, 220], "left contact".into()),
            ],
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn net_over_gross_is_the_net_flux_over_the_mean_one_way_flux() {
        assert!((net_over_gross(0.00675, 0.00597) - 0.12264).abs() < 1e-5);
        assert_eq!(net_over_gross(0.0, 0.0), 0.0);
    }

    #[test]
    fn shipped_scenes_are_valid() {
        let (reduced, full, _) = crate::experiments::shipped_scenes::<ReentryScene>("c_reentry");
        reduced.validate().unwrap();
        full.validate().unwrap();
        let mut bad = reduced.clone();
        bad.flux_dzeta = 100.0;
        let e = bad.validate().unwrap_err().to_string();
        assert!(e.contains("flux_dzeta"), "{e}");
    }
}
