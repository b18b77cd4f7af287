//! Magnification sweeps: one realization solved at a sequence of magnifications, each solve
//! warm-started from the previous one (paper section 3: "we keep changing the resolution").
//!
//! The load is either a fixed mean pressure `p0` (the paper's protocol: `p0` constant while
//! roughness is added) or found once, at a reference magnification, from a target contact
//! area (the paper states loads as `a_r` at a given `zeta`).
//!
//! # Predicted warm starts
//!
//! When the magnification changes, the heights change by `dh` (the modes of the shells
//! added or removed). To first order the contact set stays and follows the new roughness,
//! as in full contact, where the exact answer is `p + K dh` and `u + dh` (`K = q E*/2`).
//! A warm start therefore begins from
//!
//! ```text
//!     p_start = max(p + K dh, 0),   u_start = u + dh     on the previous contact set,
//!     p_start = 0,                  u_start = u          elsewhere,
//! ```
//!
//! exact in full contact and a step towards the solution in partial contact, which saves
//! iterations of both solvers (`docs/measured.md` gives the figures). The
//! prediction costs one inverse transform (of `K dh`; `dh` is the difference of the
//! heights).
//!
//! # Better predictions (opt-in)
//!
//! [`Prediction`] chooses the warm start; [`Prediction::Shell`], the default, is the one
//! above, and every committed result was computed with it. Two alternatives, kept so that
//! the measurement can be repeated (`benches/history.rs`; `docs/measured.md`, "A re-entry
//! history's cost": neither saves time, and the response costs iterations on 512^2):
//!
//! * [`Prediction::Response`]: as above on the contact set, and off it the displacement
//!   moves by the elastic response to the predicted change of the pressure,
//!   `u_start = u + K^-1 (p_start - p)`, the displacement a constrained-CG start derives
//!   from `p_start` (a dynamics solver starts from `u` alone). One convolution more.
//! * [`Prediction::Extrapolate`]: as above, plus `w` times the correction the solver made
//!   to the previous step's start (pressure on the predicted contact set, displacement
//!   off it): the part of a step that the shell's own response does not explain, carried
//!   on to the next step.
//!
//! # What roughness a sweep climbs
//!
//! A sweep adds the modes of a [`Roughness`]: a generated [`Surface`], or a measured
//! scan's truncated spectrum. On a periodic model the modes live on the model's grid; on a
//! free-boundary model ([`Model::free_window`]) they live on the window's grid, and each
//! magnification's heights are padded with the model's floor ([`Model::pad_heights`]).
//! The floor moves with the heights' range, so on a free window the warm start is the
//! previous solution as it stands, not predicted.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use crate::engine::contact::{ContactProblem, ContactSolution, Model};
use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::engine::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use crate::engine::solver::SolverKind;
use crate::engine::solver::{SolveOptions, Solver, Start};
use crate::engine::surface::Surface;
use crate::engine::tolerance::ZETA_SLACK;
use crate::error::Result;

/// Roughness that a sweep adds magnification by magnification.
pub trait Roughness: Sync {
    /// The grid of the modes: the model's grid, or a free-boundary model's window.
    fn grid(&self) -> &Grid;

    /// The half spectrum of the heights with `|q| <= zeta q_l` (every other mode zero).
    fn modes_at(&self, zeta: f64, out: &mut [Complex64]);

    /// The magnifications at which its shells holding roughness are resolved, increasing.
    fn shell_zetas(&self) -> Vec<f64>;
}

impl Roughness for Surface {
    fn grid(&self) -> &Grid {
        Surface::grid(self)
    }

    fn modes_at(&self, zeta: f64, out: &mut [Complex64]) {
        Surface::modes_at(self, zeta, out);
    }

    fn shell_zetas(&self) -> Vec<f64> {
        let grid = Surface::grid(self);
        self.shell_sequence()
            .into_iter()
            .map(|k2| grid.zeta_of_shell(k2, self.lambda_l()))
            .collect()
    }
}

/// How a sweep predicts the warm start at a new magnification (see the module docs).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub enum Prediction {
    /// `p + K dh` and `u + dh` on the previous contact set, the previous solution
    /// elsewhere: the prediction of every committed result.
    #[default]
    Shell,
    /// [`Prediction::Shell`], and off the predicted contact set the displacement moved by
    /// the elastic response to the predicted change of the pressure.
    Response,
    /// [`Prediction::Shell`] plus this weight times the correction the solver made to the
    /// previous step's start.
    Extrapolate(f64),
}

impl Prediction {
    /// Whether this is the default, [`Prediction::Shell`].
    pub fn is_shell(&self) -> bool {
        *self == Prediction::Shell
    }
}

/// A free-boundary model's window: the transform of the window's grid, and the window's
/// heights before padding.
struct Window {
    fft: Fft2,
    heights: Vec<f64>,
}

/// A realization, its model and a solver, stepping through magnifications.
pub struct Sweep<'a, R: Roughness = Surface> {
    surface: &'a R,
    model: &'a Model,
    /// The window's transform when the model has a free boundary.
    window: Option<Window>,
    solver: Box<dyn Solver + Send>,
    opts: SolveOptions,
    spec: Vec<Complex64>,
    /// Spectrum work space (kept: a sweep sets thousands of magnifications).
    work: Vec<Complex64>,
    heights: Vec<f64>,
    /// The change of the heights since the previous solution (valid while `change` is),
    /// and the pressure response `K dh` (work space, kept as `work` is).
    dh: Vec<f64>,
    response: Vec<f64>,
    zeta: f64,
    previous: Option<ContactSolution>,
    /// Spectrum of the change of the heights since the previous solution, when the
    /// magnification changed since then.
    change: Option<Vec<Complex64>>,
    /// How the warm start is predicted.
    prediction: Prediction,
    /// Work space of [`Prediction::Response`]: the change of the pressure, then the
    /// displacement it causes.
    dp: Vec<f64>,
    /// The start of the last predicted solve, for [`Prediction::Extrapolate`].
    last_start: Option<(Vec<f64>, Vec<f64>)>,
}

impl<'a, R: Roughness> Sweep<'a, R> {
    /// A sweep of `surface` on `model` with a fresh solver of `kind`.
    ///
    /// # Panics
    ///
    /// As [`Sweep::with_solver`].
    pub fn new(surface: &'a R, model: &'a Model, kind: SolverKind, opts: SolveOptions) -> Self {
        Self::with_solver(surface, model, kind.build(), opts)
    }

    /// A sweep of `surface` on `model` with `solver` (for example one wrapped to report
    /// progress or to be cancelled).
    ///
    /// # Panics
    ///
    /// If the surface's grid is not the model's (periodic) or its window's (free boundary).
    pub fn with_solver(
        surface: &'a R,
        model: &'a Model,
        solver: Box<dyn Solver + Send>,
        opts: SolveOptions,
    ) -> Self {
        let shape = (surface.grid().rows(), surface.grid().cols());
        let window = match model.window {
            None => {
                assert_eq!(
                    shape,
                    (model.grid.rows(), model.grid.cols()),
                    "the surface's grid is the model's"
                );
                None
            }
            Some(window) => {
                assert_eq!(shape, window, "the surface's grid is the model's window");
                Some(Window {
                    fft: Fft2::new(surface.grid()),
                    heights: vec![0.0; surface.grid().points()],
                })
            }
        };
        let fft = window.as_ref().map_or(&model.fft, |w| &w.fft);
        Self {
            surface,
            model,
            solver,
            opts,
            spec: fft.new_spectrum(),
            work: fft.new_spectrum(),
            window,
            heights: vec![0.0; model.grid.points()],
            dh: Vec::new(),
            response: Vec::new(),
            zeta: f64::NAN,
            previous: None,
            change: None,
            prediction: Prediction::Shell,
            dp: Vec::new(),
            last_start: None,
        }
    }

    /// The sweep with another prediction of its warm starts ([`Prediction`]).
    #[must_use]
    pub fn with_prediction(mut self, prediction: Prediction) -> Self {
        self.prediction = prediction;
        self
    }

    /// Sets the substrate to magnification `zeta` (heights with `|q| <= zeta q_l`), and
    /// keeps the change of the spectrum and of the heights since the previous solution.
    fn set_zeta(&mut self, zeta: f64) {
        if zeta == self.zeta {
            return;
        }
        let next = &mut self.work;
        self.surface.modes_at(zeta, next);
        let track = self.previous.is_some() && self.zeta.is_finite() && self.window.is_none();
        if track {
            if self.change.is_none() {
                // A change that starts now: dh accumulates from zero.
                self.dh.clear();
                self.dh.resize(self.heights.len(), 0.0);
            }
            let change = self
                .change
                .get_or_insert_with(|| vec![Complex64::default(); next.len()]);
            change
                .par_iter_mut()
                .zip(next.par_iter())
                .zip(self.spec.par_iter())
                .for_each(|((c, new), old)| *c += new - old);
            self.dh
                .par_iter_mut()
                .zip(self.heights.par_iter())
                .for_each(|(d, &h)| *d -= h);
        }
        self.spec
            .par_iter_mut()
            .zip(next.par_iter())
            .for_each(|(s, n)| *s = *n);
        match &mut self.window {
            None => self.model.fft.inverse_in_place(next, &mut self.heights),
            Some(w) => {
                w.fft.inverse_in_place(next, &mut w.heights);
                self.heights = self
                    .model
                    .pad_heights(&w.heights)
                    .expect("the window's heights fill the window");
            }
        }
        if track {
            self.dh
                .par_iter_mut()
                .zip(self.heights.par_iter())
                .for_each(|(d, &h)| *d += h);
        }
        self.zeta = zeta;
    }

    /// The predicted warm start for the current heights (see the module docs), when the
    /// magnification changed since the previous solution; the previous solution becomes
    /// the prediction.
    fn predicted(&mut self) -> Option<ContactSolution> {
        let change = self.change.take()?;
        let mut start = self.previous.take()?;
        let correction = match self.prediction {
            Prediction::Extrapolate(w) => self.last_start.take().map(|(sp, su)| (w, sp, su)),
            _ => None,
        };
        let correction = correction.map(|(w, mut sp, mut su)| {
            // The correction of the last solve: its solution less its start.
            subtract_from(&start.pressure, &mut sp);
            subtract_from(&start.displacement, &mut su);
            (w, sp, su)
        });
        if self.prediction == Prediction::Response {
            self.dp.clear();
            self.dp.extend_from_slice(&start.pressure);
        }
        let dh = &self.dh;
        // The mean height never changes (the q = 0 mode is not a shell): the response has
        // zero mean.
        self.model
            .halfspace
            .pressure_from_displacement(&change, 0.0, &mut self.work);
        self.response.resize(dh.len(), 0.0);
        self.model
            .fft
            .inverse_in_place(&mut self.work, &mut self.response);
        start
            .pressure
            .par_iter_mut()
            .zip(start.displacement.par_iter_mut())
            .zip(self.response.par_iter().zip(dh))
            .for_each(|((p, u), (dp, du))| {
                if *p > 0.0 {
                    *p = (*p + dp).max(0.0);
                    *u += du;
                }
            });
        match self.prediction {
            Prediction::Shell => {}
            Prediction::Response => self.respond(&mut start),
            Prediction::Extrapolate(_) => {
                if let Some((w, cp, cu)) = correction {
                    start
                        .pressure
                        .par_iter_mut()
                        .zip(start.displacement.par_iter_mut())
                        .zip(cp.par_iter().zip(&cu))
                        .for_each(|((p, u), (&cp, &cu))| {
                            if *p > 0.0 {
                                *p = (*p + w * cp).max(0.0);
                            } else {
                                *u += w * cu;
                            }
                        });
                }
                self.last_start = Some((start.pressure.clone(), start.displacement.clone()));
            }
        }
        Some(start)
    }

    /// [`Prediction::Response`]: off the predicted contact set, `u += K^-1 (p_start - p)`
    /// (where a point left the contact set, in place of `+ dh`); `self.dp` holds `p`.
    fn respond(&mut self, start: &mut ContactSolution) {
        let model = self.model;
        self.dp
            .par_iter_mut()
            .zip(start.pressure.par_iter())
            .for_each(|(d, &p)| *d = p - *d);
        model.fft.forward(&self.dp, &mut self.work);
        for (w, c) in self.work.iter_mut().zip(model.halfspace.compliance()) {
            *w *= c;
        }
        // The response, in `response` (the pressure response is used up).
        model
            .fft
            .inverse_in_place(&mut self.work, &mut self.response);
        start
            .pressure
            .par_iter()
            .zip(start.displacement.par_iter_mut())
            .zip(self.response.par_iter().zip(&self.dp))
            .zip(&self.dh)
            .for_each(|(((&p, u), (&du, &dp)), &dh)| {
                if p <= 0.0 {
                    // A point that was in contact (its pressure changed) moved by dh.
                    let moved = if dp != 0.0 { dh } else { 0.0 };
                    *u += du - moved;
                }
            });
    }

    /// Heights at the current magnification.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The current magnification.
    pub fn zeta(&self) -> f64 {
        self.zeta
    }

    /// The last solution.
    pub fn solution(&self) -> Option<&ContactSolution> {
        self.previous.as_ref()
    }

    /// Takes the last solution out (the next solve starts cold).
    pub fn take_solution(&mut self) -> Option<ContactSolution> {
        self.change = None;
        self.last_start = None;
        self.previous.take()
    }

    /// Restores a solution as the warm start of the next solve, with what the solver
    /// carried after it ([`Sweep::carried`]): a sweep resumed from a checkpoint then solves
    /// as the uninterrupted one did.
    pub fn restore(&mut self, zeta: f64, solution: ContactSolution, carried: Option<f64>) {
        self.change = None;
        self.last_start = None;
        self.previous = None;
        self.set_zeta(zeta);
        self.previous = Some(solution);
        self.solver.carry(carried);
    }

    /// What the solver carries to the next solve besides the solution
    /// ([`Solver::carried`]), for a checkpoint.
    pub fn carried(&self) -> Option<f64> {
        self.solver.carried()
    }

    /// Solves at magnification `zeta` and load `p0`, warm-started from the last solution
    /// (predicted for the change of magnification, see the module docs). When the
    /// magnification changed, the last solution becomes the prediction: if that solve
    /// fails, the sweep holds no solution and the next solve starts cold.
    ///
    /// # Errors
    ///
    /// If `p0` is not positive, or the solve fails or is stopped (see [`Solver::solve`]);
    /// the sweep then keeps its previous solution as the next step's start.
    pub fn solve_at(&mut self, zeta: f64, p0: f64) -> Result<&ContactSolution> {
        self.set_zeta(zeta);
        let predicted = self.predicted();
        let problem = ContactProblem::new(self.model, &self.heights, p0)?;
        let start = match (&predicted, &self.previous) {
            (Some(start), _) => Start::Warm(start),
            (None, Some(prev)) => Start::Warm(prev),
            (None, None) => Start::Cold,
        };
        let solution = self.solver.solve(&problem, start, &self.opts)?;
        self.previous = Some(solution);
        Ok(self.previous.as_ref().expect("just set"))
    }
}

impl Sweep<'_, Surface> {
    /// Finds the load that gives `contact_area` at magnification `zeta` and keeps that
    /// solution as the warm start; returns `p0`.
    ///
    /// # Errors
    ///
    /// As [`solve_for_area`].
    pub fn find_load(&mut self, zeta: f64, contact_area: f64) -> Result<f64> {
        self.find_load_within(zeta, contact_area, &AreaSearch::default())
    }

    /// [`Sweep::find_load`] with the search's own tolerance (`search`): a step at fixed
    /// contact area holds the area far more tightly than a load is set
    /// ([`AreaSearch::held`]).
    ///
    /// # Errors
    ///
    /// As [`solve_for_area`].
    pub fn find_load_within(
        &mut self,
        zeta: f64,
        contact_area: f64,
        search: &AreaSearch,
    ) -> Result<f64> {
        self.set_zeta(zeta);
        let g_bar = self.surface.rms_gradient(zeta).max(f64::MIN_POSITIVE);
        let guess = match &self.previous {
            Some(prev) => prev.p0,
            None => persson_load_guess(contact_area, g_bar, self.model.halfspace.e_star()),
        };
        let predicted = self.predicted();
        let start = match (&predicted, &self.previous) {
            (Some(start), _) => Start::Warm(start),
            (None, Some(prev)) => Start::Warm(prev),
            (None, None) => Start::Cold,
        };
        let found = solve_for_area(
            self.solver.as_mut(),
            self.model,
            &self.heights,
            AreaTarget {
                contact_area,
                p0_guess: guess,
            },
            start,
            &self.opts,
            search,
        )?;
        let p0 = found.solution.p0;
        self.previous = Some(found.solution);
        Ok(p0)
    }
}

/// `into = of - into`, element by element.
fn subtract_from(of: &[f64], into: &mut [f64]) {
    into.par_iter_mut()
        .zip(of.par_iter())
        .for_each(|(d, &a)| *d = a - *d);
}

/// Magnifications at which each shell of `surface` with `zeta_from < zeta <= zeta_to` is
/// resolved, in increasing order: the steps of a sweep that adds every shell one at a time.
pub fn shell_steps(surface: &impl Roughness, zeta_from: f64, zeta_to: f64) -> Vec<f64> {
    surface
        .shell_zetas()
        .into_iter()
        .filter(|&z| z > zeta_from * (1.0 + ZETA_SLACK) && z <= zeta_to * (1.0 + ZETA_SLACK))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::surface::SurfaceModel;
    use crate::engine::testing::rough_contact;

    #[test]
    fn sweep_reaches_the_cold_solution_and_finds_loads() {
        let (surface, model) = rough_contact(64, 0.8, 9);
        let opts = SolveOptions::with_tol(1e-10);
        let mut sweep = Sweep::new(&surface, &model, SolverKind::Cg, opts);
        let p0 = sweep.find_load(4.0, 0.2).unwrap();
        let a = sweep.solution().unwrap().contact_area();
        assert!((a - 0.2).abs() <= 2e-3 * 0.2 + 1.5 / 4096.0, "a_r = {a}");
        for zeta in [4.5, 5.0, 8.0] {
            sweep.solve_at(zeta, p0).unwrap();
        }
        let warm = sweep.take_solution().unwrap();
        let cold = sweep.solve_at(8.0, p0).unwrap();
        assert!(
            (warm.elastic_energy() - cold.elastic_energy()).abs() < 1e-8 * cold.elastic_energy()
        );
    }

    #[test]
    fn predicted_start_is_exact_in_full_contact() {
        // Under a load far above the full-contact pressure every point stays in contact,
        // and p + K dh is the exact solution at the new magnification: the warm solve has
        // nothing left to do, while the previous solution alone needs iterations.
        let (surface, model) = rough_contact(64, 0.8, 3);
        let opts = SolveOptions::with_tol(1e-10);
        let p0 = 20.0;
        let (z0, z1) = (4.0, 6.0);
        let mut sweep = Sweep::new(&surface, &model, SolverKind::Cg, opts);
        sweep.solve_at(z0, p0).unwrap();
        let predicted = sweep.solve_at(z1, p0).unwrap();
        assert_eq!(predicted.contact_area(), 1.0);
        let it_predicted = predicted.stats.iterations;
        let energy = predicted.elastic_energy();
        // The same step from the previous solution, unpredicted.
        let h0 = surface.heights_at(z0, &model.fft);
        let h1 = surface.heights_at(z1, &model.fft);
        let mut cg = SolverKind::Cg.build();
        let from = cg
            .solve(
                &ContactProblem::new(&model, &h0, p0).unwrap(),
                Start::Cold,
                &opts,
            )
            .unwrap();
        let plain = cg
            .solve(
                &ContactProblem::new(&model, &h1, p0).unwrap(),
                Start::Warm(&from),
                &opts,
            )
            .unwrap();
        // (Preconditioned CG needs only one iteration from the previous solution in full
        // contact, where the preconditioner inverts the problem exactly.)
        assert_eq!(it_predicted, 0, "iterations from the prediction");
        assert!(plain.stats.iterations >= 1, "{}", plain.stats.iterations);
        assert!((energy - plain.elastic_energy()).abs() < 1e-9 * energy);
    }

    #[test]
    fn every_prediction_is_exact_in_full_contact() {
        // In full contact the alternatives start where the shell's own prediction does
        // (no point off contact; the correction carried on is zero): nothing to do.
        let (surface, model) = rough_contact(64, 0.8, 3);
        let opts = SolveOptions::with_tol(1e-10);
        for prediction in [Prediction::Response, Prediction::Extrapolate(0.5)] {
            let mut sweep =
                Sweep::new(&surface, &model, SolverKind::Cg, opts).with_prediction(prediction);
            sweep.solve_at(4.0, 20.0).unwrap();
            for zeta in [5.0, 6.0] {
                let s = sweep.solve_at(zeta, 20.0).unwrap();
                assert_eq!(s.contact_area(), 1.0);
                assert_eq!(s.stats.iterations, 0, "{prediction:?} at zeta = {zeta}");
            }
        }
    }

    #[test]
    fn a_free_window_sweep_solves_the_padded_heights_of_each_magnification() {
        // A 32^2 surface swept on the free boundary: every step's heights are the
        // surface's at that magnification padded with the model's floor, and the warm
        // solve reaches the cold solution of those heights.
        let surface = Surface::generate(&SurfaceModel::new(32, 0.8, 32.0, 4.0, 5)).unwrap();
        let model = Model::free_window(32, 32, 1.0).unwrap();
        let opts = SolveOptions::with_tol(1e-10);
        let mut sweep = Sweep::new(&surface, &model, SolverKind::Cg, opts);
        let p0 = 0.02 * 0.25;
        let mut cg = SolverKind::Cg.build();
        let fft = Fft2::new(surface.grid());
        for zeta in [1.5, 3.0, 6.0, 8.0] {
            let warm = sweep.solve_at(zeta, p0).unwrap().clone();
            let window = surface.heights_at(zeta, &fft);
            let padded = model.pad_heights(&window).unwrap();
            assert_eq!(sweep.heights(), &padded[..], "zeta = {zeta}");
            let problem = ContactProblem::new(&model, &padded, p0).unwrap();
            let cold = cg.solve(&problem, Start::Cold, &opts).unwrap();
            assert!(warm.stats.warm || zeta == 1.5);
            let (a, b) = (warm.elastic_energy(), cold.elastic_energy());
            assert!((a - b).abs() < 1e-7 * b, "zeta = {zeta}: {a} against {b}");
        }
    }

    #[test]
    #[should_panic(expected = "the surface's grid is the model's window")]
    fn a_free_window_of_another_shape_is_refused() {
        let surface = Surface::generate(&SurfaceModel::new(32, 0.8, 32.0, 4.0, 5)).unwrap();
        let model = Model::free_window(16, 32, 1.0).unwrap();
        let _ = Sweep::new(&surface, &model, SolverKind::Cg, SolveOptions::default());
    }

    #[test]
    fn a_sweep_resumed_with_what_the_solver_carried_is_the_uninterrupted_one() {
        // A climb through shells at a loose tolerance, interrupted after `k` steps and
        // resumed in a fresh sweep from the stored solution: bit for bit the uninterrupted
        // climb with every solver, once the solver's carried state comes along (GFMD's:
        // the step its last solve ended with, from which the next solve starts).
        let (surface, model) = rough_contact(64, 0.8, 7);
        let opts = SolveOptions::with_tol(1e-4);
        let steps = shell_steps(&surface, 1.0, surface.zeta_max());
        let k = steps.len() / 2;
        for kind in SolverKind::ALL {
            let mut whole = Sweep::new(&surface, &model, kind, opts);
            let p0 = whole.find_load(surface.zeta_max(), 0.2).unwrap();
            whole.take_solution();
            let mut at_k = None;
            for (i, &z) in steps.iter().enumerate() {
                whole.solve_at(z, p0).unwrap();
                if i + 1 == k {
                    at_k = Some((whole.solution().unwrap().clone(), whole.carried()));
                }
            }
            let (solution, carried) = at_k.unwrap();
            assert_eq!(carried.is_some(), kind == SolverKind::Gfmd, "{kind:?}");
            let resume = |carried: Option<f64>| {
                let mut resumed = Sweep::new(&surface, &model, kind, opts);
                resumed.restore(steps[k - 1], solution.clone(), carried);
                for &z in &steps[k..] {
                    resumed.solve_at(z, p0).unwrap();
                }
                resumed.take_solution().unwrap()
            };
            let end = whole.solution().unwrap();
            let resumed = resume(carried);
            assert_eq!(resumed.pressure, end.pressure, "{kind:?}");
            assert_eq!(resumed.displacement, end.displacement, "{kind:?}");
            if let Some(tau) = carried {
                // The carried step is what the next solve starts from: another one (as a
                // large grid's, which ends its solves on smaller steps) changes the climb.
                let other = resume(Some(tau * 0.1));
                assert!(
                    other.pressure != end.pressure,
                    "GFMD's carried step is not used"
                );
            }
        }
    }

    #[test]
    fn shell_steps_are_the_distinct_shells() {
        let surface = Surface::generate(&SurfaceModel::new(32, 0.8, 16.0, 4.0, 1)).unwrap();
        let steps = shell_steps(&surface, 1.0, 4.0);
        // Shells k2 in (4, 64] holding roughness: sums of two squares between 5 and 64.
        assert!(steps.windows(2).all(|w| w[0] < w[1]));
        assert!((steps[0] - (5f64).sqrt() / 2.0).abs() < 1e-12);
        assert!((steps.last().unwrap() - 4.0).abs() < 1e-12);
    }
}
