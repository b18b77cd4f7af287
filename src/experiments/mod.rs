//! Experiments: the measurements behind the validations, one module per thing measured.
//!
//! What it may use: [`crate::engine`], [`crate::persson`], [`crate::stats`],
//! [`crate::plot`] (figure descriptions, rendered elsewhere) and [`crate::io`]; nothing
//! above it (validations, report, commands).
//!
//! An [`Experiment`]'s scene splits into independent jobs (one realization, or one
//! realization at one load, [`Jobs`]), run one at a time ([`Jobs::run_job`]); the
//! experiment reduces the jobs' results to a [`Conclusion`] in three steps, the same in
//! every experiment ([`Experiment`]): statistics first (pure functions, unit-tested on their
//! own, in a module of statistics), then the findings as data (the headline statistic with
//! its standard error and Persson's value for it, secondary statistics ([`Detail`]), checks
//! of the paper's finding ([`Check`]) and golden values), then a thin builder of the
//! account, tables and figures.
//!
//! Every check is decided by one rule, [`crate::stats::decide`] ([`Check::new`]): a
//! claim about the interval `value +- z std_error`, not decided without an error bar (one
//! realization). An undecided check says so in its detail and leaves the reproduction
//! undecided; texts print "(no error bar with one realization)" where an error bar would
//! stand.
//!
//! * [`contact_area`]: the contact-area law, `a_r` against `p~0`;
//! * [`transitions`]: assumptions (a) pressure-independent diffusion and (b) no drift;
//! * [`reentry`]: assumption (c), no re-entry into contact;
//! * [`source`]: assumption (c) in one step, the share of the zero-pressure bin that
//!   moves into contact (the paper's "about 1%");
//! * [`modes`]: assumptions (d) a mode holds energy only once resolved, (e) and keeps it;
//! * [`total_energy`]: the integrated elastic energy against the original and corrected
//!   theories.
//!
//! Shared machinery: [`scene`] (the fields every scene repeats), [`ensemble`] (the
//! seeds x contact areas job grid and the per-load ensemble statistics), [`climb`] (the
//! fixed-load magnification climb with optional checkpoints) and [`contact_change`] (which
//! points entered or left contact in a step).

pub mod climb;
pub mod contact_area;
pub mod contact_change;
pub mod ensemble;
pub mod flux;
pub mod modes;
pub mod reentry;
pub mod scene;
pub mod source;
pub mod study;
pub mod total_energy;
pub mod transitions;

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use self::study::Study;
use crate::error::{Error, Result};
use crate::plot::{Axis, Figure, Raster, Waterfall};
use crate::stats::{Decision, Estimate};

/// What a conclusion is judged by: the validation's name, its verdict rule's significance
/// and resolution, the paper's value of the headline statistic, and the paper's values of
/// its claims by key (data from the definition, never typed into code).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Criteria {
    /// The validation's name (the stem of its first table).
    pub name: String,
    /// Significance `z`, in standard errors.
    pub significance: f64,
    /// Smallest deviation from Persson's prediction that matters.
    pub resolution: f64,
    /// The paper's value of the headline statistic, if it states one.
    pub paper_value: Option<f64>,
    /// The paper's value of each claim that states one, by the claim's key.
    pub paper: BTreeMap<String, f64>,
}

impl Criteria {
    /// The paper's value of the claim `key`, if the definition states one.
    pub fn paper(&self, key: &str) -> Option<f64> {
        self.paper.get(key).copied()
    }
}

/// A secondary statistic, shown in the validation's section of the scorecard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Detail {
    /// Stable identifier (tests and the report use it, never the label).
    #[serde(default)]
    pub key: String,
    /// Label, in words.
    pub name: String,
    /// Measurement.
    pub value: Estimate,
    /// Persson's value, if any.
    pub persson: Option<f64>,
    /// The paper's value, if any.
    pub paper: Option<f64>,
    /// Points per side of the grid the value was measured on, when the detail is one step
    /// of a resolution study (one key, measured on several grids).
    #[serde(default)]
    pub grid: Option<usize>,
}

impl Detail {
    /// A detail with key `key` and label `name`, without Persson's or the paper's value.
    pub fn new(key: impl Into<String>, name: impl Into<String>, value: Estimate) -> Self {
        Self {
            key: key.into(),
            name: name.into(),
            value,
            persson: None,
            paper: None,
            grid: None,
        }
    }

    /// With Persson's value.
    pub fn persson(mut self, v: f64) -> Self {
        self.persson = Some(v);
        self
    }

    /// With the paper's value (if any).
    pub fn paper(mut self, v: Option<f64>) -> Self {
        self.paper = v;
        self
    }

    /// Measured on a grid of `n` points per side.
    pub fn on_grid(mut self, n: usize) -> Self {
        self.grid = Some(n);
        self
    }
}

/// A check of the paper's finding; all must pass for the finding to count as reproduced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// Stable identifier.
    #[serde(default)]
    pub key: String,
    /// What is checked, in words.
    pub name: String,
    /// Whether it passed (false when not decided).
    pub passed: bool,
    /// The numbers behind it.
    pub detail: String,
    /// Whether the data decide it: false for a check that needs an error bar when there
    /// is one realization. An undecided check leaves the reproduction undecided.
    #[serde(default = "decided_default", skip_serializing_if = "is_decided")]
    pub decided: bool,
}

fn decided_default() -> bool {
    true
}

fn is_decided(decided: &bool) -> bool {
    *decided
}

impl Check {
    /// A check decided by `decision`, from the one rule of [`crate::stats::decide`]:
    /// passed, failed, or not decided, which the detail says first.
    pub fn new(
        key: impl Into<String>,
        name: impl Into<String>,
        decision: Decision,
        detail: impl Into<String>,
    ) -> Self {
        let detail = detail.into();
        Self {
            key: key.into(),
            name: name.into(),
            passed: decision.passed(),
            decided: decision.is_decided(),
            detail: if decision.is_decided() {
                detail
            } else {
                format!("{UNDECIDED}: {detail}")
            },
        }
    }
}

/// What the detail of a check the data do not decide starts with.
pub const UNDECIDED: &str = "not decided with 1 realization (no error bar)";

/// A table of numbers, written as CSV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Table {
    /// File stem.
    pub name: String,
    /// Column names.
    pub columns: Vec<String>,
    /// Rows (one value per column).
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table with `columns`.
    pub fn new(name: impl Into<String>, columns: &[&str]) -> Self {
        Self {
            name: name.into(),
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<f64>) {
        assert_eq!(
            row.len(),
            self.columns.len(),
            "a row has one value per column"
        );
        self.rows.push(row);
    }

    /// Writes the table as CSV to `path`, atomically.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let mut w = csv::Writer::from_writer(Vec::new());
        let to_io = |e: csv::Error| Error::io(path, std::io::Error::other(e));
        w.write_record(&self.columns).map_err(to_io)?;
        for row in &self.rows {
            w.write_record(row.iter().map(|&v| cell(v)))
                .map_err(to_io)?;
        }
        let bytes = w
            .into_inner()
            .map_err(|e| Error::io(path, std::io::Error::other(e.to_string())))?;
        crate::io::write_atomic(path, &bytes)
    }
}

/// A CSV cell: the number, or nothing where there is none (NaN: no error bar from one
/// realization, no walkers in a bin).
fn cell(v: f64) -> String {
    if v.is_nan() {
        String::new()
    } else {
        format!("{v}")
    }
}

/// What an experiment concludes from its jobs.
#[derive(Debug, Clone, Default)]
pub struct Conclusion {
    /// The headline statistic.
    pub measured: Option<Estimate>,
    /// Persson's prediction of the headline statistic.
    pub persson: f64,
    /// Secondary statistics.
    pub details: Vec<Detail>,
    /// Checks of the paper's finding beyond the headline verdict and range.
    pub checks: Vec<Check>,
    /// A short account, generated from the numbers (no wall times: it must not depend on
    /// the machine).
    pub account: String,
    /// Values kept as golden snapshots (rounded by the experiment).
    pub golden: BTreeMap<String, f64>,
    /// Tables; the first is written as `<name>.csv`.
    pub tables: Vec<Table>,
    /// Figures.
    pub figures: Vec<Figure>,
    /// Raster images (contact maps).
    pub rasters: Vec<Raster>,
    /// Largest solver residual over all solves.
    pub max_residual: f64,
    /// Studies: tables of rows beside the headline, with their notes.
    pub studies: Vec<Study>,
    /// Waterfalls of cross sections.
    pub waterfalls: Vec<Waterfall>,
}

impl Conclusion {
    /// A conclusion with the headline `measured`, Persson's value of it and the largest
    /// residual of the solves; the rest is added by the experiment.
    pub fn new(measured: Estimate, persson: f64, max_residual: f64) -> Self {
        Self {
            measured: Some(measured),
            persson,
            max_residual,
            ..Default::default()
        }
    }

    /// The detail with key `key`, if any.
    pub fn detail(&self, key: &str) -> Option<&Detail> {
        self.details.iter().find(|d| d.key == key)
    }

    /// The check with key `key`, if any.
    pub fn check(&self, key: &str) -> Option<&Check> {
        self.checks.iter().find(|c| c.key == key)
    }
}

/// A figure with its axes and no series yet (no right axis).
pub fn figure(name: &str, title: impl Into<String>, x: Axis, y: Axis) -> Figure {
    Figure {
        name: name.into(),
        title: title.into(),
        x,
        y,
        y2: None,
        series: Vec::new(),
    }
}

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
    /// A search for the load on an `n x n` grid followed by `solves` warm-started solves
    /// and `shells` single-shell steps (a magnification climb, or a transition with one
    /// step).
    pub fn climb(n: usize, solves: usize, shells: usize) -> Self {
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
///    secondary statistics ([`Experiment::details`]), checks of the paper's finding, each
///    decided by the one rule of [`crate::stats::decide`] ([`Experiment::checks`]), and
///    golden values ([`Experiment::golden`]);
/// 3. **a thin builder** of what a reader sees: the account, tables and figures.
///
/// [`Experiment::conclude`] runs the three steps; an experiment implements the steps only.
pub trait Experiment {
    /// The scene (the `reduced` and `full` tables of a definition), which knows its jobs.
    type Scene: Jobs;
    /// The statistics an experiment draws from a run's results.
    type Stats;

    /// Checks the scene's ranges for this experiment: the scene's own checks
    /// ([`Jobs::validate`]), and any this experiment adds.
    fn validate(scene: &Self::Scene) -> Result<()> {
        scene.validate()
    }

    /// The statistics of a run (errors: results that do not fit together).
    fn stats(run: &Run<Self>) -> Result<Self::Stats>;

    /// The headline statistic and Persson's prediction of it.
    fn headline(stats: &Self::Stats) -> (Estimate, f64);

    /// Secondary statistics, with stable keys.
    fn details(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Detail> {
        Vec::new()
    }

    /// Checks of the paper's finding beyond the headline's verdict.
    fn checks(_run: &Run<Self>, _stats: &Self::Stats) -> Vec<Check> {
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
        let run = Run {
            criteria,
            scene,
            results,
        };
        let stats = Self::stats(&run)?;
        let (measured, persson) = Self::headline(&stats);
        let max_residual = results
            .iter()
            .map(|(_, r)| Self::Scene::residual(r))
            .fold(0.0, f64::max);
        Ok(Conclusion {
            details: Self::details(&run, &stats),
            checks: Self::checks(&run, &stats),
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

/// The reduced scene of a shipped definition (`validations/<name>.toml`), for the unit
/// tests of the experiments.
#[cfg(test)]
pub(crate) fn shipped_scenes<S: DeserializeOwned>(name: &str) -> (S, S, Criteria) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validations")
        .join(format!("{name}.toml"));
    let text = std::fs::read_to_string(&path).expect("a shipped definition");
    let mut table: toml::Table = toml::from_str(&text).expect("valid TOML");
    let scene = |t: &mut toml::Table, k: &str| -> S {
        t.remove(k)
            .expect("a scene table")
            .try_into()
            .expect("a valid scene")
    };
    let reduced = scene(&mut table, "reduced");
    let full = scene(&mut table, "full");
    let verdict = table["verdict"].as_table().expect("a verdict table");
    let criteria = Criteria {
        name: name.to_string(),
        significance: verdict["significance"].as_float().expect("significance"),
        resolution: verdict["resolution"].as_float().expect("resolution"),
        paper_value: table["paper"].get("value").and_then(|v| v.as_float()),
        paper: table
            .get("claims")
            .and_then(|c| c.as_array())
            .into_iter()
            .flatten()
            .filter_map(|c| {
                let key = c.get("key")?.as_str()?.to_string();
                Some((key, c.get("value")?.as_float()?))
            })
            .collect(),
    };
    (reduced, full, criteria)
}

/// The shipped scenes of `name`, both checked for experiment `E` (the test fails
/// otherwise): the reduced and the full scene.
#[cfg(test)]
pub(crate) fn shipped_valid<E: Experiment>(name: &str) -> (E::Scene, E::Scene) {
    let (reduced, full, _) = shipped_scenes::<E::Scene>(name);
    for (scale, scene) in [("reduced", &reduced), ("full", &full)] {
        E::validate(scene).unwrap_or_else(|e| panic!("{name} [{scale}]: {e}"));
    }
    (reduced, full)
}

/// Asserts that `scene` is refused for experiment `E` with an error that names `field`.
#[cfg(test)]
pub(crate) fn assert_refused<E: Experiment>(scene: &E::Scene, field: &str) {
    let e = E::validate(scene)
        .expect_err("an invalid scene")
        .to_string();
    assert!(e.contains(field), "{e}");
}
