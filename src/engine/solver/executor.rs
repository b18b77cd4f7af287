//! The executor: one loop that runs any hard-wall method, after argmin's executor (a
//! solver's `init`, `next_iter` and `terminate`, with an explicit termination reason).
//!
//! A [`Method`] keeps its settings and work space between solves; [`Method::init`] starts
//! one solve from a problem and a start, and the solve ([`Iteration`]) is the state that
//! [`run`] iterates. Iteration `it` is
//!
//! 1. [`Iteration::measure`]: the part of the step that yields the residual estimate the
//!    method watches (CG: the gap; GFMD: the stress), which the monitor sees;
//! 2. [`Iteration::judge`]: whether the solve ends here, converged (its full
//!    [`Residual`](crate::engine::contact::Residual) below the tolerance) or stopped (a
//!    [`Termination`]), measures again, or goes on;
//! 3. [`Iteration::step`]: the rest of the step, after which the method may stop (GFMD's
//!    step control).
//!
//! A stop, or the end of the budget, hands the state to [`Iteration::terminate`] with the
//! number of iterations completed and the reason: it returns the final state if its full
//! residual meets the tolerance after all, and the error otherwise.
//!
//! The monitor answers every estimate: [`ControlFlow::Continue`] goes on,
//! [`ControlFlow::Break`] stops the solve from outside (a time budget, a cancel) before
//! the judgement, and the solve ends in [`Error::Stopped`] with the reason and the
//! progress the monitor saw. A stopped solve is dropped where it stands: a method's state
//! between solves is its settings, work space (which every [`Method::init`] overwrites)
//! and what it carries ([`Method::carried`], changed only by a solve that converges), so
//! the next solve, warm or cold, runs as it would have without the stopped one.

use std::ops::ControlFlow;

use crate::engine::contact::{ContactProblem, ContactSolution};
use crate::engine::solver::{Progress, SolveOptions, Start};
use crate::error::{Error, Result, StopReason, Termination};

/// What [`Iteration::judge`] decided at one iteration: the solve ends (converged or
/// stopped), measures again, or goes on with its step.
pub enum Judgement {
    /// The full residual is below the tolerance: the solve returns this solution.
    Converged(ContactSolution),
    /// The solve stops for this reason before the step (see [`Iteration::terminate`]).
    Stopped(Termination),
    /// The state changed in judging (CG made `u` exact): measure it again, as the next
    /// iteration.
    Remeasure,
    /// Go on with the step.
    Go,
}

/// A hard-wall method: its settings and work space, kept from solve to solve.
pub trait Method {
    /// Short name, the solver's name everywhere (scenes, the command line, Python,
    /// outcomes).
    const NAME: &'static str;
    /// The wall time of a warm-started solve relative to CG's (1 for CG), for planning
    /// runs: each method says where its value comes from.
    const RELATIVE_COST: f64;
    /// One solve's state, borrowing the method's work space.
    type Solve<'a>: Iteration
    where
        Self: 'a;

    /// The state at `start` for `problem`, or an error when the start does not fit the
    /// problem. `opts` has been validated.
    fn init<'a>(
        &'a mut self,
        problem: &'a ContactProblem<'a>,
        start: Start,
        opts: &SolveOptions,
    ) -> Result<Self::Solve<'a>>;

    /// What the method carries from one solve to the next besides the solution
    /// ([`super::Solver::carried`]); `None` when it carries nothing.
    fn carried(&self) -> Option<f64> {
        None
    }

    /// Sets what [`Method::carried`] returns (a sweep resumed from a checkpoint).
    fn carry(&mut self, _carried: Option<f64>) {}
}

/// One solve's state and its iteration (see the module docs).
pub trait Iteration: Sized {
    /// What [`Iteration::measure`] found, handed on to [`Iteration::judge`] and
    /// [`Iteration::step`].
    type Measure;

    /// The first part of iteration `it`, up to the residual estimate.
    fn measure(&mut self, it: usize) -> Result<Self::Measure>;

    /// The residual estimate in `measured`, for the monitor.
    fn estimate(measured: &Self::Measure) -> f64;

    /// Whether the solve ends, measures again or goes on at iteration `it`.
    fn judge(&mut self, it: usize, measured: &Self::Measure) -> Judgement;

    /// The rest of iteration `it`; a reason to stop ends the solve after it.
    fn step(&mut self, it: usize, measured: Self::Measure) -> Result<Option<Termination>>;

    /// The end of a solve stopped after `iterations` iterations for `reason`: the final
    /// state if its full residual meets the tolerance, the error otherwise.
    fn terminate(self, iterations: usize, reason: Termination) -> Result<ContactSolution>;
}

/// Runs `solve` by the method `solver` for at most `max_iter` iterations; `monitor` sees
/// every estimate and answers whether the solve goes on.
///
/// # Errors
///
/// [`Error::Stopped`] when the monitor stops the solve; the errors of the iteration's
/// steps, and of [`Iteration::terminate`] when the solve stops or the budget ends short
/// of the tolerance.
pub fn run<S: Iteration>(
    mut solve: S,
    solver: &'static str,
    max_iter: usize,
    monitor: &mut dyn FnMut(Progress) -> ControlFlow<StopReason>,
) -> Result<ContactSolution> {
    for it in 0..max_iter {
        let measured = solve.measure(it)?;
        let progress = Progress {
            iteration: it,
            residual: S::estimate(&measured),
        };
        if let ControlFlow::Break(reason) = monitor(progress) {
            return Err(Error::Stopped {
                solver,
                reason,
                iteration: progress.iteration,
                residual: progress.residual,
            });
        }
        match solve.judge(it, &measured) {
            Judgement::Converged(solution) => return Ok(solution),
            Judgement::Stopped(reason) => return solve.terminate(it, reason),
            Judgement::Remeasure => continue,
            Judgement::Go => {}
        }
        if let Some(reason) = solve.step(it, measured)? {
            return solve.terminate(it + 1, reason);
        }
    }
    solve.terminate(max_iter, Termination::BudgetExhausted)
}
