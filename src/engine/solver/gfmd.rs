//! Green's function molecular dynamics (GFMD) with mass weighting and FIRE.
//!
//! The paper's method (section 2.3; Campana & Müser, PRB 74, 075420 (2006); Prodanov,
//! Dapp & Müser, Tribol. Lett. 53, 433 (2014)): damped Newtonian dynamics of the surface
//! displacement, whose elastic force is diagonal in reciprocal space,
//!
//! ```text
//!     F~_el(q) = -(q E*/2) u~(q)    (q != 0),     F~_el(0) = -p0,
//! ```
//!
//! against a hard wall in real space. Each step:
//!
//! 1. stress `s = K u + p0` (one forward and one inverse FFT);
//! 2. total force `F = -s`, except at points on the wall (`u = h`) where the wall's reaction
//!    cancels a compressive stress: `F = max(-s, 0)` there;
//! 3. mass-weighted acceleration `a~(q) = F~(q) / m(q)` (one forward and one inverse FFT);
//! 4. FIRE update of the velocity, then `v += dt a`, `u += dt v`;
//! 5. the wall: `u < h` is set to `u = h` and its velocity into the wall removed.
//!
//! Mass weighting (Zhou, Moseler & Müser, PRB 99, 144103 (2019)): `m(q) = q E*/2`, so every
//! free mode oscillates with the same frequency `omega = 1` and the time step is set by one
//! frequency instead of the stiffest mode; the rigid mode `q = 0` gets the mass of the
//! softest non-zero mode. This is what removes the `O(L)` critical slowing-down of
//! real-space damped dynamics. The wall reaction must be part of `F` before the mass
//! filter is applied: the filter is non-local, and an unbalanced push at contact points
//! would otherwise drive the free points next to them into the wall.
//!
//! FIRE (Bitzek et al., PRL 97, 170201 (2006)) with the preconditioned force as direction:
//! with the power `P = sum F v`, `v <- (1 - alpha) v + alpha |v| a / |a|`, and the step
//! grows while `P > 0`; at `P <= 0` the velocity is zeroed, the step shrinks and `alpha`
//! resets.
//!
//! Cold and warm starts are damped differently ([`FireParams`]). From a cold start the
//! surface has to travel to the wall as a whole (at very low load, onto a few contact
//! points): Bitzek's light mixing (`alpha_start = 0.1`) lets that slow, global motion
//! gather speed. A warm start is already near equilibrium; what is left is the
//! rearrangement around the contact set's edges, whose modes the constraint couples, and
//! heavy mixing (`alpha_warm = 0.7`) damps their oscillation best. A warm start also
//! begins at the largest step, since a ramp from a small one would spend its first
//! iterations rediscovering that the state is close. Mass weighting gives every free mode
//! one frequency, so the step may grow at once (`n_min = 1`) to one mode period.
//!
//! Convergence: the stress of step 1 gives the pressure `p = max(s, 0)` on the wall and 0
//! elsewhere, and with it the two parts of the residual GFMD does not satisfy by
//! construction (equilibrium and load); when both are below the tolerance the full
//! [`Residual`] is evaluated.

use std::time::Instant;

use rayon::prelude::*;
use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use super::ensure_len;
use crate::engine::contact::{ContactProblem, ContactSolution, Residual, SolveStats};
use crate::engine::field::{fold_chunks, CHUNK};
use crate::engine::solver::{Progress, SolveOptions, Solver, Start};
use crate::error::{Error, Result, Termination};

/// FIRE's constants, with time steps in units of the common mode period `1/omega`.
///
/// The defaults are Bitzek et al.'s for a cold start but for the delay before the step
/// grows (`n_min = 1` instead of 5) and the largest step (one period); a warm start mixes
/// more strongly (`alpha_warm`) and starts at the largest step (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FireParams {
    /// Initial time step.
    pub dt_init: f64,
    /// Largest time step.
    pub dt_max: f64,
    /// Steps with `P > 0` before the step may grow.
    pub n_min: usize,
    /// Growth factor of the step.
    pub f_inc: f64,
    /// Shrink factor of the step at `P <= 0`.
    pub f_dec: f64,
    /// Initial mixing parameter of a cold start (and after every restart of one).
    pub alpha_start: f64,
    /// Initial mixing parameter of a warm start (and after every restart of one).
    pub alpha_warm: f64,
    /// Decay of the mixing parameter.
    pub f_alpha: f64,
}

impl Default for FireParams {
    fn default() -> Self {
        Self {
            dt_init: 0.1,
            dt_max: 1.0,
            n_min: 1,
            f_inc: 1.1,
            f_dec: 0.5,
            alpha_start: 0.1,
            alpha_warm: 0.7,
            f_alpha: 0.99,
        }
    }
}

/// GFMD solver with its work buffers.
#[derive(Debug, Clone)]
pub struct Gfmd {
    /// FIRE constants.
    pub fire: FireParams,
    /// Mass weighting on (the default). Off, every mode has the mass of the stiffest one:
    /// plain damped dynamics, kept to measure what mass weighting buys.
    pub mass_weighted: bool,
    spec: Vec<Complex64>,
    u: Vec<f64>,
    v: Vec<f64>,
    force: Vec<f64>,
    accel: Vec<f64>,
    inv_mass: Vec<f64>,
}

impl Default for Gfmd {
    fn default() -> Self {
        Self {
            fire: FireParams::default(),
            mass_weighted: true,
            spec: Vec::new(),
            u: Vec::new(),
            v: Vec::new(),
            force: Vec::new(),
            accel: Vec::new(),
            inv_mass: Vec::new(),
        }
    }
}

const NAME: &str = "gfmd";

impl Gfmd {
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
        let model = problem.model;
        let grid = &model.grid;
        let (n2, modes) = (grid.points(), grid.modes());
        let h = problem.heights;
        ensure_len(&mut self.spec, modes);
        ensure_len(&mut self.u, n2);
        ensure_len(&mut self.v, n2);
        ensure_len(&mut self.force, n2);
        ensure_len(&mut self.accel, n2);
        // Mass weighting: m(q) = q E*/2, and the softest mode's mass for q = 0.
        let stiffness = model.halfspace.stiffness();
        let k_min = stiffness
            .iter()
            .copied()
            .filter(|&k| k > 0.0)
            .fold(f64::INFINITY, f64::min);
        self.inv_mass.clear();
        self.inv_mass.extend(
            stiffness
                .iter()
                .map(|&k| 1.0 / if k > 0.0 { k } else { k_min }),
        );
        if !self.mass_weighted {
            let k_max = stiffness.iter().copied().fold(0.0, f64::max);
            self.inv_mass.iter_mut().for_each(|w| *w = 1.0 / k_max);
        }

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
                self.u
                    .par_iter_mut()
                    .zip(&prev.displacement)
                    .zip(h)
                    .for_each(|((u, &v), &hh)| *u = v.max(hh));
            }
        }
        self.v.fill(0.0);

        let mut fire = self.fire;
        if warm {
            // Near equilibrium: the largest step, and strong mixing.
            fire.dt_init = fire.dt_max;
            fire.alpha_start = fire.alpha_warm;
        }
        let mut dt = fire.dt_init;
        let mut alpha = fire.alpha_start;
        let mut since_negative = 0usize;

        for it in 0..opts.max_iter {
            // 1-2: stress, total force with the wall's reaction, and the balance residual.
            let (equilibrium, load, finite) = self.forces(problem);
            if !finite {
                return Err(Error::NonFinite {
                    solver: NAME,
                    what: "stress",
                    iteration: it,
                });
            }
            monitor(Progress {
                iteration: it,
                residual: equilibrium.max(load),
            });
            if equilibrium.max(load) <= opts.tol {
                let solution = self.finish(problem, it, warm, timer);
                if solution.stats.residual.value() <= opts.tol {
                    return Ok(solution);
                }
                self.u = solution.displacement;
            }
            // 3: mass-weighted acceleration.
            model.fft.forward(&self.force, &mut self.spec);
            for (s, w) in self.spec.iter_mut().zip(&self.inv_mass) {
                *s *= *w;
            }
            model.fft.inverse_in_place(&mut self.spec, &mut self.accel);
            // 4: FIRE.
            let (f, v, a) = (&self.force, &self.v, &self.accel);
            let (power, v2, a2) = fold_chunks(
                n2,
                (0.0, 0.0, 0.0),
                |rg| {
                    let (mut pw, mut v2, mut a2) = (0.0, 0.0, 0.0);
                    for i in rg {
                        pw += f[i] * v[i];
                        v2 += v[i] * v[i];
                        a2 += a[i] * a[i];
                    }
                    (pw, v2, a2)
                },
                |x, y| (x.0 + y.0, x.1 + y.1, x.2 + y.2),
            );
            let (keep, mix) = if power > 0.0 {
                since_negative += 1;
                let mix = if a2 > 0.0 {
                    alpha * (v2 / a2).sqrt()
                } else {
                    0.0
                };
                let keep = 1.0 - alpha;
                if since_negative > fire.n_min {
                    dt = (dt * fire.f_inc).min(fire.dt_max);
                    alpha *= fire.f_alpha;
                }
                (keep, mix)
            } else {
                since_negative = 0;
                dt *= fire.f_dec;
                alpha = fire.alpha_start;
                (0.0, 0.0)
            };
            // 4-5: kick, drift, wall. Points held by the wall (on it, with a compressive
            // stress, so zero total force) stay put: the mass filter is non-local and would
            // otherwise lift them.
            let (a, f) = (&self.accel, &self.force);
            self.u
                .par_chunks_mut(CHUNK)
                .zip(self.v.par_chunks_mut(CHUNK))
                .enumerate()
                .for_each(|(c, (uc, vc))| {
                    let base = c * CHUNK;
                    for k in 0..uc.len() {
                        let i = base + k;
                        if uc[k] <= h[i] && f[i] == 0.0 {
                            vc[k] = 0.0;
                            continue;
                        }
                        let mut vel = vc[k] * keep + a[i] * (mix + dt);
                        let mut pos = uc[k] + dt * vel;
                        if pos < h[i] {
                            pos = h[i];
                            vel = vel.max(0.0);
                        }
                        uc[k] = pos;
                        vc[k] = vel;
                    }
                });
        }
        // Budget exhausted: the state the last step reached (its stress recomputed, step 3
        // having overwritten it) may have converged; if not, report its residual.
        if !self.forces(problem).2 {
            return Err(Error::NonFinite {
                solver: NAME,
                what: "stress",
                iteration: opts.max_iter,
            });
        }
        let solution = self.finish(problem, opts.max_iter, warm, timer);
        if solution.stats.residual.value() <= opts.tol {
            return Ok(solution);
        }
        Err(Error::NotConverged {
            solver: NAME,
            reason: Termination::BudgetExhausted,
            iterations: opts.max_iter,
            residual: solution.stats.residual.value(),
            tol: opts.tol,
        })
    }

    /// Stress `s = K u + p0` and the total force `F` (into `self.force`); returns the
    /// equilibrium and load parts of the residual for the pressure `p = max(s, 0)` on the
    /// wall (0 elsewhere), and whether the stress is finite. `self.accel` receives `s`.
    fn forces(&mut self, problem: &ContactProblem) -> (f64, f64, bool) {
        let model = problem.model;
        model.fft.forward(&self.u, &mut self.spec);
        for (w, k) in self.spec.iter_mut().zip(model.halfspace.stiffness()) {
            *w *= *k;
        }
        self.spec[0] = Complex64::new(problem.p0, 0.0);
        model.fft.inverse_in_place(&mut self.spec, &mut self.accel);
        let (h, u, s) = (problem.heights, &self.u, &self.accel);
        let parts: Vec<(f64, f64, f64, bool)> = self
            .force
            .par_chunks_mut(CHUNK)
            .enumerate()
            .map(|(c, fc)| {
                let base = c * CHUNK;
                let (mut ub, mut sp, mut sp2, mut fin) = (0.0, 0.0, 0.0, true);
                for (k, f) in fc.iter_mut().enumerate() {
                    let i = base + k;
                    let on_wall = u[i] <= h[i];
                    let p = if on_wall { s[i].max(0.0) } else { 0.0 };
                    *f = if on_wall { (-s[i]).max(0.0) } else { -s[i] };
                    ub += (s[i] - p) * (s[i] - p);
                    sp += p;
                    sp2 += p * p;
                    fin &= s[i].is_finite();
                }
                (ub, sp, sp2, fin)
            })
            .collect();
        let (unbalanced, sum_p, sum_p2, finite) =
            parts.into_iter().fold((0.0, 0.0, 0.0, true), |a, b| {
                (a.0 + b.0, a.1 + b.1, a.2 + b.2, a.3 && b.3)
            });
        let npts = u.len() as f64;
        let rms_p = (sum_p2 / npts).sqrt().max(f64::MIN_POSITIVE);
        let equilibrium = (unbalanced / npts).sqrt() / rms_p;
        let load = (sum_p / npts - problem.p0).abs() / problem.p0;
        (equilibrium, load, finite)
    }

    /// Packs the current state into a solution with its residual, moving `u` into it.
    /// Expects the stress of the current state in `self.accel` (as left by
    /// [`Gfmd::forces`]).
    fn finish(
        &mut self,
        problem: &ContactProblem,
        iterations: usize,
        warm: bool,
        timer: Instant,
    ) -> ContactSolution {
        let h = problem.heights;
        let pressure: Vec<f64> = self
            .u
            .par_iter()
            .zip(self.accel.par_iter().zip(h))
            .map(|(&u, (&s, &hh))| if u <= hh { s.max(0.0) } else { 0.0 })
            .collect();
        // The solution takes the displacement buffer (the caller hands it back to go on).
        let displacement = std::mem::take(&mut self.u);
        let residual = Residual::evaluate(
            problem,
            &pressure,
            &displacement,
            &mut self.spec,
            &mut self.force,
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
