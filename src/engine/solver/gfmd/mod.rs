//! Green's function molecular dynamics (GFMD): mass-weighted damped dynamics of the surface
//! displacement, with a momentum schedule and adaptive restart.
//!
//! The paper's method (section 2.3; Campana & Müser, PRB 74, 075420 (2006); Prodanov,
//! Dapp & Müser, Tribol. Lett. 53, 433 (2014)): damped Newtonian dynamics of the surface
//! displacement `u`, mass-weighted, against the hard wall, as in
//! [`super::dynamics`] (the elastic force, the masses, the wall's reaction and the points
//! it holds).
//!
//! # One step
//!
//! The state is the position `u` and the last displacement step `v = u_k - u_(k-1)` (the
//! velocity times the time step). A step ([`Dynamics`]) is four named parts:
//!
//! 1. the stress ([`State::stress`]) at the look-ahead position `y = max(u + beta v, h)`,
//!    with the equilibrium and load parts of the residual;
//! 2. the total force at `y`, with the wall's reaction, and its mass-weighted acceleration
//!    `a` ([`State::accelerate`]);
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
//! When both cheap residual parts are below the tolerance, the look-ahead position
//! becomes the state ([`Dynamics::settle`]: no momentum) and the full
//! [`Residual`](crate::engine::contact::Residual) of `(p, y)` is evaluated; it decides
//! convergence. If it fails, the dynamics goes on from
//! there.
//!
//! # Requirements
//!
//! * The model's stiffness `K` (the elastic force) and inverse masses `M^-1`
//!   ([`crate::engine::contact::Model::inverse_mass`]), both diagonal in reciprocal space;
//!   a free boundary's padded kernel gives both as a periodic one does.
//! * A positive load `p0`: it drives the rigid mode into the wall. A state whose contact
//!   set empties fails as [`crate::Error::LostContact`].
//! * A tolerance above the residual's rounding floor: below it the solve fails as
//!   [`Termination::Stalled`] with the residual it reached.
//! * A warm start from a solution on the problem's grid
//!   ([`crate::engine::solver::workspace`] checks it).
//!
//! # References
//!
//! * C. Campana and M. H. Müser, Phys. Rev. B 74, 075420 (2006): GFMD.
//! * N. Prodanov, W. B. Dapp and M. H. Müser, Tribol. Lett. 53, 433 (2014): GFMD for
//!   rough contact, the method of the paper.
//! * Y. Zhou, M. Moseler and M. H. Müser, Phys. Rev. B 99, 144103 (2019): mass weighting.
//! * Y. Nesterov, Soviet Math. Dokl. 27, 372 (1983); W. Su, S. Boyd and E. J. Candès,
//!   J. Mach. Learn. Res. 17, 1 (2016): the momentum schedule as damped dynamics.
//! * B. O'Donoghue and E. Candès, Found. Comput. Math. 15, 715 (2015): adaptive restart.
//! * D. P. Bertsekas, SIAM J. Control Optim. 20, 221 (1982): the two-metric projection
//!   (the points the wall holds).

use crate::engine::contact::ContactProblem;
use crate::engine::contact::ContactSolution;
use crate::engine::field::map_chunks_mut;
use crate::engine::solver::dynamics::{held, look_ahead, total_force, Balance, State};
use crate::engine::solver::executor::{Iteration, Judgement, Method};
use crate::engine::solver::workspace::Workspace;
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
    /// `u`, `v`, the stress and the acceleration (see [`State`]) and a half spectrum.
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
        let Gfmd {
            params,
            last_tau,
            work,
        } = self;
        let (state, warm) = State::start(Self::NAME, problem, start, opts, work)?;
        let tau = params.first_step(warm, *last_tau);
        Ok(Dynamics {
            state,
            momentum: Momentum::new(*params, tau),
            beta: 0.0,
            last_tau,
            stalled_at: f64::NAN,
        })
    }

    /// The step the last solve ended with: the next solve of a sweep starts from it.
    fn carried(&self) -> Option<f64> {
        self.last_tau
    }

    fn carry(&mut self, carried: Option<f64>) {
        self.last_tau = carried;
    }
}

/// One solve's state: the mass-weighted dynamics' state, the schedule, and the solver's
/// record of the step a solve ended with.
pub struct Dynamics<'a> {
    state: State<'a>,
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
        self.state.measure(self.beta, it)
    }

    fn estimate(balance: &Balance) -> f64 {
        balance.value()
    }

    /// When the cheap parts of the residual pass, the look-ahead position becomes the
    /// state and its full residual decides; if it fails, the dynamics goes on from there.
    fn judge(&mut self, it: usize, balance: &Balance) -> Judgement {
        if balance.value() <= self.state.tol {
            self.settle();
            let solution = self.state.solution(it);
            if solution.stats.residual.value() <= self.state.tol {
                *self.last_tau = Some(self.momentum.tau);
                return Judgement::Converged(solution);
            }
        }
        Judgement::Go
    }

    /// Steps 2 to 4; the step control may give up (the residual cannot improve).
    fn step(&mut self, _it: usize, balance: Balance) -> Result<Option<Termination>> {
        self.state.accelerate(self.beta, |force| force);
        let power = self.advance();
        if !self.momentum.control(power, balance.value()) {
            self.stalled_at = balance.value();
            return Ok(Some(Termination::Stalled));
        }
        self.beta = self.momentum.beta();
        Ok(None)
    }

    /// [`State::conclude`]; a solve that ends converged records its step.
    fn terminate(self, iterations: usize, reason: Termination) -> Result<ContactSolution> {
        let Dynamics {
            state,
            momentum,
            beta,
            last_tau,
            stalled_at,
        } = self;
        let accepted = state.conclude((iterations, reason), stalled_at, beta);
        if accepted.is_ok() {
            *last_tau = Some(momentum.tau);
        }
        accepted
    }
}

impl Dynamics<'_> {
    /// Step 3: the position moves to `max(y + tau a, h)`, points held by the wall stay on
    /// it; returns the power `F . (u_new - u_old)` of the step.
    fn advance(&mut self) -> f64 {
        let state = &mut self.state;
        let problem = state.problem;
        let (h, p0, beta, tau) = (problem.heights, problem.p0, self.beta, self.momentum.tau);
        let (a, ky) = (&*state.accel, &*state.stress);
        let powers = map_chunks_mut(
            state.u,
            state.v,
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
        self.state.settle(self.beta);
        self.beta = 0.0;
        self.momentum.restart();
    }
}
