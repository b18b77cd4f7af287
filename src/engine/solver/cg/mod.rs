//! Constrained conjugate gradients for the hard-wall problem (Polonsky & Keer, Wear 231,
//! 206 (1999)); the algorithm of tamaas's `PolonskyKeerRey` and of ContactMechanics.
//!
//! The unknown is the pressure `p >= 0` with `mean(p) = p0`; the displacement is
//! `u = K^-1 p` (zero mean) and the gap `g = u - h - gbar`, where the rigid shift `gbar` is
//! the mean of `u - h` over the contact set `Ic = {p > 0}`. Each iteration:
//!
//! 1. `G = sum_Ic g z` with the preconditioned gap `z` (below; `z = g` without
//!    preconditioning); search direction `t = z + delta (G / G_old) t` on `Ic`, 0 elsewhere;
//! 2. `r = K^-1 t` (one forward and one inverse FFT), `rbar = mean_Ic r`;
//! 3. step `tau = sum_Ic g t / sum_Ic (r - rbar) t`; `p <- max(p - tau t, 0)` on `Ic`;
//! 4. points out of contact that penetrate (`p = 0`, `g < 0`) enter with `p = -tau k g`
//!    (`k = 1`, or with preconditioning the Rayleigh quotient `g.z / g.g`, the stiffness
//!    the preconditioner applied, so that the entering pressure has the units of `t`), and
//!    conjugacy is reset (`delta = 0`) when more than 1% of the contact set enters
//!    (Polonsky & Keer reset it when any point enters; see [`KEEP_CONJUGACY`]). When the
//!    gap vanishes on the contact set (a lone contact point), `t = 0` and `tau` is `0/0`:
//!    then `p` stays and the penetrating points enter with `p = -g / G(0)`, `G(0)` the
//!    displacement of a point under unit pressure on it alone;
//! 5. `p <- p p0 / mean(p)` restores the load.
//!
//! Preconditioning (on by default; Vollebregt, J. Comput. Phys. 257, 333 (2014)): the
//! Hessian of the complementary energy is the compliance `K^-1`, whose condition number
//! grows like `N`; the search direction is built from `z = K g` (the stiffness applied to
//! the gap, restricted to the contact set and made mean-free) instead of `g`, and `beta`
//! from `g.z`. One more FFT pair per iteration buys a several times smaller iteration
//! count (the README's measured section gives the figures).
//!
//! The displacement is updated incrementally, `u <- u - tau r`, which is exact as long as
//! step 3 clips nothing and step 4 adds nothing; otherwise `u = K^-1 p` is recomputed. `u`
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
//! Stopping: the iteration watches an estimate of the residual (complementarity and
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

use self::sums::{add_all, contact_sums, GapSums, Step, View};

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
    fn run(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress),
    ) -> Result<ContactSolution> {
        opts.validate()?;
        let timer = Instant::now();
        let model = problem.model;
        let n = model.grid.n();
        let n2 = model.grid.points();
        let h = problem.heights;
        let p0 = problem.p0;
        let ell = problem.length_scale;
        let stiffness_table = &model.stiffness;
        let compliance_table = &model.compliance;
        ensure_len(&mut self.p, n2);
        ensure_len(&mut self.u, n2);
        ensure_len(&mut self.t, n2);
        ensure_len(&mut self.r, n2);
        ensure_len(&mut self.spec, model.grid.modes());

        let warm = matches!(start, Start::Warm(_));
        match start {
            Start::Cold => {
                self.p.fill(p0);
                self.u.fill(0.0);
            }
            Start::Warm(prev) => {
                if prev.pressure.len() != n2 {
                    return Err(Error::invalid(
                        "warm start",
                        format!("{} points", prev.pressure.len()),
                        format!("a solution on the same grid ({n2} points)"),
                    ));
                }
                self.p
                    .par_iter_mut()
                    .zip(&prev.pressure)
                    .for_each(|(p, &q)| *p = q.max(0.0));
                let mean = crate::engine::field::mean(&self.p);
                if !(mean > 0.0 && mean.is_finite()) {
                    self.p.fill(p0);
                }
            }
        }
        // The load scale that makes mean(p) = p0.
        let mut scale = p0 / crate::engine::field::mean(&self.p);
        // Points in contact, and the rigid shift. A uniform pressure displaces nothing
        // (the compliance has no q = 0 mode): a cold start needs no transform.
        let (mut gbar, mut n_c) = if warm {
            self.exact_displacement(problem, &mut scale)
        } else {
            (-crate::engine::field::mean(h), n2 as f64)
        };
        self.t.fill(0.0);

        let mut rho_old = 1.0;
        let mut conjugate = false;
        let mut exact = true; // u == K^-1 p up to one transform's rounding
        let mut since_refresh = 0usize;
        // Whether the last update changed the contact set, so that u had to be recomputed
        // (see steps 3-4 below); taken as so at the start.
        let mut set_changed = true;
        let mut internal_tol = opts.tol;
        let mut precond = self.preconditioned;
        let (mut best, mut best_at) = (f64::INFINITY, 0usize);
        // Smallest full residual evaluated, and the iterations spent.
        let mut reached = f64::INFINITY;
        let mut spent = opts.max_iter;
        let mut reason = Termination::BudgetExhausted;

        for it in 0..opts.max_iter {
            if !gbar.is_finite() || !scale.is_finite() {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "gap",
                    iteration: it,
                });
            }
            // 1. The gap and the preconditioned gap z = K g (or z = g).
            let view = View {
                p: &self.p,
                u: &self.u,
                h,
                scale,
                gbar,
            };
            let (gap, sz, rho) = if precond {
                let (rows, outs) = model.fft.convolve(
                    stiffness_table,
                    &mut self.spec,
                    None,
                    |i, row, _, _| view.gap_sums_into(i * n..(i + 1) * n, Some(row)),
                    // z shares r's memory: it is read while t is generated, before r is
                    // written (see `Fft2::convolve`).
                    &mut self.r,
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
                let gap = rows.into_iter().fold(GapSums::default(), GapSums::add);
                let [sz, gz] = add_all(outs);
                (gap, sz, gz)
            } else {
                let gap = view.gap_sums();
                (gap, 0.0, gap.gg)
            };
            if !(gap.gg.is_finite() && rho.is_finite()) {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "gap",
                    iteration: it,
                });
            }
            let estimate = gap.estimate(ell);
            monitor(Progress {
                iteration: it,
                residual: estimate,
            });
            // Safeguard: if the preconditioned iteration stops improving, finish this solve
            // with plain Polonsky-Keer, which always converges (slowly).
            if estimate < 0.5 * best {
                best = estimate;
                best_at = it;
            } else if it - best_at > STAGNATION {
                if precond {
                    precond = false;
                    conjugate = false;
                    best_at = it;
                } else if internal_tol < opts.tol {
                    spent = it;
                    reason = Termination::Stalled;
                    break;
                }
            }
            if estimate <= internal_tol {
                if !exact {
                    (gbar, n_c) = self.exact_displacement(problem, &mut scale);
                    exact = true;
                    since_refresh = 0;
                    // The estimate of the exact state, without the preconditioner's
                    // transforms: if it still holds, the solve is done.
                    let view = View {
                        p: &self.p,
                        u: &self.u,
                        h,
                        scale,
                        gbar,
                    };
                    if view.gap_sums().estimate(ell) > internal_tol {
                        continue;
                    }
                }
                let solution = self.finish(problem, scale, gbar, it, warm, timer);
                if solution.stats.residual.value() <= opts.tol {
                    return Ok(solution);
                }
                reached = reached.min(solution.stats.residual.value());
                internal_tol *= 0.25;
                self.resume(solution, gbar);
                scale = 1.0;
            }

            // 2. Search direction t (kept in self.t) and r = K^-1 t, with the step's sums.
            let zbar = if precond { sz / n_c } else { 0.0 };
            let beta = if conjugate { rho / rho_old } else { 0.0 };
            rho_old = rho;
            // Gap-to-pressure conversion for points entering contact (see step 4).
            let stiffness = if precond && gap.gg > 0.0 {
                rho / gap.gg
            } else {
                1.0
            };
            let view = View {
                p: &self.p,
                u: &self.u,
                h,
                scale,
                gbar,
            };
            let (_, outs) = model.fft.convolve(
                compliance_table,
                &mut self.spec,
                Some(&mut self.t),
                |i, row, t, z| {
                    let (p, u, h) = view.row(i, n);
                    let (s, gbar) = (view.scale, view.gbar);
                    if precond {
                        for (((x, tk), &zk), &pk) in row.iter_mut().zip(t.iter_mut()).zip(z).zip(p)
                        {
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
                &mut self.r,
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
            // Pressure per unit penetration given to points entering contact (step 4).
            let (tau, admit) = if gap.gg == 0.0 {
                // The gap vanishes on the contact set (always so for a lone contact
                // point), so t = 0 and the step length is 0/0: the contact set is at rest
                // and only penetrating points can move the solve on. They enter with the
                // pressure that would lift a lone point by its penetration.
                (0.0, 1.0 / point_compliance(model))
            } else {
                let denom = rt - sum_r / n_c * sum_t;
                let tau = gt / denom;
                if !(denom > 0.0 && tau.is_finite()) {
                    if conjugate {
                        conjugate = false;
                        continue;
                    }
                    return Err(Error::NonFinite {
                        solver: NAME,
                        what: "step length",
                        iteration: it,
                    });
                }
                (tau, tau * stiffness)
            };

            // 3-4. Update p, counting projections, and sum what the next rigid shift needs
            // (sum_Ic u, sum_Ic h, |Ic| of the new contact set). When the last update
            // changed the contact set, this one most likely will too (points enter or leave at
            // nearly every iteration of a warm solve): the update then generates the new
            // pressure as the input of the convolution u = K^-1 p, and the incremental
            // update of u is skipped.
            let step = Step {
                scale,
                gbar,
                tau,
                admit,
            };
            let (t, r) = (&self.t, &self.r);
            let (new_sum_p, clipped, entered, su, sh, cnt);
            if set_changed {
                let (rows, outs) = model.fft.convolve(
                    &model.compliance,
                    &mut self.spec,
                    Some(&mut self.p),
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
                    &mut self.u,
                    |i, u, p| contact_sums(u, p, &h[i * n..(i + 1) * n]),
                );
                [new_sum_p, clipped, entered] = add_all(rows);
                [su, sh, cnt] = add_all(outs);
            } else {
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
                [new_sum_p, clipped, entered, su, sh, cnt] = add_all(parts);
            }
            // Conjugacy survives when few points entered contact (see KEEP_CONJUGACY), and
            // never a step without a direction (rho = 0 would make the next beta 0/0).
            conjugate = tau != 0.0 && entered <= KEEP_CONJUGACY * cnt;
            scale = p0 * n2 as f64 / new_sum_p;
            if !scale.is_finite() || cnt == 0.0 {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "pressure",
                    iteration: it,
                });
            }
            since_refresh += 1;
            n_c = cnt;
            let fused = set_changed;
            set_changed = clipped + entered > 0.0;
            if fused {
                // u = K^-1 p of the stored (unscaled) pressure: the scale applies to both.
                gbar = (scale * su - sh) / cnt;
                exact = true;
                since_refresh = 0;
            } else if set_changed || since_refresh >= self.refresh_every {
                (gbar, n_c) = self.exact_displacement(problem, &mut scale);
                exact = true;
                since_refresh = 0;
            } else {
                gbar = (scale * su - sh) / cnt;
                exact = false;
            }
        }
        // Budget exhausted or stalled: the last step may have converged; if not, report
        // the smallest residual reached, the exact state's or an earlier one's.
        (gbar, _) = self.exact_displacement(problem, &mut scale);
        let solution = self.finish(problem, scale, gbar, spent, warm, timer);
        if solution.stats.residual.value() <= opts.tol {
            return Ok(solution);
        }
        Err(Error::NotConverged {
            solver: NAME,
            reason,
            iterations: spent,
            residual: solution.stats.residual.value().min(reached),
            tol: opts.tol,
        })
    }

    /// Applies the load scale to `p` (leaving `scale = 1`), recomputes `u = K^-1 p`, and
    /// returns the rigid shift (the mean of `u - h` over the contact set) and the number of
    /// points in contact.
    fn exact_displacement(&mut self, problem: &ContactProblem, scale: &mut f64) -> (f64, f64) {
        let model = problem.model;
        let n = model.grid.n();
        let h = problem.heights;
        let s = *scale;
        let (_, outs) = model.fft.convolve(
            &model.compliance,
            &mut self.spec,
            Some(&mut self.p),
            |_, row, p, _| {
                for (x, pj) in row.iter_mut().zip(p.iter_mut()) {
                    *pj *= s;
                    *x = *pj;
                }
            },
            &mut self.u,
            |i, u, p| contact_sums(u, p, &h[i * n..(i + 1) * n]),
        );
        *scale = 1.0;
        let [su, sh, cnt] = add_all(outs);
        let gbar = if cnt > 0.0 { (su - sh) / cnt } else { f64::NAN };
        (gbar, cnt)
    }

    /// Packs the current state (load scale `scale`, rigid shift `gbar`) into a solution
    /// with its residual, moving `p` and `u` into it.
    fn finish(
        &mut self,
        problem: &ContactProblem,
        scale: f64,
        gbar: f64,
        iterations: usize,
        warm: bool,
        timer: Instant,
    ) -> ContactSolution {
        // The solution takes the solver's buffers rather than copying them (16 bytes per
        // point at the peak); `resume` hands them back when the solve must go on.
        let mut pressure = std::mem::take(&mut self.p);
        let mut displacement = std::mem::take(&mut self.u);
        pressure.par_iter_mut().for_each(|p| *p *= scale);
        displacement
            .par_iter_mut()
            .for_each(|u| *u = scale * *u - gbar);
        let residual = Residual::evaluate(
            problem,
            &pressure,
            &displacement,
            &mut self.spec,
            &mut self.r,
        );
        ContactSolution {
            pressure,
            displacement,
            p0: problem.p0,
            stats: SolveStats {
                solver: NAME,
                iterations,
                residual,
                wall_s: timer.elapsed().as_secs_f64(),
                warm,
            },
        }
    }

    /// Takes back the buffers of a [`Self::finish`]ed state to iterate on (the load scale
    /// is then 1, and the rigid shift `gbar` the one it was packed with).
    fn resume(&mut self, solution: ContactSolution, gbar: f64) {
        self.p = solution.pressure;
        self.u = solution.displacement;
        self.u.par_iter_mut().for_each(|u| *u += gbar);
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
