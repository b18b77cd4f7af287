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
//!   at `zeta + dzeta` (paper, 4096^2, H = 0.8, a_r = 0.14, zeta 128 -> 129.5: 0.675%);
//! * `flux_out`: in contact at `zeta`, out at `zeta + dzeta` (paper: 0.597%);
//! * the headline, `flux_in / flux_out`, the points entering contact per point leaving it
//!   (Persson: 0; paper: 1.13), and the net flux over the mean one-way flux,
//!   `|out - in| / ((out + in) / 2)` (paper: about 0.12).
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
//! Unlike the re-entry histories ([`super::reentry`]), which climb through every shell, a
//! step needs two solves, so this runs at the paper's 4096^2 in its full scene.

pub mod reading;
pub mod sensitivity;
pub mod waterfall;

use serde::{Deserialize, Serialize};

use self::sensitivity::{SensitivityPlan, StudyJob, StudyResult};
use self::waterfall::{WaterfallPlan, WaterfallResult};
use super::reentry::history::{pack_categories, unpack_categories};
use super::reentry::net_over_gross;
use super::scene::scene;
use super::{
    max_residual, Check, Conclusion, Criteria, Detail, Experiment, JobContext, Jobs, Work,
};
use crate::engine::scene::check_zeta;
use crate::error::{check_open, check_positive, Error, Result};
use crate::plot::Raster;
use crate::stats::{realizations, round_sig, Claim, Estimate};

/// The paper's flux into contact from zeta = 128 to 129.5, fraction of the nominal area.
pub const PAPER_IN: f64 = 0.00675;
/// The paper's flux out of contact over the same step.
pub const PAPER_OUT: f64 = 0.00597;

/// Map categories: in contact at both, entered, out at both, left.
const BOTH: u8 = 0;
const ENTERED: u8 = 1;
const NEITHER: u8 = 2;
const LEFT: u8 = 3;

scene! {
    /// Scene of the one-step flux.
    pub struct FluxScene {
        /// Relative contact area at `zeta` (sets the load).
        pub contact_area: f64,
        /// Magnification before the step.
        pub zeta: f64,
        /// The step.
        pub dzeta: f64,
        /// The sensitivity study (none: not run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub sensitivity: Option<SensitivityPlan>,
        /// The cross-section waterfall (none: not drawn).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub waterfall: Option<WaterfallPlan>,
    }
}

/// A job: one realization's step (stored as the bare seed), one realization of one
/// configuration of the sensitivity study, or the waterfall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FluxJob {
    /// The sensitivity study.
    Study(StudyJob),
    /// The waterfall of the scene's plan.
    Waterfall,
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

/// The category of a point from its pressure before and after the step.
fn category(before: f64, after: f64) -> u8 {
    match (before > 0.0, after > 0.0) {
        (true, true) => BOTH,
        (false, true) => ENTERED,
        (false, false) => NEITHER,
        (true, false) => LEFT,
    }
}

/// `(flux_in, flux_out)`: the fractions of points that entered and that left contact.
pub fn fluxes(categories: &[u8]) -> (f64, f64) {
    let n = categories.len().max(1) as f64;
    let count = |c: u8| categories.iter().filter(|&&x| x == c).count() as f64 / n;
    (count(ENTERED), count(LEFT))
}

impl Jobs for FluxScene {
    const FAMILY: &'static str = "flux";
    type Job = FluxJob;
    type JobResult = FluxOutput;

    fn validate(&self) -> Result<()> {
        let scene = self;
        scene.base().validate()?;
        check_open("contact_area", scene.contact_area, 0.0, 1.0)?;
        check_positive("dzeta", scene.dzeta)?;
        check_zeta(scene.zeta + scene.dzeta, scene.base().zeta_max())?;
        if let Some(plan) = &scene.sensitivity {
            plan.validate(scene.hurst)?;
        }
        if let Some(plan) = &scene.waterfall {
            plan.validate(scene.base().zeta_max())?;
        }
        Ok(())
    }

    fn jobs(&self) -> Vec<FluxJob> {
        let scene = self;
        let mut jobs: Vec<FluxJob> = scene.seeds.iter().map(|&s| FluxJob::Step(s)).collect();
        if let Some(plan) = &scene.sensitivity {
            jobs.extend(plan.jobs().into_iter().map(FluxJob::Study));
        }
        if scene.waterfall.is_some() {
            jobs.push(FluxJob::Waterfall);
        }
        jobs
    }

    fn headline_only(job: &FluxJob) -> bool {
        !matches!(job, FluxJob::Step(_))
    }

    fn work(&self, job: &FluxJob) -> Work {
        let scene = self;
        match job {
            FluxJob::Step(_) => Work::climb(scene.n, 1, 0),
            FluxJob::Study(j) => Work::climb(j.config.n, 1, 0),
            FluxJob::Waterfall => {
                let panels = scene.waterfall.as_ref().map_or(0, |w| w.zetas.len());
                Work::climb(scene.n, panels, 0)
            }
        }
    }

    fn run_job(&self, job: &FluxJob, ctx: &JobContext) -> Result<FluxOutput> {
        let scene = self;
        match job {
            FluxJob::Step(seed) => step(scene, *seed, ctx).map(FluxOutput::Step),
            FluxJob::Study(j) => sensitivity::run(scene.hurst, j).map(FluxOutput::Study),
            FluxJob::Waterfall => {
                let plan = scene
                    .waterfall
                    .as_ref()
                    .ok_or_else(|| Error::invalid("waterfall", "none", "a waterfall plan"))?;
                waterfall::run(scene, plan).map(FluxOutput::Waterfall)
            }
        }
    }
}

impl Experiment for Flux {
    type Scene = FluxScene;

    fn conclude(
        criteria: &Criteria,
        scene: &FluxScene,
        results: &[(FluxJob, FluxOutput)],
    ) -> Result<Conclusion> {
        let steps: Vec<(u64, FluxResult)> = results
            .iter()
            .filter_map(|(j, r)| match (j, r) {
                (FluxJob::Step(s), FluxOutput::Step(r)) => Some((*s, r.clone())),
                _ => None,
            })
            .collect();
        let mut c = conclude_steps(criteria, scene, &steps)?;
        if let Some(plan) = &scene.sensitivity {
            let study: Vec<(&StudyJob, &StudyResult)> = results
                .iter()
                .filter_map(|(j, r)| match (j, r) {
                    (FluxJob::Study(j), FluxOutput::Study(r)) => Some((j, r)),
                    _ => None,
                })
                .collect();
            c.sensitivity = plan.conclude(&study);
            if !c.sensitivity.is_empty() {
                let value = |k: &str| c.detail(k).map(|d| d.value);
                let headline = match (value("flux_in"), value("flux_out")) {
                    (Some(i), Some(o)) => Some((scene.dzeta / scene.zeta, i, o)),
                    _ => None,
                };
                let before = value("contact_area_before").map_or(f64::NAN, |e| e.value);
                let after = value("contact_area_after").map_or(f64::NAN, |e| e.value);
                c.notes = reading::notes(&c.sensitivity, before, after);
                c.figures.push(reading::figure(&c.sensitivity, headline));
                let max = study
                    .iter()
                    .map(|(_, r)| r.max_residual)
                    .fold(0.0, f64::max);
                c.max_residual = c.max_residual.max(max);
            }
        }
        if let Some(plan) = &scene.waterfall {
            for (_, r) in results {
                if let FluxOutput::Waterfall(w) = r {
                    c.waterfalls.push(waterfall::figure(scene, plan, w));
                }
            }
        }
        Ok(c)
    }
}

/// One realization's step at the scene's settings.
fn step(scene: &FluxScene, seed: u64, ctx: &JobContext) -> Result<FluxResult> {
    let base = scene.base();
    let r = base.realization(seed)?;
    let mut sweep = base.sweep(&r, ctx.solver);
    let p0 = sweep.find_load(scene.zeta, scene.contact_area)?;
    let old = sweep
        .solution()
        .expect("find_load keeps its solution")
        .clone();
    let new = sweep.solve_at(scene.zeta + scene.dzeta, p0)?;
    let categories: Vec<u8> = old
        .pressure
        .iter()
        .zip(&new.pressure)
        .map(|(&a, &b)| category(a, b))
        .collect();
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

/// The headline conclusion from the steps of every seed.
fn conclude_steps(
    criteria: &Criteria,
    scene: &FluxScene,
    results: &[(u64, FluxResult)],
) -> Result<Conclusion> {
    let over = |f: fn(&FluxResult) -> f64| {
        Estimate::mean_of(&results.iter().map(|(_, r)| f(r)).collect::<Vec<_>>())
    };
    let flux_in = over(|r| r.flux_in);
    let flux_out = over(|r| r.flux_out);
    // Per realization, so that the error bar holds the realizations' spread.
    let ratio = over(|r| r.flux_in / r.flux_out.max(f64::MIN_POSITIVE));
    let net = over(|r| net_over_gross(r.flux_in, r.flux_out));
    let a_old = over(|r| r.a_r_old);
    let a_new = over(|r| r.a_r_new);
    let mut c = Conclusion {
        measured: Some(ratio),
        persson: 0.0,
        max_residual: max_residual(results, |r| r.max_residual),
        ..Default::default()
    };
    c.details = vec![
        Detail::new(
            "flux_in",
            "fraction of the nominal area entering contact",
            flux_in,
        )
        .paper(Some(PAPER_IN)),
        Detail::new(
            "flux_out",
            "fraction of the nominal area leaving contact",
            flux_out,
        )
        .paper(Some(PAPER_OUT)),
        Detail::new(
            "net_over_gross",
            "net flux over the mean one-way flux, |out - in| / ((out + in) / 2)",
            net,
        )
        .paper(Some(net_over_gross(PAPER_IN, PAPER_OUT))),
        Detail::new("contact_area_before", "a_r at zeta", a_old),
        Detail::new("contact_area_after", "a_r at zeta + dzeta", a_new),
    ];
    for (key, e) in [
        ("ratio", ratio),
        ("flux_in", flux_in),
        ("flux_out", flux_out),
    ] {
        c.golden.insert(key.into(), round_sig(e.value, 2));
    }
    c.checks.push(Check::claim(
        "points_enter_contact",
        format!(
            "points enter contact in the step (flux in more than {} standard errors above 0)",
            criteria.significance
        ),
        flux_in,
        Claim::Above(0.0),
        criteria.significance,
        format!("flux in = {}", flux_in.text(1.0, 5, "")),
    ));
    c.account = format!(
        "Over {} (H = {}, {}x{} grid, lambda_l = {}, lambda_s = {}), at the \
             load that gives a_r = {:.3} at zeta = {}, the step to zeta = {} moves {:.3}% of \
             the nominal area into contact and {:.3}% out of it: {} points \
             enter per point that leaves, where Persson's absorbing boundary allows none. \
             The net flux is {} of the mean one-way flux; a_r goes from {:.4} \
             to {:.4}.",
        realizations(results.len()),
        scene.hurst,
        scene.n,
        scene.n,
        scene.lambda_l,
        scene.lambda_s,
        a_old.value,
        scene.zeta,
        scene.zeta + scene.dzeta,
        100.0 * flux_in.value,
        100.0 * flux_out.value,
        ratio.text(1.0, 3, ""),
        net.text(1.0, 3, ""),
        a_old.value,
        a_new.value,
    );
    if let Some((seed, r)) = results.iter().find(|(_, r)| r.map.is_some()) {
        c.rasters.push(Raster {
            name: "flux_map".into(),
            title: format!(
                "Contact changes from zeta = {} to {} (seed {seed}, a_r = {:.3})",
                scene.zeta,
                scene.zeta + scene.dzeta,
                r.a_r_old
            ),
            n: scene.n,
            pixels: unpack_categories(r.map.as_deref().unwrap_or(""), scene.n * scene.n),
            palette: vec![
                ([150, 150, 150], "in contact at both".into()),
                ([220, 40, 40], "entered contact".into()),
                ([255, 255, 255], "out of contact at both".into()),
                ([40, 80, 220], "left contact".into()),
            ],
        });
    }
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn categories_follow_the_contact_at_both_magnifications() {
        let before = [1.0, 0.0, 0.0, 2.0, 0.5];
        let after = [0.5, 0.1, 0.0, 0.0, 0.3];
        let c: Vec<u8> = before
            .iter()
            .zip(&after)
            .map(|(&a, &b)| category(a, b))
            .collect();
        assert_eq!(c, vec![BOTH, ENTERED, NEITHER, LEFT, BOTH]);
        assert_eq!(fluxes(&c), (0.2, 0.2));
    }

    #[test]
    fn shipped_scenes_are_valid() {
        let (reduced, full, _) = crate::experiments::shipped_scenes::<FluxScene>("c_flux");
        reduced.validate().unwrap();
        full.validate().unwrap();
        assert_eq!(full.n, 4096);
    }
}
