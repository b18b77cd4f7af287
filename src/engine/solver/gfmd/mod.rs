//! Green's function molecular dynamics (GFMD): mass-weighted damped dynamics of the surface
//! displacement, with a momentum schedule and adaptive restart.
//!
//! The paper's method (section 2.3; Campana & Müser, PRB 74, 075420 (2006); Prodanov,
//! Dapp & Müser, Tribol. Lett. 53, 433 (2014)): damped Newtonian dynamics of the surface
//! displacement `u`, whose elastic force is diagonal in reciprocal space,
//!
//! ```text
//!     F~_el(q) = -(q E*/2) u~(q)    (q != 0),     F~_el(0) = -p0,
//! ```
//!
//! against a hard wall `u >= h` in real space. Mass weighting (Zhou, Moseler & Müser,
//! PRB 99, 144103 (2019)): `m(q) = q E*/2`, the rigid mode `q = 0` with the mass of the
//! softest non-zero mode, so that every free mode oscillates with one frequency; this is
//! what removes the `O(L)` critical slowing-down of real-space damped dynamics.
//!
//! # One step
//!
//! The state is the position `u` and the last displacement step `v = u_k - u_(k-1)` (the
//! velocity times the time step). A step ([`Dynamics`]) is four named parts:
//!
//! 1. [`Dynamics::stress`]: the look-ahead position `y = max(u + beta v, h)` and its
//!    stress `s = K y + p0` (one fused convolution), with the two parts of the residual
//!    GFMD does not satisfy by construction (equilibrium and load) for the pressure
//!    `p = max(s, 0)` on the wall and 0 elsewhere;
//! 2. [`Dynamics::acceleration`]: the total force `F = -s`, except on the wall, where the
//!    wall's reaction cancels a compressive stress (`F = max(-s, 0)`), and the
//!    mass-weighted acceleration `a~(q) = F~(q) / m(q)` (one fused convolution; the
//!    inverse masses are the model's,
//!    [`Model::inverse_mass`](crate::engine::contact::Model::inverse_mass));
//! 3. [`Dynamics::advance`]: `u <- max(y + tau a, h)`, except at points held by the wall
//!    (on it under a compressive stress, `s >= 0`), which stay put; `v` becomes the step
//!    taken;
//! 4. [`Momentum::control`]: the damping schedule `beta` of the next step.
//!
//! The executor ([`crate::engine::solver::executor`]) runs them: step 1 is the measure,
//! the convergence check below the judgement, steps 2 to 4 the step.
//!
//! With `beta = 0` this is a damped (overdamped) dynamics step of length `tau` in units of
//! the squared mode period; with `beta_k = k / (k + 3)` it is Nesterov's accelerated
//! gradient (Nesterov 1983), which is damped Newtonian dynamics whose friction decays as
//! `3 / t` (Su, Boyd & Candès, JMLR 17, 1 (2016)). The friction schedule restarts
//! (O'Donoghue & Candès, Found. Comput. Math. 15, 715 (2015)) when the force opposes the
//! last step (`F . v <= 0`, FIRE's power criterion), so the dynamics never climbs.
//!
//! # Step control
//!
//! On the free points near the contact patches the hard wall makes modes stiffer than the
//! free modes (the constrained operator `(M^-1)_ff K_ff` has eigenvalues above 1 in the
//! mass metric; about 2 to 6 for contact sets like a random surface's), so a step of one
//! squared period (`tau = 1`, the exact step of the unconstrained problem) is unstable:
//! momentum methods are stable for `tau lambda_max` below about 4/3. How stiff the
//! stiffest mode is depends on the contact set, which changes during a solve, so the step
//! adapts ([`GfmdParams`]; the constants and where their values come from are in
//! [`control`]). It starts at `tau` (0.3, measured best on the speed study's scenes); it
//! shrinks (by `shrink`, and the momentum restarts) when the residual shows a
//! mode that the step makes unstable: the residual zigzags (rises and falls in turn) for
//! `zigzag_window` steps, or rises for `rise_window` steps in a row to above twice its
//! low, or reaches no new low for `stall_window` steps (a limit cycle through the wall);
//! at every new low it grows back by `regrow`, up to where it started. `beta` stays below
//! `beta_max`: the schedule's limit, 1, is optimal only for problems without a smallest
//! curvature, and without a cap a smooth, slow mode is never restarted. A solver used for
//! a sequence of solves (a magnification sweep) begins each solve one shrink above where
//! the last one ended. A step that shrinks below `tau_floor` times the first means the
//! residual cannot improve (a tolerance below its rounding floor): the solve fails as
//! [`Termination::Stalled`] with the residual reached.
//!
//! The wall reaction must be part of `F` before the mass filter is applied: the filter is
//! non-local, and an unbalanced push at contact points would otherwise drive the free
//! points next to them into the wall. Holding the points the wall pushes is Bertsekas'
//! two-metric projection (SIAM J. Control Optim. 20, 221 (1982)): the non-local metric
//! acts on the free points only.
//!
//! When both cheap residual parts are below the tolerance, the look-ahead position
//! becomes the state ([`Dynamics::settle`]: no momentum) and the full [`Residual`] of
//! `(p, y)` is evaluated; it decides convergence. If it fails, the dynamics goes on from
//! there.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use crate::engine::contact::{ContactProblem, ContactSolution, Residual};
use crate::engine::fft::{FusedPass, Kernel};
use crate::engine::field::map_chunks_mut;
use crate::engine::solver::executor::{Iteration, Method, Verdict};
use crate::engine::solver::workspace::{warm_start, Record, Workspace};
use crate::engine::solver::{SolveOptions, Start};
use crate::error::{Result, Termination};

pub mod control;

pub use self::control::GfmdParams;
use self::control::Momentum;

/// GFMD solver with its work buffers.
#[derive(Debug, Clone, Default)]
pub struct Gfmd {
    /// Step and step control.
    pub params: GfmdParams,
    /// The step the last solve ended with (a sweep's next solve begins one shrink above).
    last_tau: Option<f64>,
    /// `u`, `v`, the stress and the acceleration (see [`Dynamics`]) and a half spectrum.
    work: Workspace<4>,
}

impl Method for Gfmd {
    const NAME: &'static str = "gfmd";
    /// From a 300-shell sweep segment at 512^2 (zeta 20 -> 25.7, tol 1e-6) in which GFMD
    /// took 1.13 times CG's time (2.9 times with the FIRE dynamics the planning constants
    /// were first fitted to), rounded up.
    const RELATIVE_COST: f64 = 1.2;
    type Solve<'a> = Dynamics<'a>;

    /// The state at `start`: every point on the wall from cold; warm, the previous
    /// displacement, with the previous contact set exactly on the wall (a displacement
    /// carried over, or predicted, differs from the heights by rounding). No momentum.
    fn init<'a>(
        &'a mut self,
        problem: &'a ContactProblem<'a>,
        start: Start,
        opts: &SolveOptions,
    ) -> Result<Dynamics<'a>> {
        let record = Record::begin(Self::NAME, matches!(start, Start::Warm(_)));
        let grid = &problem.model.grid;
        let h = problem.heights;
        let prev = warm_start(start, grid)?;
        let Gfmd {
            params,
            last_tau,
            work,
        } = self;
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
        let tau = params.first_step(prev.is_some(), *last_tau);
        Ok(Dynamics {
            problem,
            inverse_mass: problem.model.inverse_mass(),
            record,
            tol: opts.tol,
            spec,
            u,
            v,
            stress,
            accel,
            momentum: Momentum::new(*params, tau),
            beta: 0.0,
            last_tau,
            stalled_at: f64::NAN,
        })
    }
}

/// Whether a point at `y` is on the wall at `h`.
#[inline]
fn on_wall(y: f64, h: f64) -> bool {
    y <= h
}

/// The look-ahead position `y = max(u + beta v, h)` of one point.
#[inline]
fn look_ahead(u: f64, v: f64, beta: f64, h: f64) -> f64 {
    (u + beta * v).max(h)
}

/// The contact pressure at a point at `y` (wall at `h`) under the stress `s`: the
/// compressive stress on the wall, 0 elsewhere.
#[inline]
fn pressure(y: f64, h: f64, s: f64) -> f64 {
    if on_wall(y, h) {
        s.max(0.0)
    } else {
        0.0
    }
}

/// The total force at a point at `y` (wall at `h`) under the stress `s`: `-s`, and on the
/// wall only what pulls the point off it.
#[inline]
fn total_force(y: f64, h: f64, s: f64) -> f64 {
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
fn held(y: f64, h: f64, s: f64) -> bool {
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

/// The equilibrium and load parts of the residual at the look-ahead position.
#[derive(Debug, Clone, Copy)]
pub struct Balance {
    equilibrium: f64,
    load: f64,
    finite: bool,
}

impl Balance {
    fn value(&self) -> f64 {
        self.equilibrium.max(self.load)
    }
}

/// The look-ahead positions `y = max(u + beta v, h)` of a step, row by row.
#[derive(Clone, Copy)]
struct LookAhead<'a> {
    u: &'a [f64],
    v: &'a [f64],
    h: &'a [f64],
    beta: f64,
    n: usize,
}

impl<'a> LookAhead<'a> {
    /// The look-ahead `max(u + beta v, h)` of `problem`'s heights.
    fn new(problem: &'a ContactProblem, u: &'a [f64], v: &'a [f64], beta: f64) -> Self {
        Self {
            u,
            v,
            h: problem.heights,
            beta,
            n: problem.model.grid.n(),
        }
    }

    /// Row `i` of `u`, `v` and `h`.
    #[inline(always)]
    fn row(&self, i: usize) -> (&'a [f64], &'a [f64], &'a [f64]) {
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
struct ForcePass<'a> {
    at: LookAhead<'a>,
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

/// One solve's state: the problem, the fields, the masses and the schedule.
pub struct Dynamics<'a> {
    problem: &'a ContactProblem<'a>,
    inverse_mass: &'a Kernel,
    record: Record,
    tol: f64,
    spec: &'a mut [Complex64],
    /// Position `u`.
    u: &'a mut [f64],
    /// Last step `u_k - u_(k-1)`.
    v: &'a mut [f64],
    /// `K y` at the look-ahead position (the stress without `p0`).
    stress: &'a mut [f64],
    /// Mass-weighted acceleration at the look-ahead position.
    accel: &'a mut [f64],
    momentum: Momentum,
    /// `beta` of the current look-ahead.
    beta: f64,
    /// The solver's record of the step a solve ended with, set when one converges.
    last_tau: &'a mut Option<f64>,
    /// The residual estimate of the step after which the step control gave up.
    stalled_at: f64,
}

impl Iteration for Dynamics<'_> {
    type Measure = Balance;

    /// Step 1, and an error when the stress is not finite.
    fn measure(&mut self, it: usize) -> Result<Balance> {
        let balance = self.stress();
        if !balance.finite {
            return Err(self.record.non_finite("stress", it));
        }
        Ok(balance)
    }

    fn estimate(balance: &Balance) -> f64 {
        balance.value()
    }

    /// When the cheap parts of the residual pass, the look-ahead position becomes the
    /// state and its full residual decides; if it fails, the dynamics goes on from there.
    fn judge(&mut self, it: usize, balance: &Balance) -> Verdict {
        if balance.value() <= self.tol {
            self.settle();
            let solution = self.solution(it);
            if solution.stats.residual.value() <= self.tol {
                *self.last_tau = Some(self.momentum.tau);
                return Verdict::Converged(solution);
            }
        }
        Verdict::Go
    }

    /// Steps 2 to 4; the step control may give up (the residual cannot improve).
    fn step(&mut self, _it: usize, balance: Balance) -> Result<Option<Termination>> {
        self.acceleration();
        let power = self.advance();
        if !self.momentum.control(power, balance.value()) {
            self.stalled_at = balance.value();
            return Ok(Some(Termination::Stalled));
        }
        self.beta = self.momentum.beta();
        Ok(None)
    }

    /// A stalled solve fails with the estimate it stalled at; at the end of the budget
    /// the state the last step reached may have converged, and if not the error reports
    /// its residual.
    fn terminate(mut self, iterations: usize, reason: Termination) -> Result<ContactSolution> {
        if reason != Termination::BudgetExhausted {
            return Err(self
                .record
                .not_converged((iterations, reason), self.stalled_at, self.tol));
        }
        self.measure(iterations)?;
        self.settle();
        let solution = self.solution(iterations);
        let accepted = self
            .record
            .accept(solution, self.tol, (iterations, reason), None);
        if accepted.is_ok() {
            *self.last_tau = Some(self.momentum.tau);
        }
        accepted
    }
}

impl Dynamics<'_> {
    /// Step 1: the look-ahead position's stress, and its equilibrium and load residuals.
    fn stress(&mut self) -> Balance {
        let problem = self.problem;
        let model = problem.model;
        let pass = StressPass {
            at: LookAhead::new(problem, self.u, self.v, self.beta),
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

    /// Step 2: the total force at the look-ahead position, with the wall's reaction, and
    /// its mass-weighted acceleration.
    fn acceleration(&mut self) {
        let problem = self.problem;
        let model = problem.model;
        let pass = ForcePass {
            at: LookAhead::new(problem, self.u, self.v, self.beta),
            stress: self.stress,
            p0: self.problem.p0,
        };
        model
            .fft
            .convolve(self.inverse_mass, self.spec, None, &pass, self.accel);
    }

    /// Step 3: the position moves to `max(y + tau a, h)`, points held by the wall stay on
    /// it; returns the power `F . (u_new - u_old)` of the step.
    fn advance(&mut self) -> f64 {
        let problem = self.problem;
        let (h, p0, beta, tau) = (problem.heights, problem.p0, self.beta, self.momentum.tau);
        let (a, ky) = (&*self.accel, &*self.stress);
        let powers = map_chunks_mut(
            self.u,
            self.v,
            #[inline(always)]
            |range, uc, vc| {
                let (h, ky, a) = (&h[range.clone()], &ky[range.clone()], &a[range]);
                let mut power = 0.0;
                for ((((ui, vi), &hi), &k), &ai) in
                    uc.iter_mut().zip(vc.iter_mut()).zip(h).zip(ky).zip(a)
                {
                    let y = look_ahead(*ui, *vi, beta, hi);
                    let s = k + p0;
                    let next = if held(y, hi, s) {
                        hi
                    } else {
                        (y + tau * ai).max(hi)
                    };
                    power += total_force(y, hi, s) * (next - *ui);
                    *vi = next - *ui;
                    *ui = next;
                }
                power
            },
        );
        powers.iter().sum()
    }

    /// The look-ahead position becomes the state, without momentum (before its full
    /// residual is evaluated).
    fn settle(&mut self) {
        let (h, beta) = (self.problem.heights, self.beta);
        self.u
            .par_iter_mut()
            .zip(self.v.par_iter_mut())
            .zip(h.par_iter())
            .for_each(|((u, v), &hi)| {
                *u = look_ahead(*u, *v, beta, hi);
                *v = 0.0;
            });
        self.beta = 0.0;
        self.momentum.restart();
    }

    /// The state, settled on its look-ahead position, and its pressure as a solution with
    /// its residual (the spectrum and the acceleration are work space for it).
    fn solution(&mut self, iterations: usize) -> ContactSolution {
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
