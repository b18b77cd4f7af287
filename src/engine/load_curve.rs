//! A load curve: one surface on one model solved at a sequence of loads, each solve
//! warm-started from the last solution kept, as a magnification [`crate::engine::sweep`]
//! is solved at a sequence of magnifications.
//!
//! The caller decides which solutions the curve keeps ([`LoadCurve::keep`]): a solve that
//! failed, or one whose solution the caller refuses, is dropped with what the solver
//! carried from it ([`LoadCurve::reject`]), and the next load starts warm from the last
//! solution kept, as a solver built afresh would. One load never costs the others.
//!
//! A time budget stops a solve from its per-iteration monitor ([`solve_bounded`]): past
//! the deadline the monitor answers stop ([`StopReason::OutOfTime`]) and the solve ends
//! in [`SolveEnd::OutOfTime`]; the solver is left ready for the next load. A solve stopped
//! from outside (a cancel, through the monitor) ends in [`Error::Stopped`].

use std::ops::ControlFlow;
use std::time::Instant;

use crate::engine::contact::{ContactProblem, ContactSolution, Model};
use crate::engine::solver::{Progress, SolveOptions, Solver, Start};
use crate::error::{Error, StopReason};

/// One surface on a model and a solver, stepping through loads.
pub struct LoadCurve<'a> {
    model: &'a Model,
    heights: &'a [f64],
    solver: Box<dyn Solver + Send>,
    opts: SolveOptions,
    last: Option<ContactSolution>,
}

impl<'a> LoadCurve<'a> {
    /// A load curve of `heights` on `model` with `solver`, every solve to `opts`.
    pub fn new(
        model: &'a Model,
        heights: &'a [f64],
        solver: Box<dyn Solver + Send>,
        opts: SolveOptions,
    ) -> Self {
        Self {
            model,
            heights,
            solver,
            opts,
            last: None,
        }
    }

    /// The options of every solve.
    pub fn opts(&self) -> &SolveOptions {
        &self.opts
    }

    /// Solves at mean pressure `p0` over the model's grid, warm-started from the last
    /// solution kept (cold before the first), stopped once `deadline` has passed;
    /// `monitor` sees every iteration first. The solution is the caller's to
    /// [`LoadCurve::keep`]; after a failure, [`LoadCurve::reject`].
    ///
    /// # Errors
    ///
    /// The problem's or the solver's error, or the time budget spent
    /// ([`SolveEnd::OutOfTime`]).
    pub fn solve(
        &mut self,
        p0: f64,
        deadline: Option<Instant>,
        monitor: &mut dyn FnMut(Progress) -> ControlFlow<StopReason>,
    ) -> std::result::Result<ContactSolution, SolveEnd> {
        let problem = ContactProblem::new(self.model, self.heights, p0).map_err(SolveEnd::Error)?;
        let start = self.last.as_ref().map_or(Start::Cold, Start::Warm);
        solve_bounded(
            self.solver.as_mut(),
            &problem,
            start,
            &self.opts,
            deadline,
            monitor,
        )
    }

    /// Keeps `solution` as the next solve's start.
    pub fn keep(&mut self, solution: ContactSolution) {
        self.last = Some(solution);
    }

    /// Drops what the solver carried from its last solve (GFMD's step): the next load
    /// starts warm from the last solution kept, with nothing from the solves after it.
    pub fn reject(&mut self) {
        self.solver.carry(None);
    }
}

/// `engine.solve_monitored`, stopped once `deadline` has passed: then the error says so,
/// with the iterations done and the last residual estimate. `monitor` sees every
/// iteration first, and may stop the solve itself (a cancel), which ends in its
/// [`Error::Stopped`].
///
/// # Errors
///
/// The solver's error, or the time budget spent ([`SolveEnd::OutOfTime`]).
pub fn solve_bounded(
    engine: &mut dyn Solver,
    problem: &ContactProblem,
    start: Start,
    opts: &SolveOptions,
    deadline: Option<Instant>,
    monitor: &mut dyn FnMut(Progress) -> ControlFlow<StopReason>,
) -> std::result::Result<ContactSolution, SolveEnd> {
    let run = engine.solve_monitored(problem, start, opts, &mut |p| {
        monitor(p)?;
        if deadline.is_some_and(|d| Instant::now() > d) {
            return ControlFlow::Break(StopReason::OutOfTime);
        }
        ControlFlow::Continue(())
    });
    match run {
        Ok(solution) => Ok(solution),
        Err(Error::Stopped {
            reason: StopReason::OutOfTime,
            iteration,
            residual,
            ..
        }) => Err(SolveEnd::OutOfTime(Progress {
            iteration,
            residual,
        })),
        Err(e) => Err(SolveEnd::Error(e)),
    }
}

/// How a bounded solve ended without a solution.
#[derive(Debug)]
pub enum SolveEnd {
    /// The solver's own error (or the problem's).
    Error(Error),
    /// Over the time budget, at this iteration and estimate.
    OutOfTime(Progress),
}

/// Whether `e` ends one solve only (the solver stopped: no convergence, a value not
/// finite, contact lost), rather than the whole curve (bad input, a cancel).
pub fn ends_the_solve(e: &Error) -> bool {
    matches!(
        e,
        Error::NotConverged { .. } | Error::NonFinite { .. } | Error::LostContact { .. }
    )
}
