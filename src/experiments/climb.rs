//! The fixed-load magnification climb: the paper's protocol of adding roughness one
//! magnification at a time while the load stays constant ("we keep changing the
//! resolution", section 3).
//!
//! A climb finds the load `p0` that gives the job's contact area at full resolution
//! (`zeta_max`, where the paper labels its loads), then, at that fixed `p0`, solves the
//! realization at every magnification of a list, each solve warm-started from the
//! previous one ([`crate::engine::sweep`]). The first step starts cold: at small `zeta`
//! the surface is nearly flat, and a cold start is closer than the full-resolution
//! solution. What each experiment measures along the way is a [`Recorder`].
//!
//! With [`Checkpointing`], the climb saves its state (the last solution, its counters
//! and the recorder's state) every so many seconds ([`crate::io::checkpoint`]); a climb
//! started again on the same folder continues after the last saved step and ends with the
//! same numbers as an uninterrupted one (solves are deterministic, and the warm start is
//! part of the state).

use std::path::Path;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::scene::{Base, Realization};
use super::JobContext;
use crate::engine::contact::{ContactSolution, Residual, SolveStats};
use crate::engine::solver::SolverKind;
use crate::engine::tolerance::{STEP_MERGE, ZETA_SLACK};
use crate::error::{Error, Result};
use crate::io::checkpoint::{Array, Checkpoints};

pub use crate::engine::climb::{climb_steps, Arrays, Recorder, Stepped};

/// Where and how often a climb saves its state.
#[derive(Debug, Clone, Copy)]
pub struct Checkpointing<'a> {
    /// The job's state folder.
    pub dir: &'a Path,
    /// Seconds between checkpoints.
    pub seconds: f64,
}

/// What a climb did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Climbed {
    /// The load.
    pub p0: f64,
    /// Solver iterations of the climb's steps (the load search excluded), interrupted
    /// runs included.
    pub iterations: u64,
    /// Largest residual of all solves, the load search included.
    pub max_residual: f64,
    /// Wall time, seconds, interrupted runs included.
    pub wall_s: f64,
}

/// Checkpoint header.
#[derive(Serialize, Deserialize)]
struct Progress {
    /// Steps done.
    step: usize,
    p0: f64,
    iterations: u64,
    wall_s: f64,
    max_residual: f64,
    recorder: serde_json::Value,
    /// What the solver carried after the last step ([`Sweep::carried`]); absent from
    /// checkpoints written before it was kept (such a climb resumes without it, and
    /// differs from an uninterrupted one at the solver's tolerance).
    #[serde(default)]
    solver: Option<f64>,
}

/// Checks the steps per octave of a [`ladder`]: an integer in `[1, 64]`.
pub fn check_steps_per_octave(steps_per_octave: usize) -> Result<()> {
    if (1..=64).contains(&steps_per_octave) {
        Ok(())
    } else {
        Err(Error::invalid(
            "steps_per_octave",
            steps_per_octave,
            "an integer in [1, 64]",
        ))
    }
}

/// Magnification steps: `per_octave` log-spaced steps from `start` to `end` (both
/// included), merged with the `extra` points that lie in `[start, end]`, sorted, with
/// points closer than a relative [`STEP_MERGE`] merged.
pub fn ladder(start: f64, end: f64, per_octave: usize, extra: &[f64]) -> Vec<f64> {
    let octaves = (end / start).log2();
    let count = ((octaves * per_octave as f64).ceil() as usize).max(1);
    let mut z: Vec<f64> = (0..=count)
        .map(|k| start * (end / start).powf(k as f64 / count as f64))
        .collect();
    z.extend(
        extra
            .iter()
            .copied()
            .filter(|&x| x >= start * (1.0 - ZETA_SLACK) && x <= end * (1.0 + ZETA_SLACK)),
    );
    z.sort_by(f64::total_cmp);
    z.dedup_by(|a, b| (*a - *b).abs() <= STEP_MERGE * b.abs());
    z
}

/// Index of `zeta` in `steps` (to a relative [`STEP_MERGE`]).
pub fn step_of(steps: &[f64], zeta: f64) -> usize {
    steps
        .iter()
        .position(|&z| (z - zeta).abs() <= STEP_MERGE * zeta)
        .expect("the ladder holds every requested point")
}

/// A job's climb: [`climb`] with the job's solver, saving its state in the job's state
/// folder every `seconds` ([`Checkpointing`]), so that a job killed mid-climb resumes.
pub fn climb_job(
    base: &Base,
    ctx: &JobContext,
    realization: &Realization,
    contact_area: f64,
    steps: &[f64],
    recorder: &mut impl Recorder,
    seconds: f64,
) -> Result<Climbed> {
    let checkpointing = Checkpointing {
        dir: &ctx.state_dir,
        seconds,
    };
    climb(
        base,
        ctx.solver,
        realization,
        contact_area,
        steps,
        recorder,
        Some(checkpointing),
    )
}

/// Climbs `realization` through the magnifications `steps` with `solver`, at the load that
/// gives `contact_area` at full resolution, recording every step.
pub fn climb(
    base: &Base,
    solver: SolverKind,
    realization: &Realization,
    contact_area: f64,
    steps: &[f64],
    recorder: &mut impl Recorder,
    checkpointing: Option<Checkpointing>,
) -> Result<Climbed> {
    let timer = Instant::now();
    let mut sweep = base.sweep(realization, solver);
    let mut checkpoints = checkpointing.map(|c| Checkpoints::new(c.dir));
    let saved = checkpoints.as_mut().and_then(|c| c.load_meta::<Progress>());
    let (next, p0, iterations, wall_before, max_residual) = match saved {
        Some(pr) => {
            let ck = checkpoints.as_ref().expect("loaded from it");
            let points = realization.model.grid.points();
            let solution = ContactSolution {
                pressure: ck.load_f64("pressure")?,
                displacement: ck.load_f64("displacement")?,
                p0: pr.p0,
                stats: SolveStats {
                    solver: solver.name(),
                    iterations: 0,
                    residual: Residual::default(),
                    wall_s: 0.0,
                    warm: true,
                },
            };
            if solution.pressure.len() != points || pr.step == 0 || pr.step > steps.len() {
                return Err(Error::bad_file(
                    checkpointing.expect("loaded from it").dir,
                    "checkpoint of another grid or another climb",
                ));
            }
            recorder.start(pr.p0)?;
            recorder.restore(pr.recorder, ck)?;
            sweep.restore(steps[pr.step - 1], solution, pr.solver);
            (pr.step, pr.p0, pr.iterations, pr.wall_s, pr.max_residual)
        }
        None => {
            let p0 = sweep.find_load(realization.surface.zeta_max(), contact_area)?;
            let residual = sweep.solution().map_or(0.0, |s| s.stats.residual.value());
            sweep.take_solution();
            recorder.start(p0)?;
            (0, p0, 0, 0.0, residual)
        }
    };

    let mut last_save = Instant::now();
    let done = Stepped {
        step: next,
        iterations,
        max_residual,
    };
    let done = climb_steps(
        &mut sweep,
        p0,
        steps,
        done,
        recorder,
        |sweep, recorder, done| {
            let (Some(c), Some(ck)) = (checkpointing, checkpoints.as_mut()) else {
                return Ok(());
            };
            if last_save.elapsed().as_secs_f64() >= c.seconds && done.step < steps.len() {
                let s = sweep.solution().expect("just solved");
                let (meta, extra) = recorder.state();
                let progress = Progress {
                    step: done.step,
                    p0,
                    iterations: done.iterations,
                    wall_s: wall_before + timer.elapsed().as_secs_f64(),
                    max_residual: done.max_residual,
                    recorder: meta,
                    solver: sweep.carried(),
                };
                let mut arrays = vec![
                    ("pressure", Array::F64(&s.pressure)),
                    ("displacement", Array::F64(&s.displacement)),
                ];
                arrays.extend(extra);
                ck.save(&progress, &arrays)?;
                last_save = Instant::now();
            }
            Ok(())
        },
    )?;
    Ok(Climbed {
        p0,
        iterations: done.iterations,
        max_residual: done.max_residual,
        wall_s: wall_before + timer.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ladder_merges_extra_points_and_keeps_the_ends() {
        let z = ladder(1.0, 8.0, 2, &[3.0, 2.0, 20.0]);
        assert_eq!(z.first(), Some(&1.0));
        assert!((z.last().unwrap() - 8.0).abs() < 1e-12);
        // 2^(k/2) for k = 0..6, plus 3 (2 is already there, 20 is outside).
        assert_eq!(z.len(), 8);
        assert!(z.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(step_of(&z, 3.0), 4);
    }
}
