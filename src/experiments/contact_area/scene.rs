//! The scene of the contact-area law (its grids, loads, realizations and the studies it
//! plans beside the load ladders), the checks of its parameters, and its jobs: the
//! ladders, and the scaling, gap and system-size studies' solves.

use std::collections::BTreeSet;

use serde::{Deserialize, Serialize};

use super::gap::{GapJob, GapPlan, GapResult};
use super::ladder::{AreaJob, AreaResult, FinerGrid};
use super::scaling::{ScalingJob, ScalingPlan, ScalingResult};
use super::system_size::{SizeJob, SizePlan};
use crate::engine::solver::SolveOptions;
use crate::error::{check_open, check_positive, Error, Result};
use crate::experiments::scene::{
    check_increasing, increasing, leaves_out_planned, list_error, PLANNED,
};
use crate::experiments::{JobContext, Jobs, Work};

/// Scene of the contact-area experiment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AreaScene {
    /// Points per side.
    pub n: usize,
    /// Hurst exponents.
    pub hursts: Vec<f64>,
    /// Long-wavelength cutoff.
    pub lambda_l: f64,
    /// Short-wavelength cutoff.
    pub lambda_s: f64,
    /// Realizations.
    pub seeds: Vec<u64>,
    /// Realizations a plan of sample sizes added after the scene's results were stored
    /// (`docs/power-plan.md`): run and concluded as `seeds` are, left out of the jobs'
    /// keys, and a part of their own ([`PLANNED`]) until all their jobs have results.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub more_seeds: Vec<u64>,
    /// Grid refinements: each realization is also solved with `n`, `lambda_l` and
    /// `lambda_s` multiplied by these factors (increasing, starting at 1).
    pub refinements: Vec<usize>,
    /// Reduced pressures `p~0` at full resolution, increasing.
    pub reduced_pressures: Vec<f64>,
    /// Loads with `p~0 <= low_load` enter `kappa`.
    pub low_load: f64,
    /// Range of `a_r` over which eq. (contactArea) is checked.
    pub law_range: (f64, f64),
    /// Largest relative deviation from eq. (contactArea) that reproduces the paper.
    pub law_tolerance: f64,
    /// Residual tolerance.
    pub tol: f64,
    /// A further grid, finer than the last of `refinements`, for some Hurst exponents at
    /// some loads: with three grids, whether the grid error is first order in `eps_c`
    /// (what the extrapolation assumes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub finer_grid: Option<FinerGrid>,
    /// The solvers' iterations against the system size (none: not run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scaling: Option<ScalingPlan>,
    /// The mean gap at low loads (none: not run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gap: Option<GapPlan>,
    /// The ladders on a larger system at the same resolution (none: not run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub system_size: Option<SizePlan>,
}

/// A job: one realization's load ladder (stored bare, as before the scaling study
/// existed), or one cold solve of the scaling study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ContactAreaJob {
    /// A cold solve of the scaling study.
    Scaling(ScalingJob),
    /// A ladder of low loads recording the mean gap.
    Gap(GapJob),
    /// A load ladder on the larger system.
    Size(SizeJob),
    /// A load ladder.
    #[serde(untagged)]
    Ladder(AreaJob),
}

/// What a job measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ContactAreaOutput {
    /// A cold solve of the scaling study.
    Scaling(ScalingResult),
    /// The mean gaps of a ladder of low loads.
    Gap(GapResult),
    /// A load ladder on the larger system.
    Size(AreaResult),
    /// A load ladder.
    #[serde(untagged)]
    Ladder(AreaResult),
}

impl Jobs for AreaScene {
    const FAMILY: &'static str = "contact_area";
    type Job = ContactAreaJob;
    type JobResult = ContactAreaOutput;

    fn validate(&self) -> Result<()> {
        if self.hursts.is_empty() {
            return Err(Error::invalid(
                "hursts",
                "[]",
                "at least one Hurst exponent",
            ));
        }
        if self.refinements.first() != Some(&1) || !increasing(&self.refinements) {
            return Err(list_error(
                "refinements",
                &self.refinements,
                "an increasing list starting at 1, e.g. [1, 2]",
            ));
        }
        for &hurst in &self.hursts {
            for &refine in &self.refinements {
                let p = self.params(&AreaJob {
                    hurst,
                    seed: 0,
                    refine,
                });
                p.spectrum()
                    .validate(&crate::engine::grid::Grid::new(p.n, 1.0)?)?;
            }
        }
        crate::error::check_seeds(&self.seeds)?;
        check_increasing("reduced_pressures", &self.reduced_pressures)?;
        for &p in &self.reduced_pressures {
            check_positive("reduced_pressures", p)?;
        }
        check_positive("low_load", self.low_load)?;
        if self.reduced_pressures[0] > self.low_load {
            return Err(Error::invalid(
                "low_load",
                self.low_load,
                format!(
                    ">= the smallest reduced pressure {}",
                    self.reduced_pressures[0]
                ),
            ));
        }
        check_open("law_range.0", self.law_range.0, 0.0, 1.0)?;
        check_open("law_range.1", self.law_range.1, self.law_range.0, 1.0)?;
        check_positive("law_tolerance", self.law_tolerance)?;
        if let Some(f) = &self.finer_grid {
            self.validate_finer_grid(f)?;
        }
        if let Some(plan) = &self.scaling {
            plan.validate()?;
        }
        if let Some(plan) = &self.gap {
            plan.validate(self)?;
        }
        if let Some(plan) = &self.system_size {
            plan.validate(self)?;
        }
        SolveOptions::with_tol(self.tol).validate()
    }

    /// The ladders, then the scaling study's solves.
    fn jobs(&self) -> Vec<ContactAreaJob> {
        let mut jobs: Vec<ContactAreaJob> = self
            .ladders()
            .into_iter()
            .map(ContactAreaJob::Ladder)
            .collect();
        if let Some(plan) = &self.scaling {
            jobs.extend(plan.jobs().into_iter().map(ContactAreaJob::Scaling));
        }
        if let Some(plan) = &self.gap {
            jobs.extend(
                plan.jobs(&self.all_seeds())
                    .into_iter()
                    .map(ContactAreaJob::Gap),
            );
        }
        if let Some(plan) = &self.system_size {
            jobs.extend(plan.jobs(self).into_iter().map(ContactAreaJob::Size));
        }
        jobs
    }

    /// The planned realizations' jobs ([`PLANNED`]): their ladders, gaps and larger
    /// systems.
    fn part(&self, job: &ContactAreaJob) -> Option<String> {
        let seed = match job {
            ContactAreaJob::Ladder(j) => j.seed,
            ContactAreaJob::Gap(j) => j.seed,
            ContactAreaJob::Size(j) => j.seed,
            ContactAreaJob::Scaling(_) => return None,
        };
        self.more_seeds.contains(&seed).then(|| PLANNED.into())
    }

    fn leave_out(&mut self, parts: &BTreeSet<String>) {
        if leaves_out_planned(parts) {
            self.more_seeds.clear();
        }
    }

    /// The mean gaps and the larger system are read on the headline solver's solutions.
    fn headline_only(job: &ContactAreaJob) -> bool {
        matches!(job, ContactAreaJob::Gap(_) | ContactAreaJob::Size(_))
    }

    /// The ladders depend on the scene without the scaling, gap and system-size studies:
    /// their keys are those of the scenes that had none of them.
    fn key_scene(&self) -> serde_json::Value {
        let mut scene = self.clone();
        scene.scaling = None;
        scene.gap = None;
        scene.system_size = None;
        serde_json::to_value(scene).expect("scenes serialise")
    }

    fn work(&self, job: &ContactAreaJob) -> Work {
        match job {
            ContactAreaJob::Ladder(j) => self.ladder_work(j),
            ContactAreaJob::Scaling(j) => j.work(),
            ContactAreaJob::Gap(j) => j.work(self),
            ContactAreaJob::Size(j) => j.work(),
        }
    }

    fn run_job(&self, job: &ContactAreaJob, ctx: &JobContext) -> Result<ContactAreaOutput> {
        match job {
            ContactAreaJob::Ladder(j) => self.run_ladder(j, ctx).map(ContactAreaOutput::Ladder),
            ContactAreaJob::Scaling(j) => j.run(ctx).map(ContactAreaOutput::Scaling),
            ContactAreaJob::Gap(j) => j.run(self, ctx).map(ContactAreaOutput::Gap),
            ContactAreaJob::Size(j) => j.run(self.tol, ctx).map(ContactAreaOutput::Size),
        }
    }

    fn residual(result: &ContactAreaOutput) -> f64 {
        match result {
            ContactAreaOutput::Ladder(r) => r.max_residual,
            ContactAreaOutput::Scaling(r) => r.max_residual,
            ContactAreaOutput::Gap(r) => r.max_residual,
            ContactAreaOutput::Size(r) => r.max_residual,
        }
    }
}
