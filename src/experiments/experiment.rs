//! The two traits every experiment implements: [`Jobs`] (how a scene splits into
//! independent jobs, what one costs ([`Work`]) and how one runs) and [`Experiment`] (how
//! the jobs' results reduce to a [`Conclusion`], in three steps: statistics, findings as
//! data, a thin builder of what a reader sees).

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::PathBuf;

use serde::de::DeserializeOwned;
use serde::Serialize;

use super::declared::DetailTable;
use super::findings::{Conclusion, Criteria, Guard, Table};
use super::keys::Keys;
use super::study::Study;
use crate::error::Result;
use crate::plot::{Figure, Raster, Waterfall};
use crate::stats::Estimate;

/// How a job runs: its solver, and where it keeps state that must survive interruption.
#[derive(Debug, Clone)]
pub struct JobContext {
    /// The solver of every solve of the job.
    pub solver: crate::engine::solver::SolverKind,
    /// Directory for the job's checkpoints. The runner empties it before a fresh run and
    /// removes it once the job's result is stored; a job only reads and writes it.
    pub state_dir: PathBuf,
}

/// What a job costs: the solves it makes on its grid. The runner turns it into an
/// estimated time per solver ([`crate::validation::plan`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Work {
    /// Grid points of each solve.
    pub points: usize,
    /// Searches for the load that gives a contact area (several solves each, the first
    /// from cold).
    pub searches: f64,
    /// Solves at a given load, each started from the previous solution.
    pub solves: f64,
    /// Solves that add a single shell of modes to the previous solution's surface (the
    /// cheapest warm starts).
    pub shells: f64,
}

impl Work {
    /// One search for the load on an `n x n` grid, then `solves` solves warm-started from
    /// its solution and `shells` single-shell steps: the cost of any job that finds its
    /// load once and goes on from there (a magnification climb, a transition of one step,
    /// a search alone with `0, 0`).
    pub fn search_then(n: usize, solves: usize, shells: usize) -> Self {
        Self {
            points: n * n,
            searches: 1.0,
            solves: solves as f64,
            shells: shells as f64,
        }
    }
}

/// A scene and its jobs: how a scene splits into independent jobs, what one costs, and how
/// one runs. Validations that draw different statistics from the same runs share their
/// scene type, and so their jobs and, through [`Jobs::FAMILY`], their stored results.
pub trait Jobs: Serialize + DeserializeOwned + Sync + fmt::Debug {
    /// Name of the job family (the folder of the stored results).
    const FAMILY: &'static str;
    /// One independent unit of work (usually one realization).
    type Job: Serialize + DeserializeOwned + Clone + Send + Sync + fmt::Debug;
    /// A job's result (kept on disk for resuming).
    type JobResult: Serialize + DeserializeOwned + Send;

    /// Checks the scene's ranges; errors name the field.
    fn validate(&self) -> Result<()>;

    /// The jobs of the scene.
    fn jobs(&self) -> Vec<Self::Job>;

    /// Whether a job runs with the headline solver only (a study whose solver is part of
    /// the job, or a figure): the runner does not repeat it for the cross-check.
    fn headline_only(_job: &Self::Job) -> bool {
        false
    }

    /// The solver the scene fixes for every job, if it fixes one (a study of one solver's
    /// solutions): the runner then runs each job once, with it, whatever solvers the run
    /// asks for, and the outcome names it.
    fn solver(&self) -> Option<crate::engine::solver::SolverKind> {
        None
    }

    /// The scene as a job's key sees it ([`crate::validation::store::job_key`]): the whole
    /// scene, unless an experiment leaves out a part its jobs' results do not depend on (a
    /// study plan added after the headline's results were stored).
    fn key_scene(&self) -> serde_json::Value {
        serde_json::to_value(self).expect("scenes serialise")
    }

    /// The scene (as its keys see it) and the job whose stored result `job` shares, when
    /// `job` is another scene's job run here for comparison (a reference surface's sweep):
    /// it is keyed and stored as that job, so both validations read one result and neither
    /// runs it twice. `None` (the default): the job is this scene's own.
    fn shared_job(&self, _job: &Self::Job) -> Option<(serde_json::Value, Self::Job)> {
        None
    }

    /// The optional part of the scene that `job` belongs to, by name (a scene beside the
    /// headline's, as a re-entry variant), or `None` for a job of the scene proper. A merge
    /// that allows pending parts (`validate --merge --partial`) concludes without a part
    /// whose jobs do not all have results yet ([`Jobs::leave_out`]), and the outcome names
    /// it as pending; a job of the scene proper must always have its result.
    fn part(&self, _job: &Self::Job) -> Option<String> {
        None
    }

    /// Removes the optional parts named `parts` ([`Jobs::part`]) from the scene. The jobs
    /// of what remains must keep their keys ([`Jobs::key_scene`] leaves the parts out),
    /// which the runner checks.
    fn leave_out(&mut self, _parts: &BTreeSet<String>) {}

    /// What one job costs (its grid and its solves), for splitting a run into shares
    /// before anything runs.
    fn work(&self, job: &Self::Job) -> Work;

    /// Runs one job.
    fn run_job(&self, job: &Self::Job, ctx: &JobContext) -> Result<Self::JobResult>;

    /// The largest solver residual of a job's solves (0 for a job that keeps none).
    fn residual(result: &Self::JobResult) -> f64;
}

/// A job of experiment `E`.
pub type JobOf<E> = <<E as Experiment>::Scene as Jobs>::Job;
/// A job's result of experiment `E`.
pub type ResultOf<E> = <<E as Experiment>::Scene as Jobs>::JobResult;

/// The results of one solver's run of an experiment on a scene, with what they are judged
/// by: what every step of a conclusion reads.
pub struct Run<'a, E: Experiment + ?Sized> {
    /// The validation's name, significance, resolution and the paper's value.
    pub criteria: &'a Criteria,
    /// The scene run.
    pub scene: &'a E::Scene,
    /// Every job with its result, in job order.
    pub results: &'a [(JobOf<E>, ResultOf<E>)],
}

/// The code behind a validation: the scene it runs (and so its jobs) and what it concludes
/// from the jobs' results, in three steps that every experiment follows:
///
/// 1. **statistics** ([`Experiment::stats`]): the numbers, from pure functions of the
///    results, unit-tested on their own;
/// 2. **findings as data**: the headline with Persson's value ([`Experiment::headline`]),
///    secondary statistics declared once ([`Experiment::detail_table`]), implementation
///    guards that never enter a verdict ([`Experiment::guards`]), and golden values
///    ([`Experiment::golden`]); the paper's statements are the definition's claims,
///    judged by [`crate::validation::claims`];
/// 3. **a thin builder** of what a reader sees: the account, tables and figures.
///
/// [`Experiment::conclude`] runs the three steps; an experiment implements the steps only.
pub trait Experiment {
    /// The scene (the `reduced` and `full` tables of a definition), which knows its jobs.
    type Scene: Jobs;
    /// The statistics an experiment draws from a run's results.
    type Stats;

    /// The claims whose paper values ([`Criteria::paper`]) this experiment reads: a
    /// definition of it must state each with a value, or it is refused when it loads.
    const PAPER_CLAIMS: &'static [&'static str] = &[];

    /// Checks the scene's ranges for this experiment: the scene's own checks
    /// ([`Jobs::validate`]), and any this experiment adds.
    fn validate(scene: &Self::Scene) -> Result<()> {
        scene.validate()
    }

    /// The statistics of a run (errors: results that do not fit together).
    fn stats(run: &Run<Self>) -> Result<Self::Stats>;

    /// The headline statistic and Persson's prediction of it.
    fn headline(stats: &Self::Stats) -> (Estimate, f64);

    /// The secondary statistics a run of `scene` can have, declared once
    /// ([`DetailTable`]): each detail's key, label, Persson's and the paper's values, and
    /// how its value is read from the statistics. What a run writes (the rows it has values
    /// for) and what a claim may name ([`keys_of`]) both derive from it, and nothing
    /// else declares a detail. `criteria` gives the paper's values (the default where only
    /// the keys are wanted).
    fn detail_table<'s>(
        _scene: &'s Self::Scene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, Self::Stats> {
        DetailTable::default()
    }

    /// The studies a run of `scene` can have, with their columns, as [`Experiment::studies`]
    /// writes them.
    fn declare_studies(_scene: &Self::Scene, _keys: &mut Keys) {}

    /// Implementation guards (a conservation law, a counting identity): shown, never part
    /// of a verdict.
    fn guards(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Guard> {
        Vec::new()
    }

    /// Values kept as golden snapshots, rounded.
    fn golden(_run: &Run<Self>, _stats: &Self::Stats) -> BTreeMap<String, f64> {
        BTreeMap::new()
    }

    /// Studies: tables of rows beside the headline (a sensitivity study, the readings of
    /// a statement the paper leaves open), each with its notes.
    fn studies(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Study> {
        Vec::new()
    }

    /// The account, from the numbers (nothing that depends on the machine).
    fn account(run: &Run<Self>, stats: &Self::Stats) -> String;

    /// Tables; the first is written as `<name>.csv`.
    fn tables(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Table> {
        Vec::new()
    }

    /// Figures.
    fn figures(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Figure> {
        Vec::new()
    }

    /// Raster images (contact maps).
    fn rasters(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Raster> {
        Vec::new()
    }

    /// Waterfalls of cross sections.
    fn waterfalls(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Waterfall> {
        Vec::new()
    }

    /// Reduces all jobs' results (in job order) to a conclusion: the three steps above,
    /// and the largest residual of the jobs ([`Jobs::residual`]).
    fn conclude(
        criteria: &Criteria,
        scene: &Self::Scene,
        results: &[(JobOf<Self>, ResultOf<Self>)],
    ) -> Result<Conclusion>
    where
        Self: Sized,
    {
        // The planned realizations (`more_seeds`) count as the others do.
        let scene = &crate::experiments::scene::with_planned_folded(scene);
        let run = Run {
            criteria,
            scene,
            results,
        };
        let stats = Self::stats(&run)?;
        let (measured, persson) = Self::headline(&stats);
        let details = Self::detail_table(scene, criteria).details(&stats);
        let max_residual = results
            .iter()
            .map(|(_, r)| Self::Scene::residual(r))
            .fold(0.0, f64::max);
        Ok(Conclusion {
            details,
            guards: Self::guards(&run, &stats),
            golden: Self::golden(&run, &stats),
            studies: Self::studies(&run, &stats),
            account: Self::account(&run, &stats),
            tables: Self::tables(&run, &stats),
            figures: Self::figures(&run, &stats),
            rasters: Self::rasters(&run, &stats),
            waterfalls: Self::waterfalls(&run, &stats),
            ..Conclusion::new(measured, persson, max_residual)
        })
    }
}

/// The measures a run of `scene` gives the claims ([`Keys`]): the rows of
/// [`Experiment::detail_table`] and the studies of [`Experiment::declare_studies`]. A claim
/// that names another is refused when its definition loads. A free function, not a trait
/// method, so that no experiment can declare its keys a second time.
pub fn keys_of<E: Experiment>(scene: &E::Scene) -> Keys {
    let criteria = Criteria::default();
    let mut keys = E::detail_table(scene, &criteria).keys();
    E::declare_studies(scene, &mut keys);
    keys
}
