//! Steps 4 to 6 of a CG iteration (see the module docs): the update of the pressure, the
//! load, and the displacement and rigid shift of the new pressure.

use super::sums::{Step, Update};
use super::{passes, Solve, KEEP_CONJUGACY};
use crate::engine::field::{add_all, map_chunks_mut};
use crate::error::Result;
use rayon::prelude::*;

impl Solve<'_> {
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
    pub(super) fn update(&mut self, step: Step) -> Update {
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
        let n = model.grid.cols();
        let h = problem.heights;
        let pass = passes::Update {
            step,
            t: &self.t[..],
            h,
            n,
        };
        let (rows, outs) = model.fft.convolve(
            &model.compliance,
            &mut self.spec[..],
            Some(&mut self.p[..]),
            &pass,
            &mut self.u[..],
        );
        Update::new(add_all(rows), add_all(outs))
    }

    /// Step 4 in one sweep with the incremental update of the displacement,
    /// `u <- scale u - tau r` (exact while no point is clipped or enters).
    fn update_incremental(&mut self, step: Step) -> Update {
        let h = self.problem.heights;
        let (t, r) = (&self.t[..], &self.r[..]);
        let (scale, tau) = (step.frame.scale, step.tau);
        let parts = map_chunks_mut(self.p, self.u, |range, pc, uc| {
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
        });
        let [sum_p, clipped, entered, su, sh, cnt] = add_all(parts);
        Update::new([sum_p, clipped, entered], [su, sh, cnt])
    }

    /// Step 5: the load, `p <- p p0 / mean(p)`, applied lazily as the load scale. A
    /// contact set that emptied leaves no pressure to scale: the solve fails, saying so.
    pub(super) fn restore_load(&mut self, it: usize, update: &Update) -> Result<()> {
        let problem = self.problem;
        if update.cnt == 0.0 {
            return Err(self.record.lost_contact(problem, it));
        }
        self.frame.scale = problem.p0 * problem.model.grid.points() as f64 / update.sum_p;
        if !self.frame.scale.is_finite() {
            return Err(self.record.non_finite("pressure", it));
        }
        Ok(())
    }

    /// Step 5 once rescaling has stalled (see the module docs): the load restored by the
    /// Euclidean projection of the updated pressure onto `{p >= 0, sum p = N p0}`,
    /// `p <- max(p - lambda, 0)` on the contact set, then `u = K^-1 p`, the rigid shift
    /// and the contact set of the projected pressure (step 6). `lambda` by Michelot's
    /// algorithm: the mean excess over the points still above it, until none leaves (at
    /// most one sweep per point that leaves, a handful in practice). A contact set that
    /// emptied fails as in [`Self::restore_load`].
    pub(super) fn project_load(&mut self, it: usize, update: &Update) -> Result<()> {
        let problem = self.problem;
        if update.cnt == 0.0 {
            return Err(self.record.lost_contact(problem, it));
        }
        // After step 4 the stored pressure is the true one (the old load scale applied).
        let target = problem.p0 * problem.model.grid.points() as f64;
        let mut lambda = (update.sum_p - target) / update.cnt;
        loop {
            let (sum, count) = self
                .p
                .iter()
                .filter(|&&p| p > 0.0 && p > lambda)
                .fold((0.0, 0.0), |(s, c), &p| (s + p, c + 1.0));
            if count == 0.0 {
                return Err(self.record.lost_contact(problem, it));
            }
            let next = (sum - target) / count;
            if !next.is_finite() {
                return Err(self.record.non_finite("pressure", it));
            }
            // lambda only grows while points leave; it is settled when none does.
            if next <= lambda {
                lambda = next;
                break;
            }
            lambda = next;
        }
        self.p.par_iter_mut().for_each(|p| {
            *p = if *p > 0.0 && *p > lambda {
                *p - lambda
            } else {
                0.0
            };
        });
        self.frame.scale = 1.0;
        self.exact_displacement();
        self.set_changed = true;
        Ok(())
    }

    /// Step 6: the displacement and the rigid shift `gbar = mean_Ic (u - h)` of the new
    /// pressure. After a fused update `u = K^-1 p` is exact already; after an
    /// incremental one it is recomputed when the contact set changed or every
    /// [`ConstrainedCg::refresh_every`] iterations, and otherwise kept.
    pub(super) fn refresh(&mut self, update: &Update) {
        let Update { su, sh, cnt, .. } = *update;
        self.since_refresh += 1;
        self.n_c = cnt;
        let fused = self.set_changed;
        self.set_changed = update.clipped + update.entered > 0.0;
        if fused {
            // u = K^-1 p of the stored (unscaled) pressure: the scale applies to both.
            self.frame.gbar = (self.frame.scale * su - sh) / cnt;
            self.exact = true;
            self.since_refresh = 0;
        } else if self.set_changed || self.since_refresh >= self.refresh_every {
            self.exact_displacement();
        } else {
            self.frame.gbar = (self.frame.scale * su - sh) / cnt;
            self.exact = false;
        }
    }

    /// Applies the load scale to `p` (leaving `scale = 1`), recomputes `u = K^-1 p`, the
    /// rigid shift `gbar = mean_Ic (u - h)` and the number of points in contact: the
    /// state is exact.
    pub(super) fn exact_displacement(&mut self) {
        let problem = self.problem;
        let model = problem.model;
        let n = model.grid.cols();
        let h = problem.heights;
        let s = self.frame.scale;
        let pass = passes::Rescale { scale: s, h, n };
        let (_, outs) = model.fft.convolve(
            &model.compliance,
            &mut self.spec[..],
            Some(&mut self.p[..]),
            &pass,
            &mut self.u[..],
        );
        self.frame.scale = 1.0;
        let [su, sh, cnt] = add_all(outs);
        self.frame.gbar = if cnt > 0.0 { (su - sh) / cnt } else { f64::NAN };
        self.n_c = cnt;
        self.exact = true;
        self.since_refresh = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::super::ConstrainedCg;
    use super::*;
    use crate::engine::contact::{ContactProblem, Model};
    use crate::engine::grid::Grid;
    use crate::engine::solver::executor::Method;
    use crate::engine::solver::{SolveOptions, Start};
    use crate::Error;

    /// Runs `check` on a cold CG solve of a sine on an 8 x 8 grid at the load `p0 = 0.05`.
    fn on_a_cold_solve(check: impl FnOnce(&mut Solve<'_>)) {
        let model = Model::new(Grid::new(8, 1.0).unwrap(), 1.0).unwrap();
        let h: Vec<f64> = (0..64).map(|k| (k as f64 * 0.7).sin()).collect();
        let problem = ContactProblem::new(&model, &h, 0.05).unwrap();
        let mut cg = ConstrainedCg::default();
        let mut solve = cg
            .init(&problem, Start::Cold, &SolveOptions::default())
            .unwrap();
        check(&mut solve);
    }

    #[test]
    fn a_contact_set_that_empties_is_reported_as_such() {
        on_a_cold_solve(|solve| {
            // An update that clipped every point: nothing is left to carry the load.
            let emptied = Update::new([0.0, 64.0, 0.0], [0.0, 0.0, 0.0]);
            match solve.restore_load(3, &emptied) {
                Err(Error::LostContact {
                    solver,
                    iteration,
                    p0,
                }) => assert_eq!((solver, iteration, p0), ("cg", 3, 0.05)),
                other => panic!("expected a lost contact, got {other:?}"),
            }
        });
    }

    #[test]
    fn the_projection_takes_the_same_from_every_point_and_restores_the_load() {
        on_a_cold_solve(|solve| {
            // A spike holding most of the load, small pressures and points out of contact:
            // 4.32 in all against the load's 64 x 0.05 = 3.2.
            let before: Vec<f64> = (0..64)
                .map(|k| match k {
                    0 => 4.0,
                    k if k % 2 == 1 => 0.01,
                    _ => 0.0,
                })
                .collect();
            solve.p.copy_from_slice(&before);
            let sum_p: f64 = before.iter().sum();
            let cnt = before.iter().filter(|&&p| p > 0.0).count() as f64;
            let update = Update::new([sum_p, 0.0, 0.0], [0.0, 0.0, cnt]);
            solve.project_load(1, &update).unwrap();
            let after = solve.p.clone();
            let total: f64 = after.iter().sum();
            assert!((total - 3.2).abs() < 1e-12, "the load: {total}");
            // 1.12 too much: taken evenly (1.12 / 33 each), every small point (0.01) leaves,
            // and the spike gives the rest: it keeps the whole load.
            assert!((after[0] - 3.2).abs() < 1e-12, "the spike: {}", after[0]);
            assert!(after[1..].iter().all(|&p| p == 0.0), "{after:?}");
            // Rescaling would have left it 4.0 x 3.2 / 4.32 = 2.96.
            assert!(after[0] > 4.0 * 3.2 / sum_p + 0.2);
            // The displacement and the contact set are those of the projected pressure.
            assert_eq!(solve.n_c, 1.0);
            assert!(solve.exact && solve.set_changed);
        });
    }
}
