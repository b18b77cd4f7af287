//! Constrained conjugate gradients for the hard-wall problem (Polonsky & Keer, Wear 231,
//! 206 (1999)); the algorithm of tamaas's `PolonskyKeerRey` and of ContactMechanics.
//!
//! The unknown is the pressure `p >= 0` with `mean(p) = p0`; the displacement is
//! `u = K^-1 p` (zero mean) and the gap `g = u - h - gbar`, where the rigid shift `gbar` is
//! the mean of `u - h` over the contact set `Ic = {p > 0}`.
//!
//! # One iteration
//!
//! The state of a solve is a [`Solve`]; an iteration is its steps, in this order:
//!
//! 1. [`Solve::gap`]: the gap `g`, the preconditioned gap `z` (below; `z = g` without
//!    preconditioning) and `G = sum_Ic g z`;
//! 2. [`Solve::direction`]: the search direction `t = z + delta (G / G_old) t` on `Ic`,
//!    0 elsewhere, and `r = K^-1 t` (one forward and one inverse FFT) with the sums the
//!    step needs (`rbar = mean_Ic r`);
//! 3. [`Solve::step_length`]: `tau = sum_Ic g t / sum_Ic (r - rbar) t`;
//! 4. [`Solve::update`]: `p <- max(p - tau t, 0)` on `Ic`; points out of contact that
//!    penetrate (`p = 0`, `g < 0`) enter with `p = -tau k g` (`k = 1`, or with
//!    preconditioning the Rayleigh quotient `g.z / g.g`, the stiffness the preconditioner
//!    applied, so that the entering pressure has the units of `t`), and conjugacy is reset
//!    (`delta = 0`) when more than 1% of the contact set enters (Polonsky & Keer reset it
//!    when any point enters; see [`KEEP_CONJUGACY`]). When the gap vanishes on the contact
//!    set (a lone contact point), `t = 0` and `tau` is `0/0`: then `p` stays and the
//!    penetrating points enter with `p = -g / G(0)`, `G(0)` the displacement of a point
//!    under unit pressure on it alone;
//! 5. [`Solve::restore_load`]: `p <- p p0 / mean(p)` restores the load;
//! 6. [`Solve::refresh`]: `u` and the rigid shift `gbar` of the new pressure.
//!
//! Between steps 1 and 2, [`Solve::stalled`] and [`Solve::check`] decide whether the
//! solve stops (see "Stopping" below).
//!
//! Preconditioning (on by default; Vollebregt, J. Comput. Phys. 257, 333 (2014)): the
//! Hessian of the complementary energy is the compliance `K^-1`, whose condition number
//! grows like `N`; the search direction is built from `z = K g` (the stiffness applied to
//! the gap, restricted to the contact set and made mean-free) instead of `g`, and `beta`
//! from `g.z`. One more FFT pair per iteration buys a several times smaller iteration
//! count (the README's measured section gives the figures).
//!
//! The displacement is updated incrementally, `u <- u - tau r`, which is exact as long as
//! step 4 clips nothing and adds nothing; otherwise `u = K^-1 p` is recomputed. `u`
//! is also recomputed every [`ConstrainedCg::refresh_every`] iterations and before the
//! final residual, so rounding in the incremental update never reaches a result. In a
//! warm solve points enter or leave at nearly every iteration, so after an update that
//! changed the contact set the next one recomputes `u` whatever happens: its update of `p`
//! is the input pass of the convolution `K^-1 p` (no incremental update, and no separate
//! sweep over `p`; the guess costs a transform when it is wrong, once per solve or so). The
//! load rescaling of step 5 is applied lazily (a scale factor read with `p` and `u`), and
//! the rigid shift of the next iteration is summed in the same sweep that updates `p`.
//!
//! A cold start (`p = p0` everywhere) needs no transform: a uniform pressure displaces
//! nothing, `u = 0`. The number of points in contact comes from the sweep that updates `p`.
//!
//! # Stopping
//!
//! The iteration watches an estimate of the residual (complementarity and
//! penetration); when it falls below the tolerance with an incrementally updated `u`, `u`
//! is recomputed and the estimate taken again by one sweep over the fields (no
//! preconditioning transforms); once it holds for the exact state the full [`Residual`]
//! is evaluated, and
//! if that is still above, the estimate's target is lowered and the solve goes on. The
//! full residual has a rounding floor: its equilibrium part compares `K u`, rounded at the
//! scale of the heights, with pressures that shrink with the load (about `1e-12` at
//! `a_r = 2e-4` on 128^2). A tolerance below that floor cannot be met: once the
//! estimate is below the tolerance and stops improving (see [`STAGNATION`]), the solve
//! fails with the smallest residual it reached instead of spending its whole budget.
//!
//! # Cost
//!
//! An iteration is two fused convolutions ([`crate::engine::fft::Fft2::convolve`]) and one update
//! sweep, or three convolutions when `u` is recomputed (the update then being the third's
//! input): the gap and the search direction are generated row by row as the transforms
//! read them, and the sums the step needs are taken row by row as the inverse transforms
//! write them, so apart from the FFTs the iteration reads and writes each field about
//! once per transform. Memory traffic is what the sweeps cost on large grids. Fusing the
//! update into the recomputation of `u` saves about four passes over a field per
//! iteration, with the same iterations.

use std::time::Instant;

use rustfft::num_complex::Complex64;

use super::ensure_len;
use crate::engine::contact::{ContactProblem, ContactSolution, Residual, SolveStats};
use crate::engine::field::{fold_chunks, CHUNK};
use crate::engine::solver::{Progress, SolveOptions, Solver, Start};
use crate::error::{Error, Result, Termination};
use rayon::prelude::*;

mod sums;

use self::sums::{add_all, contact_sums, Direction, Gap, GapSums, Step, Update, View};

/// Constrained conjugate-gradient solver with its work buffers.
#[derive(Debug, Clone)]
pub struct ConstrainedCg {
    /// Recompute `u = K^-1 p` from scratch at least this often (iterations).
    pub refresh_every: usize,
    /// Precondition the gap with the stiffness `K` (one more FFT pair per iteration).
    pub preconditioned: bool,
    p: Vec<f64>,
    u: Vec<f64>,
    t: Vec<f64>,
    r: Vec<f64>,
    spec: Vec<Complex64>,
}

impl Default for ConstrainedCg {
    fn default() -> Self {
        Self {
            refresh_every: 50,
            preconditioned: true,
            p: Vec::new(),
            u: Vec::new(),
            t: Vec::new(),
            r: Vec::new(),
            spec: Vec::new(),
        }
    }
}

const NAME: &str = "cg";
/// Iterations without halving the residual estimate after which a preconditioned solve
/// continues unpreconditioned, and after which an unpreconditioned solve whose estimate
/// is already below the tolerance gives up (see "Stopping" in the module docs): iterating
/// on at rounding level only lets the conjugate directions drift away from the solution.
const STAGNATION: usize = 200;
/// Polonsky & Keer reset conjugacy whenever a point enters contact. Late in a solve a few
/// points enter or leave at every iteration, so that rule turns CG into steepest descent;
/// resetting only when more than this fraction of the contact set enters keeps the
/// conjugate directions through those small changes (fewer iterations: the README's
/// measured section; 0 restores the original rule).
const KEEP_CONJUGACY: f64 = 0.01;

impl ConstrainedCg {
    /// Solves `problem` from `start`: the steps of the module docs, until the residual is
    /// below the tolerance, the budget is spent, or the solve stalls.
    fn run(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress),
    ) -> Result<ContactSolution> {
        opts.validate()?;
        let mut solve = Solve::start(self, problem, start, opts.tol)?;
        let mut stop = (opts.max_iter, Termination::BudgetExhausted);
        for it in 0..opts.max_iter {
            let gap = solve.gap(it)?;
            monitor(Progress {
                iteration: it,
                residual: gap.estimate,
            });
            if solve.stalled(it, gap.estimate) {
                stop = (it, Termination::Stalled);
                break;
            }
            match solve.check(it, gap.estimate) {
                Check::Converged(solution) => return Ok(solution),
                Check::Retry => continue,
                Check::Iterate => {}
            }
            let direction = solve.direction(&gap);
            let Some(step) = solve.step_length(it, &gap, &direction)? else {
                continue; // conjugacy reset: the next iteration starts along the gap
            };
            let update = solve.update(step);
            solve.restore_load(it, &update)?;
            solve.refresh(&update);
        }
        solve.conclude(stop)
    }
}

/// The error of a solve that met a non-finite `what` at iteration `iteration`.
fn non_finite(what: &'static str, iteration: usize) -> Error {
    Error::NonFinite {
        solver: NAME,
        what,
        iteration,
    }
}

/// What [`Solve::check`] found.
enum Check {
    /// Not converged: go on with this iteration.
    Iterate,
    /// `u` was recomputed and the estimate no longer holds: start the next iteration.
    Retry,
    /// The full residual is below the tolerance.
    Converged(ContactSolution),
}

/// The stopping bookkeeping of a solve (see "Stopping" in the module docs).
#[derive(Debug, Clone, Copy)]
struct Stopping {
    /// The requested tolerance of the full residual.
    tol: f64,
    /// The estimate's target: the tolerance, lowered each time the full residual fails.
    target: f64,
    /// The lowest estimate that halved the one before, and its iteration.
    best: f64,
    best_at: usize,
    /// Smallest full residual evaluated.
    reached: f64,
}

impl Stopping {
    fn new(tol: f64) -> Self {
        Self {
            tol,
            target: tol,
            best: f64::INFINITY,
            best_at: 0,
            reached: f64::INFINITY,
        }
    }

    /// Records the estimate of iteration `it`; true when it has not halved for
    /// [`STAGNATION`] iterations.
    fn stagnant(&mut self, it: usize, estimate: f64) -> bool {
        if estimate < 0.5 * self.best {
            self.best = estimate;
            self.best_at = it;
            false
        } else {
            it - self.best_at > STAGNATION
        }
    }
}

/// The state of one solve: the fields (in the solver's buffers), with the load scale and
/// the rigid shift they are read with, the conjugate-gradient recurrence, and when `u`
/// was last recomputed.
struct Solve<'a> {
    problem: &'a ContactProblem<'a>,
    refresh_every: usize,
    warm: bool,
    timer: Instant,
    /// The pressure as stored: the true pressure is `scale p`.
    p: &'a mut Vec<f64>,
    /// The displacement `K^-1 p` of the stored pressure (the true one is `scale u`).
    u: &'a mut Vec<f64>,
    /// The search direction `t`.
    t: &'a mut Vec<f64>,
    /// `r = K^-1 t`; the preconditioned gap `z` before it.
    r: &'a mut Vec<f64>,
    spec: &'a mut Vec<Complex64>,
    /// The load scale that makes `mean(scale p) = p0`.
    scale: f64,
    /// The rigid shift `gbar = mean_Ic (scale u - h)`.
    gbar: f64,
    /// The number of points in contact, `|Ic|`.
    n_c: f64,
    /// `G` of the last direction.
    rho_old: f64,
    /// Whether the next direction is conjugate to the last (`delta = 1`).
    conjugate: bool,
    /// Whether the gap is preconditioned (see [`STAGNATION`]).
    precond: bool,
    /// Whether `u == K^-1 p` up to one transform's rounding.
    exact: bool,
    since_refresh: usize,
    /// Whether the last update changed the contact set, so that `u` had to be recomputed
    /// (see [`Solve::update`]); taken as so at the start.
    set_changed: bool,
    stopping: Stopping,
}

impl<'a> Solve<'a> {
    /// The state at `start`: `p = p0` and `u = 0` from cold, or the previous pressure
    /// (clipped at 0) with its displacement, and no search direction.
    fn start(
        cg: &'a mut ConstrainedCg,
        problem: &'a ContactProblem<'a>,
        start: Start,
        tol: f64,
    ) -> Result<Self> {
        let timer = Instant::now();
        let model = problem.model;
        let n2 = model.grid.points();
        let p0 = problem.p0;
        ensure_len(&mut cg.p, n2);
        ensure_len(&mut cg.u, n2);
        ensure_len(&mut cg.t, n2);
        ensure_len(&mut cg.r, n2);
        ensure_len(&mut cg.spec, model.grid.modes());

        let warm = matches!(start, Start::Warm(_));
        match start {
            Start::Cold => {
                cg.p.fill(p0);
                cg.u.fill(0.0);
            }
            Start::Warm(prev) => {
                if prev.pressure.len() != n2 {
                    return Err(Error::invalid(
                        "warm start",
                        format!("{} points", prev.pressure.len()),
                        format!("a solution on the same grid ({n2} points)"),
                    ));
                }
                cg.p.par_iter_mut()
                    .zip(&prev.pressure)
                    .for_each(|(p, &q)| *p = q.max(0.0));
                let mean = crate::engine::field::mean(&cg.p);
                if !(mean > 0.0 && mean.is_finite()) {
                    cg.p.fill(p0);
                }
            }
        }
        let mut solve = Solve {
            problem,
            refresh_every: cg.refresh_every,
            warm,
            timer,
            // The load scale that makes mean(p) = p0.
            scale: p0 / crate::engine::field::mean(&cg.p),
            p: &mut cg.p,
            u: &mut cg.u,
            t: &mut cg.t,
            r: &mut cg.r,
            spec: &mut cg.spec,
            // Set below.
            gbar: f64::NAN,
            n_c: 0.0,
            rho_old: 1.0,
            conjugate: false,
            precond: cg.preconditioned,
            exact: true,
            since_refresh: 0,
            set_changed: true,
            stopping: Stopping::new(tol),
        };
        // Points in contact, and the rigid shift. A uniform pressure displaces nothing (the
        // compliance has no q = 0 mode): a cold start needs no transform.
        if warm {
            solve.exact_displacement();
        } else {
            solve.gbar = -crate::engine::field::mean(problem.heights);
            solve.n_c = n2 as f64;
        }
        solve.t.fill(0.0);
        Ok(solve)
    }

    /// Step 1: the gap `g = scale u - h - gbar` on `Ic` with its sums, the preconditioned
    /// gap `z = K g` (in `r`; `z = g` without preconditioning), and
    /// `G = sum_Ic g z` (`sum_Ic g^2` without preconditioning) and `sum_Ic z`.
    fn gap(&mut self, it: usize) -> Result<Gap> {
        if !self.gbar.is_finite() || !self.scale.is_finite() {
            return Err(non_finite("gap", it));
        }
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.n();
        let view = View::new(
            &self.p[..],
            &self.u[..],
            problem.heights,
            self.scale,
            self.gbar,
        );
        let (sums, sz, rho) = if self.precond {
            let (rows, outs) = model.fft.convolve(
                &model.stiffness,
                &mut self.spec[..],
                None,
                |i, row, _, _| view.gap_sums_into(i * n..(i + 1) * n, Some(row)),
                // z shares r's memory: it is read while t is generated, before r is
                // written (see `Fft2::convolve`).
                &mut self.r[..],
                |i, z, _| {
                    let (p, u, h) = view.row(i, n);
                    let (s, gbar) = (view.scale, view.gbar);
                    let (mut sz, mut gz) = (0.0, 0.0);
                    for (((&zk, &pk), &uk), &hk) in z.iter().zip(p).zip(u).zip(h) {
                        let zm = if pk > 0.0 { zk } else { 0.0 };
                        sz += zm;
                        gz += (s * uk - hk - gbar) * zm;
                    }
                    [sz, gz]
                },
            );
            let sums = rows.into_iter().fold(GapSums::default(), GapSums::add);
            let [sz, gz] = add_all(outs);
            (sums, sz, gz)
        } else {
            let sums = view.gap_sums();
            (sums, 0.0, sums.gg)
        };
        if !(sums.gg.is_finite() && rho.is_finite()) {
            return Err(non_finite("gap", it));
        }
        Ok(Gap {
            sums,
            sz,
            rho,
            estimate: sums.estimate(problem.length_scale),
        })
    }

    /// The safeguard of "Stopping": when the estimate stops improving, a preconditioned
    /// solve goes on with plain Polonsky-Keer, which always converges (slowly); an
    /// unpreconditioned one whose full residual has already failed has stalled (true).
    fn stalled(&mut self, it: usize, estimate: f64) -> bool {
        if !self.stopping.stagnant(it, estimate) {
            return false;
        }
        if self.precond {
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
    /// if that fails, the target is lowered and the iteration goes on.
    fn check(&mut self, it: usize, estimate: f64) -> Check {
        if estimate <= self.stopping.target {
            if !self.exact {
                self.exact_displacement();
                // The estimate of the exact state, without the preconditioner's
                // transforms: if it still holds, the solve is done.
                let view = View::new(
                    &self.p[..],
                    &self.u[..],
                    self.problem.heights,
                    self.scale,
                    self.gbar,
                );
                if view.gap_sums().estimate(self.problem.length_scale) > self.stopping.target {
                    return Check::Retry;
                }
            }
            let solution = self.finish(it);
            if solution.stats.residual.value() <= self.stopping.tol {
                return Check::Converged(solution);
            }
            self.stopping.reached = self.stopping.reached.min(solution.stats.residual.value());
            self.stopping.target *= 0.25;
            self.resume(solution);
        }
        Check::Iterate
    }

    /// Step 2: the search direction `t = (z - zbar) + delta (G / G_old) t` on `Ic`, 0
    /// elsewhere (`zbar = mean_Ic z`; without preconditioning `z - zbar` is the gap `g`
    /// itself), and its convolution `r = K^-1 t` with the sums the step length needs
    /// (`sum_Ic r`, `sum_Ic t`, `sum_Ic g t`, `sum_Ic r t`).
    fn direction(&mut self, gap: &Gap) -> Direction {
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.n();
        let precond = self.precond;
        let zbar = if precond { gap.sz / self.n_c } else { 0.0 };
        let beta = if self.conjugate {
            gap.rho / self.rho_old
        } else {
            0.0
        };
        self.rho_old = gap.rho;
        let view = View::new(
            &self.p[..],
            &self.u[..],
            problem.heights,
            self.scale,
            self.gbar,
        );
        let (_, outs) = model.fft.convolve(
            &model.compliance,
            &mut self.spec[..],
            Some(&mut self.t[..]),
            |i, row, t, z| {
                let (p, u, h) = view.row(i, n);
                let (s, gbar) = (view.scale, view.gbar);
                if precond {
                    for (((x, tk), &zk), &pk) in row.iter_mut().zip(t.iter_mut()).zip(z).zip(p) {
                        let d = zk - zbar + beta * *tk;
                        *tk = if pk > 0.0 { d } else { 0.0 };
                        *x = *tk;
                    }
                } else {
                    for ((((x, tk), &pk), &uk), &hk) in
                        row.iter_mut().zip(t.iter_mut()).zip(p).zip(u).zip(h)
                    {
                        let d = s * uk - hk - gbar + beta * *tk;
                        *tk = if pk > 0.0 { d } else { 0.0 };
                        *x = *tk;
                    }
                }
            },
            &mut self.r[..],
            |i, r, t| {
                let (p, u, h) = view.row(i, n);
                let (s, gbar) = (view.scale, view.gbar);
                let (mut sr, mut st, mut gt, mut rt) = (0.0, 0.0, 0.0, 0.0);
                // t = 0 outside contact: only the sum of r needs a mask.
                for ((((&rk, &tk), &pk), &uk), &hk) in r.iter().zip(t).zip(p).zip(u).zip(h) {
                    sr += if pk > 0.0 { rk } else { 0.0 };
                    st += tk;
                    gt += (s * uk - hk - gbar) * tk;
                    rt += rk * tk;
                }
                [sr, st, gt, rt]
            },
        );
        let [sum_r, sum_t, gt, rt] = add_all(outs);
        Direction {
            sum_r,
            sum_t,
            gt,
            rt,
        }
    }

    /// Step 3: the step length `tau = sum_Ic g t / sum_Ic (r - rbar) t`, and the pressure
    /// per unit penetration given to points entering contact in step 4 (`tau k`). When
    /// the gap vanishes on `Ic`, `t = 0`: then `tau = 0` and the entering points get
    /// `1 / G(0)`. `None` when a conjugate direction is not a descent (conjugacy is then
    /// reset and the next iteration starts along the gap); an error when the gap is not.
    fn step_length(&mut self, it: usize, gap: &Gap, dir: &Direction) -> Result<Option<Step>> {
        let (tau, admit) = if gap.sums.gg == 0.0 {
            // The gap vanishes on the contact set (always so for a lone contact
            // point), so t = 0 and the step length is 0/0: the contact set is at rest
            // and only penetrating points can move the solve on. They enter with the
            // pressure that would lift a lone point by its penetration.
            (0.0, 1.0 / point_compliance(self.problem.model))
        } else {
            let denom = dir.rt - dir.sum_r / self.n_c * dir.sum_t;
            let tau = dir.gt / denom;
            if !(denom > 0.0 && tau.is_finite()) {
                if self.conjugate {
                    self.conjugate = false;
                    return Ok(None);
                }
                return Err(non_finite("step length", it));
            }
            // Gap-to-pressure conversion for entering points: the stiffness the
            // preconditioner applied (the Rayleigh quotient g.z / g.g), or 1.
            let stiffness = if self.precond && gap.sums.gg > 0.0 {
                gap.rho / gap.sums.gg
            } else {
                1.0
            };
            (tau, tau * stiffness)
        };
        Ok(Some(Step {
            scale: self.scale,
            gbar: self.gbar,
            tau,
            admit,
        }))
    }

    /// Step 4: `p <- max(p - tau t, 0)` on `Ic`, `p <- -admit g` where `p = 0` and
    /// `g < 0`, counting the points clipped and entered, with the sums the next rigid
    /// shift needs (`sum_Ic u`, `sum_Ic h` and `|Ic|` of the new contact set). Conjugacy
    /// survives when few points entered (see [`KEEP_CONJUGACY`]), and never a step
    /// without a direction (`G = 0` would make the next `beta` `0/0`).
    ///
    /// When the last update changed the contact set, this one most likely will too
    /// (points enter or leave at nearly every iteration of a warm solve): the update then
    /// generates the new pressure as the input of the convolution `u = K^-1 p`
    /// ([`Self::update_fused`]); otherwise `u` is updated incrementally
    /// ([`Self::update_incremental`]).
    fn update(&mut self, step: Step) -> Update {
        let update = if self.set_changed {
            self.update_fused(step)
        } else {
            self.update_incremental(step)
        };
        self.conjugate = step.tau != 0.0 && update.entered <= KEEP_CONJUGACY * update.cnt;
        update
    }

    /// Step 4 as the input pass of `u = K^-1 p` (of the stored, unscaled pressure).
    fn update_fused(&mut self, step: Step) -> Update {
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.n();
        let h = problem.heights;
        let t = &self.t[..];
        let (rows, outs) = model.fft.convolve(
            &model.compliance,
            &mut self.spec[..],
            Some(&mut self.p[..]),
            |i, row, pr, ur| {
                let rg = i * n..(i + 1) * n;
                let mut acc = [0.0; 3];
                for ((((x, pk), &uk), &tk), &hk) in row
                    .iter_mut()
                    .zip(pr.iter_mut())
                    .zip(ur)
                    .zip(&t[rg.clone()])
                    .zip(&h[rg])
                {
                    let (q, clip, enter) = step.point(*pk, uk, hk, tk);
                    *pk = q;
                    *x = q;
                    acc[0] += q;
                    acc[1] += clip;
                    acc[2] += enter;
                }
                acc
            },
            &mut self.u[..],
            |i, u, p| contact_sums(u, p, &h[i * n..(i + 1) * n]),
        );
        let [sum_p, clipped, entered] = add_all(rows);
        let [su, sh, cnt] = add_all(outs);
        Update {
            sum_p,
            clipped,
            entered,
            su,
            sh,
            cnt,
        }
    }

    /// Step 4 in one sweep with the incremental update of the displacement,
    /// `u <- scale u - tau r` (exact while no point is clipped or enters).
    fn update_incremental(&mut self, step: Step) -> Update {
        let h = self.problem.heights;
        let (t, r) = (&self.t[..], &self.r[..]);
        let (scale, tau) = (step.scale, step.tau);
        let parts: Vec<[f64; 6]> = self
            .p
            .par_chunks_mut(CHUNK)
            .zip(self.u.par_chunks_mut(CHUNK))
            .enumerate()
            .map(|(c, (pc, uc))| {
                let range = c * CHUNK..c * CHUNK + pc.len();
                let (t, r, h) = (&t[range.clone()], &r[range.clone()], &h[range]);
                let mut acc = [0.0; 6];
                for ((((pk, uk), &tk), &rk), &hk) in
                    pc.iter_mut().zip(uc.iter_mut()).zip(t).zip(r).zip(h)
                {
                    let (q, clip, enter) = step.point(*pk, *uk, hk, tk);
                    let u_new = scale * *uk - tau * rk;
                    *pk = q;
                    *uk = u_new;
                    let w = if q > 0.0 { 1.0 } else { 0.0 };
                    acc[0] += q;
                    acc[1] += clip;
                    acc[2] += enter;
                    acc[3] += w * u_new;
                    acc[4] += w * hk;
                    acc[5] += w;
                }
                acc
            })
            .collect();
        let [sum_p, clipped, entered, su, sh, cnt] = add_all(parts);
        Update {
            sum_p,
            clipped,
            entered,
            su,
            sh,
            cnt,
        }
    }

    /// Step 5: the load, `p <- p p0 / mean(p)`, applied lazily as the load scale.
    fn restore_load(&mut self, it: usize, update: &Update) -> Result<()> {
        let problem = self.problem;
        self.scale = problem.p0 * problem.model.grid.points() as f64 / update.sum_p;
        if !self.scale.is_finite() || update.cnt == 0.0 {
            return Err(non_finite("pressure", it));
        }
        Ok(())
    }

    /// Step 6: the displacement and the rigid shift `gbar = mean_Ic (u - h)` of the new
    /// pressure. After a fused update `u = K^-1 p` is exact already; after an
    /// incremental one it is recomputed when the contact set changed or every
    /// [`ConstrainedCg::refresh_every`] iterations, and otherwise kept.
    fn refresh(&mut self, update: &Update) {
        let Update { su, sh, cnt, .. } = *update;
        self.since_refresh += 1;
        self.n_c = cnt;
        let fused = self.set_changed;
        self.set_changed = update.clipped + update.entered > 0.0;
        if fused {
            // u = K^-1 p of the stored (unscaled) pressure: the scale applies to both.
            self.gbar = (self.scale * su - sh) / cnt;
            self.exact = true;
            self.since_refresh = 0;
        } else if self.set_changed || self.since_refresh >= self.refresh_every {
            self.exact_displacement();
        } else {
            self.gbar = (self.scale * su - sh) / cnt;
            self.exact = false;
        }
    }

    /// Applies the load scale to `p` (leaving `scale = 1`), recomputes `u = K^-1 p`, the
    /// rigid shift `gbar = mean_Ic (u - h)` and the number of points in contact: the
    /// state is exact.
    fn exact_displacement(&mut self) {
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.n();
        let h = problem.heights;
        let s = self.scale;
        let (_, outs) = model.fft.convolve(
            &model.compliance,
            &mut self.spec[..],
            Some(&mut self.p[..]),
            |_, row, p, _| {
                for (x, pj) in row.iter_mut().zip(p.iter_mut()) {
                    *pj *= s;
                    *x = *pj;
                }
            },
            &mut self.u[..],
            |i, u, p| contact_sums(u, p, &h[i * n..(i + 1) * n]),
        );
        self.scale = 1.0;
        let [su, sh, cnt] = add_all(outs);
        self.gbar = if cnt > 0.0 { (su - sh) / cnt } else { f64::NAN };
        self.n_c = cnt;
        self.exact = true;
        self.since_refresh = 0;
    }

    /// Packs the current state into a solution with its residual, moving `p` and `u`
    /// into it.
    fn finish(&mut self, iterations: usize) -> ContactSolution {
        let problem = self.problem;
        let (scale, gbar) = (self.scale, self.gbar);
        // The solution takes the solver's buffers rather than copying them (16 bytes per
        // point at the peak); `resume` hands them back when the solve must go on.
        let mut pressure = std::mem::take(&mut *self.p);
        let mut displacement = std::mem::take(&mut *self.u);
        pressure.par_iter_mut().for_each(|p| *p *= scale);
        displacement
            .par_iter_mut()
            .for_each(|u| *u = scale * *u - gbar);
        let residual = Residual::evaluate(
            problem,
            &pressure,
            &displacement,
            &mut *self.spec,
            &mut *self.r,
        );
        ContactSolution {
            pressure,
            displacement,
            p0: problem.p0,
            stats: SolveStats {
                solver: NAME,
                iterations,
                residual,
                wall_s: self.timer.elapsed().as_secs_f64(),
                warm: self.warm,
            },
        }
    }

    /// Takes back the buffers of a [`Self::finish`]ed state to iterate on (the load scale
    /// is then 1, and the rigid shift the one it was packed with).
    fn resume(&mut self, solution: ContactSolution) {
        *self.p = solution.pressure;
        *self.u = solution.displacement;
        let gbar = self.gbar;
        self.u.par_iter_mut().for_each(|u| *u += gbar);
        self.scale = 1.0;
    }

    /// The end of a solve whose loop ended at iteration `spent` for `reason` (budget
    /// exhausted or stalled): the last step may have converged; if not, the error reports
    /// the smallest residual reached, the exact state's or an earlier one's.
    fn conclude(mut self, (spent, reason): (usize, Termination)) -> Result<ContactSolution> {
        self.exact_displacement();
        let solution = self.finish(spent);
        let residual = solution.stats.residual.value();
        if residual <= self.stopping.tol {
            return Ok(solution);
        }
        Err(Error::NotConverged {
            solver: NAME,
            reason,
            iterations: spent,
            residual: residual.min(self.stopping.reached),
            tol: self.stopping.tol,
        })
    }
}

/// The displacement of a point under unit pressure on that point alone,
/// `N^-2 sum_q 2 / (q E*)` (the diagonal of the compliance in real space).
fn point_compliance(model: &crate::engine::contact::Model) -> f64 {
    let grid = &model.grid;
    let sum: f64 = model
        .halfspace
        .compliance()
        .enumerate()
        .map(|(s, c)| grid.weight_of(s) * c)
        .sum();
    sum / grid.points() as f64
}

impl Solver for ConstrainedCg {
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
