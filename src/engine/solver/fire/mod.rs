//! FIRE, the fast inertial relaxation engine (Bitzek, Koskinen, Gähler, Moseler & Gumbsch,
//! PRL 97, 170201 (2006)), on GFMD's masses: the mass-weighted dynamics of
//! [`super::dynamics`] (Zhou, Moseler & Müser, PRB 99, 144103 (2019), relax mass-weighted
//! GFMD with FIRE), with FIRE's velocity mixing and adaptive time step in place of GFMD's
//! momentum schedule.
//!
//! # One step
//!
//! The state is the position `u` and the velocity `w`. A step ([`Relaxation`]):
//!
//! 1. the stress at `u` ([`State::stress`] with no look-ahead), with the equilibrium and
//!    load parts of the residual;
//! 2. the total force `F` at `u`, with the wall's reaction, and its mass-weighted
//!    acceleration `a` ([`State::accelerate`]), summing the power `P = F . w` and the
//!    products `w . w`, `w . a`, `a . a` as the passes generate and consume the rows;
//! 3. the schedule ([`Control::next`]): `P > 0` keeps the velocity, and after
//!    `n_delay` such steps lets `dt` grow and `alpha` shrink; `P <= 0` drops the velocity
//!    (`w = 0`), shrinks `dt` and restarts `alpha`; the constants, and where their values
//!    come from, are in [`control`];
//! 4. [`Relaxation::advance`], semi-implicit Euler with FIRE's mixing:
//!    `w' = w + dt a` (`dt a` after a restart), `w'' = (1 - alpha) w' + alpha |w'| a / |a|`,
//!    and `u <- max(u + dt w'', h)`, except at points held by the wall (on it under a
//!    compressive stress), which stay put (`w = 0`); a point the wall stops keeps the
//!    velocity of the move it took, `(h - u) / dt`, and every other point `w''` (which
//!    may move it by less than the rounding of `u` for a while: the velocity keeps what the
//!    position cannot show yet).
//!
//! FIRE mixes the velocity towards the force's direction; here that direction is the
//! mass-weighted acceleration `a = M^-1 F` (the steepest descent in the mass metric), and
//! `|w'|` and `|a|` are real-space norms, both known from the sums of step 2 before the
//! move (`|w'|^2 = w.w + 2 dt w.a + dt^2 a.a`). A step is two fused convolutions and one
//! sweep over the fields, as GFMD's.
//!
//! When both cheap residual parts are below the tolerance, the full
//! [`Residual`](crate::engine::contact::Residual) of `(p, u)` decides; if it fails, the
//! dynamics goes on. A residual that reaches no new low for `stall_window` steps cannot
//! improve (a tolerance below its rounding floor): the solve fails as
//! [`Termination::Stalled`] with the residual reached.
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
//! * E. Bitzek, P. Koskinen, F. Gähler, M. Moseler and P. Gumbsch, Phys. Rev. Lett. 97,
//!   170201 (2006): FIRE.
//! * J. Guénolé et al., Comput. Mater. Sci. 175, 109584 (2020): FIRE 2.0, the step back
//!   at a restart ([`control`]).
//! * Y. Zhou, M. Moseler and M. H. Müser, Phys. Rev. B 99, 144103 (2019): FIRE on
//!   mass-weighted GFMD.
//! * D. P. Bertsekas, SIAM J. Control Optim. 20, 221 (1982): the two-metric projection
//!   (the points the wall holds).

use crate::engine::contact::{ContactProblem, ContactSolution};
use crate::engine::fft::FusedPass;
use crate::engine::field::{add_all, map_chunks_mut};
use crate::engine::solver::dynamics::{held, Balance, ForcePass, State};
use crate::engine::solver::executor::{Iteration, Judgement, Method};
use crate::engine::solver::workspace::Workspace;
use crate::engine::solver::{SolveOptions, Start};
use crate::error::{Result, Termination};

pub mod control;

pub use self::control::FireParams;
use self::control::{Control, Schedule};

/// FIRE on GFMD's masses, with its work buffers.
#[derive(Debug, Clone, Default)]
pub struct Fire {
    /// The schedule's constants.
    pub params: FireParams,
    /// `u`, `w`, the stress and the acceleration (see [`State`]) and a half spectrum.
    work: Workspace<4>,
}

impl Method for Fire {
    const NAME: &'static str = "fire";
    /// A load search at 512^2 (four warm-started solves) took FIRE 1.29 times CG's CPU
    /// time, cold solves 1.07 to 1.17 at tol 1e-8 and 1e-10 (docs/measured.md: "FIRE").
    const RELATIVE_COST: f64 = 1.3;
    type Solve<'a> = Relaxation<'a>;

    /// The state at `start` (as GFMD's: every point on the wall from cold; warm, the
    /// previous displacement), at rest.
    fn init<'a>(
        &'a mut self,
        problem: &'a ContactProblem<'a>,
        start: Start,
        opts: &SolveOptions,
    ) -> Result<Relaxation<'a>> {
        let (state, _) = State::start(Self::NAME, problem, start, opts, &mut self.work)?;
        Ok(Relaxation {
            state,
            control: Control::new(self.params),
            stalled_at: f64::NAN,
        })
    }
}

/// One solve's state: the mass-weighted dynamics' state (its second field the velocity)
/// and FIRE's schedule.
pub struct Relaxation<'a> {
    state: State<'a>,
    control: Control,
    /// The residual estimate of the step after which the schedule gave up.
    stalled_at: f64,
}

/// The sums FIRE's schedule and mixing take over a step: the power `F . w` and the
/// products `w . w`, `w . a`, `a . a`.
#[derive(Debug, Clone, Copy)]
struct Sums {
    power: f64,
    ww: f64,
    wa: f64,
    aa: f64,
}

impl Iteration for Relaxation<'_> {
    type Measure = Balance;

    /// Step 1, and an error when the stress is not finite.
    fn measure(&mut self, it: usize) -> Result<Balance> {
        self.state.measure(0.0, it)
    }

    fn estimate(balance: &Balance) -> f64 {
        balance.value()
    }

    /// When the cheap parts of the residual pass, the full residual of the state decides.
    fn judge(&mut self, it: usize, balance: &Balance) -> Judgement {
        if balance.value() <= self.state.tol {
            let solution = self.state.solution(it);
            if solution.stats.residual.value() <= self.state.tol {
                return Judgement::Converged(solution);
            }
        }
        Judgement::Go
    }

    /// Steps 2 to 4; the schedule may give up (the residual cannot improve).
    fn step(&mut self, _it: usize, balance: Balance) -> Result<Option<Termination>> {
        let sums = self.acceleration();
        let Some(schedule) = self.control.next(sums.power, balance.value()) else {
            self.stalled_at = balance.value();
            return Ok(Some(Termination::Stalled));
        };
        self.advance(schedule, &sums);
        Ok(None)
    }

    /// [`State::conclude`].
    fn terminate(self, iterations: usize, reason: Termination) -> Result<ContactSolution> {
        self.state
            .conclude((iterations, reason), self.stalled_at, 0.0)
    }
}

/// Step 2's pass: the force's, summing `[F . w, w . w]` over each generated row of the
/// force and `[w . a, a . a]` over each row of the acceleration.
struct Tallied<'a> {
    force: ForcePass<'a>,
}

impl Tallied<'_> {
    /// Row `i` of the velocity.
    #[inline(always)]
    fn velocity(&self, i: usize) -> &[f64] {
        let n = self.force.at.n;
        &self.force.at.v[i * n..(i + 1) * n]
    }
}

impl FusedPass for Tallied<'_> {
    type Generated = [f64; 2];
    type Consumed = [f64; 2];

    #[inline(always)]
    fn generate(&self, i: usize, f: &mut [f64], side: &mut [f64], old: &[f64]) -> [f64; 2] {
        self.force.generate(i, f, side, old);
        let (mut fw, mut ww) = (0.0, 0.0);
        for (&fi, &wi) in f.iter().zip(self.velocity(i)) {
            fw += fi * wi;
            ww += wi * wi;
        }
        [fw, ww]
    }

    #[inline(always)]
    fn consume(&self, i: usize, a: &[f64], _: &[f64]) -> [f64; 2] {
        let (mut wa, mut aa) = (0.0, 0.0);
        for (&ai, &wi) in a.iter().zip(self.velocity(i)) {
            wa += wi * ai;
            aa += ai * ai;
        }
        [wa, aa]
    }
}

impl Relaxation<'_> {
    /// Step 2: the force at `u` and its mass-weighted acceleration, with FIRE's sums.
    fn acceleration(&mut self) -> Sums {
        let (generated, consumed) = self.state.accelerate(0.0, |force| Tallied { force });
        let [power, ww] = add_all(generated);
        let [wa, aa] = add_all(consumed);
        Sums { power, ww, wa, aa }
    }

    /// Step 4: the velocity `w' = w + dt a` (or `dt a` after a restart) mixed towards
    /// `a`, and the move to `max(u + dt w'', h)`, points held by the wall staying on it;
    /// the wall stops what runs into it.
    fn advance(
        &mut self,
        Schedule {
            dt,
            keep,
            alpha,
            back,
        }: Schedule,
        sums: &Sums,
    ) {
        let state = &mut self.state;
        let problem = state.problem;
        let (h, p0) = (problem.heights, problem.p0);
        let (a, ky) = (&*state.accel, &*state.stress);
        let (kept, ww, wa) = if keep {
            (1.0, sums.ww, sums.wa)
        } else {
            (0.0, 0.0, 0.0)
        };
        // |w'|^2 = |kept w + dt a|^2, and the mixing's factor alpha |w'| / |a|.
        let speed = (ww + 2.0 * dt * wa + dt * dt * sums.aa).max(0.0).sqrt();
        let towards = if sums.aa > 0.0 {
            alpha * speed / sums.aa.sqrt()
        } else {
            0.0
        };
        let inverse_dt = 1.0 / dt;
        map_chunks_mut(
            state.u,
            state.v,
            #[inline(always)]
            |range, uc, wc| {
                let (h, ky, a) = (&h[range.clone()], &ky[range.clone()], &a[range]);
                for ((((ui, wi), &hi), &k), &ai) in
                    uc.iter_mut().zip(wc.iter_mut()).zip(h).zip(ky).zip(a)
                {
                    let (next, w) = if held(*ui, hi, k + p0) {
                        (hi, 0.0)
                    } else {
                        let w = kept * *wi + dt * ai;
                        let mixed = (1.0 - alpha) * w + towards * ai;
                        let free = *ui - back * *wi + dt * mixed;
                        if free >= hi {
                            (free, mixed)
                        } else {
                            (hi, (hi - *ui) * inverse_dt)
                        }
                    };
                    *wi = w;
                    *ui = next;
                }
            },
        );
    }
}
