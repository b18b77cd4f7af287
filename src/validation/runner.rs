//! Runs validations: jobs in parallel, each job's result on disk as soon as it finishes,
//! then the conclusion, the verdict and the output files.
//!
//! A job's state directory ([`JobContext::state_dir`]) belongs to the runner: it is emptied
//! before a job runs without `--resume` (so a fresh run never continues a stale sweep),
//! left alone with `--resume` (so the job continues from its last checkpoint), and removed
//! once the job's result is stored, never before. Besides the checkpoints it holds the
//! runner's record of the job's earlier segments ([`segments`]), so that a resumed job's
//! stored wall time is that of all its segments.

use std::collections::{BTreeSet, HashSet};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Instant, SystemTime};

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use super::claims;
use super::conclusion::{conclude, Results};
use super::definition::{Definition, Scale};
use super::outcome::{MergeRecord, Outcome, ShardRecord};
use super::pending::{pending_parts, PartJob};
use super::plan::{estimate_seconds, PlannedUnit};
use super::segments;
use super::shard::Shard;
use super::source::Source;
use super::store::{
    self, job_key, jobs_dir, mark_written, remove_state, written_here, JobRun, Stored,
};
use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};
use crate::experiments::{keys_of, Experiment, JobContext, JobOf, Jobs, Keys, ResultOf, Work};
use crate::provenance::epoch_seconds;

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
    /// The solvers to run every scene with, each at most once: the first gives the
    /// headline statistic, each of the others a cross-check. A scene that fixes its solver
    /// ([`crate::experiments::Jobs::solver`]) runs with that one alone.
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
        /// Whether the optional parts of a scene whose jobs do not all have results are
        /// left out (recorded as pending in the outcome) instead of refusing the merge.
        partial: bool,
    },
}

impl RunOptions {
    /// The solvers of a run unless it names others: GFMD (the paper's method) for the
    /// headline and CG for the cross-check.
    pub const DEFAULT_SOLVERS: [SolverKind; 2] = [SolverKind::Gfmd, SolverKind::Cg];

    /// Options for `scale` written to `out`: the default solvers, no resume, no progress
    /// bars.
    pub fn new(scale: Scale, out: impl Into<PathBuf>) -> Self {
        Self {
            scale,
            out: out.into(),
            resume: false,
            progress: false,
            solvers: Self::DEFAULT_SOLVERS.to_vec(),
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

/// One job of one solver, and where its result and checkpoints live.
pub(crate) struct Unit<J> {
    pub solver: SolverKind,
    pub job: J,
    /// The job as its key and its stored result name it: the job itself, or the other
    /// scene's job it shares its result with ([`Jobs::shared_job`]).
    pub keyed: J,
    /// `keyed` as JSON (what the key hashes, beside the scale and the scene).
    pub job_json: String,
    /// The stored result's file.
    pub path: PathBuf,
    /// The checkpoint folder.
    pub state_dir: PathBuf,
    /// What it costs.
    pub work: Work,
    /// The optional part of the scene it belongs to ([`Jobs::part`]).
    pub part: Option<String>,
}

/// A parsed, checked definition with its units of work.
pub(crate) struct Prepared<E: Experiment> {
    pub def: Definition<E::Scene>,
    pub scene_json: serde_json::Value,
    pub units: Vec<Unit<JobOf<E>>>,
}

impl<E: Experiment> Prepared<E> {
    /// The scene being run.
    pub fn scene(&self, scale: Scale) -> &E::Scene {
        self.def.scene(scale)
    }
}

/// Parses and checks `source` and lists its jobs for every solver of `opts`, the scene's
/// optional parts named in `leave_out` left out ([`Jobs::leave_out`]; the definition is
/// checked before, with them).
pub(crate) fn prepare<E: Experiment>(
    source: &Source,
    opts: &RunOptions,
    leave_out: &BTreeSet<String>,
) -> Result<Prepared<E>> {
    if opts.solvers.is_empty() {
        return Err(Error::invalid("solvers", "none", "at least one solver"));
    }
    if let Some(twice) = opts
        .solvers
        .iter()
        .enumerate()
        .find_map(|(k, s)| opts.solvers[..k].contains(s).then_some(s))
    {
        return Err(Error::invalid(
            "solvers",
            format!("{} twice", twice.name()),
            "each solver at most once",
        ));
    }
    let mut def = source.parse::<E::Scene>()?;
    checked_scene::<E>(source, &def, opts.scale)?;
    if !leave_out.is_empty() {
        def.scene_mut(opts.scale).leave_out(leave_out);
    }
    let scene = def.scene(opts.scale);
    let jobs = scene.jobs();
    let scene_json = serde_json::to_value(scene).expect("scenes serialise");
    let key_json = crate::experiments::scene::without_planned(scene.key_scene());
    let state = jobs_dir(&opts.out, <E::Scene as Jobs>::FAMILY, opts.scale);
    let solvers = scene
        .solver()
        .map_or_else(|| opts.solvers.clone(), |s| vec![s]);
    let mut units = Vec::new();
    for (k, &solver) in solvers.iter().enumerate() {
        for job in &jobs {
            if k > 0 && <E::Scene as Jobs>::headline_only(job) {
                continue;
            }
            // A job shared with another scene is keyed and stored as that scene's job.
            let shared = scene
                .shared_job(job)
                .map(|(s, j)| (crate::experiments::scene::without_planned(s), j));
            let (key_scene, keyed) = match &shared {
                Some((s, j)) => (s, j),
                None => (&key_json, job),
            };
            let job_json = serde_json::to_string(keyed).expect("jobs serialise");
            let key = job_key(opts.scale, key_scene, solver, &job_json);
            units.push(Unit {
                solver,
                job: job.clone(),
                keyed: keyed.clone(),
                job_json,
                path: state.join(format!("{key}.json")),
                state_dir: state.join(format!("{key}.checkpoint")),
                work: scene.work(job),
                part: scene.part(job),
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
    let prepared = prepare::<E>(source, opts, &BTreeSet::new())?;
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
            part: u.part,
        })
        .collect())
}

/// Runs (or, with `--resume` or when this process already stored it, loads) one unit.
fn execute<E: Experiment>(
    source: &Source,
    name: &str,
    scene: &E::Scene,
    unit: &Unit<JobOf<E>>,
    opts: &RunOptions,
) -> Result<ResultOf<E>> {
    let ctx = JobContext {
        solver: unit.solver,
        state_dir: unit.state_dir.clone(),
    };
    if opts.reuses_results() || written_here(&unit.path) {
        if let Some(stored) = store::load::<JobOf<E>, ResultOf<E>>(&unit.path) {
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
    let earlier_s = segments::start(&ctx.state_dir, started)?;
    let result = scene.run_job(&unit.job, &ctx).map_err(|e| {
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
    let wall_s = earlier_s + timer.elapsed().as_secs_f64();
    let ended = SystemTime::now();
    let stored = Stored {
        solver: unit.solver,
        job: unit.keyed.clone(),
        result,
        run: Some(JobRun {
            host: crate::io::host_name(),
            start: crate::provenance::rfc3339_utc(started),
            end: crate::provenance::rfc3339_utc(ended),
            span: (epoch_seconds(started), epoch_seconds(ended)),
            wall_s,
            earlier_s: (earlier_s > 0.0).then_some(earlier_s),
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

/// Runs experiment `E` on `source`: every job and the outcome ([`Mode::All`]), the
/// outcome from stored results ([`Mode::Merge`]), or one share's jobs and no outcome
/// ([`Mode::Share`], returns `None`).
pub fn run_experiment<E: Experiment>(
    source: &Source,
    opts: &RunOptions,
) -> Result<Option<Outcome>> {
    let timer = Instant::now();
    let mut prepared = prepare::<E>(source, opts, &BTreeSet::new())?;
    let pending = match opts.mode {
        Mode::Merge { partial: true, .. } => {
            let jobs: Vec<PartJob> = prepared
                .units
                .iter()
                .map(|u| PartJob {
                    part: u.part.as_deref(),
                    path: &u.path,
                    cost: estimate_seconds(u.work, u.solver),
                })
                .collect();
            pending_parts::<E>(source, prepared.scene(opts.scale), &jobs, opts.scale)?
        }
        _ => Vec::new(),
    };
    if !pending.is_empty() {
        let names: BTreeSet<String> = pending.iter().map(|p| p.name.clone()).collect();
        let rest = prepare::<E>(source, opts, &names)?;
        let keys: HashSet<&PathBuf> = prepared.units.iter().map(|u| &u.path).collect();
        if let Some(u) = rest.units.iter().find(|u| !keys.contains(&u.path)) {
            return Err(Error::bad_file(
                &source.path,
                format!(
                    "leaving out {names:?} changes the key of job {}: the scene's keys must \
                     not depend on its optional parts",
                    u.job_json
                ),
            ));
        }
        prepared = rest;
    }
    let scene = prepared.scene(opts.scale);
    let selected: Vec<&Unit<JobOf<E>>> = match &opts.mode {
        Mode::Share { jobs, .. } => prepared
            .units
            .iter()
            .filter(|u| jobs.contains(&u.path))
            .collect(),
        _ => prepared.units.iter().collect(),
    };
    let bar = progress_bar(opts.progress, &prepared.def.name, selected.len());
    let results: Vec<ResultOf<E>> = selected
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
            ..
        } => {
            let runs = prepared
                .units
                .iter()
                .filter_map(|u| store::load_run(&u.path).and_then(|s| s.run))
                .collect::<Vec<_>>();
            let record = MergeRecord {
                commit: crate::provenance::commit_label(),
                other_commits_accepted: *other_commits_accepted,
                shards: ShardRecord::from_runs(&runs),
                pending,
            };
            (busy_seconds(runs.iter().map(|r| r.span)), Some(record))
        }
        _ => (timer.elapsed().as_secs_f64(), None),
    };
    // Each solver's jobs with their results, in unit order (headline solver first).
    let mut by_solver: Vec<(SolverKind, Results<E>)> = Vec::new();
    for (unit, result) in prepared.units.iter().zip(results) {
        match by_solver.iter_mut().find(|(s, _)| *s == unit.solver) {
            Some((_, v)) => v.push((unit.job.clone(), result)),
            None => by_solver.push((unit.solver, vec![(unit.job.clone(), result)])),
        }
    }
    conclude::<E>(
        source,
        &prepared.def,
        &prepared.scene_json,
        by_solver,
        opts.scale,
        &opts.out,
        wall_s,
        merge,
    )
    .map(Some)
}

/// The time during which at least one of the jobs ran: the length of the union of their
/// spans `(start, end)`, epoch seconds. A merge's wall time: results gathered from runs
/// days apart (or shared with another validation) count the hours their jobs ran, not the
/// days between them.
fn busy_seconds(spans: impl IntoIterator<Item = (f64, f64)>) -> f64 {
    let mut spans: Vec<(f64, f64)> = spans.into_iter().filter(|(a, b)| b > a).collect();
    spans.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut busy = 0.0;
    let mut open: Option<(f64, f64)> = None;
    for (a, b) in spans {
        open = match open {
            Some((s, e)) if a <= e => Some((s, e.max(b))),
            Some((s, e)) => {
                busy += e - s;
                Some((a, b))
            }
            None => Some((a, b)),
        };
    }
    busy + open.map_or(0.0, |(s, e)| e - s)
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

/// The measures that experiment `E` declares for `source`'s scene at `scale` (its detail
/// keys and studies, [`crate::experiments::keys_of`]), once the definition is checked at that scale.
pub fn declared_keys<E: Experiment>(source: &Source, scale: Scale) -> Result<Keys> {
    let def = source.parse::<E::Scene>()?;
    let (scene, _) = checked_scene::<E>(source, &def, scale)?;
    Ok(keys_of::<E>(scene))
}

/// The scene of `def` at `scale` with its jobs, once its ranges are checked, the claims
/// judged on it name measures its experiment declares ([`claims::check_declared`]) and it
/// has at least one job; errors name the file and the scene's table.
fn checked_scene<'a, E: Experiment>(
    source: &Source,
    def: &'a Definition<E::Scene>,
    scale: Scale,
) -> Result<(&'a E::Scene, Vec<JobOf<E>>)> {
    for key in E::PAPER_CLAIMS {
        if !def
            .claims
            .iter()
            .any(|c| c.key == *key && c.value.is_some())
        {
            return Err(Error::bad_file(
                &source.path,
                format!(
                    "[[claims]] must hold the claim `{key}` with a value: the experiment \
                     `{}` reads the paper's value from it",
                    def.experiment
                ),
            ));
        }
    }
    let scene = def.scene(scale);
    E::validate(scene).map_err(|e| Error::bad_file(&source.path, format!("[{scale}] {e}")))?;
    claims::check_declared(
        &def.claims,
        &keys_of::<E>(scene),
        &serde_json::to_value(scene).expect("scenes serialise"),
        scale == Scale::Reduced,
        scene.solver().is_some(),
    )
    .map_err(|e| Error::bad_file(&source.path, format!("[{scale}] {e}")))?;
    let jobs = scene.jobs();
    if jobs.is_empty() {
        return Err(Error::bad_file(
            &source.path,
            format!("[{scale}] the scene has no jobs (no seeds?)"),
        ));
    }
    Ok((scene, jobs))
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

#[cfg(test)]
mod tests {
    use super::busy_seconds;

    #[test]
    fn busy_time_is_the_union_of_the_job_spans() {
        // Two jobs side by side, one nested in another, and a run two days later: the
        // overlaps count once and the gap not at all.
        let day = 86_400.0;
        let spans = [
            (0.0, 100.0),
            (10.0, 50.0),
            (60.0, 130.0),
            (2.0 * day, 2.0 * day + 20.0),
        ];
        assert_eq!(busy_seconds(spans), 150.0);
        assert_eq!(busy_seconds([]), 0.0);
        // A span that ends before it starts (a clock step) counts nothing.
        assert_eq!(busy_seconds([(5.0, 1.0), (0.0, 1.0)]), 1.0);
    }
}
