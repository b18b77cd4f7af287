//! When a CG solve stops (see "Stopping" in the module docs): the estimate's target and
//! the stagnation safeguard, the convergence check, and the packaging of the state into
//! a solution.

use rayon::prelude::*;

use super::sums::View;
use super::{Solve, DAMPING};
use crate::engine::contact::ContactSolution;
use crate::engine::solver::executor::Judgement;
use crate::error::{Result, Termination};

/// An estimate counts as progress when it is below this fraction of the best before it
/// (a halving): the stagnation safeguard's measure, not a tuned value.
const PROGRESS: f64 = 0.5;
/// When the full residual fails although the estimate met its target, the target is
/// lowered by this factor and the solve goes on: a safeguard, not a tuned value.
const TARGET_CUT: f64 = 0.25;

/// The stopping bookkeeping of a solve.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stopping {
    /// The requested tolerance of the full residual.
    tol: f64,
    /// The estimate's target: the tolerance, lowered each time the full residual fails.
    target: f64,
    /// The lowest estimate that halved the one before, and its iteration.
    best: f64,
    best_at: usize,
    /// Smallest full residual evaluated.
    reached: f64,
    /// Iterations without progress before a safeguard acts
    /// ([`super::ConstrainedCg::stagnation`]).
    window: usize,
}

impl Stopping {
    pub(super) fn new(tol: f64, window: usize) -> Self {
        Self {
            window,
            tol,
            target: tol,
            best: f64::INFINITY,
            best_at: 0,
            reached: f64::INFINITY,
        }
    }

    /// Records the estimate of iteration `it`; true when it has not halved for the
    /// window's iterations.
    fn stagnant(&mut self, it: usize, estimate: f64) -> bool {
        if estimate < PROGRESS * self.best {
            self.best = estimate;
            self.best_at = it;
            false
        } else {
            it - self.best_at > self.window
        }
    }
}

impl Solve<'_> {
    /// The safeguards of "Stopping", when the estimate stops improving: first, if the
    /// estimate has never met the tolerance (a cycle, not the rounding floor), the step
    /// length is damped ([`DAMPING`]: the full step may cycle); if it stagnates again
    /// without meeting it, the load is restored by projection from then on
    /// ([`Solve::project_load`]: the rescaling may cycle); then a preconditioned
    /// solve goes on with plain Polonsky-Keer, which always converges (slowly); an
    /// unpreconditioned one whose full residual has already failed has stalled (true).
    pub(super) fn safeguard(&mut self, it: usize, estimate: f64) -> bool {
        if !self.stopping.stagnant(it, estimate) {
            return false;
        }
        if self.damping == 1.0 && self.stopping.target == self.stopping.tol {
            self.damping = DAMPING;
            self.conjugate = false;
            self.stopping.best_at = it;
            false
        } else if !self.project && self.stopping.target == self.stopping.tol {
            self.project = true;
            self.conjugate = false;
            self.stopping.best_at = it;
            false
        } else if self.precond {
            self.precond = false;
            self.conjugate = false;
            self.stopping.best_at = it;
            false
        } else {
            self.stopping.target < self.stopping.tol
        }
    }

    /// The convergence check of "Stopping": when the estimate is below its target, `u`
    /// is made exact and, if the estimate still holds, the full residual is evaluated;
    /// if that fails, the target is lowered and the iteration goes on. When the estimate
    /// no longer holds for the exact state, that state is measured again, as the next
    /// iteration.
    pub(super) fn check(&mut self, it: usize, estimate: f64) -> Judgement {
        if estimate <= self.stopping.target {
            if !self.exact {
                self.exact_displacement();
                // The estimate of the exact state, without the preconditioner's
                // transforms: if it still holds, the solve is done.
                let view = View::new(&self.p[..], &self.u[..], self.problem.heights, self.frame);
                if view.gap_sums().estimate(self.problem.length_scale) > self.stopping.target {
                    return Judgement::Remeasure;
                }
            }
            let solution = self.finish(it);
            let residual = solution.stats.residual.value();
            if residual <= self.stopping.tol {
                return Judgement::Converged(solution);
            }
            self.stopping.reached = self.stopping.reached.min(residual);
            self.stopping.target *= TARGET_CUT;
            self.resume(solution);
        }
        Judgement::Go
    }

    /// Packs the current state into a solution with its residual, moving `p` and `u`
    /// into it.
    fn finish(&mut self, iterations: usize) -> ContactSolution {
        let (scale, gbar) = (self.frame.scale, self.frame.gbar);
        // The solution takes the solver's buffers rather than copying them (16 bytes per
        // point at the peak); `resume` hands them back when the solve must go on.
        let mut pressure = std::mem::take(&mut *self.p);
        let mut displacement = std::mem::take(&mut *self.u);
        pressure.par_iter_mut().for_each(|p| *p *= scale);
        displacement
            .par_iter_mut()
            .for_each(|u| *u = scale * *u - gbar);
        self.record.solution(
            self.problem,
            (pressure, displacement),
            iterations,
            &mut self.spec[..],
            &mut self.r[..],
        )
    }

    /// Takes back the buffers of a [`Self::finish`]ed state to iterate on (the load scale
    /// is then 1, and the rigid shift the one it was packed with).
    fn resume(&mut self, solution: ContactSolution) {
        *self.p = solution.pressure;
        *self.u = solution.displacement;
        let gbar = self.frame.gbar;
        self.u.par_iter_mut().for_each(|u| *u += gbar);
        self.frame.scale = 1.0;
    }

    /// The end of a solve stopped after `iterations` iterations for `reason` (budget
    /// exhausted or stalled): the last step may have converged; if not, the error reports
    /// the smallest residual reached, the exact state's or an earlier one's.
    pub(super) fn conclude(
        mut self,
        iterations: usize,
        reason: Termination,
    ) -> Result<ContactSolution> {
        self.exact_displacement();
        let solution = self.finish(iterations);
        self.record.accept(
            solution,
            self.stopping.tol,
            (iterations, reason),
            Some(self.stopping.reached),
        )
    }
}
