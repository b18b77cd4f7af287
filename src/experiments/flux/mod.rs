//! One step of magnification and the points it moves into and out of contact: the flux
//! of the paper's contact-change figure, assumption (c) ([`crate::conventions`], section 6,
//! row c; paper section 3.3).
//!
//! Persson's diffusion picture absorbs a walker at `p = 0`: as the magnification grows,
//! points only leave contact. Here each realization is solved at `zeta`, at the load that
//! gives the scene's contact area there, and again at `zeta + dzeta` at the same load
//! (warm start); every point is classified by its contact at the two magnifications:
//!
//! * `flux_in`: the fraction of the nominal area out of contact at `zeta` and in contact
//!   at `zeta + dzeta` (the paper's figure: 4096^2, H = 0.8, a_r = 0.14, zeta 128 ->
//!   129.5);
//! * `flux_out`: in contact at `zeta`, out at `zeta + dzeta`;
//! * the headline, `flux_in / flux_out`, the points entering contact per point leaving it
//!   (Persson: 0), and the net flux over the mean one-way flux, `|out - in| / ((out + in)
//!   / 2)`;
//! * the net flow to non-contact, `flux_out - flux_in`, with the residual of the identity
//!   that makes it the fall of the contact area over a step at fixed load
//!   ([`net_flow_residual`]).
//!
//! The paper's numbers for each are claims of the definition (`validations/c_flux.toml`).
//!
//! The map of the first realization is coloured as the paper's figure: grey, in contact at
//! both magnifications; red, entered contact; white, out of contact at both; blue, left
//! contact. Error bars are standard errors over realizations.
//!
//! Two studies ride along, each run once, with the headline solver's jobs
//! ([`Jobs::headline_only`]): the [`sensitivity`] of the flux to the solver, the step,
//! the discretisation and the control (what sets its magnitude, [`reading`]), and the
//! cross-section [`waterfall`] of the paper's figure "reentry_waterfall".
//!
//! # Files
//!
//! * `mod.rs`: the scene, its jobs (a realization's step, a configuration of the
//!   sensitivity study, the waterfall) and the [`Experiment`] implementation;
//! * `stats.rs`: the statistics of the steps and their findings as data, and the study's
//!   rows;
//! * `figures.rs`: the account, the map of the first realization's step and the flux per
//!   step against the step;
//! * `study/`: the two studies (`study/mod.rs` says which file holds what).
//!
//! Unlike the re-entry histories ([`super::reentry`]), which climb through every shell, a
//! step needs two solves, so this runs at the paper's 4096^2 in its full scene.

mod figures;
pub mod stats;
pub mod study;

use serde::{Deserialize, Serialize};

use std::collections::{BTreeMap, BTreeSet};

use self::stats::FluxStats;
use self::study::reading::{self, PaperFlux};
use self::study::sensitivity::{self, SensitivityPlan, SensitivityRow, StudyJob, StudyResult};
use self::study::waterfall::{self, WaterfallPlan, WaterfallResult};
use super::contact_change::{categories, pack_categories, ENTERED, LEFT};
use super::declared::DetailTable;
use super::scene::{leaves_out_planned, step_scene, Step, PLANNED};
use super::study::Study;
use super::{Criteria, Experiment, Guard, JobContext, Jobs, Keys, Work};
use crate::error::{Error, Result};
use crate::plot::{Figure, Raster, Waterfall};
use crate::stats::Estimate;

step_scene! {
    /// Scene of the one-step flux.
    pub struct FluxScene {
        /// The sensitivity study (none: not run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub sensitivity: Option<SensitivityPlan>,
        /// The cross-section waterfall (none: not drawn).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub waterfall: Option<WaterfallPlan>,
        /// The parts a merge left out ([`Jobs::leave_out`]): not part of a definition.
        #[serde(skip)]
        pub left_out: BTreeSet<String>,
    }
}

/// A job: one realization's step (stored as the bare seed), one realization of one
/// configuration of the sensitivity study, or the waterfall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FluxJob {
    /// The sensitivity study.
    Study(StudyJob),
    /// The waterfall of the scene's plan (its seed: the figure's).
    Waterfall,
    /// The waterfall of one of the plan's further seeds (`more_seeds`): its details join
    /// the figure's.
    WaterfallOf(u64),
    /// The headline step of one seed.
    #[serde(untagged)]
    Step(u64),
}

/// What a job measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[allow(clippy::large_enum_variant)]
pub enum FluxOutput {
    /// The sensitivity study.
    Study(StudyResult),
    /// The waterfall.
    Waterfall(WaterfallResult),
    /// The headline step.
    #[serde(untagged)]
    Step(FluxResult),
}

/// What one realization's step measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FluxResult {
    /// Load.
    pub p0: f64,
    /// Contact area at `zeta`.
    pub a_r_old: f64,
    /// Contact area at `zeta + dzeta`.
    pub a_r_new: f64,
    /// Fraction of the nominal area entering contact.
    pub flux_in: f64,
    /// Fraction of the nominal area leaving contact.
    pub flux_out: f64,
    /// Largest solver residual.
    pub max_residual: f64,
    /// Categories of every point (2 bits a point, hex), first seed only.
    pub map: Option<String>,
}

/// The experiment.
pub struct Flux;

impl FluxScene {
    /// The headline step's relative size `dzeta / zeta`, the unit of the study's steps.
    pub fn relative_step(&self) -> f64 {
        self.dzeta / self.zeta
    }
}

/// `(flux_in, flux_out)`: the fractions of points that entered and that left contact.
pub fn fluxes(categories: &[u8]) -> (f64, f64) {
    let n = categories.len().max(1) as f64;
    let count = |c: u8| categories.iter().filter(|&&x| x == c).count() as f64 / n;
    (count(ENTERED), count(LEFT))
}

/// The residual of the net-flow identity of a step, `(flux_out - flux_in) + (a_r_after -
/// a_r_before)`, all fractions of the nominal area.
///
/// The points in contact after a step are those in contact before, plus those that
/// entered, less those that left: `a_r_after = a_r_before + flux_in - flux_out`. The net
/// flow to non-contact, `flux_out - flux_in`, is then the fall of the contact area over the
/// step: at fixed load, a fall that the contact-area law predicts from the roughness the
/// step adds. The residual is zero up to rounding where the contact areas count the same
/// points as the fluxes (both count `p > 0`, [`categories`] and
/// [`crate::engine::contact::ContactSolution::contact_area`]).
pub fn net_flow_residual(a_r_before: f64, a_r_after: f64, flux_in: f64, flux_out: f64) -> f64 {
    (flux_out - flux_in) + (a_r_after - a_r_before)
}

impl Jobs for FluxScene {
    const FAMILY: &'static str = "flux";
    type Job = FluxJob;
    type JobResult = FluxOutput;

    fn validate(&self) -> Result<()> {
        self.validate_one_step()?;
        if let Some(plan) = &self.sensitivity {
            plan.validate(self.hurst, self.relative_step())?;
        }
        if let Some(plan) = &self.waterfall {
            plan.validate(self.base().zeta_max())?;
        }
        Ok(())
    }

    fn jobs(&self) -> Vec<FluxJob> {
        let mut jobs: Vec<FluxJob> = self.all_seeds().into_iter().map(FluxJob::Step).collect();
        if let Some(plan) = &self.sensitivity {
            let held_area_left_out = self.left_out.contains(HELD_AREA);
            jobs.extend(
                plan.jobs(self.relative_step())
                    .into_iter()
                    .filter(|j| !(held_area_left_out && j.config.fixed_area))
                    .map(FluxJob::Study),
            );
        }
        if let Some(plan) = &self.waterfall {
            jobs.push(FluxJob::Waterfall);
            jobs.extend(plan.more_seeds.iter().map(|&s| FluxJob::WaterfallOf(s)));
        }
        jobs
    }

    /// The planned realizations' steps and further waterfalls ([`PLANNED`]), and the
    /// study's steps at fixed area ([`HELD_AREA`]), run again since the area is held to
    /// [`crate::engine::load::HELD_AREA_REL_TOL`].
    fn part(&self, job: &FluxJob) -> Option<String> {
        match job {
            FluxJob::Step(s) if self.more_seeds.contains(s) => Some(PLANNED.into()),
            FluxJob::WaterfallOf(_) => Some(PLANNED.into()),
            FluxJob::Study(j) if j.config.fixed_area => Some(HELD_AREA.into()),
            _ => None,
        }
    }

    fn leave_out(&mut self, parts: &BTreeSet<String>) {
        if leaves_out_planned(parts) {
            self.more_seeds.clear();
            if let Some(w) = &mut self.waterfall {
                w.more_seeds.clear();
            }
        }
        if parts.contains(HELD_AREA) {
            self.left_out.insert(HELD_AREA.into());
        }
    }

    fn headline_only(job: &FluxJob) -> bool {
        !matches!(job, FluxJob::Step(_))
    }

    /// The scene without the study's later Hurst exponents (`later_hurst_values`) and the
    /// waterfall's further seeds (`more_seeds`): the keys of the jobs stored before they
    /// were added stay those of the plan that had none. A later row's jobs differ by their
    /// configuration, which names the exponent, and a further waterfall's by its seed.
    fn key_scene(&self) -> serde_json::Value {
        let mut scene = self.clone();
        if let Some(plan) = &mut scene.sensitivity {
            plan.later_hurst_values.clear();
        }
        if let Some(plan) = &mut scene.waterfall {
            plan.more_seeds.clear();
        }
        serde_json::to_value(scene).expect("scenes serialise")
    }

    fn work(&self, job: &FluxJob) -> Work {
        match job {
            FluxJob::Step(_) => Work::search_then(self.n, 1, 0),
            FluxJob::Study(j) => Work::search_then(j.config.n, 1, 0),
            FluxJob::Waterfall | FluxJob::WaterfallOf(_) => {
                let panels = self.waterfall.as_ref().map_or(0, |w| w.zetas.len());
                Work::search_then(self.n, panels, 0)
            }
        }
    }

    fn run_job(&self, job: &FluxJob, ctx: &JobContext) -> Result<FluxOutput> {
        match job {
            FluxJob::Step(seed) => step(self, *seed, ctx).map(FluxOutput::Step),
            FluxJob::Study(j) => sensitivity::run(self.hurst, j).map(FluxOutput::Study),
            FluxJob::Waterfall | FluxJob::WaterfallOf(_) => {
                let plan = self
                    .waterfall
                    .as_ref()
                    .ok_or_else(|| Error::invalid("waterfall", "none", "a waterfall plan"))?;
                let seed = match job {
                    FluxJob::WaterfallOf(s) => *s,
                    _ => plan.seed,
                };
                waterfall::run(self, plan, seed).map(FluxOutput::Waterfall)
            }
        }
    }

    /// The steps' and the study's residuals; the waterfall keeps none.
    fn residual(result: &FluxOutput) -> f64 {
        match result {
            FluxOutput::Step(r) => r.max_residual,
            FluxOutput::Study(r) => r.max_residual,
            FluxOutput::Waterfall(_) => 0.0,
        }
    }
}

type Run<'a> = super::Run<'a, Flux>;

/// The part of the scene that the study's steps at fixed contact area make up.
pub const HELD_AREA: &str = "held_area";

impl Experiment for Flux {
    type Scene = FluxScene;
    type Stats = FluxStats;
    const PAPER_CLAIMS: &'static [&'static str] =
        &[study::reading::CLAIM_IN, study::reading::CLAIM_OUT];

    fn stats(run: &Run) -> Result<FluxStats> {
        Ok(FluxStats::of(run.scene, run.results))
    }

    fn headline(s: &FluxStats) -> (Estimate, f64) {
        (s.steps.ratio, 0.0)
    }

    /// The steps' details, then the waterfall's over its seeds (where the scene draws
    /// one): `table`.
    fn detail_table<'s>(
        scene: &'s FluxScene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, FluxStats> {
        table(scene)
    }

    fn declare_studies(scene: &FluxScene, keys: &mut Keys) {
        if scene.sensitivity.is_some() {
            keys.study(sensitivity::KEY, sensitivity::COLUMNS);
        }
    }

    fn guards(run: &Run, s: &FluxStats) -> Vec<Guard> {
        vec![stats::identity_guard(run.scene.n, &s.steps)]
    }

    fn golden(_run: &Run, s: &FluxStats) -> BTreeMap<String, f64> {
        stats::golden(&s.steps)
    }

    fn account(run: &Run, s: &FluxStats) -> String {
        figures::account(run.scene, &s.steps)
    }

    /// The sensitivity study as a table, with its reading against the paper's flux
    /// (where the definition states the paper's numbers) as notes.
    fn studies(run: &Run, s: &FluxStats) -> Vec<Study> {
        if s.rows.is_empty() {
            return Vec::new();
        }
        let mut study = sensitivity::study(&s.rows);
        let step = run.scene.relative_step();
        if let (Some(p), Some(plan)) = (PaperFlux::of(run.criteria, step), &run.scene.sensitivity) {
            let (before, after) = (s.steps.a_before.value, s.steps.a_after.value);
            study.notes = reading::notes(&s.rows, &plan.planned(step), &p, before, after);
        }
        vec![study]
    }

    /// The flux per step against the step, the study's rows beside the headline step
    /// (placed at the study's row of the same step, where there is one).
    fn figures(run: &Run, s: &FluxStats) -> Vec<Figure> {
        let paper = PaperFlux::of(run.criteria, run.scene.relative_step());
        let (Some(p), false) = (paper, s.rows.is_empty()) else {
            return Vec::new();
        };
        let headline =
            same_step(run.scene, &s.rows).map(|row| (row, s.steps.flux_in, s.steps.flux_out));
        vec![figures::figure(&s.rows, &p, headline)]
    }

    fn rasters(run: &Run, s: &FluxStats) -> Vec<Raster> {
        figures::flux_map(run.scene, &s.results)
            .into_iter()
            .collect()
    }

    fn waterfalls(run: &Run, _s: &FluxStats) -> Vec<Waterfall> {
        let Some(plan) = &run.scene.waterfall else {
            return Vec::new();
        };
        // The figure's seed alone; the further seeds give the details' error bars.
        run.results
            .iter()
            .filter_map(|(job, r)| match (job, r) {
                (FluxJob::Waterfall, FluxOutput::Waterfall(w)) => {
                    Some(waterfall::figure(run.scene, plan, w))
                }
                _ => None,
            })
            .collect()
    }
}

/// The details a run of `scene` can have, in the order a run writes them: the steps', then
/// the waterfall's where the scene draws one (its labels read from the run's statistics).
fn table(scene: &FluxScene) -> DetailTable<'_, FluxStats> {
    let mut t = DetailTable::default();
    stats::rows(&mut t);
    if let Some(plan) = &scene.waterfall {
        waterfall::rows(&mut t, plan, |s: &FluxStats| s.waterfall.as_ref());
    }
    t
}

/// The study's row of the headline's own step, where there is one: a step row with the
/// scene's grid, step, load, Hurst exponent and control.
fn same_step(scene: &FluxScene, rows: &[SensitivityRow]) -> Option<usize> {
    rows.iter().position(|r| {
        let k = &r.config;
        r.parameter == "dzeta_over_zeta"
            && (k.n, k.lambda_l, k.lambda_s) == (scene.n, scene.lambda_l, scene.lambda_s)
            && (k.zeta, k.dzeta, k.contact_area) == (scene.zeta, scene.dzeta, scene.contact_area)
            && k.hurst.is_none()
            && !k.fixed_area
    })
}

/// One realization's step at the scene's settings.
fn step(scene: &FluxScene, seed: u64, ctx: &JobContext) -> Result<FluxResult> {
    let r = scene.base().realization(seed)?;
    let Step {
        p0,
        before: old,
        after: new,
    } = scene.one_step(&r, ctx.solver)?;
    let categories = categories(&old.pressure, &new.pressure);
    let (flux_in, flux_out) = fluxes(&categories);
    Ok(FluxResult {
        p0,
        a_r_old: old.contact_area(),
        a_r_new: new.contact_area(),
        flux_in,
        flux_out,
        max_residual: old.stats.residual.value().max(new.stats.residual.value()),
        map: (seed == scene.seeds[0]).then(|| pack_categories(&categories)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::contact_change::{BOTH, NEITHER};

    #[test]
    fn categories_follow_the_contact_at_both_magnifications() {
        let before = [1.0, 0.0, 0.0, 2.0, 0.5];
        let after = [0.5, 0.1, 0.0, 0.0, 0.3];
        let c = categories(&before, &after);
        assert_eq!(c, vec![BOTH, ENTERED, NEITHER, LEFT, BOTH]);
        assert_eq!(fluxes(&c), (0.2, 0.2));
    }

    #[test]
    fn the_net_flow_is_the_fall_of_the_contact_area() {
        use crate::engine::field::positive_fraction;
        // Six points: 3 in contact before, 2 after; one entered, two left.
        let before = [1.0, 0.0, 0.0, 2.0, 0.5, 0.7];
        let after = [0.5, 0.1, 0.0, 0.0, 0.0, 0.3];
        let (fin, fout) = fluxes(&categories(&before, &after));
        let (a0, a1) = (positive_fraction(&before), positive_fraction(&after));
        assert_eq!((fin, fout), (1.0 / 6.0, 2.0 / 6.0));
        assert_eq!((a0, a1), (4.0 / 6.0, 3.0 / 6.0));
        assert!(net_flow_residual(a0, a1, fin, fout).abs() < 1e-15);
        // A synthetic step on 1000 points (fractions that round), both ways across: the
        // identity holds to rounding, far below one point (1e-3).
        let n = 1000;
        let pressure = |shift: usize, share: usize| -> Vec<f64> {
            (0..n)
                .map(|i| ((i * 37 + shift) % 101 < share).then_some(1.0 + i as f64))
                .map(|p| p.unwrap_or(0.0))
                .collect()
        };
        let (before, after) = (pressure(0, 30), pressure(5, 27));
        let (fin, fout) = fluxes(&categories(&before, &after));
        let (a0, a1) = (positive_fraction(&before), positive_fraction(&after));
        assert!(
            fin > 0.01 && fout > fin && a1 < a0,
            "{fin} {fout} {a0} {a1}"
        );
        let r = net_flow_residual(a0, a1, fin, fout);
        assert!(r.abs() < 1e-14, "residual {r}");
        // An area that counts one point more than the fluxes do leaves one point.
        let off = net_flow_residual(a0, a1 + 1.0 / n as f64, fin, fout);
        assert!((off - 1e-3).abs() < 1e-14, "{off}");
    }

    /// A plan's later Hurst exponents leave the keys' scene unchanged: the jobs stored
    /// before they were added keep their keys, and the new rows' jobs name their exponent.
    #[test]
    fn later_hurst_exponents_leave_the_keys_scene_alone() {
        let (_, full) = crate::experiments::shipped_valid::<Flux>("c_flux");
        let plan = full.sensitivity.as_ref().unwrap();
        assert!(!plan.later_hurst_values.is_empty());
        let mut without = full.clone();
        without
            .sensitivity
            .as_mut()
            .unwrap()
            .later_hurst_values
            .clear();
        assert_eq!(full.key_scene(), without.key_scene());
        assert_eq!(
            without.key_scene(),
            crate::experiments::scene::without_planned(serde_json::to_value(&without).unwrap())
        );
        assert_ne!(full.key_scene(), serde_json::to_value(&full).unwrap());
        // Every job of the plan without them is a job of the plan with them; the new ones
        // are the later exponents' rows, one per seed.
        let (old, new) = (without.jobs(), full.jobs());
        assert!(old.iter().all(|j| new.contains(j)));
        let added: Vec<&FluxJob> = new.iter().filter(|j| !old.contains(j)).collect();
        assert_eq!(
            added.len(),
            plan.later_hurst_values.len() * plan.seeds.len()
        );
        for job in added {
            let FluxJob::Study(j) = job else {
                panic!("{job:?}")
            };
            let h = j.config.hurst.expect("a later row names its exponent");
            assert!(plan.later_hurst_values.contains(&h), "{h}");
        }
    }

    #[test]
    fn shipped_scenes_are_valid() {
        let (_, full) = crate::experiments::shipped_valid::<Flux>("c_flux");
        assert_eq!(full.n, 4096);
    }
}
