//! One hard-wall contact problem (`persson-check solve`, Python's `solve`): a surface at a
//! magnification pressed onto the elastic half-space at a mean pressure `p0`, or at the
//! load that gives a target contact area, and its summary (`summary.json`, Python's
//! `Solution.summary()`).
//!
//! A contact-area target is met by root finding on the load ([`crate::engine::load`]),
//! starting from Persson's estimate `p0 = sqrt2 (E* g_bar / 2) erfinv(a_r)` with the rms
//! gradient `g_bar` of the heights solved against; every solve after the first starts from
//! the previous solution.

use std::fmt;
use std::path::Path;

use serde::Serialize;

use crate::engine::contact::{ContactProblem, ContactSolution, Model, Residual};
use crate::engine::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use crate::engine::scene::check_zeta;
use crate::engine::solver::{SolveOptions, Solver, Start};
use crate::engine::surface::Surface;
use crate::error::{Error, Result, Termination};

use super::parse::Load;
use super::Spelling;

/// Where the heights of a solve came from (`summary.json`'s `source`).
#[derive(Debug, Clone, Copy)]
pub enum Origin<'a> {
    /// A `.npy` file of heights.
    File(&'a Path),
    /// A scene file's surface, realization `seed`.
    Scene {
        /// The scene file.
        path: &'a Path,
        /// The realization.
        seed: u64,
    },
    /// A surface generated from parameters given one by one, realization `seed`.
    Generated {
        /// The realization.
        seed: u64,
    },
    /// Heights handed over in memory (a numpy array from Python).
    Array,
}

impl fmt::Display for Origin<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::File(path) => write!(f, "{}", path.display()),
            Origin::Scene { path, seed } => write!(f, "{} (seed {seed})", path.display()),
            Origin::Generated { seed } => write!(f, "generated (seed {seed})"),
            Origin::Array => f.write_str("array"),
        }
    }
}

/// What to solve, besides the surface: the load, the magnification, the solver's options
/// and the effective modulus.
#[derive(Debug, Clone, Copy)]
pub struct SolveRequest {
    /// The load.
    pub load: Load,
    /// The magnification (see [`magnification`]).
    pub zeta: f64,
    /// Tolerance and iteration budget of each solve.
    pub opts: SolveOptions,
    /// Effective modulus `E*`.
    pub e_star: f64,
}

/// The summary of a solve: `summary.json` (conventions, section 7, plus additions) and
/// Python's `Solution.summary()`, key for key.
#[derive(Debug, Clone, Serialize)]
pub struct SolveSummary {
    /// Points per side.
    pub n: usize,
    /// Mean pressure (given, or found for the target contact area).
    pub p0: f64,
    /// Relative contact area `a_r`.
    pub contact_area: f64,
    /// Elastic energy per unit area.
    pub elastic_energy: f64,
    /// Mean gap.
    pub mean_gap: f64,
    /// The solver-independent residual reached.
    pub residual: f64,
    /// Iterations of the (last) solve.
    pub iterations: usize,
    /// Wall time of the (last) solve, seconds.
    pub wall_s: f64,
    /// The solver's name.
    pub solver: &'static str,
    /// Why the solve stopped: always `converged` here (a solve that stops otherwise is an
    /// error that names its reason).
    pub termination: Termination,
    /// The magnification solved at.
    pub zeta: f64,
    /// Rms gradient `g_bar` of the heights at `zeta`.
    pub rms_gradient: f64,
    /// `p0 / (E* g_bar)`.
    pub reduced_pressure: f64,
    /// Effective modulus.
    pub e_star: f64,
    /// Tolerance asked for.
    pub tol: f64,
    /// Solves spent (more than one when a contact area was the target).
    pub load_solves: usize,
    /// Where the heights came from.
    pub source: String,
    /// The residual's parts.
    pub residual_components: Residual,
    /// tamaas' error measure of this solution.
    pub tamaas_error: f64,
}

/// A solved contact problem: the heights solved against, the solution and its summary.
pub struct Solved {
    /// The heights at the magnification solved at.
    pub heights: Vec<f64>,
    /// Pressure and displacement fields, with the solver's statistics.
    pub solution: ContactSolution,
    /// The summary.
    pub summary: SolveSummary,
}

/// The magnification to solve `surface` at: `zeta`, checked against `[1, zeta_max]`, or
/// by default full resolution, `zeta_max`.
///
/// # Errors
///
/// If `zeta` is outside `[1, zeta_max]`.
pub fn magnification(surface: &Surface, zeta: Option<f64>, s: &dyn Spelling) -> Result<f64> {
    let zeta_max = surface.zeta_max().max(1.0);
    let zeta = zeta.unwrap_or(zeta_max);
    check_zeta(zeta, zeta_max).map_err(|e| s.rename(e))?;
    Ok(zeta)
}

/// Solves `surface` as `request` asks with `solver` (a fresh one, or one wrapped to show
/// progress or to be cancelled), from `start`.
///
/// # Errors
///
/// If the modulus or the load is out of range, a contact area is asked of a flat surface,
/// or the solve or the load search fails.
pub fn solve(
    surface: &Surface,
    request: &SolveRequest,
    solver: &mut dyn Solver,
    start: Start,
    origin: Origin,
    s: &dyn Spelling,
) -> Result<Solved> {
    let SolveRequest {
        load,
        zeta,
        opts,
        e_star,
    } = *request;
    let model = Model::new(surface.grid().clone(), e_star)?;
    let heights = surface.heights_at(zeta, &model.fft);
    let g_bar = surface.rms_gradient(zeta);
    let (solution, solves) = match load {
        Load::Pressure(p0) => {
            let problem = ContactProblem::new(&model, &heights, p0)?;
            (solver.solve(&problem, start, &opts)?, 1)
        }
        Load::Area(a) => {
            if g_bar <= 0.0 {
                return Err(Error::invalid(
                    "contact_area",
                    a,
                    format!(
                        "reachable: the surface is flat (zero rms gradient), so contact is \
                         complete at any load; give {} instead",
                        s.name("p0")
                    ),
                ));
            }
            let target = AreaTarget {
                contact_area: a,
                p0_guess: persson_load_guess(a, g_bar.max(1e-300), e_star),
            };
            let found = solve_for_area(
                solver,
                &model,
                &heights,
                target,
                start,
                &opts,
                &AreaSearch::default(),
            )?;
            (found.solution, found.solves)
        }
    };
    let summary = SolveSummary {
        n: model.grid.n(),
        p0: solution.p0,
        contact_area: solution.contact_area(),
        elastic_energy: solution.elastic_energy(),
        mean_gap: solution.mean_gap(&heights),
        residual: solution.stats.residual.value(),
        iterations: solution.stats.iterations,
        wall_s: solution.stats.wall_s,
        solver: solution.stats.solver,
        termination: Termination::Converged,
        zeta,
        rms_gradient: g_bar,
        reduced_pressure: solution.p0 / (e_star * g_bar),
        e_star,
        tol: opts.tol,
        load_solves: solves,
        source: origin.to_string(),
        residual_components: solution.stats.residual,
        tamaas_error: solution.stats.residual.tamaas,
    };
    Ok(Solved {
        heights,
        solution,
        summary,
    })
}

#[cfg(test)]
mod tests {
    use super::super::{surface, Keywords};
    use super::*;
    use crate::engine::scene::SurfaceScene;
    use crate::engine::solver::SolverKind;
    use crate::engine::surface::Amplitudes;

    fn rough() -> Surface {
        let scene = SurfaceScene {
            n: 32,
            hurst: 0.8,
            lambda_l: 16.0,
            lambda_s: 4.0,
            lambda_r: None,
            amplitudes: Amplitudes::Gaussian,
            rms_gradient: 1.0,
            seed: None,
        };
        let h = surface::generate(&scene, 3, None, &Keywords).unwrap();
        surface::from_heights(32, &h, Some(16.0)).unwrap()
    }

    #[test]
    fn the_summary_describes_the_solution_it_comes_with() {
        let surface = rough();
        let request = SolveRequest {
            load: Load::Area(0.2),
            zeta: magnification(&surface, None, &Keywords).unwrap(),
            opts: SolveOptions::default(),
            e_star: 1.0,
        };
        let mut solver = SolverKind::Cg.build();
        let solved = solve(
            &surface,
            &request,
            solver.as_mut(),
            Start::Cold,
            Origin::Array,
            &Keywords,
        )
        .unwrap();
        let s = &solved.summary;
        assert_eq!(s.n, 32);
        assert_eq!(s.zeta, 4.0);
        assert_eq!(s.contact_area, solved.solution.contact_area());
        assert!((s.contact_area - 0.2).abs() <= 0.01, "{}", s.contact_area);
        assert!(s.load_solves > 1 && s.residual <= 1e-8);
        assert_eq!(s.source, "array");
        let json = serde_json::to_value(s).unwrap();
        assert_eq!(json["termination"], "converged");
        assert_eq!(json["residual_components"]["tamaas"], s.tamaas_error);
        // A warm re-solve from that solution at its own load needs fewer iterations.
        let again = SolveRequest {
            load: Load::Pressure(s.p0),
            ..request
        };
        let warm = solve(
            &surface,
            &again,
            solver.as_mut(),
            Start::Warm(&solved.solution),
            Origin::Array,
            &Keywords,
        )
        .unwrap();
        assert!(warm.summary.iterations <= s.iterations);
    }

    #[test]
    fn a_magnification_beyond_the_surface_is_refused_by_name() {
        let e = magnification(&rough(), Some(8.0), &Keywords).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid zeta = 8: must be in [1, zeta_max = 4]"
        );
    }
}
