//! Mass-weighted dynamics of the surface displacement against the hard wall: what every
//! dynamics method shares ([`super::Gfmd`]'s momentum schedule, [`super::Fire`]'s
//! velocity mixing).
//!
//! The surface displacement `u` moves under its elastic force, which is diagonal in
//! reciprocal space,
//!
//! ```text
//!     F~_el(q) = -(q E*/2) u~(q)    (q != 0),     F~_el(0) = -p0,
//! ```
//!
//! against a hard wall `u >= h` in real space (the paper, section 2.3; Campana & Müser,
//! PRB 74, 075420 (2006)). Mass weighting (Zhou, Moseler & Müser, PRB 99, 144103 (2019)):
//! `m(q) = q E*/2`, the rigid mode `q = 0` with the mass of the softest non-zero mode, so
//! that every free mode oscillates with one frequency; this is what removes the `O(L)`
//! critical slowing-down of real-space damped dynamics. Times are in units of the inverse
//! of that frequency.
//!
//! A method's state is the position `u` and a second field `v` (GFMD: the last step;
//! FIRE: the velocity), in a [`State`]. What a step of every method takes from here:
//!
//! 1. [`State::stress`]: a position `y = max(u + beta v, h)` (GFMD's look-ahead; `y = u`
//!    with `beta = 0`) and its stress `s = K y + p0` (one fused convolution), with the two
//!    parts of the residual the dynamics does not satisfy by construction (equilibrium and
//!    load, [`Balance`]) for the pressure `p = max(s, 0)` on the wall and 0 elsewhere;
//! 2. [`State::accelerate`]: the total force `F = -s`, except on the wall, where the
//!    wall's reaction cancels a compressive stress (`F = max(-s, 0)`), and the
//!    mass-weighted acceleration `a~(q) = F~(q) / m(q)` (one fused convolution; the
//!    inverse masses are the model's,
//!    [`Model::inverse_mass`](crate::engine::contact::Model::inverse_mass));
//! 3. the method's own move of `u`, in which points held by the wall ([`held`]: on it
//!    under a compressive stress, `s >= 0`) stay put and every other point stays above it
//!    (`u <- max(..., h)`).
//!
//! The wall reaction must be part of `F` before the mass filter is applied: the filter is
//! non-local, and an unbalanced push at contact points would otherwise drive the free
//! points next to them into the wall. Holding the points the wall pushes is Bertsekas'
//! two-metric projection (SIAM J. Control Optim. 20, 221 (1982)): the non-local metric
//! acts on the free points only.
//!
//! When both cheap residual parts are below the tolerance, the full [`Residual`] of the
//! state ([`State::solution`]) decides convergence.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use crate::engine::contact::{ContactProblem, ContactSolution, Residual};
use crate::engine::fft::{FusedPass, Kernel, PassValues};
use crate::engine::solver::workspace::{warm_start, SolveRecord, Workspace};
use crate::engine::solver::{SolveOptions, Start};
use crate::error::{Result, Termination};

/// One solve's state: the problem, the masses, the fields, and the record of the solve.
pub(super) struct State<'a> {
    pub(super) problem: &'a ContactProblem<'a>,
    inverse_mass: &'a Kernel,
    pub(super) record: SolveRecord,
    pub(super) tol: f64,
    spec: &'a mut [Complex64],
    /// Position `u`.
    pub(super) u: &'a mut [f64],
    /// The method's second field (GFMD: the last step; FIRE: the velocity).
    pub(super) v: &'a mut [f64],
    /// `K y` at the position of the last [`State::stress`] (the stress without `p0`).
    pub(super) stress: &'a mut [f64],
    /// Mass-weighted acceleration at that position.
    pub(super) accel: &'a mut [f64],
}

impl<'a> State<'a> {
    /// The state at `start` for a solve by the method `name`, in `work` (`u`, `v`, the
    /// stress, the acceleration and a half spectrum), and whether it starts warm: every
    /// point on the wall from cold; warm, the previous displacement, with the previous
    /// contact set exactly on the wall (a displacement carried over, or predicted, differs
    /// from the heights by rounding). `v = 0`.
    pub(super) fn start(
        name: &'static str,
        problem: &'a ContactProblem<'a>,
        start: Start,
        opts: &SolveOptions,
        work: &'a mut Workspace<4>,
    ) -> Result<(Self, bool)> {
        let record = SolveRecord::begin(name, matches!(start, Start::Warm(_)));
        let grid = &problem.model.grid;
        let h = problem.heights;
        let prev = warm_start(start, grid)?;
        let (spec, [u, v, stress, accel]) = work.on(grid);
        match prev {
            None => problem.cold_displacement(u),
            Some(prev) => u
                .par_iter_mut()
                .zip(prev.displacement.par_iter().zip(&prev.pressure))
                .zip(h)
                .for_each(|((u, (&v, &p)), &hh)| *u = if p > 0.0 { hh } else { v.max(hh) }),
        }
        v.fill(0.0);
        let state = State {
            problem,
            inverse_mass: problem.model.inverse_mass(),
            record,
            tol: opts.tol,
            spec,
            u,
            v,
            stress,
            accel,
        };
        Ok((state, prev.is_some()))
    }

    /// Step 1 as the measure of an iteration `it`: [`State::stress`], and an error when
    /// the stress is not finite.
    pub(super) fn measure(&mut self, beta: f64, it: usize) -> Result<Balance> {
        let balance = self.stress(beta);
        if !balance.finite {
            return Err(self.record.non_finite("stress", it));
        }
        Ok(balance)
    }

    /// Step 1: the stress of the position `max(u + beta v, h)`, and its equilibrium and
    /// load residuals.
    pub(super) fn stress(&mut self, beta: f64) -> Balance {
        let problem = self.problem;
        let model = problem.model;
        let pass = StressPass {
            at: LookAhead::new(problem, self.u, self.v, beta),
            p0: problem.p0,
        };
        let (_, rows) = model
            .fft
            .convolve(&model.stiffness, self.spec, None, &pass, self.stress);
        let sums = rows
            .into_iter()
            .fold(BalanceSums::default(), BalanceSums::add);
        let npts = problem.heights.len() as f64;
        // Where no point is pressed, the full residual measures the stress against p0;
        // this estimate only keeps its scale off zero. The two differ only there, where
        // the estimate's larger value steers the step control: kept as it is.
        let rms_p = Residual::rms_of(sums.sum_p2, npts).max(f64::MIN_POSITIVE);
        Balance {
            equilibrium: Residual::equilibrium_of(sums.unbalanced, npts, rms_p),
            load: Residual::load_of(sums.sum_p, npts, problem.p0),
            finite: !sums.nonfinite,
        }
    }

    /// Step 2: the total force at the position `max(u + beta v, h)` of the last
    /// [`State::stress`], with the wall's reaction, and its mass-weighted acceleration,
    /// through the pass `fused(force)` makes of the force's pass (the force's own, or one
    /// that also sums what the method needs); returns what that pass returned.
    pub(super) fn accelerate<'s, P: FusedPass>(
        &'s mut self,
        beta: f64,
        fused: impl FnOnce(ForcePass<'s>) -> P,
    ) -> PassValues<P> {
        let problem = self.problem;
        let model = problem.model;
        let pass = fused(ForcePass {
            at: LookAhead::new(problem, self.u, self.v, beta),
            stress: self.stress,
            p0: problem.p0,
        });
        model
            .fft
            .convolve(self.inverse_mass, self.spec, None, &pass, self.accel)
    }

    /// The position `max(u + beta v, h)` becomes the state, at rest (`v = 0`).
    pub(super) fn settle(&mut self, beta: f64) {
        let h = self.problem.heights;
        self.u
            .par_iter_mut()
            .zip(self.v.par_iter_mut())
            .zip(h.par_iter())
            .for_each(|((u, v), &hi)| {
                *u = look_ahead(*u, *v, beta, hi);
                *v = 0.0;
            });
    }

    /// The end of a solve stopped after `iterations` iterations for `reason`: a stalled
    /// solve fails with `stalled_at`, the estimate it stalled at; at the end of the budget
    /// the position `max(u + beta v, h)` the last step reached may have converged, and if
    /// not the error reports its residual.
    pub(super) fn conclude(
        mut self,
        (iterations, reason): (usize, Termination),
        stalled_at: f64,
        beta: f64,
    ) -> Result<ContactSolution> {
        let tol = self.tol;
        if reason != Termination::BudgetExhausted {
            return Err(self
                .record
                .not_converged((iterations, reason), stalled_at, tol));
        }
        self.measure(beta, iterations)?;
        self.settle(beta);
        let solution = self.solution(iterations);
        self.record
            .accept(solution, tol, (iterations, reason), None)
    }

    /// The state, at the position of the last [`State::stress`] (`u` itself), and its
    /// pressure as a solution with its residual (the spectrum and the acceleration are
    /// work space for it).
    pub(super) fn solution(&mut self, iterations: usize) -> ContactSolution {
        let problem = self.problem;
        let (h, p0) = (problem.heights, problem.p0);
        let pressure: Vec<f64> = self
            .u
            .par_iter()
            .zip(self.stress.par_iter().zip(h))
            .map(|(&u, (&k, &hh))| pressure(u, hh, k + p0))
            .collect();
        let displacement = self.u.to_vec();
        self.record.solution(
            problem,
            (pressure, displacement),
            iterations,
            self.spec,
            self.accel,
        )
    }
}

/// Whether a point at `y` is on the wall at `h`.
#[inline]
pub(super) fn on_wall(y: f64, h: f64) -> bool {
    y <= h
}

/// The look-ahead position `y = max(u + beta v, h)` of one point.
#[inline]
pub(super) fn look_ahead(u: f64, v: f64, beta: f64, h: f64) -> f64 {
    (u + beta * v).max(h)
}

/// The contact pressure at a point at `y` (wall at `h`) under the stress `s`: the
/// compressive stress on the wall, 0 elsewhere.
#[inline]
pub(super) fn pressure(y: f64, h: f64, s: f64) -> f64 {
    if on_wall(y, h) {
        s.max(0.0)
    } else {
        0.0
    }
}

/// The total force at a point at `y` (wall at `h`) under the stress `s`: `-s`, and on the
/// wall only what pulls the point off it.
#[inline]
pub(super) fn total_force(y: f64, h: f64, s: f64) -> f64 {
    if on_wall(y, h) {
        (-s).max(0.0)
    } else {
        -s
    }
}

/// Whether the wall holds a point at `y` (wall at `h`) under the finite stress `s`: on the
/// wall under a compressive (or zero) stress, which the wall's reaction cancels, so that
/// the total force vanishes. For finite `s` this is `total_force(y, h, s) == 0` exactly:
/// on the wall `max(-s, 0)` is a zero just when `-s <= 0`.
#[inline]
pub(super) fn held(y: f64, h: f64, s: f64) -> bool {
    on_wall(y, h) && s >= 0.0
}

/// Sums of the stress pass from which the equilibrium and load residuals follow.
#[derive(Debug, Clone, Copy, Default)]
struct BalanceSums {
    unbalanced: f64,
    sum_p: f64,
    sum_p2: f64,
    nonfinite: bool,
}

impl BalanceSums {
    fn add(self, o: Self) -> Self {
        Self {
            unbalanced: self.unbalanced + o.unbalanced,
            sum_p: self.sum_p + o.sum_p,
            sum_p2: self.sum_p2 + o.sum_p2,
            nonfinite: self.nonfinite || o.nonfinite,
        }
    }
}

/// The equilibrium and load parts of the residual at the position whose stress was taken.
#[derive(Debug, Clone, Copy)]
pub struct Balance {
    equilibrium: f64,
    load: f64,
    pub(super) finite: bool,
}

impl Balance {
    /// The larger part: the estimate the methods watch.
    pub(super) fn value(&self) -> f64 {
        self.equilibrium.max(self.load)
    }
}

/// The look-ahead positions `y = max(u + beta v, h)` of a step, row by row.
#[derive(Clone, Copy)]
pub(super) struct LookAhead<'a> {
    pub(super) u: &'a [f64],
    pub(super) v: &'a [f64],
    h: &'a [f64],
    beta: f64,
    pub(super) n: usize,
}

impl<'a> LookAhead<'a> {
    /// The look-ahead `max(u + beta v, h)` of `problem`'s heights.
    fn new(problem: &'a ContactProblem, u: &'a [f64], v: &'a [f64], beta: f64) -> Self {
        Self {
            u,
            v,
            h: problem.heights,
            beta,
            n: problem.model.grid.cols(),
        }
    }

    /// Row `i` of `u`, `v` and `h`.
    #[inline(always)]
    pub(super) fn row(&self, i: usize) -> (&'a [f64], &'a [f64], &'a [f64]) {
        let rg = i * self.n..(i + 1) * self.n;
        (&self.u[rg.clone()], &self.v[rg.clone()], &self.h[rg])
    }
}

/// Step 1 as the fused pass of `K y`: the look-ahead position generated, the sums of
/// [`Balance`] taken over its stress `s = K y + p0`.
struct StressPass<'a> {
    at: LookAhead<'a>,
    p0: f64,
}

impl FusedPass for StressPass<'_> {
    type Generated = ();
    type Consumed = BalanceSums;

    #[inline(always)]
    fn generate(&self, i: usize, row: &mut [f64], _: &mut [f64], _: &[f64]) {
        let beta = self.at.beta;
        let (u, v, h) = self.at.row(i);
        for (((y, &ui), &vi), &hi) in row.iter_mut().zip(u).zip(v).zip(h) {
            *y = look_ahead(ui, vi, beta, hi);
        }
    }

    #[inline(always)]
    fn consume(&self, i: usize, ky: &[f64], _: &[f64]) -> BalanceSums {
        let (beta, p0) = (self.at.beta, self.p0);
        let (u, v, h) = self.at.row(i);
        let mut acc = BalanceSums::default();
        for (((&k, &ui), &vi), &hi) in ky.iter().zip(u).zip(v).zip(h) {
            let s = k + p0;
            let p = pressure(look_ahead(ui, vi, beta, hi), hi, s);
            acc.unbalanced += (s - p) * (s - p);
            acc.sum_p += p;
            acc.sum_p2 += p * p;
            acc.nonfinite |= !s.is_finite();
        }
        acc
    }
}

/// Step 2 as the fused pass of `M^-1 F`: the total force at the look-ahead position, with
/// the wall's reaction, generated from its stress.
pub(super) struct ForcePass<'a> {
    pub(super) at: LookAhead<'a>,
    /// `K y` at the look-ahead position.
    stress: &'a [f64],
    p0: f64,
}

impl FusedPass for ForcePass<'_> {
    type Generated = ();
    type Consumed = ();

    #[inline(always)]
    fn generate(&self, i: usize, row: &mut [f64], _: &mut [f64], _: &[f64]) {
        let (beta, p0, n) = (self.at.beta, self.p0, self.at.n);
        let (u, v, h) = self.at.row(i);
        let ky = &self.stress[i * n..(i + 1) * n];
        for ((((f, &ui), &vi), &hi), &k) in row.iter_mut().zip(u).zip(v).zip(h).zip(ky) {
            *f = total_force(look_ahead(ui, vi, beta, hi), hi, k + p0);
        }
    }

    fn consume(&self, _: usize, _: &[f64], _: &[f64]) {}
}
