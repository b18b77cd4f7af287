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
//! solve stops (see "Stopping" below). The executor
//! ([`crate::engine::solver::executor`]) runs these steps: step 1 is the measure, the two
//! checks the judgement, steps 2 to 6 the step, and [`Solve::conclude`] the termination.
//!
//! Preconditioning (on by default; Vollebregt, J. Comput. Phys. 257, 333 (2014)): the
//! Hessian of the complementary energy is the compliance `K^-1`, whose condition number
//! grows like `N`; the search direction is built from `z = K g` (the stiffness applied to
//! the gap, restricted to the contact set and made mean-free) instead of `g`, and `beta`
//! from `g.z`. One more FFT pair per iteration buys a several times smaller iteration
//! count (`docs/measured.md` gives the figures).
//!
//! The displacement is updated incrementally, `u <- u - tau r`, which is exact as long as
//! step 4 clips nothing and adds nothing; otherwise `u = K^-1 p` is recomputed. `u`
//! is also recomputed every [`ConstrainedCg::refresh_every`] ([`REFRESH_EVERY`])
//! iterations and before the final residual, so rounding in the incremental update never
//! reaches a result. In a warm solve points enter or leave at nearly every iteration, so
//! after an update that changed the contact set the next one recomputes `u` whatever
//! happens: its update of `p` is the input pass of the convolution `K^-1 p` (no
//! incremental update, and no separate sweep over `p`; the guess costs a transform when it
//! is wrong, once per solve or so). The load rescaling of step 5 is applied lazily (a
//! scale factor read with `p` and `u`), and the rigid shift of the next iteration is
//! summed in the same sweep that updates `p`.
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
//! The full step can also cycle far above the tolerance: on a nearly flat surface with
//! pixel-sharp particles, the contact set alternates between two sets thousands of points
//! apart, conjugacy is reset at every step and the particle tips stay inside the wall
//! (Polonsky-Keer without preconditioning cycles alike). When the estimate stagnates
//! before it ever met the tolerance, the step length is halved ([`DAMPING`]) for the rest
//! of the solve, which breaks the cycle; a solve that never stagnates takes exactly the
//! steps it took before.
//!
//! A contact carried by a lone spike beside a smooth contact patch cycles even with the
//! damped step: the spike needs a share of the load thousands of times the smooth points'
//! pressure, and step 5's rescaling `p <- p p0 / mean(p)` takes from each point in
//! proportion to its pressure, so that the spike loses at every step what the step gave
//! it when points enter, and the smooth contact swings by thousands of points around it
//! (SurfaceTopography's interferometer scan `metropro-1.dat`: a two-step cycle of some
//! 60 000 points with the spike 0.55 pixel inside the wall). When the estimate stagnates
//! again with the damped step before it ever met the tolerance, step 5 restores the load
//! by the Euclidean projection onto `{p >= 0, mean(p) = p0}` instead
//! ([`Solve::project_load`]): `p <- max(p - lambda, 0)` on the contact set, the same
//! amount taken from every point, so that the smooth points of least pressure leave and
//! the spike keeps its share (the step is then a projected gradient step; the
//! projection's `lambda` by Michelot's algorithm, J. Optim. Theory Appl. 50, 195
//! (1986)).
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
//!
//! # Requirements
//!
//! * The model's compliance `K^-1` (steps 2 and 6) and, with preconditioning, its
//!   stiffness `K`, both convolutions on the grid ([`crate::engine::contact::Model`]),
//!   symmetric and positive definite on mean-free fields: the complementary energy is then
//!   convex and its minimum under `p >= 0`, `mean(p) = p0` unique. The rigid mode `q = 0`
//!   is carried by the load constraint (step 5), not by the kernel.
//! * A positive load `p0`, and the wall over the whole periodic grid or over a free
//!   boundary's window (the pressure stays 0 off the window).
//! * A tolerance above the residual's rounding floor ("Stopping" above): below it the
//!   solve stops at [`STAGNATION`] and fails with the smallest residual it reached.
//! * A warm start from a solution on the problem's grid
//!   ([`crate::engine::solver::workspace`] checks it).
//!
//! # References
//!
//! * I. A. Polonsky and L. M. Keer, Wear 231, 206 (1999): the constrained conjugate
//!   gradients, the entering points and the reset of conjugacy.
//! * J. Rey, G. Anciaux and J.-F. Molinari, Comput. Mech. 60, 69 (2017): the form tamaas
//!   implements (`PolonskyKeerRey`).
//! * E. A. H. Vollebregt, J. Comput. Phys. 257, 333 (2014): the preconditioner.
//! * C. Michelot, J. Optim. Theory Appl. 50, 195 (1986): the projection that restores the
//!   load when the rescaling cycles.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use crate::engine::contact::{ContactProblem, ContactSolution};
use crate::engine::field::add_all;
use crate::engine::solver::executor::{Iteration, Judgement, Method};
use crate::engine::solver::workspace::{warm_start, SolveRecord, Workspace};
use crate::engine::solver::{SolveOptions, Start};
use crate::error::{Result, Termination};

mod passes;
mod stopping;
mod sums;
mod update;

use self::stopping::Stopping;
use self::sums::{Direction, Frame, Gap, GapSums, Step, View};

/// Recompute `u = K^-1 p` from scratch at least this often (iterations): a safeguard
/// against rounding in the incremental update `u <- u - tau r`, not a tuned value (a warm
/// solve recomputes `u` at nearly every iteration anyway, and every final residual is
/// taken after a recomputation).
pub const REFRESH_EVERY: usize = 50;
/// Iterations without halving the residual estimate after which a preconditioned solve
/// continues unpreconditioned, and after which an unpreconditioned solve whose estimate
/// is already below the tolerance gives up (see "Stopping" in the module docs): iterating
/// on at rounding level only lets the conjugate directions drift away from the solution.
/// A safeguard, not a tuned value.
pub const STAGNATION: usize = 200;
/// Polonsky & Keer reset conjugacy whenever a point enters contact. Late in a solve a few
/// points enter or leave at every iteration, so that rule turns CG into steepest descent;
/// resetting only when more than this fraction of the contact set enters keeps the
/// conjugate directions through those small changes (`docs/measured.md`:
/// 83 -> 50 iterations at 1024^2; 0 restores the original rule).
pub const KEEP_CONJUGACY: f64 = 0.01;
/// The factor on the step length once the estimate has stagnated for [`STAGNATION`]
/// iterations (see "Stopping" in the module docs). On a nearly flat scan with pixel-sharp
/// particles (`tests/hard_scenes.rs`, the terrace with particles) the full step
/// overshoots: the contact set alternates between two sets thousands of points apart,
/// conjugacy is reset at every step, and the particle tips stay inside the wall, with or
/// without preconditioning. Half the step breaks the cycle (there, free boundary, 1e-8:
/// 243 iterations, 200 of them the stagnation that reveals the cycle, where the full step
/// ends its 100 000 at a residual of 17.6). A safeguard, not a tuned value; a solve that
/// never stagnates never takes it.
pub const DAMPING: f64 = 0.5;
/// The stagnation window of measured scans ([`ConstrainedCg::stagnation`]). On a scan
/// whose contact is carried by a few instrument spikes the full step cycles from the
/// first iteration, and each safeguard waits out its window: two windows of
/// `STAGNATION` (200) cost SurfaceTopography's 640 x 480 interferometer scan `metropro-1.dat`
/// some 450 iterations at every load, where the projected load then converges in about
/// 50. A window of 25 iterations gives 96 to 112 a load there, and 739 rather than 1473
/// over the eight loads of the 960 x 600 `mnt-1.mnt`, with the same contact areas;
/// solves that converge without stagnating (generated surfaces, 256^2 and 512^2: 17 to 36
/// iterations a load) take the same steps. `docs/check-surface.md` has the timings.
pub const SCAN_STAGNATION: usize = 25;

/// Constrained conjugate-gradient solver with its work buffers.
#[derive(Debug, Clone)]
pub struct ConstrainedCg {
    /// Recompute `u = K^-1 p` from scratch at least this often (iterations).
    pub refresh_every: usize,
    /// Precondition the gap with the stiffness `K` (one more FFT pair per iteration;
    /// `docs/measured.md`: 104 -> 37 iterations at 256^2, 488 -> 85 at 1024^2).
    pub preconditioned: bool,
    /// Iterations without halving the residual estimate before each safeguard of
    /// "Stopping" acts (`STAGNATION`, 200, by default). A solve that never stagnates this long
    /// takes the same steps whatever the window; a shorter window reaches the damped step
    /// and the projected load sooner where the full step cycles (measured scans with
    /// spikes: [`SCAN_STAGNATION`]).
    pub stagnation: usize,
    /// `p`, `u`, `t` and `r` (see [`Solve`]) and a half spectrum.
    work: Workspace<4>,
}

impl Default for ConstrainedCg {
    fn default() -> Self {
        Self {
            refresh_every: REFRESH_EVERY,
            preconditioned: true,
            stagnation: STAGNATION,
            work: Workspace::default(),
        }
    }
}

impl Method for ConstrainedCg {
    const NAME: &'static str = "cg";
    /// The unit of the others.
    const RELATIVE_COST: f64 = 1.0;
    type Solve<'a> = Solve<'a>;

    fn init<'a>(
        &'a mut self,
        problem: &'a ContactProblem<'a>,
        start: Start,
        opts: &SolveOptions,
    ) -> Result<Solve<'a>> {
        Solve::start(self, problem, start, opts.tol)
    }
}

impl Iteration for Solve<'_> {
    type Measure = Gap;

    fn measure(&mut self, it: usize) -> Result<Gap> {
        self.gap(it)
    }

    fn estimate(gap: &Gap) -> f64 {
        gap.estimate
    }

    fn judge(&mut self, it: usize, gap: &Gap) -> Judgement {
        if self.safeguard(it, gap.estimate) {
            return Judgement::Stopped(Termination::Stalled);
        }
        self.check(it, gap.estimate)
    }

    fn step(&mut self, it: usize, gap: Gap) -> Result<Option<Termination>> {
        let direction = self.direction(&gap);
        let Some(step) = self.step_length(it, &gap, &direction)? else {
            return Ok(None); // conjugacy reset: the next iteration starts along the gap
        };
        let update = self.update(step);
        if self.project {
            self.project_load(it, &update)?;
        } else {
            self.restore_load(it, &update)?;
            self.refresh(&update);
        }
        Ok(None)
    }

    fn terminate(self, iterations: usize, reason: Termination) -> Result<ContactSolution> {
        self.conclude(iterations, reason)
    }
}

/// The state of one solve: the fields (in the solver's buffers), with the load scale and
/// the rigid shift they are read with, the conjugate-gradient recurrence, and when `u`
/// was last recomputed.
pub struct Solve<'a> {
    problem: &'a ContactProblem<'a>,
    refresh_every: usize,
    record: SolveRecord,
    /// The pressure as stored: the true pressure is `scale p` ([`Frame`]).
    p: &'a mut Vec<f64>,
    /// The displacement `K^-1 p` of the stored pressure (the true one is `scale u`).
    u: &'a mut Vec<f64>,
    /// The search direction `t`.
    t: &'a mut Vec<f64>,
    /// `r = K^-1 t`; the preconditioned gap `z` before it.
    r: &'a mut Vec<f64>,
    spec: &'a mut Vec<Complex64>,
    /// The load scale that makes `mean(scale p) = p0`, and the rigid shift
    /// `gbar = mean_Ic (scale u - h)`.
    frame: Frame,
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
    /// The factor on every step length: 1, or [`DAMPING`] once the estimate stagnated
    /// (see [`Self::safeguard`]).
    damping: f64,
    /// Whether step 5 restores the load by projection ([`Self::project_load`]) rather
    /// than by rescaling: set once the damped step stagnated too.
    project: bool,
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
        let record = SolveRecord::begin(ConstrainedCg::NAME, matches!(start, Start::Warm(_)));
        let grid = &problem.model.grid;
        let n2 = grid.points();
        let p0 = problem.p0;
        let prev = warm_start(start, grid)?;
        let (spec, [p, u, t, r]) = cg.work.on(grid);
        match prev {
            None => {
                problem.cold_pressure(p);
                u.fill(0.0);
            }
            Some(prev) => {
                p.par_iter_mut()
                    .zip(&prev.pressure)
                    .for_each(|(p, &q)| *p = q.max(0.0));
                let mean = crate::engine::field::mean(p);
                if !(mean > 0.0 && mean.is_finite()) {
                    p.fill(p0);
                }
            }
        }
        let mut solve = Solve {
            problem,
            refresh_every: cg.refresh_every,
            record,
            // The load scale that makes mean(p) = p0; the rigid shift is set below.
            frame: Frame {
                scale: p0 / crate::engine::field::mean(p),
                gbar: f64::NAN,
            },
            p,
            u,
            t,
            r,
            spec,
            n_c: 0.0,
            rho_old: 1.0,
            conjugate: false,
            precond: cg.preconditioned,
            exact: true,
            since_refresh: 0,
            set_changed: true,
            stopping: Stopping::new(tol, cg.stagnation),
            damping: 1.0,
            project: false,
        };
        // Points in contact, and the rigid shift. A uniform pressure displaces nothing (the
        // compliance has no q = 0 mode): a cold start needs no transform, but for a free
        // boundary, whose pressure covers the window only.
        if prev.is_some() || problem.model.window.is_some() {
            solve.exact_displacement();
        } else {
            solve.frame.gbar = -crate::engine::field::mean(problem.heights);
            solve.n_c = n2 as f64;
        }
        solve.t.fill(0.0);
        Ok(solve)
    }

    /// Step 1: the gap `g = scale u - h - gbar` on `Ic` with its sums, the preconditioned
    /// gap `z = K g` (in `r`; `z = g` without preconditioning), and
    /// `G = sum_Ic g z` (`sum_Ic g^2` without preconditioning) and `sum_Ic z`.
    fn gap(&mut self, it: usize) -> Result<Gap> {
        if !self.frame.gbar.is_finite() || !self.frame.scale.is_finite() {
            return Err(self.record.non_finite("gap", it));
        }
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.cols();
        let view = View::new(&self.p[..], &self.u[..], problem.heights, self.frame);
        let (sums, sz, rho) = if self.precond {
            // z shares r's memory: it is read while t is generated, before r is written
            // (see `Fft2::convolve`).
            let pass = passes::Precondition { view, n };
            let (rows, outs) = model.fft.convolve(
                &model.stiffness,
                &mut self.spec[..],
                None,
                &pass,
                &mut self.r[..],
            );
            let sums = rows.into_iter().fold(GapSums::default(), GapSums::add);
            let [sz, gz] = add_all(outs);
            (sums, sz, gz)
        } else {
            let sums = view.gap_sums();
            (sums, 0.0, sums.gg)
        };
        if !(sums.gg.is_finite() && rho.is_finite()) {
            return Err(self.record.non_finite("gap", it));
        }
        Ok(Gap {
            sums,
            sz,
            rho,
            estimate: sums.estimate(problem.length_scale),
        })
    }

    /// Step 2: the search direction `t = (z - zbar) + delta (G / G_old) t` on `Ic`, 0
    /// elsewhere (`zbar = mean_Ic z`; without preconditioning `z - zbar` is the gap `g`
    /// itself), and its convolution `r = K^-1 t` with the sums the step length needs
    /// (`sum_Ic r`, `sum_Ic t`, `sum_Ic g t`, `sum_Ic r t`).
    fn direction(&mut self, gap: &Gap) -> Direction {
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.cols();
        let precond = self.precond;
        let zbar = if precond { gap.sz / self.n_c } else { 0.0 };
        let beta = if self.conjugate {
            gap.rho / self.rho_old
        } else {
            0.0
        };
        self.rho_old = gap.rho;
        let view = View::new(&self.p[..], &self.u[..], problem.heights, self.frame);
        let pass = passes::Direction {
            view,
            n,
            precond,
            zbar,
            beta,
        };
        let (_, outs) = model.fft.convolve(
            &model.compliance,
            &mut self.spec[..],
            Some(&mut self.t[..]),
            &pass,
            &mut self.r[..],
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
            (0.0, 1.0 / self.problem.model.point_compliance())
        } else {
            let denom = dir.rt - dir.sum_r / self.n_c * dir.sum_t;
            let tau = self.damping * (dir.gt / denom);
            if !(denom > 0.0 && tau.is_finite()) {
                if self.conjugate {
                    self.conjugate = false;
                    return Ok(None);
                }
                return Err(self.record.non_finite("step length", it));
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
            frame: self.frame,
            tau,
            admit,
        }))
    }
}
