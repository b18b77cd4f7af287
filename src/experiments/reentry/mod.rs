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
//!   back, so both readings are visible. Persson: 0. The paper's shares (H = 0.8, 1024^2,
//!   lambda_l = 512) are claims of the definition (`validations/c_reentry.toml`). Their
//!   difference, the share out of contact at the first shell only, bounds from below the
//!   final contact's share out of contact at `zeta = 1` (paper: none, tex 748-749).
//! * **Shells**: the distinct `|q|^2` a history adds one at a time (paper: "~4,400 wave
//!   numbers", tex 764-769).
//! * **Flux** between `flux_zeta` and `flux_zeta + flux_dzeta`: the fractions of the nominal
//!   area that enter and leave contact, the net flux over the mean one-way flux, and the
//!   transition probability out of the `p = 0` bin, the share of non-contact that enters
//!   contact. Persson: no flux into contact.
//! * **Contact map** at `zeta_max` coloured as the paper's re-entry figures: grey, in
//!   contact at every step; red, in contact after having been out (re-entered); white, out
//!   of contact and never back; blue, out of contact after having come back at least once.
//!
//! The climb ([`crate::experiments::climb`]) checkpoints its state, with the history of
//! every point ([`crate::experiments::history`]), every `checkpoint_seconds`; a run killed
//! mid-sweep resumes (`--resume`) from the last checkpoint and ends with the same numbers
//! as an uninterrupted run. A run without `--resume` starts every sweep afresh.
//!
//! # Files
//!
//! * `mod.rs`: the scene, its jobs and the [`Experiment`] implementation;
//! * `history_job.rs`: one history of the headline (the sweep and the counts it ends
//!   with); the contact history of every point of a climb is
//!   [`crate::experiments::history`];
//! * `stats.rs`: the re-entry shares and the flux, means over realizations;
//! * `figures.rs`: the table and the contact maps;
//! * `tolerance.rs`: the speed-against-error study of a history (the same climbs at
//!   several solver tolerances), run where the scene states a plan, and its table;
//! * `range.rs`: the share against the range of magnification (the headline against the
//!   tolerance study's smaller range);
//! * `variants/`: histories of scenes beside the headline's (another Hurst exponent,
//!   `eps_c`, range of magnification or `lambda_l / L`), for the paper's statements that
//!   compare scenes: `mod.rs` their scenes, jobs and runs, `findings.rs` their statistics,
//!   study, maps and details;
//! * `shells.rs`: what a variant's history does shell by shell (entries and departures
//!   per added shell, how soon a re-entered point leaves again), where the variant asks.

mod figures;
mod history_job;
pub mod range;
pub mod shells;
pub mod stats;
pub mod tolerance;
pub mod variants;

use crate::experiments::keys::{DetailKey, Tag};
use std::collections::{BTreeMap, BTreeSet};

use serde::{Deserialize, Serialize};

use self::figures::{maps, table};
use self::history_job::run_history;
pub use self::history_job::ReentryResult;
use self::range::{range_gains, RangeGain};
use self::stats::ReentryStats;
use self::tolerance::{ToleranceJob, TolerancePlan, ToleranceResult};
use self::variants::{Variant, VariantJob, VariantResult, VariantStats};
use super::declared::DetailTable;
use super::ensemble::{by_load, check_contact_areas, seed_load_jobs, SeedLoad};
use super::scene::{scene, PLANNED};
use super::study::Study;
use super::{Criteria, Experiment, JobContext, Jobs, Keys, Table, Work};
use crate::engine::scene::check_zeta;
use crate::error::{check_positive, Error, Result};
use crate::plot::Raster;
use crate::stats::{round_sig, Estimate};

scene! {
    /// Scene of the re-entry experiment.
    pub struct ReentryScene {
        /// Contact areas at `zeta_max` (the first is the headline).
        pub contact_areas: Vec<f64>,
        /// Start of the flux interval.
        pub flux_zeta: f64,
        /// Length of the flux interval.
        pub flux_dzeta: f64,
        /// Seconds between checkpoints of a sweep.
        pub checkpoint_seconds: f64,
        /// The speed-against-error study (none: not run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub tolerance: Option<TolerancePlan>,
        /// Scenes beside the headline's, each with its own histories (none: not run).
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        pub variants: Vec<Variant>,
    }
}

/// A job: one history of the headline (stored as the bare seed and load, as before the
/// study existed), or one history of the tolerance study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ReentryJob {
    /// A history of the tolerance study.
    Tolerance(ToleranceJob),
    /// A history of a variant scene.
    Variant(VariantJob),
    /// A history of the headline.
    #[serde(untagged)]
    History(SeedLoad),
}

/// What a job measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ReentryOutput {
    /// A history of the tolerance study.
    Tolerance(ToleranceResult),
    /// A history of a variant scene.
    Variant(VariantResult),
    /// A history of the headline.
    #[serde(untagged)]
    History(ReentryResult),
}

/// The experiment.
pub struct Reentry;

impl Jobs for ReentryScene {
    const FAMILY: &'static str = "reentry";
    type Job = ReentryJob;
    type JobResult = ReentryOutput;

    fn validate(&self) -> Result<()> {
        self.base().validate()?;
        check_contact_areas(&self.contact_areas)?;
        let zeta_max = self.base().zeta_max();
        check_zeta(self.flux_zeta, zeta_max)?;
        check_positive("flux_dzeta", self.flux_dzeta)?;
        if self.flux_zeta + self.flux_dzeta > zeta_max {
            return Err(Error::invalid(
                "flux_dzeta",
                self.flux_dzeta,
                format!("with flux_zeta + flux_dzeta <= zeta_max = {zeta_max}"),
            ));
        }
        check_positive("checkpoint_seconds", self.checkpoint_seconds)?;
        if let Some(plan) = &self.tolerance {
            plan.validate(self.hurst)?;
        }
        variants::validate_all(&self.variants)?;
        Ok(())
    }

    /// The headline's histories, then the study's that the headline does not hold.
    fn jobs(&self) -> Vec<ReentryJob> {
        let mut jobs: Vec<ReentryJob> = seed_load_jobs(&self.contact_areas, &self.all_seeds())
            .into_iter()
            .map(ReentryJob::History)
            .collect();
        if let Some(plan) = &self.tolerance {
            jobs.extend(
                plan.jobs()
                    .into_iter()
                    .filter(|j| self.headline_job(j).is_none())
                    .map(ReentryJob::Tolerance),
            );
        }
        for v in &self.variants {
            jobs.extend(v.jobs().into_iter().map(ReentryJob::Variant));
        }
        jobs
    }

    fn headline_only(job: &ReentryJob) -> bool {
        matches!(job, ReentryJob::Tolerance(_) | ReentryJob::Variant(_))
    }

    /// The headline's histories depend on the scene without the study and the variants:
    /// their keys are those of the scenes that had neither.
    fn key_scene(&self) -> serde_json::Value {
        let mut scene = self.clone();
        scene.tolerance = None;
        scene.variants.clear();
        serde_json::to_value(scene).expect("scenes serialise")
    }

    /// A variant is an optional part, named by its name: its histories are scenes of
    /// their own, outside the headline's keys. The histories of a variant's planned
    /// realizations (its `more_seeds`) are a part of their own, `<name>.planned`, so that
    /// the variant's stored histories conclude while they run; the headline's planned
    /// histories are the part `planned`.
    fn part(&self, job: &ReentryJob) -> Option<String> {
        let j = match job {
            ReentryJob::History(h) if self.more_seeds.contains(&h.seed) => {
                return Some(PLANNED.into())
            }
            ReentryJob::Variant(j) => j,
            _ => return None,
        };
        let v = self.variants.iter().find(|v| v.jobs().contains(j))?;
        Some(if v.more_seeds.contains(&j.seed) {
            format!("{}.{PLANNED}", v.name)
        } else {
            v.name.clone()
        })
    }

    fn leave_out(&mut self, parts: &BTreeSet<String>) {
        self.variants.retain(|v| !parts.contains(&v.name));
        if parts.contains(PLANNED) {
            self.more_seeds.clear();
        }
        for v in &mut self.variants {
            if parts.contains(&format!("{}.{PLANNED}", v.name)) {
                v.more_seeds.clear();
            }
        }
    }

    fn work(&self, job: &ReentryJob) -> Work {
        match job {
            // The load at full resolution, then every shell from the first.
            ReentryJob::History(_) => {
                let base = self.base();
                Work::search_then(self.n, 0, base.shells(0.0, base.zeta_max()))
            }
            ReentryJob::Tolerance(j) => tolerance::work(j, self.hurst),
            ReentryJob::Variant(j) => variants::work(j),
        }
    }

    fn run_job(&self, job: &ReentryJob, ctx: &JobContext) -> Result<ReentryOutput> {
        match job {
            ReentryJob::History(j) => {
                let keep_maps = j.seed == self.seeds[0];
                run_history(self, j, ctx, keep_maps).map(ReentryOutput::History)
            }
            ReentryJob::Tolerance(j) => tolerance::run(j, self.hurst, ctx, self.checkpoint_seconds)
                .map(ReentryOutput::Tolerance),
            ReentryJob::Variant(j) => {
                // The map of the first history of each variant (first load, first seed).
                // A variant that records its shells repeats a scene whose map is shown.
                let keep_map = self
                    .variants
                    .iter()
                    .any(|v| !v.record_shells && v.job(v.seeds[0], v.contact_areas[0]) == *j);
                variants::run(j, ctx, self.checkpoint_seconds, keep_map).map(ReentryOutput::Variant)
            }
        }
    }

    fn residual(result: &ReentryOutput) -> f64 {
        match result {
            ReentryOutput::History(r) => r.max_residual,
            ReentryOutput::Tolerance(r) => r.max_residual,
            ReentryOutput::Variant(r) => r.max_residual,
        }
    }
}

impl ReentryScene {
    /// The headline's history that a study job repeats, if any: the same grid, tolerance,
    /// seed and load.
    fn headline_job(&self, j: &ToleranceJob) -> Option<SeedLoad> {
        let same = (j.n, j.lambda_l, j.lambda_s, j.tol)
            == (self.n, self.lambda_l, self.lambda_s, self.tol)
            && self.seeds.contains(&j.seed)
            && self.contact_areas.contains(&j.contact_area);
        same.then_some(SeedLoad {
            seed: j.seed,
            contact_area: j.contact_area,
        })
    }

    /// The headline's histories among the results.
    fn histories(results: &[(ReentryJob, ReentryOutput)]) -> Vec<(SeedLoad, ReentryResult)> {
        results
            .iter()
            .filter_map(|(j, r)| match (j, r) {
                (ReentryJob::History(j), ReentryOutput::History(r)) => Some((j.clone(), r.clone())),
                _ => None,
            })
            .collect()
    }
}

type Run<'a> = super::Run<'a, Reentry>;

/// The key of the share out of contact at the first shell only, at load `a_r`.
pub fn out_at_first_key(contact_area: f64) -> DetailKey {
    DetailKey::new("out_at_first").at(Tag::ContactArea, contact_area)
}

/// The key of the re-entry share at load `contact_area`.
fn share_key(contact_area: f64) -> DetailKey {
    DetailKey::new("share").at(Tag::ContactArea, contact_area)
}

/// The key of the share that left after `zeta = 1` and came back, at load `contact_area`.
fn after_first_key(contact_area: f64) -> DetailKey {
    DetailKey::new("share_after_first").at(Tag::ContactArea, contact_area)
}

/// The keys of the details of one history ([`Experiment::detail_table`]): its shells, and
/// the flux of the interval at the headline load.
const SHELLS: &str = "shells";
const FLUX_IN: &str = "flux_in";
const FLUX_OUT: &str = "flux_out";
const NET_OVER_GROSS: &str = "net_over_gross";
// The detail of `flux_in_of_noncontact`: the stored key is kept for the committed results.
const ZERO_BIN_REENTRY: &str = "zero_bin_reentry";

/// Declares the shares at load `a` (Persson: 0): the re-entry share, the share that left
/// after `zeta = 1` and came back, and the share out of contact at the first shell only.
fn declare_shares(t: &mut DetailTable<'_, RunStats>, a: f64) {
    let share = move |s: &RunStats| s.shares.iter().find(|h| h.load == a).copied();
    t.row(
        share_key(a),
        format!("re-entry share at a_r = {a}"),
        move |s| share(s).map(|h| h.share),
    )
    .persson(0.0);
    t.row(
        after_first_key(a),
        format!("share that left after zeta = 1 and came back, a_r = {a}"),
        move |s| share(s).map(|h| h.after_first),
    )
    .persson(0.0);
    t.row(
        out_at_first_key(a),
        format!(
            "share of the contact at a_r = {a} out of contact at zeta = 1 only (in contact at \
             every later shell)"
        ),
        move |s| share(s).map(|h| h.out_at_first),
    )
    .persson(0.0);
}

/// The statistics of a run, with the headline's histories they came from and the
/// tolerance study (where the scene plans one).
pub struct RunStats {
    /// The shares and the flux.
    pub stats: ReentryStats,
    /// The headline's histories, in job order.
    pub histories: Vec<(SeedLoad, ReentryResult)>,
    /// The tolerance study.
    pub tolerance: Option<Study>,
    /// The variant scenes, each with the statistics of its loads.
    pub variants: Vec<VariantStats>,
    /// The re-entry share at `zeta_max` minus the share over a smaller range of
    /// magnification at the same `eps_c` (a grid of the tolerance study at the headline's
    /// tolerance), per headline load.
    pub range_gain: Vec<RangeGain>,
}

impl std::ops::Deref for RunStats {
    type Target = ReentryStats;
    fn deref(&self) -> &ReentryStats {
        &self.stats
    }
}

impl Experiment for Reentry {
    type Scene = ReentryScene;
    type Stats = RunStats;

    fn stats(run: &Run) -> Result<RunStats> {
        let histories = ReentryScene::histories(run.results);
        let stats = ReentryStats::of(&by_load(&run.scene.contact_areas, &histories));
        let tolerance =
            run.scene.tolerance.as_ref().map(|plan| {
                tolerance::of_results(run.scene, plan, run.results, &histories, &stats)
            });
        Ok(RunStats {
            range_gain: range_gains(run.scene, run.results, &stats),
            variants: variants::stats(
                &run.scene.variants,
                &run.results
                    .iter()
                    .filter_map(|(j, r)| match (j, r) {
                        (ReentryJob::Variant(j), ReentryOutput::Variant(r)) => {
                            Some((j.clone(), r.clone()))
                        }
                        _ => None,
                    })
                    .collect::<Vec<_>>(),
                &|v| range::same_cutoffs(run.scene, v, run.results),
            ),
            stats,
            histories,
            tolerance,
        })
    }

    fn studies(_run: &Run, s: &RunStats) -> Vec<Study> {
        let mut studies: Vec<Study> = s.tolerance.iter().cloned().collect();
        if !s.variants.is_empty() {
            studies.push(variants::study(&s.variants, &s.shares));
        }
        studies
    }

    fn headline(s: &RunStats) -> (Estimate, f64) {
        (s.shares[0].share, 0.0)
    }

    /// The shares at every load, the shells, the flux of the interval at the headline
    /// load, the gains over a smaller range and the variants' details.
    fn detail_table<'s>(
        scene: &'s ReentryScene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, RunStats> {
        let mut t = DetailTable::default();
        for &a in &scene.contact_areas {
            declare_shares(&mut t, a);
        }
        t.always(
            SHELLS,
            "shells |q|^2 added one at a time from q_l to q_s (wave numbers of a history)",
            |s: &RunStats| s.shells,
        );
        let flux_in = format!(
            "flux into contact, zeta {} -> {} (fraction of A0)",
            scene.flux_zeta,
            scene.flux_zeta + scene.flux_dzeta
        );
        t.always(FLUX_IN, flux_in, |s: &RunStats| s.flux_in)
            .persson(0.0);
        t.always(
            FLUX_OUT,
            "flux out of contact (fraction of A0)",
            |s: &RunStats| s.flux_out,
        )
        .persson(0.0);
        t.always(
            NET_OVER_GROSS,
            "net flux / mean one-way flux",
            |s: &RunStats| s.net_over_gross,
        )
        .persson(0.0);
        // The detail of `flux_in_of_noncontact`: the stored key is kept for the committed
        // results.
        t.always(
            ZERO_BIN_REENTRY,
            "share of non-contact entering contact (transition out of p = 0)",
            |s: &RunStats| s.flux_in_of_noncontact,
        )
        .persson(0.0);
        range::declare(&mut t, scene);
        let headline = variants::Headline {
            loads: &scene.contact_areas,
            zeta_max: scene.base().zeta_max(),
        };
        for v in &scene.variants {
            let same_cutoffs = range::same_cutoffs_grid(scene, v).map(|g| g.n);
            variants::declare(&mut t, v, headline, same_cutoffs);
        }
        t
    }

    fn declare_studies(scene: &ReentryScene, keys: &mut Keys) {
        if scene.tolerance.is_some() {
            keys.study(tolerance::STUDY, &tolerance::columns());
        }
        if !scene.variants.is_empty() {
            keys.study(variants::STUDY, &variants::columns());
        }
    }

    /// The golden values: every share (the variants' too, with their shell statistics) and
    /// the flux of the interval.
    fn golden(_run: &Run, s: &RunStats) -> BTreeMap<String, f64> {
        let mut golden = BTreeMap::new();
        for share in &s.shares {
            let target = share.load;
            golden.insert(format!("share_{target}"), round_sig(share.share.value, 3));
            golden.insert(
                format!("share_after_first_{target}"),
                round_sig(share.after_first.value, 3),
            );
        }
        for v in &s.variants {
            for l in v.loads.iter().filter(|l| l.realizations > 0) {
                golden.insert(
                    format!("{}_share_{}", v.variant.name, l.load),
                    round_sig(l.share.value, 3),
                );
                if let Some(p) = &l.per_shell {
                    golden.insert(
                        format!("{}_leave_soon_excess_{}", v.variant.name, l.load),
                        round_sig(p.leave_soon_excess.value, 3),
                    );
                    golden.insert(
                        format!("{}_changes_octave_drop_{}", v.variant.name, l.load),
                        round_sig(p.changes_octave_drop.value, 3),
                    );
                }
            }
        }
        golden.insert("flux_in".into(), round_sig(s.flux_in.value, 3));
        golden.insert("flux_out".into(), round_sig(s.flux_out.value, 3));
        golden
    }

    /// The account of the conclusion, from its numbers.
    fn account(run: &Run, s: &RunStats) -> String {
        let (scene, results) = (run.scene, &s.histories);
        let shells = results.first().map_or(0, |r| r.1.shells);
        let head = scene.contact_areas[0];
        format!(
            "{} were swept through all {} shells one at a time at fixed load, from the flat \
             interface to zeta_max = {}. Of the points in contact at zeta_max, {} had been \
             out of contact at a lower magnification. Between zeta = {} and {}, \
             {:.3}% of the nominal area entered contact and {:.3}% left it, at a_r = \
             {head}. A sweep took {} solver iterations on average.",
            scene.base().runs(),
            shells,
            scene.lambda_l / scene.lambda_s,
            s.shares
                .iter()
                .map(|s| format!("{} at a_r = {}", s.share.text(100.0, 1, "%"), s.load))
                .collect::<Vec<_>>()
                .join(", "),
            scene.flux_zeta,
            scene.flux_zeta + scene.flux_dzeta,
            100.0 * s.flux_in.value,
            100.0 * s.flux_out.value,
            results.iter().map(|r| r.1.iterations).sum::<u64>() / results.len().max(1) as u64,
        )
    }

    fn tables(run: &Run, s: &RunStats) -> Vec<Table> {
        vec![table(&run.criteria.name, run.scene, &s.histories)]
    }

    fn rasters(run: &Run, s: &RunStats) -> Vec<Raster> {
        let mut rasters = maps(
            run.scene,
            &by_load(&run.scene.contact_areas, &s.histories)[0],
        );
        rasters.extend(s.variants.iter().filter_map(variants::raster));
        rasters
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detail_keys_name_the_load() {
        assert_eq!(out_at_first_key(0.14), "out_at_first_ar0.14");
        assert_eq!(share_key(0.14), "share_ar0.14");
        assert_eq!(after_first_key(0.14), "share_after_first_ar0.14");
    }

    #[test]
    fn shipped_scenes_are_valid() {
        let (reduced, _) = crate::experiments::shipped_valid::<Reentry>("c_reentry");
        let mut bad = reduced.clone();
        bad.flux_dzeta = 100.0;
        crate::experiments::assert_refused::<Reentry>(&bad, "flux_dzeta");
    }
}
