//! Magnification sweeps: one realization solved at a sequence of magnifications, each solve
//! warm-started from the previous one (paper section 3: "we keep changing the resolution").
//!
//! The load is either a fixed mean pressure `p0` (the paper's protocol: `p0` constant while
//! roughness is added) or found once, at a reference magnification, from a target contact
//! area (the paper states loads as `a_r` at a given `zeta`).

use rustfft::num_complex::Complex64;

use crate::contact::{ContactProblem, ContactSolution, Model, SolveOptions, Solver, Start};
use crate::error::Result;
use crate::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use crate::solver::SolverKind;
use crate::surface::Surface;

/// A realization, its model and a solver, stepping through magnifications.
pub struct Sweep<'a> {
    surface: &'a Surface,
    model: &'a Model,
    solver: Box<dyn Solver + Send>,
    opts: SolveOptions,
    spec: Vec<Complex64>,
    heights: Vec<f64>,
    zeta: f64,
    previous: Option<ContactSolution>,
}

impl<'a> Sweep<'a> {
    /// A sweep of `surface` on `model` with a fresh solver of `kind`.
    pub fn new(
        surface: &'a Surface,
        model: &'a Model,
        kind: SolverKind,
        opts: SolveOptions,
    ) -> Self {
        Self {
            surface,
            model,
            solver: kind.build(),
            opts,
            spec: model.fft.new_spectrum(),
            heights: vec![0.0; model.grid.points()],
            zeta: f64::NAN,
            previous: None,
        }
    }

    /// Sets the substrate to magnification `zeta` (heights with `|q| <= zeta q_l`).
    fn set_zeta(&mut self, zeta: f64) {
        if zeta != self.zeta {
            self.surface.modes_at(zeta, &mut self.spec);
            self.model
                .fft
                .inverse_in_place(&mut self.spec, &mut self.heights);
            self.zeta = zeta;
        }
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
        self.previous.take()
    }

    /// Restores a solution as the warm start of the next solve (resuming a sweep).
    pub fn restore(&mut self, zeta: f64, solution: ContactSolution) {
        self.set_zeta(zeta);
        self.previous = Some(solution);
    }

    /// Solves at magnification `zeta` and load `p0`, warm-started from the last solution.
    pub fn solve_at(&mut self, zeta: f64, p0: f64) -> Result<&ContactSolution> {
        self.set_zeta(zeta);
        let problem = ContactProblem::new(self.model, &self.heights, p0)?;
        let start = match &self.previous {
            Some(prev) => Start::Warm(prev),
            None => Start::Cold,
        };
        let solution = self.solver.solve(&problem, start, &self.opts)?;
        self.previous = Some(solution);
        Ok(self.previous.as_ref().expect("just set"))
    }

    /// Finds the load that gives `contact_area` at magnification `zeta` and keeps that
    /// solution as the warm start; returns `p0`.
    pub fn find_load(&mut self, zeta: f64, contact_area: f64) -> Result<f64> {
        self.set_zeta(zeta);
        let g_bar = self.surface.rms_gradient(zeta).max(f64::MIN_POSITIVE);
        let guess = match &self.previous {
            Some(prev) => prev.p0,
            None => persson_load_guess(contact_area, g_bar, self.model.halfspace.e_star()),
        };
        let start = match &self.previous {
            Some(prev) => Start::Warm(prev),
            None => Start::Cold,
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
            &AreaSearch::default(),
        )?;
        let p0 = found.solution.p0;
        self.previous = Some(found.solution);
        Ok(p0)
    }
}

/// Magnifications at which each shell of `surface` with `zeta_from < zeta <= zeta_to` is
/// resolved, in increasing order: the steps of a sweep that adds every shell one at a time.
pub fn shell_steps(surface: &Surface, zeta_from: f64, zeta_to: f64) -> Vec<f64> {
    let grid = surface.grid();
    surface
        .shell_sequence()
        .into_iter()
        .map(|k2| grid.zeta_of_shell(k2, surface.lambda_l()))
        .filter(|&z| z > zeta_from * (1.0 + 1e-12) && z <= zeta_to * (1.0 + 1e-12))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::SurfaceParams;

    #[test]
    fn sweep_reaches_the_cold_solution_and_finds_loads() {
        let surface = Surface::generate(&SurfaceParams::new(64, 0.8, 32.0, 4.0, 9)).unwrap();
        let model = Model::new(surface.grid().clone(), 1.0).unwrap();
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
    fn shell_steps_are_the_distinct_shells() {
        let surface = Surface::generate(&SurfaceParams::new(32, 0.8, 16.0, 4.0, 1)).unwrap();
        let steps = shell_steps(&surface, 1.0, 4.0);
        // Shells k2 in (4, 64] holding roughness: sums of two squares between 5 and 64.
        assert!(steps.windows(2).all(|w| w[0] < w[1]));
        assert!((steps[0] - (5f64).sqrt() / 2.0).abs() < 1e-12);
        assert!((steps.last().unwrap() - 4.0).abs() < 1e-12);
    }
}
