//! Runs validations: jobs in parallel, each job's result on disk as soon as it finishes,
//! then the conclusion, the verdict and the output files.
//!
//! A job's state directory ([`JobContext::state_dir`]) belongs to the runner: it is emptied
//! before a job runs without `--resume` (so a fresh run never continues a stale sweep),
//! left alone with `--resume` (so the job continues from its last checkpoint), and removed
//! once the job's result is stored, never before.

use std::path::{Path, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use super::definition::{Definition, Scale, Verdict};
use super::outcome::Outcome;
use super::source::Source;
use super::store::{self, job_key, jobs_dir, mark_written, remove_state, written_here, Stored};
use crate::error::{Error, Result};
use crate::experiments::{Experiment, JobContext};

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
}

/// Runs experiment `E` on `source`.
pub fn run_experiment<E: Experiment>(source: &Source, opts: &RunOptions) -> Result<Outcome> {
    let timer = Instant::now();
    let def = source.parse::<E::Scene>()?;
    let (scene, jobs) = checked_scene::<E>(source, &def, opts.scale)?;
    let scene_json = serde_json::to_value(scene).expect("scenes serialise");
    let dir = opts.out.join(&def.name);
    let state = jobs_dir(&opts.out, E::FAMILY, opts.scale);

    let bar = progress_bar(opts.progress, &def.name, jobs.len());
    let results: Vec<(E::Job, E::JobResult)> = jobs
        .par_iter()
        .map(|job| -> Result<(E::Job, E::JobResult)> {
            let job_json = serde_json::to_string(job).expect("jobs serialise");
            let key = job_key(opts.scale, &scene_json, &job_json);
            let path = state.join(format!("{key}.json"));
            let job_ctx = JobContext {
                state_dir: state.join(format!("{key}.checkpoint")),
            };
            if opts.resume || written_here(&path) {
                if let Some(result) = store::load::<E::Job, E::JobResult>(&path) {
                    // Checkpoints of a run killed after storing this result are spent.
                    remove_state(&job_ctx.state_dir).ok();
                    bar.inc(1);
                    return Ok((job.clone(), result));
                }
            }
            if !opts.resume {
                // A fresh run recomputes the job from the start: checkpoints an interrupted
                // run left behind are continued only on request.
                remove_state(&job_ctx.state_dir)?;
            }
            let result = E::run_job(scene, job, &job_ctx).map_err(|e| {
                Error::bad_file(
                    &source.path,
                    format!("[{}] job {job_json}: {e}", opts.scale),
                )
            })?;
            let stored = Stored {
                job: job.clone(),
                result,
            };
            store::store(&path, &stored)?;
            // Only now that the result is stored are the job's checkpoints dispensable; a
            // run killed before this point resumes from them. A leftover is harmless (the
            // next run of the job removes it), hence `ok()`.
            remove_state(&job_ctx.state_dir).ok();
            mark_written(path);
            bar.inc(1);
            Ok((stored.job, stored.result))
        })
        .collect::<Result<Vec<_>>>()?;
    bar.finish_and_clear();

    let conclusion = E::conclude(&def.criteria(), scene, &results)?;
    let measured = conclusion
        .measured
        .ok_or_else(|| Error::bad_file(&source.path, "the experiment measured nothing"))?;
    let verdict = def.verdict.judge(measured, conclusion.persson);
    let in_range = def.paper.range.is_none_or(|(lo, hi)| {
        // The measurement's interval overlaps the paper's range.
        let half = def.verdict.significance * measured.std_error;
        measured.value + half >= lo && measured.value - half <= hi
    });
    let reproduced = match verdict {
        Verdict::Inconclusive => None,
        v => Some(v == def.paper.verdict && in_range && conclusion.checks.iter().all(|c| c.passed)),
    };

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
        scene: scene_json,
        definition_sha256: source.sha256(),
        wall_s: timer.elapsed().as_secs_f64(),
        max_residual: conclusion.max_residual,
        details: conclusion.details,
        checks: conclusion.checks,
        account: conclusion.account,
        golden: conclusion.golden,
        files,
        threads: rayon::current_num_threads(),
    };
    let json = serde_json::to_vec_pretty(&outcome).expect("outcomes serialise");
    crate::io::write_atomic(&opts.out.join(format!("{}.json", def.name)), &json)?;
    Ok(outcome)
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
