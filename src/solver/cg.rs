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
//!    conjugacy is reset (`delta = 0`) when there are any;
//! 5. `p <- p p0 / mean(p)` restores the load.
//!
//! Preconditioning (on by default; Vollebregt, J. Comput. Phys. 257, 333 (2014)): the
//! Hessian of the complementary energy is the compliance `K^-1`, whose condition number
//! grows like `N`; the search direction is built from `z = K g` (the stiffness applied to
//! the gap, restricted to the contact set and made mean-free) instead of `g`, and `beta`
//! from `g.z`. One more FFT pair per iteration buys a 3-6x smaller iteration count
//! (256^2: 104 -> 37; 1024^2: 488 -> 85, H = 0.8, p0 = 0.1).
//!
//! The displacement is updated incrementally, `u <- u - tau r`, which is exact as long as
//! step 3 clips nothing and step 4 adds nothing; otherwise `u = K^-1 p` is recomputed. Late
//! iterations, where the contact set has settled, therefore cost one FFT pair each. `u` is
//! also recomputed every [`ConstrainedCg::refresh_every`] iterations and before the final
//! residual, so rounding in the incremental update never reaches a result.

use std::time::Instant;

use rustfft::num_complex::Complex64;

use super::{apply_compliance, ensure_len};
use crate::contact::{
    ContactProblem, ContactSolution, Progress, Residual, SolveOptions, SolveStats, Solver, Start,
};
use crate::error::{Error, Result};
use crate::field::{fold_chunks, reduce_chunks, CHUNK};
use rayon::prelude::*;

/// Constrained conjugate-gradient solver with its work buffers.
#[derive(Debug, Clone)]
pub struct ConstrainedCg {
    /// Recompute `u = K^-1 p` from scratch at least this often (iterations).
    pub refresh_every: usize,
    /// Precondition the gap with the stiffness `K` (one more FFT pair per iteration).
    pub preconditioned: bool,
    z: Vec<f64>,
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
            z: Vec::new(),
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
/// continues unpreconditioned.
const STAGNATION: usize = 200;

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
        let n2 = model.grid.points();
        let h = problem.heights;
        let p0 = problem.p0;
        let ell = problem.length_scale;
        ensure_len(&mut self.p, n2);
        ensure_len(&mut self.u, n2);
        ensure_len(&mut self.t, n2);
        ensure_len(&mut self.r, n2);
        if self.preconditioned {
            ensure_len(&mut self.z, n2);
        }
        ensure_len(&mut self.spec, model.grid.modes());

        let warm = matches!(start, Start::Warm(_));
        match start {
            Start::Cold => self.p.fill(p0),
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
                let mean = crate::field::mean(&self.p);
                if mean > 0.0 && mean.is_finite() {
                    let c = p0 / mean;
                    self.p.par_iter_mut().for_each(|p| *p *= c);
                } else {
                    self.p.fill(p0);
                }
            }
        }
        apply_compliance(model, &self.p, &mut self.u, &mut self.spec);
        self.t.fill(0.0);

        let mut g_old = 1.0;
        let mut conjugate = false;
        let mut exact = true; // u == K^-1 p up to one transform's rounding
        let mut since_refresh = 0usize;
        let mut internal_tol = opts.tol;
        let mut precond = self.preconditioned;
        let (mut best, mut best_at) = (f64::INFINITY, 0usize);

        for it in 0..opts.max_iter {
            let (p, u) = (&self.p, &self.u);
            // Pass 1: the rigid shift, mean of u - h over the contact set.
            let [sum_d, n_c] = reduce_chunks(n2, |rg| {
                let (mut s, mut c) = (0.0, 0.0);
                for i in rg {
                    if p[i] > 0.0 {
                        s += u[i] - h[i];
                        c += 1.0;
                    }
                }
                [s, c]
            });
            if n_c == 0.0 {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "contact set (empty)",
                    iteration: it,
                });
            }
            let gbar = sum_d / n_c;
            // Pass 2: G, and the parts of the residual that CG does not satisfy by
            // construction: gap inside contact and penetration outside.
            let (big_g, p_gap, sum_p, penetration) = fold_chunks(
                n2,
                (0.0, 0.0, 0.0, 0.0f64),
                |rg| {
                    let (mut gg, mut pg, mut sp, mut pen) = (0.0, 0.0, 0.0, 0.0f64);
                    for i in rg {
                        let g = u[i] - h[i] - gbar;
                        if p[i] > 0.0 {
                            gg += g * g;
                            pg += p[i] * g.abs();
                            sp += p[i];
                        } else {
                            pen = pen.max(-g);
                        }
                    }
                    (gg, pg, sp, pen)
                },
                |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2, a.3.max(b.3)),
            );
            if !big_g.is_finite() || !gbar.is_finite() {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "gap",
                    iteration: it,
                });
            }
            let estimate = (p_gap / (ell * sum_p)).max(penetration / ell);
            monitor(Progress {
                iteration: it,
                residual: estimate,
            });
            // Safeguard: if the preconditioned iteration stops improving, finish this solve
            // with plain Polonsky-Keer, which always converges (slowly).
            if estimate < 0.5 * best {
                best = estimate;
                best_at = it;
            } else if precond && it - best_at > STAGNATION {
                precond = false;
                conjugate = false;
                best_at = it;
            }
            if estimate <= internal_tol {
                if !exact {
                    apply_compliance(model, &self.p, &mut self.u, &mut self.spec);
                    exact = true;
                    since_refresh = 0;
                    continue;
                }
                let solution = self.finish(problem, gbar, it, warm, timer)?;
                if solution.stats.residual.value() <= opts.tol {
                    return Ok(solution);
                }
                internal_tol *= 0.25;
            }

            // Pass 3: search direction. `stiffness` converts a gap into the pressure that
            // closes it in the search direction's units: 1 without preconditioning, the
            // Rayleigh quotient g.Kg / g.g on the contact set with it.
            let stiffness;
            if precond {
                {
                    let (p, u) = (&self.p, &self.u);
                    self.z.par_iter_mut().enumerate().for_each(|(i, zi)| {
                        *zi = if p[i] > 0.0 { u[i] - h[i] - gbar } else { 0.0 };
                    });
                }
                model.fft.forward(&self.z, &mut self.spec);
                for (s, k) in self.spec.iter_mut().zip(model.halfspace.stiffness()) {
                    *s *= *k;
                }
                model.fft.inverse_in_place(&mut self.spec, &mut self.r);
                let (p, u, r) = (&self.p, &self.u, &self.r);
                let [sz, rho] = reduce_chunks(n2, |rg| {
                    let (mut sz, mut rho) = (0.0, 0.0);
                    for i in rg {
                        if p[i] > 0.0 {
                            sz += r[i];
                            rho += (u[i] - h[i] - gbar) * r[i];
                        }
                    }
                    [sz, rho]
                });
                // g has zero mean on C, so subtracting zbar from z leaves g.z unchanged.
                let zbar = sz / n_c;
                let beta = if conjugate { rho / g_old } else { 0.0 };
                g_old = rho;
                stiffness = if big_g > 0.0 { rho / big_g } else { 1.0 };
                let (p, r) = (&self.p, &self.r);
                self.t.par_iter_mut().enumerate().for_each(|(i, ti)| {
                    *ti = if p[i] > 0.0 {
                        r[i] - zbar + beta * *ti
                    } else {
                        0.0
                    };
                });
            } else {
                let beta = if conjugate { big_g / g_old } else { 0.0 };
                g_old = big_g;
                stiffness = 1.0;
                let (p, u) = (&self.p, &self.u);
                self.t
                    .par_chunks_mut(CHUNK)
                    .enumerate()
                    .for_each(|(c, tc)| {
                        let base = c * CHUNK;
                        for (k, ti) in tc.iter_mut().enumerate() {
                            let i = base + k;
                            *ti = if p[i] > 0.0 {
                                u[i] - h[i] - gbar + beta * *ti
                            } else {
                                0.0
                            };
                        }
                    });
            }
            apply_compliance(model, &self.t, &mut self.r, &mut self.spec);
            // Pass 4: step length.
            let (p, u, t, r) = (&self.p, &self.u, &self.t, &self.r);
            let [sum_r, sum_t, gt, rt] = reduce_chunks(n2, |rg| {
                let (mut sr, mut st, mut gt, mut rt) = (0.0, 0.0, 0.0, 0.0);
                for i in rg {
                    if p[i] > 0.0 {
                        let g = u[i] - h[i] - gbar;
                        sr += r[i];
                        st += t[i];
                        gt += g * t[i];
                        rt += r[i] * t[i];
                    }
                }
                [sr, st, gt, rt]
            });
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
            // Pass 5: update pressure and (incrementally) displacement.
            let [new_sum_p, clipped, entered] = {
                let (t, r) = (&self.t, &self.r);
                let parts: Vec<[f64; 3]> = self
                    .p
                    .par_chunks_mut(CHUNK)
                    .zip(self.u.par_chunks_mut(CHUNK))
                    .enumerate()
                    .map(|(c, (pc, uc))| {
                        let base = c * CHUNK;
                        let (mut sp, mut clip, mut enter) = (0.0, 0.0, 0.0);
                        for k in 0..pc.len() {
                            let i = base + k;
                            if pc[k] > 0.0 {
                                let q = pc[k] - tau * t[i];
                                if q > 0.0 {
                                    pc[k] = q;
                                } else {
                                    pc[k] = 0.0;
                                    clip += 1.0;
                                }
                            } else {
                                let g = uc[k] - h[i] - gbar;
                                if g < 0.0 {
                                    pc[k] = -tau * stiffness * g;
                                    enter += 1.0;
                                }
                            }
                            uc[k] -= tau * r[i];
                            sp += pc[k];
                        }
                        [sp, clip, enter]
                    })
                    .collect();
                let mut acc = [0.0; 3];
                for part in &parts {
                    for (a, v) in acc.iter_mut().zip(part) {
                        *a += v;
                    }
                }
                acc
            };
            let projected = clipped + entered > 0.0;

            // Conjugacy survives only when no point entered contact (Polonsky & Keer).
            conjugate = entered == 0.0;
            let scale = p0 * n2 as f64 / new_sum_p;
            if !scale.is_finite() {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "pressure",
                    iteration: it,
                });
            }
            since_refresh += 1;
            if projected || since_refresh >= self.refresh_every {
                self.p.par_iter_mut().for_each(|x| *x *= scale);
                apply_compliance(model, &self.p, &mut self.u, &mut self.spec);
                exact = true;
                since_refresh = 0;
            } else {
                self.p
                    .par_iter_mut()
                    .zip(self.u.par_iter_mut())
                    .for_each(|(x, y)| {
                        *x *= scale;
                        *y *= scale;
                    });
                exact = false;
            }
        }
        // Budget exhausted: report the residual of the exact state.
        apply_compliance(model, &self.p, &mut self.u, &mut self.spec);
        let gbar = contact_shift(&self.p, &self.u, h);
        let solution = self.finish(problem, gbar, opts.max_iter, warm, timer)?;
        Err(Error::NotConverged {
            solver: NAME,
            iterations: opts.max_iter,
            residual: solution.stats.residual.value(),
            tol: opts.tol,
        })
    }

    /// Packs the current state (with rigid shift `gbar`) into a solution with its residual.
    fn finish(
        &mut self,
        problem: &ContactProblem,
        gbar: f64,
        iterations: usize,
        warm: bool,
        timer: Instant,
    ) -> Result<ContactSolution> {
        let displacement: Vec<f64> = self.u.par_iter().map(|u| u - gbar).collect();
        let pressure = self.p.clone();
        let residual = Residual::evaluate(
            problem,
            &pressure,
            &displacement,
            &mut self.spec,
            &mut self.r,
        );
        Ok(ContactSolution {
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
        })
    }
}

/// Mean of `u - h` over the contact set.
fn contact_shift(p: &[f64], u: &[f64], h: &[f64]) -> f64 {
    let [s, c] = reduce_chunks(p.len(), |rg| {
        let (mut s, mut c) = (0.0, 0.0);
        for i in rg {
            if p[i] > 0.0 {
                s += u[i] - h[i];
                c += 1.0;
            }
        }
        [s, c]
    });
    if c > 0.0 {
        s / c
    } else {
        0.0
    }
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
