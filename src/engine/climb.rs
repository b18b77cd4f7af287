//! The fixed-load steps of a magnification climb: a [`Sweep`] solved at one load `p0` at
//! every magnification of a list, each solve warm-started from the last, with what is
//! measured along the way recorded step by step ([`Recorder`]: the contact history of
//! every point, [`super::history`], is one). Every climb of the validations
//! (`crate::experiments::climb`, which finds the load and keeps checkpoints) and a
//! measured scan's re-entry sweep (`crate::measured::reentry`) run through
//! [`climb_steps`].

use crate::engine::contact::ContactSolution;
use crate::engine::sweep::{Roughness, Sweep};
use crate::error::Result;
use crate::io::checkpoint::{Array, Checkpoints};

/// Named arrays of a recorder's checkpointed state.
pub type Arrays<'a> = Vec<(&'static str, Array<'a>)>;

/// What a climb records at each step.
pub trait Recorder {
    /// Called once the load is known, before the first step.
    fn start(&mut self, _p0: f64) -> Result<()> {
        Ok(())
    }

    /// Records the solution of step `step` (magnification `zeta`).
    fn record(&mut self, step: usize, zeta: f64, solution: &ContactSolution) -> Result<()>;

    /// The state to checkpoint: metadata and arrays (nothing by default).
    fn state(&self) -> (serde_json::Value, Arrays<'_>) {
        (serde_json::Value::Null, Vec::new())
    }

    /// Restores the state saved by [`Recorder::state`].
    fn restore(&mut self, _meta: serde_json::Value, _checkpoints: &Checkpoints) -> Result<()> {
        Ok(())
    }
}

/// How far a climb's fixed-load steps have gone: the steps done, their solver iterations
/// and the largest residual so far.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stepped {
    /// Steps done (the index of the next one).
    pub step: usize,
    /// Solver iterations of the steps done.
    pub iterations: u64,
    /// Largest residual of the solves so far.
    pub max_residual: f64,
}

/// The fixed-load part of a climb: solves `sweep` at `p0` at every magnification of
/// `steps` from `done.step` on, each warm-started from the last, records each step, and
/// calls `after` once each step is recorded (where a climb saves its checkpoints). Every
/// climb of the validations and a measured scan's re-entry sweep run through it.
///
/// # Errors
///
/// The first failed solve, or an error of the recorder or of `after`; `after` has then
/// seen every step done.
pub fn climb_steps<R: Roughness, Rec: Recorder>(
    sweep: &mut Sweep<'_, R>,
    p0: f64,
    steps: &[f64],
    mut done: Stepped,
    recorder: &mut Rec,
    mut after: impl FnMut(&Sweep<'_, R>, &Rec, &Stepped) -> Result<()>,
) -> Result<Stepped> {
    while done.step < steps.len() {
        let zeta = steps[done.step];
        let s = sweep.solve_at(zeta, p0)?;
        done.iterations += s.stats.iterations as u64;
        done.max_residual = done.max_residual.max(s.stats.residual.value());
        recorder.record(done.step, zeta, s)?;
        done.step += 1;
        after(sweep, recorder, &done)?;
    }
    Ok(done)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::solver::SolverKind;
    use crate::error::Error;

    /// Counts the steps it records and fails at step `fail_at`.
    struct FailAt {
        fail_at: usize,
        recorded: usize,
    }

    impl Recorder for FailAt {
        fn record(&mut self, step: usize, _zeta: f64, _s: &ContactSolution) -> Result<()> {
            if step == self.fail_at {
                return Err(Error::invalid(
                    "step",
                    step,
                    "a step before the failing one",
                ));
            }
            self.recorded += 1;
            Ok(())
        }
    }

    #[test]
    fn the_steps_stop_at_the_first_error_and_after_has_seen_every_step_done() {
        let (surface, model) = crate::engine::testing::rough_contact(32, 0.8, 4);
        let opts = crate::engine::solver::SolveOptions::with_tol(1e-8);
        let steps = [1.0, 2.0, 4.0, 8.0];
        let run = |fail_at: usize| {
            let mut sweep = Sweep::new(&surface, &model, SolverKind::Cg, opts);
            let mut recorder = FailAt {
                fail_at,
                recorded: 0,
            };
            let mut seen = Vec::new();
            let out = climb_steps(
                &mut sweep,
                0.05,
                &steps,
                Stepped::default(),
                &mut recorder,
                |_, _, done| {
                    seen.push(*done);
                    Ok(())
                },
            );
            (out, recorder.recorded, seen)
        };
        let (whole, recorded, all) = run(usize::MAX);
        let whole = whole.unwrap();
        assert_eq!((whole.step, recorded, all.len()), (4, 4, 4));
        assert_eq!(all.last(), Some(&whole));
        assert!(whole.iterations > 0 && whole.max_residual <= 1e-8);
        let (cut, recorded, seen) = run(2);
        assert!(cut.unwrap_err().to_string().contains("step"));
        assert_eq!((recorded, seen.len()), (2, 2));
        // The steps before the failure are those of the whole climb.
        assert_eq!(seen[..], all[..2]);
    }
}
