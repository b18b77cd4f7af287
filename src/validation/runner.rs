//! Runs validations: jobs in parallel, each job's result on disk as soon as it finishes,
//! then the conclusion, the verdict and the output files.
//!
//! A job's state directory ([`JobContext::state_dir`]) belongs to the runner: it is emptied
//! before a job runs without `--resume` (so a fresh run never continues a stale sweep),
//! left alone with `--resume` (so the job continues from its last checkpoint), and removed
//! once the job's result is stored, never before.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Instant, SystemTime, UNIX_EPOCH};

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use super::definition::{Definition, Scale, Verdict, VerdictRule};
use super::outcome::{CrossCheck, MergeRecord, Outcome, ShardRecord};
use super::plan::{estimate_seconds, PlannedUnit};
use super::shard::Shard;
use super::source::Source;
use super::store::{
    self, job_key, jobs_dir, mark_written, remove_state, written_here, JobRun, Stored,
};
use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};
use crate::experiments::{Experiment, JobContext, Work};
use crate::stats::Estimate;

/// How to run validations.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// Which scene of each definition to run.
    pub scale: Scale,
    /// Output directory.
    pub out: PathBuf,
    /// Reuse job results already on disk (from an interrupted or earlier run of the same
    /// scene); without it every job is recomputed.
    pub resume: bool,
    /// Show progress bars on stderr (when it is a terminal).
    pub progress: bool,
    /// The solvers to run every scene with: the first gives the headline statistic, the
    /// second (if any) its cross-check.
    pub solvers: Vec<SolverKind>,
    /// Run everything, one share of the jobs, or merge the shares' results.
    pub mode: Mode,
}

/// What a run does with a definition's jobs.
#[derive(Debug, Clone, Default)]
pub enum Mode {
    /// Run every job (or reuse stored results, see [`RunOptions::resume`]) and conclude.
    #[default]
    All,
    /// Run only the jobs whose result files are in `jobs` (one share of a sharded run,
    /// resuming from stored results and checkpoints) and conclude nothing.
    Share {
        /// Which share, recorded with every result.
        shard: Shard,
        /// The result files of this share's jobs.
        jobs: Arc<HashSet<PathBuf>>,
    },
    /// Run nothing: conclude from the stored results of every job (all present, checked
    /// by [`super::plan::Plan::check_merge`] first), recording the shares that computed them.
    Merge {
        /// Whether results of another commit were accepted.
        other_commits_accepted: bool,
    },
}

impl RunOptions {
    /// The headline solver (GFMD, the paper's method) and the cross-check (CG).
    pub const BOTH: [SolverKind; 2] = [SolverKind::Gfmd, SolverKind::Cg];

    /// Options for `scale` written to `out`: both solvers, no resume, no progress bars.
    pub fn new(scale: Scale, out: impl Into<PathBuf>) -> Self {
        Self {
            scale,
            out: out.into(),
            resume: false,
            progress: false,
            solvers: Self::BOTH.to_vec(),
            mode: Mode::All,
        }
    }

    /// The share of a sharded run, if this is one.
    pub fn shard(&self) -> Option<Shard> {
        match &self.mode {
            Mode::Share { shard, .. } => Some(*shard),
            _ => None,
        }
    }

    /// Whether stored results are reused: with `--resume`, and always by a share (which
    /// continues where a killed run of it stopped) or a merge.
    fn reuses_results(&self) -> bool {
        self.resume || !matches!(self.mode, Mode::All)
    }
}

/// The jobs of one solver with their results, in job order.
type Results<E> = Vec<(<E as Experiment>::Job, <E as Experiment>::JobResult)>;

/// One job of one solver, and where its result and checkpoints live.
pub(crate) struct Unit<J> {
    pub solver: SolverKind,
    pub job: J,
    /// The job as JSON (what its key hashes, beside the scale and the scene).
    pub job_json: String,
    /// The stored result's file.
    pub path: PathBuf,
    /// The checkpoint folder.
    pub state_dir: PathBuf,
    /// What it costs.
    pub work: Work,
}

/// A parsed, checked definition with its units of work.
pub(crate) struct Prepared<E: Experiment> {
    pub def: Definition<E::Scene>,
    pub scene_json: serde_json::Value,
    pub units: Vec<Unit<E::Job>>,
}

impl<E: Experiment> Prepared<E> {
    /// The scene being run.
    pub fn scene(&self, scale: Scale) -> &E::Scene {
        self.def.scene(scale)
    }
}

/// Parses and checks `source` and lists its jobs for every solver of `opts`.
pub(crate) fn prepare<E: Experiment>(source: &Source, opts: &RunOptions) -> Result<Prepared<E>> {
    if opts.solvers.is_empty() {
        return Err(Error::invalid("solvers", "none", "at least one solver"));
    }
    let def = source.parse::<E::Scene>()?;
    let (scene, jobs) = checked_scene::<E>(source, &def, opts.scale)?;
    let scene_json = serde_json::to_value(scene).expect("scenes serialise");
    let state = jobs_dir(&opts.out, E::FAMILY, opts.scale);
    let mut units = Vec::new();
    for (k, &solver) in opts.solvers.iter().enumerate() {
        for job in &jobs {
            if k > 0 && E::headline_only(job) {
                continue;
            }
            let job_json = serde_json::to_string(job).expect("jobs serialise");
            let key = job_key(opts.scale, &scene_json, solver, &job_json);
            units.push(Unit {
                solver,
                job: job.clone(),
                job_json,
                path: state.join(format!("{key}.json")),
                state_dir: state.join(format!("{key}.checkpoint")),
                work: E::work(scene, job),
            });
        }
    }
    Ok(Prepared {
        def,
        scene_json,
        units,
    })
}

/// The units of `source` run with `opts`, for planning a sharded run.
pub(crate) fn planned_units<E: Experiment>(
    source: &Source,
    opts: &RunOptions,
) -> Result<Vec<PlannedUnit>> {
    let prepared = prepare::<E>(source, opts)?;
    Ok(prepared
        .units
        .into_iter()
        .map(|u| PlannedUnit {
            validation: prepared.def.name.clone(),
            solver: u.solver,
            job: serde_json::from_str(&u.job_json).expect("jobs serialise"),
            cost: estimate_seconds(u.work, u.solver),
            work: u.work,
            path: u.path,
        })
        .collect())
}

/// Runs (or, with `--resume` or when this process already stored it, loads) one unit.
fn execute<E: Experiment>(
    source: &Source,
    name: &str,
    scene: &E::Scene,
    unit: &Unit<E::Job>,
    opts: &RunOptions,
) -> Result<E::JobResult> {
    let ctx = JobContext {
        solver: unit.solver,
        state_dir: unit.state_dir.clone(),
    };
    if opts.reuses_results() || written_here(&unit.path) {
        if let Some(stored) = store::load::<E::Job, E::JobResult>(&unit.path) {
            // Checkpoints of a run killed after storing this result are spent.
            remove_state(&ctx.state_dir).ok();
            return Ok(stored.result);
        }
    }
    if matches!(opts.mode, Mode::Merge { .. }) {
        return Err(Error::bad_file(
            &unit.path,
            "no readable job result to merge (removed after the check?)",
        ));
    }
    if !opts.reuses_results() {
        // A fresh run recomputes the job from the start: checkpoints an interrupted run
        // left behind are continued only on request.
        remove_state(&ctx.state_dir)?;
    }
    let started = SystemTime::now();
    let timer = Instant::now();
    let result = E::run_job(scene, &unit.job, &ctx).map_err(|e| {
        Error::bad_file(
            &source.path,
            format!(
                "[{}, {}] job {}: {e}",
                opts.scale,
                unit.solver.name(),
                unit.job_json
            ),
        )
    })?;
    let wall_s = timer.elapsed().as_secs_f64();
    let ended = SystemTime::now();
    let stored = Stored {
        solver: unit.solver,
        job: unit.job.clone(),
        result,
        run: Some(JobRun {
            host: crate::io::host_name(),
            start: crate::provenance::rfc3339_utc(started),
            end: crate::provenance::rfc3339_utc(ended),
            span: (epoch_seconds(started), epoch_seconds(ended)),
            wall_s,
            commit: crate::provenance::commit_label(),
            definition: name.to_string(),
            definition_sha256: source.sha256(),
            shard: opts.shard().map(|s| s.to_string()),
        }),
    };
    store::store(&unit.path, &stored)?;
    // Only now that the result is stored are the job's checkpoints dispensable; a run
    // killed before this point resumes from them. A leftover is harmless (the next run of
    // the job removes it), hence `ok()`.
    remove_state(&ctx.state_dir).ok();
    mark_written(unit.path.clone());
    Ok(stored.result)
}

fn epoch_seconds(t: SystemTime) -> f64 {
    t.duration_since(UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

/// Runs experiment `E` on `source`: every job and the outcome ([`Mode::All`]), the
/// outcome from stored results ([`Mode::Merge`]), or one share's jobs and no outcome
/// ([`Mode::Share`], returns `None`).
pub fn run_experiment<E: Experiment>(
    source: &Source,
    opts: &RunOptions,
) -> Result<Option<Outcome>> {
    let timer = Instant::now();
    let prepared = prepare::<E>(source, opts)?;
    let scene = prepared.scene(opts.scale);
    let selected: Vec<&Unit<E::Job>> = match &opts.mode {
        Mode::Share { jobs, .. } => prepared
            .units
            .iter()
            .filter(|u| jobs.contains(&u.path))
            .collect(),
        _ => prepared.units.iter().collect(),
    };
    let bar = progress_bar(opts.progress, &prepared.def.name, selected.len());
    let results: Vec<E::JobResult> = selected
        .par_iter()
        .map(|unit| {
            let r = execute::<E>(source, &prepared.def.name, scene, unit, opts);
            bar.inc(1);
            r
        })
        .collect::<Result<Vec<_>>>()?;
    bar.finish_and_clear();
    if let Mode::Share { .. } = opts.mode {
        return Ok(None);
    }
    let (wall_s, merge) = match &opts.mode {
        Mode::Merge {
            other_commits_accepted,
        } => {
            let runs = prepared
                .units
                .iter()
                .filter_map(|u| store::load_run(&u.path).and_then(|s| s.run))
                .collect::<Vec<_>>();
            let first = runs.iter().map(|r| r.span.0).fold(f64::INFINITY, f64::min);
            let last = runs.iter().map(|r| r.span.1).fold(0.0, f64::max);
            let record = MergeRecord {
                commit: crate::provenance::commit_label(),
                other_commits_accepted: *other_commits_accepted,
                shards: ShardRecord::from_runs(&runs),
            };
            ((last - first).max(0.0), Some(record))
        }
        _ => (timer.elapsed().as_secs_f64(), None),
    };
    conclude::<E>(source, &prepared, results, opts, wall_s, merge).map(Some)
}

/// The headline and the cross-check from the units' results (in unit order), the verdict,
/// and the outcome and its files.
pub(crate) fn conclude<E: Experiment>(
    source: &Source,
    prepared: &Prepared<E>,
    results: Vec<E::JobResult>,
    opts: &RunOptions,
    wall_s: f64,
    merge: Option<MergeRecord>,
) -> Result<Outcome> {
    let def = &prepared.def;
    let scene = prepared.scene(opts.scale);
    let criteria = def.criteria();
    let mut by_solver: Vec<(SolverKind, Results<E>)> = Vec::new();
    for (unit, result) in prepared.units.iter().zip(results) {
        match by_solver.iter_mut().find(|(s, _)| *s == unit.solver) {
            Some((_, v)) => v.push((unit.job.clone(), result)),
            None => by_solver.push((unit.solver, vec![(unit.job.clone(), result)])),
        }
    }
    let mut conclusions = Vec::new();
    for (solver, results) in &by_solver {
        let c = E::conclude(&criteria, scene, results)
            .map_err(|e| Error::bad_file(&source.path, format!("[{}] {e}", solver.name())))?;
        let measured = c
            .measured
            .ok_or_else(|| Error::bad_file(&source.path, "the experiment measured nothing"))?;
        conclusions.push((*solver, c, measured));
    }
    let max_residual = conclusions
        .iter()
        .map(|(_, c, _)| c.max_residual)
        .fold(0.0, f64::max);
    let mut rest = conclusions.into_iter();
    let (solver, conclusion, measured) = rest.next().expect("at least one solver");
    let cross_check = rest.next().map(|(s, _, m)| CrossCheck {
        solver: s.name().to_string(),
        value: m.value,
        std_error: m.std_error,
        agrees: agree(measured, m, &def.verdict),
    });

    let verdict = def.verdict.judge(measured, conclusion.persson);
    let in_range = def.paper.range.is_none_or(|(lo, hi)| {
        // The measurement's interval overlaps the paper's range.
        let half = def.verdict.significance * measured.std_error;
        measured.value + half >= lo && measured.value - half <= hi
    });
    let reproduced = match verdict {
        Verdict::Inconclusive => None,
        v => {
            let checks = &conclusion.checks;
            let agrees = v == def.paper.verdict
                && in_range
                && checks.iter().filter(|c| c.decided).all(|c| c.passed);
            // A check the data cannot decide (one realization) leaves a reproduction that
            // would otherwise stand undecided.
            let undecided = checks.iter().any(|c| !c.decided);
            (!agrees || !undecided).then_some(agrees)
        }
    };

    let dir = opts.out.join(&def.name);
    let mut files = Vec::new();
    for (k, table) in conclusion.tables.iter().enumerate() {
        let path = if k == 0 {
            opts.out.join(format!("{}.csv", def.name))
        } else {
            dir.join(format!("{}.csv", table.name))
        };
        table.write_csv(&path)?;
        files.push(relative(&opts.out, &path));
    }
    for figure in &conclusion.figures {
        for path in crate::plot::render(figure, &dir)? {
            files.push(relative(&opts.out, &path));
        }
    }
    for waterfall in &conclusion.waterfalls {
        for path in crate::plot::render_waterfall(waterfall, &dir)? {
            files.push(relative(&opts.out, &path));
        }
    }
    for raster in &conclusion.rasters {
        for path in crate::plot::render_raster(raster, &dir)? {
            files.push(relative(&opts.out, &path));
        }
    }

    let outcome = Outcome {
        name: def.name.clone(),
        title: def.title.clone(),
        assumption: def.assumption.clone(),
        statistic: def.statistic.clone(),
        value: measured.value,
        std_error: measured.std_error,
        persson: conclusion.persson,
        persson_text: def.persson.clone(),
        paper: def.paper.finding.clone(),
        paper_value: def.paper.value,
        paper_verdict: def.paper.verdict,
        verdict,
        reproduced,
        rule: def.verdict,
        scale: opts.scale,
        scene: prepared.scene_json.clone(),
        definition_sha256: source.sha256(),
        wall_s,
        max_residual,
        details: conclusion.details,
        checks: conclusion.checks,
        account: conclusion.account,
        golden: conclusion.golden,
        sensitivity: conclusion.sensitivity,
        notes: conclusion.notes,
        files,
        threads: rayon::current_num_threads(),
        solver: solver.name().to_string(),
        cross_check,
        merge,
    };
    let json = serde_json::to_vec_pretty(&outcome).expect("outcomes serialise");
    crate::io::write_atomic(&opts.out.join(format!("{}.json", def.name)), &json)?;
    Ok(outcome)
}

/// Whether two solvers' estimates of one statistic agree: their difference within the
/// verdict's significance times their combined standard error. Without an error bar (one
/// realization) they agree when they differ by less than the verdict's resolution.
pub fn agree(a: Estimate, b: Estimate, rule: &VerdictRule) -> bool {
    let diff = (a.value - b.value).abs();
    let combined = a.std_error.hypot(b.std_error);
    if combined.is_finite() {
        diff <= rule.significance * combined
    } else {
        diff <= rule.resolution
    }
}

/// Parses `source` as a definition of experiment `E` and checks both of its scenes,
/// without running anything.
pub fn check_experiment<E: Experiment>(source: &Source) -> Result<()> {
    let def = source.parse::<E::Scene>()?;
    for scale in [Scale::Reduced, Scale::Full] {
        checked_scene::<E>(source, &def, scale)?;
    }
    Ok(())
}

/// The scene of `def` at `scale` with its jobs, once its ranges are checked and it has
/// at least one job; errors name the file and the scene's table.
fn checked_scene<'a, E: Experiment>(
    source: &Source,
    def: &'a Definition<E::Scene>,
    scale: Scale,
) -> Result<(&'a E::Scene, Vec<E::Job>)> {
    let scene = def.scene(scale);
    E::validate(scene).map_err(|e| Error::bad_file(&source.path, format!("[{scale}] {e}")))?;
    let jobs = E::jobs(scene);
    if jobs.is_empty() {
        return Err(Error::bad_file(
            &source.path,
            format!("[{scale}] the scene has no jobs (no seeds?)"),
        ));
    }
    Ok((scene, jobs))
}

fn relative(base: &Path, path: &Path) -> String {
    path.strip_prefix(base)
        .unwrap_or(path)
        .to_string_lossy()
        .to_string()
}

fn progress_bar(show: bool, name: &str, len: usize) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len as u64);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>16} [{elapsed_precise}] {bar:30} {pos}/{len} jobs")
            .expect("static template"),
    );
    bar.set_prefix(name.to_string());
    bar.tick();
    bar
}
