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
//!    mass-weighted acceleration `a~(q) = F~(q) / m(q)` (one fused convolution);
//! 3. [`Dynamics::advance`]: `u <- max(y + tau a, h)`, except at points held by the wall
//!    (on it with a compressive stress), which stay put; `v` becomes the step taken;
//! 4. [`Momentum::control`]: the damping schedule `beta` of the next step.
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
//! adapts ([`GfmdParams`]). It starts at `tau` (0.3, measured best on the speed study's
//! scenes); it shrinks (by `shrink`, and the momentum restarts) when the residual shows a
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
//! When both cheap residual parts are below the tolerance, the full
//! [`Residual`] of `(p, y)` is evaluated; it decides convergence.

use std::time::Instant;

use rayon::prelude::*;
use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use super::ensure_len;
use crate::engine::contact::{ContactProblem, ContactSolution, Residual, SolveStats};
use crate::engine::fft::Kernel;
use crate::engine::field::CHUNK;
use crate::engine::solver::{Progress, SolveOptions, Solver, Start};
use crate::error::{Error, Result, Termination};

/// GFMD's constants: the step in units of the squared mode period (`1/omega^2`), and the
/// step control (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GfmdParams {
    /// First step `tau` of a cold solve.
    pub tau: f64,
    /// First step of a warm solve (the contact set of a warm start has more isolated
    /// points, and stiffer modes, than a cold start meets early on).
    pub tau_warm: f64,
    /// Steps without a new lowest residual before the step shrinks.
    pub stall_window: usize,
    /// Steps in a row in which the residual alternately rises and falls before the step
    /// shrinks.
    pub zigzag_window: usize,
    /// Steps in a row in which the residual rises (to above twice its low) before the
    /// step shrinks.
    pub rise_window: usize,
    /// Largest damping factor `beta` (the schedule's limit, 1, is optimal only for
    /// problems without a smallest curvature).
    pub beta_max: f64,
    /// Growth of the step, up to the first, at every new lowest residual.
    pub regrow: f64,
    /// Factor of a shrink.
    pub shrink: f64,
    /// Smallest step, as a fraction of the first: below it the solve has stalled.
    pub tau_floor: f64,
}

impl Default for GfmdParams {
    fn default() -> Self {
        Self {
            tau: 0.3,
            tau_warm: 0.2,
            stall_window: 8,
            zigzag_window: 4,
            rise_window: 3,
            beta_max: 0.95,
            regrow: 1.02,
            shrink: 0.7,
            tau_floor: 1e-3,
        }
    }
}

/// GFMD solver with its work buffers.
#[derive(Debug, Clone, Default)]
pub struct Gfmd {
    /// Step and step control.
    pub params: GfmdParams,
    /// The step the last solve ended with (a sweep's next solve begins one shrink above).
    last_tau: Option<f64>,
    /// The inverse masses as a convolution kernel, for the grid size it was made for.
    inverse_mass: Option<(usize, f64, Kernel)>,
    spec: Vec<Complex64>,
    u: Vec<f64>,
    v: Vec<f64>,
    stress: Vec<f64>,
    accel: Vec<f64>,
}

const NAME: &str = "gfmd";

/// The look-ahead position `y = max(u + beta v, h)` of one point.
#[inline]
fn look_ahead(u: f64, v: f64, beta: f64, h: f64) -> f64 {
    (u + beta * v).max(h)
}

/// The total force at a point at `y` (wall at `h`) under the stress `s`: `-s`, and on the
/// wall only what pulls the point off it.
#[inline]
fn total_force(y: f64, h: f64, s: f64) -> f64 {
    if y <= h {
        (-s).max(0.0)
    } else {
        -s
    }
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
struct Balance {
    equilibrium: f64,
    load: f64,
    finite: bool,
}

impl Balance {
    fn value(&self) -> f64 {
        self.equilibrium.max(self.load)
    }
}

/// The momentum schedule and the step control of one solve.
#[derive(Debug, Clone, Copy)]
struct Momentum {
    params: GfmdParams,
    tau_first: f64,
    tau: f64,
    /// Steps since the last restart (`beta = k / (k + 3)`).
    k: usize,
    best: f64,
    since_best: usize,
    /// The last residual, and how many steps in a row the residual has alternated
    /// between rising and falling (positive: it last rose).
    last: f64,
    zigzag: i32,
    /// Steps in a row in which the residual rose.
    rises: usize,
}

impl Momentum {
    fn new(params: GfmdParams, tau: f64) -> Self {
        Self {
            params,
            tau_first: tau,
            tau,
            k: 0,
            best: f64::INFINITY,
            since_best: 0,
            last: f64::INFINITY,
            zigzag: 0,
            rises: 0,
        }
    }

    /// Damping of the next look-ahead.
    fn beta(&self) -> f64 {
        let k = self.k as f64;
        (k / (k + 3.0)).min(self.params.beta_max)
    }

    /// Step 4: after a step with power `power` (force times step) from a state with the
    /// residual parts `balance`, the schedule of the next. Returns false when the step has shrunk below
    /// its floor (the residual cannot improve).
    fn control(&mut self, power: f64, balance: &Balance) -> bool {
        let residual = balance.value();
        let mut restart = power <= 0.0;
        // A mode too stiff for the step flips sign every step: the residual zigzags.
        let rose = residual > self.last;
        self.zigzag = match (rose, self.zigzag) {
            (true, z) if z <= 0 => 1 - z,
            (false, z) if z > 0 => -z - 1,
            (true, _) => 1,
            (false, _) => -1,
        };
        self.last = residual;
        if residual < self.best {
            self.best = residual;
            self.since_best = 0;
            self.tau = (self.tau * self.params.regrow).min(self.tau_first);
        } else {
            self.since_best += 1;
        }
        // A mode too stiff for the step may also grow without zigzagging the residual:
        // it rises step after step, well above its low.
        self.rises = if rose { self.rises + 1 } else { 0 };
        let zigzag = self.zigzag.unsigned_abs() as usize >= self.params.zigzag_window;
        let growing = self.rises >= self.params.rise_window && residual > 2.0 * self.best;
        if zigzag || growing || self.since_best >= self.params.stall_window {
            self.tau *= self.params.shrink;
            self.best = residual;
            self.since_best = 0;
            self.zigzag = 0;
            self.rises = 0;
            restart = true;
        }
        self.k = if restart { 0 } else { self.k + 1 };
        self.tau >= self.params.tau_floor * self.tau_first
    }

    /// Forgets the momentum (after the state was replaced).
    fn restart(&mut self) {
        self.k = 0;
    }
}

/// One solve's state: the problem, the fields, the masses and the schedule.
struct Dynamics<'a> {
    problem: &'a ContactProblem<'a>,
    inverse_mass: &'a Kernel,
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
}

impl Dynamics<'_> {
    /// Step 1: the look-ahead position's stress, and its equilibrium and load residuals.
    fn stress(&mut self) -> Balance {
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.n();
        let (h, p0, beta) = (problem.heights, problem.p0, self.beta);
        let (u, v) = (&*self.u, &*self.v);
        let (_, rows) = model.fft.convolve(
            &model.stiffness,
            self.spec,
            None,
            |i, row, _, _| {
                let rg = i * n..(i + 1) * n;
                for (((y, &ui), &vi), &hi) in row
                    .iter_mut()
                    .zip(&u[rg.clone()])
                    .zip(&v[rg.clone()])
                    .zip(&h[rg])
                {
                    *y = look_ahead(ui, vi, beta, hi);
                }
            },
            self.stress,
            |i, ky, _| {
                let rg = i * n..(i + 1) * n;
                let mut acc = BalanceSums::default();
                for (((&k, &ui), &vi), &hi) in ky
                    .iter()
                    .zip(&u[rg.clone()])
                    .zip(&v[rg.clone()])
                    .zip(&h[rg])
                {
                    let s = k + p0;
                    let y = look_ahead(ui, vi, beta, hi);
                    let p = if y <= hi { s.max(0.0) } else { 0.0 };
                    acc.unbalanced += (s - p) * (s - p);
                    acc.sum_p += p;
                    acc.sum_p2 += p * p;
                    acc.nonfinite |= !s.is_finite();
                }
                acc
            },
        );
        let sums = rows
            .into_iter()
            .fold(BalanceSums::default(), BalanceSums::add);
        let npts = h.len() as f64;
        let rms_p = (sums.sum_p2 / npts).sqrt().max(f64::MIN_POSITIVE);
        Balance {
            equilibrium: (sums.unbalanced / npts).sqrt() / rms_p,
            load: (sums.sum_p / npts - p0).abs() / p0,
            finite: !sums.nonfinite,
        }
    }

    /// Step 2: the total force at the look-ahead position, with the wall's reaction, and
    /// its mass-weighted acceleration.
    fn acceleration(&mut self) {
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.n();
        let (h, p0, beta) = (problem.heights, problem.p0, self.beta);
        let (u, v, ky) = (&*self.u, &*self.v, &*self.stress);
        model.fft.convolve(
            self.inverse_mass,
            self.spec,
            None,
            |i, row, _, _| {
                let rg = i * n..(i + 1) * n;
                for ((((f, &ui), &vi), &hi), &k) in row
                    .iter_mut()
                    .zip(&u[rg.clone()])
                    .zip(&v[rg.clone()])
                    .zip(&h[rg.clone()])
                    .zip(&ky[rg])
                {
                    *f = total_force(look_ahead(ui, vi, beta, hi), hi, k + p0);
                }
            },
            self.accel,
            |_, _, _| (),
        );
    }

    /// Step 3: the position moves to `max(y + tau a, h)`, points held by the wall stay on
    /// it; returns the power `F . (u_new - u_old)` of the step.
    fn advance(&mut self) -> f64 {
        let problem = self.problem;
        let (h, p0, beta, tau) = (problem.heights, problem.p0, self.beta, self.momentum.tau);
        let (a, ky) = (&*self.accel, &*self.stress);
        let powers: Vec<f64> = self
            .u
            .par_chunks_mut(CHUNK)
            .zip(self.v.par_chunks_mut(CHUNK))
            .enumerate()
            .map(|(c, (uc, vc))| {
                let base = c * CHUNK;
                let mut power = 0.0;
                for (k, (ui, vi)) in uc.iter_mut().zip(vc.iter_mut()).enumerate() {
                    let i = base + k;
                    let y = look_ahead(*ui, *vi, beta, h[i]);
                    let s = ky[i] + p0;
                    let force = total_force(y, h[i], s);
                    let held = y <= h[i] && force == 0.0;
                    let next = if held {
                        h[i]
                    } else {
                        (y + tau * a[i]).max(h[i])
                    };
                    power += force * (next - *ui);
                    *vi = next - *ui;
                    *ui = next;
                }
                power
            })
            .collect();
        powers.iter().sum()
    }

    /// The look-ahead position as the new state (no momentum), e.g. after a rejected
    /// convergence check.
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

    /// The look-ahead position and its pressure as a solution with its residual.
    fn solution(&mut self, iterations: usize, warm: bool, timer: Instant) -> ContactSolution {
        self.settle();
        let problem = self.problem;
        let (h, p0) = (problem.heights, problem.p0);
        let pressure: Vec<f64> = self
            .u
            .par_iter()
            .zip(self.stress.par_iter().zip(h))
            .map(|(&u, (&k, &hh))| if u <= hh { (k + p0).max(0.0) } else { 0.0 })
            .collect();
        let displacement = self.u.to_vec();
        let residual = Residual::evaluate(problem, &pressure, &displacement, self.spec, self.accel);
        ContactSolution {
            pressure,
            displacement,
            p0,
            stats: SolveStats {
                solver: NAME,
                iterations,
                residual,
                wall_s: timer.elapsed().as_secs_f64(),
                warm,
            },
        }
    }
}

impl Gfmd {
    /// Makes the inverse masses `1/m(q)` as a kernel, `2/(q E*)` and the softest mode's for
    /// `q = 0`, unless the last solve's are for the same grid and modulus.
    fn prepare_inverse_mass(&mut self, problem: &ContactProblem) {
        let model = problem.model;
        let key = (model.grid.n(), model.halfspace.e_star());
        let stale = !matches!(&self.inverse_mass, Some((n, e, _)) if (*n, *e) == key);
        if stale {
            let stiffness = model.halfspace.stiffness();
            let k_min = stiffness
                .iter()
                .copied()
                .filter(|&k| k > 0.0)
                .fold(f64::INFINITY, f64::min);
            let table: Vec<f64> = stiffness
                .iter()
                .map(|&k| 1.0 / if k > 0.0 { k } else { k_min })
                .collect();
            self.inverse_mass = Some((key.0, key.1, model.fft.kernel(&table)));
        }
    }

    /// Solves `problem` from `start`.
    fn run(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress),
    ) -> Result<ContactSolution> {
        opts.validate()?;
        let timer = Instant::now();
        let grid = &problem.model.grid;
        let (n2, modes) = (grid.points(), grid.modes());
        let h = problem.heights;
        ensure_len(&mut self.spec, modes);
        ensure_len(&mut self.u, n2);
        ensure_len(&mut self.v, n2);
        ensure_len(&mut self.stress, n2);
        ensure_len(&mut self.accel, n2);
        let warm = matches!(start, Start::Warm(_));
        match start {
            Start::Cold => self.u.copy_from_slice(h),
            Start::Warm(prev) => {
                if prev.displacement.len() != n2 {
                    return Err(Error::invalid(
                        "warm start",
                        format!("{} points", prev.displacement.len()),
                        format!("a solution on the same grid ({n2} points)"),
                    ));
                }
                // The previous contact set stays on the wall exactly (a displacement carried
                // over, or predicted, differs from the heights by rounding).
                self.u
                    .par_iter_mut()
                    .zip(prev.displacement.par_iter().zip(&prev.pressure))
                    .zip(h)
                    .for_each(|((u, (&v, &p)), &hh)| *u = if p > 0.0 { hh } else { v.max(hh) });
            }
        }
        self.v.fill(0.0);
        let params = self.params;
        let first = if warm { params.tau_warm } else { params.tau };
        let tau = self
            .last_tau
            .map_or(first, |t| (t / params.shrink).min(first));
        self.prepare_inverse_mass(problem);
        let inverse_mass = &self.inverse_mass.as_ref().expect("made above").2;
        let mut dynamics = Dynamics {
            problem,
            inverse_mass,
            spec: &mut self.spec,
            u: &mut self.u,
            v: &mut self.v,
            stress: &mut self.stress,
            accel: &mut self.accel,
            momentum: Momentum::new(params, tau),
            beta: 0.0,
        };
        let mut reached = f64::INFINITY;
        let mut stop = Termination::BudgetExhausted;
        let mut iterations = opts.max_iter;
        for it in 0..opts.max_iter {
            let balance = dynamics.stress();
            if !balance.finite {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "stress",
                    iteration: it,
                });
            }
            monitor(Progress {
                iteration: it,
                residual: balance.value(),
            });
            if balance.value() <= opts.tol {
                let solution = dynamics.solution(it, warm, timer);
                reached = solution.stats.residual.value();
                if reached <= opts.tol {
                    self.last_tau = Some(dynamics.momentum.tau);
                    return Ok(solution);
                }
                // The cheap parts passed, the full residual did not: go on from the
                // look-ahead position, which is now the state.
            }
            dynamics.acceleration();
            let power = dynamics.advance();
            if !dynamics.momentum.control(power, &balance) {
                stop = Termination::Stalled;
                iterations = it + 1;
                reached = balance.value();
                break;
            }
            dynamics.beta = dynamics.momentum.beta();
        }
        if stop == Termination::BudgetExhausted {
            // The state the last step reached may have converged; if not, report its
            // residual.
            let balance = dynamics.stress();
            if !balance.finite {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "stress",
                    iteration: opts.max_iter,
                });
            }
            let solution = dynamics.solution(opts.max_iter, warm, timer);
            reached = solution.stats.residual.value();
            if reached <= opts.tol {
                self.last_tau = Some(dynamics.momentum.tau);
                return Ok(solution);
            }
        }
        Err(Error::NotConverged {
            solver: NAME,
            reason: stop,
            iterations,
            residual: reached,
            tol: opts.tol,
        })
    }
}

impl Solver for Gfmd {
    fn name(&self) -> &'static str {
        NAME
    }

    fn solve_monitored(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress),
    ) -> Result<ContactSolution> {
        self.run(problem, start, opts, monitor)
    }
}
