//! One hard-wall contact problem (`persson-check solve`, Python's `solve`): a surface at a
//! magnification pressed onto the elastic half-space at a mean pressure `p0`, or at the
//! load that gives a target contact area, and its summary (`summary.json`, Python's
//! `Solution.summary()`).
//!
//! The request is [`SolveArgs`]: a front end parses its flags or keywords into it, and
//! gets back a [`Solved`]. Its values are checked once ([`SolveArgs::check`]), before any
//! work; a scene's `[solve]` table and the defaults fill what was not given
//! ([`Checked::settle`]); [`Settled::run`] solves. Python's `sweep` takes the same request
//! ([`super::sweep::with_run`]).
//!
//! A contact-area target is met by root finding on the load ([`crate::engine::load`]),
//! starting from Persson's estimate `p0 = sqrt2 (E* g_bar / 2) erfinv(a_r)` with the rms
//! gradient `g_bar` of the heights solved against; every solve after the first starts from
//! the previous solution.

use std::fmt;
use std::ops::ControlFlow;
use std::path::Path;

use serde::Serialize;

use crate::engine::contact::{ContactProblem, ContactSolution, Model, Residual};
use crate::engine::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use crate::engine::scene::{check_zeta, SolveScene};
use crate::engine::solver::{SolveOptions, Solver, SolverKind, Start, Watched};
use crate::engine::surface::Surface;
use crate::error::{Error, Result, Termination};

use super::parse::{self, Load};
use super::{Flags, Spelling};

/// A solver's progress, as a front end's `watch` sees it.
pub use crate::engine::solver::Progress;
/// Why a front end's `watch` stops a solve (its answer `ControlFlow::Break(reason)`).
pub use crate::error::StopReason;

/// A solve as a front end asks for it: the values the user gave, `None` where not given.
/// [`SolveArgs::check`] checks them once, before any work; [`Checked::settle`] fills the
/// rest from a scene's `[solve]` table and the defaults ([`SolverKind::default`],
/// [`SolveOptions::DEFAULT_TOL`], [`SolveOptions::DEFAULT_MAX_ITER`], `E* = 1`), and
/// [`Settled::run`] solves.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolveArgs {
    /// Mean pressure `p0` (units of `E*`).
    pub p0: Option<f64>,
    /// Target relative contact area, in (0, 1).
    pub contact_area: Option<f64>,
    /// Magnification (default: full resolution).
    pub zeta: Option<f64>,
    /// The wavelength that defines `zeta = |q| / q_l` for given heights (default: the box).
    pub lambda_l: Option<f64>,
    /// Solver.
    pub solver: Option<SolverKind>,
    /// Residual tolerance, in [1e-14, 1).
    pub tol: Option<f64>,
    /// Iteration budget of each solve, at least 1.
    pub max_iter: Option<usize>,
}

/// [`SolveArgs`] whose values have been checked.
#[derive(Debug, Clone, Copy)]
pub struct Checked {
    args: SolveArgs,
}

/// A solve with every setting known: ready to [`run`](Settled::run) on a surface.
#[derive(Debug, Clone, Copy)]
pub struct Settled {
    pub(super) load: Load,
    zeta: Option<f64>,
    /// Whether `zeta` came from the scene (then named as its key, `solve.zeta`).
    zeta_from_scene: bool,
    pub(super) solver: SolverKind,
    pub(super) opts: SolveOptions,
    pub(super) e_star: f64,
}

impl SolveArgs {
    /// Checks the ranges of the values given, before any work: `p0 > 0`,
    /// `0 < contact_area < 1`, `zeta >= 1` (its upper bound comes with the surface),
    /// `lambda_l > 0`, `tol` in [1e-14, 1) and `max_iter >= 1`; errors name the parameter
    /// through `s`, except `lambda_l`, named through `lambda_l_named` (`solve --heights`
    /// reads it from `--file-lambda-l`).
    pub fn check(self, s: &dyn Spelling, lambda_l_named: &dyn Spelling) -> Result<Checked> {
        parse::check_load(self.p0, self.contact_area, s)?;
        parse::check_zeta_floor(self.zeta, s)?;
        parse::check_lambda_l(self.lambda_l, lambda_l_named)?;
        let opts = SolveOptions {
            tol: self.tol.unwrap_or(SolveOptions::DEFAULT_TOL),
            max_iter: self.max_iter.unwrap_or(SolveOptions::DEFAULT_MAX_ITER),
        };
        opts.validate().map_err(|e| s.rename(e))?;
        Ok(Checked { args: self })
    }
}

impl Checked {
    /// The values given, checked.
    pub fn args(&self) -> &SolveArgs {
        &self.args
    }

    /// The solve settled: a value given wins over the scene's (`scene`, already checked
    /// when it was read; `None` where no scene can give one), a default fills the rest, and
    /// the load is `p0` or `contact_area`, exactly one of them.
    pub fn settle(self, scene: Option<&SolveScene>, s: &dyn Spelling) -> Result<Settled> {
        let a = self.args;
        let table = scene.copied().unwrap_or_default();
        let load = parse::load(
            a.p0,
            a.contact_area,
            scene.map(|t| (t.p0, t.contact_area)),
            s,
        )?;
        Ok(Settled {
            load,
            zeta: a.zeta.or(table.zeta),
            zeta_from_scene: a.zeta.is_none() && table.zeta.is_some(),
            solver: a.solver.or(table.solver).unwrap_or_default(),
            opts: SolveOptions {
                tol: a.tol.or(table.tol).unwrap_or(SolveOptions::DEFAULT_TOL),
                max_iter: a.max_iter.unwrap_or(SolveOptions::DEFAULT_MAX_ITER),
            },
            e_star: table.e_star.unwrap_or(1.0),
        })
    }
}

impl Settled {
    /// The solver that will run.
    pub fn solver(&self) -> SolverKind {
        self.solver
    }

    /// Solves `surface` cold; `watch` sees the load `p0` and the progress of every
    /// iteration of every solve, and answers whether the solve goes on (a stop ends it in
    /// [`Error::Stopped`]).
    pub fn run(
        &self,
        surface: &Surface,
        origin: Origin,
        s: &dyn Spelling,
        watch: impl FnMut(f64, Progress) -> ControlFlow<StopReason>,
    ) -> Result<Solved> {
        // A magnification from the scene is named as its key.
        let scene_key = Flags {
            renamed: &[("zeta", "solve.zeta")],
        };
        let zeta_named: &dyn Spelling = if self.zeta_from_scene { &scene_key } else { s };
        let request = SolveRequest {
            load: self.load,
            zeta: magnification(surface, self.zeta, zeta_named)?,
            opts: self.opts,
            e_star: self.e_star,
        };
        let mut watch = watch;
        let mut solver = Watched {
            inner: self.solver.build(),
            watch: |problem: &ContactProblem, p: Progress| watch(problem.p0, p),
        };
        solve(surface, &request, &mut solver, Start::Cold, origin, s)
    }
}

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

    fn rough() -> Surface {
        let scene = surface::SurfaceArgs {
            n: Some(32),
            hurst: Some(0.8),
            lambda_l: Some(16.0),
            lambda_s: Some(4.0),
            seed: Some(3),
            ..Default::default()
        }
        .resolve(&Keywords, "given")
        .unwrap();
        let h = surface::generate(&scene, None, &Keywords).unwrap();
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
    fn a_request_takes_what_is_given_then_the_scene_then_the_defaults() {
        let given = SolveArgs {
            p0: Some(0.1),
            ..SolveArgs::default()
        };
        let table = SolveScene {
            zeta: Some(2.0),
            contact_area: Some(0.3),
            solver: Some(SolverKind::Gfmd),
            tol: Some(1e-6),
            e_star: Some(2.0),
            ..SolveScene::default()
        };
        let flags = Flags::default();
        let s = given
            .check(&flags, &flags)
            .unwrap()
            .settle(Some(&table), &flags)
            .unwrap();
        // The load given replaces the scene's; the rest comes from the scene.
        assert_eq!(s.load, Load::Pressure(0.1));
        assert_eq!((s.zeta, s.zeta_from_scene), (Some(2.0), true));
        assert_eq!(
            (s.solver(), s.opts.tol, s.e_star),
            (SolverKind::Gfmd, 1e-6, 2.0)
        );
        assert_eq!(s.opts.max_iter, SolveOptions::DEFAULT_MAX_ITER);
        // Without a scene, the defaults.
        let s = given.check(&Keywords, &Keywords).unwrap();
        let s = s.settle(None, &Keywords).unwrap();
        assert_eq!(s.opts, SolveOptions::default());
        assert_eq!(
            (s.solver(), s.e_star, s.zeta),
            (SolverKind::default(), 1.0, None)
        );
    }

    #[test]
    fn a_request_names_each_bad_value_as_its_front_end_writes_it() {
        let bad = |args: SolveArgs| {
            let heights = Flags {
                renamed: &[("lambda_l", "--file-lambda-l")],
            };
            args.check(&Flags::default(), &heights)
                .unwrap_err()
                .to_string()
        };
        let p0 = SolveArgs {
            p0: Some(0.1),
            ..SolveArgs::default()
        };
        assert_eq!(
            bad(SolveArgs {
                tol: Some(0.0),
                ..p0
            }),
            "invalid --tol = 0: must be in [1e-14, 1)"
        );
        assert_eq!(
            bad(SolveArgs {
                tol: Some(1e-20),
                ..p0
            }),
            "invalid --tol = 0.00000000000000000001: must be in [1e-14, 1)"
        );
        assert_eq!(
            bad(SolveArgs {
                max_iter: Some(0),
                ..p0
            }),
            "invalid --max-iter = 0: must be >= 1"
        );
        assert_eq!(
            bad(SolveArgs {
                lambda_l: Some(-1.0),
                ..p0
            }),
            "invalid --file-lambda-l = -1: must be a finite number > 0"
        );
        assert_eq!(
            bad(SolveArgs {
                zeta: Some(0.5),
                ..p0
            }),
            "invalid --zeta = 0.5: must be in [1, zeta_max = lambda_l / lambda_s]"
        );
        let none = SolveArgs::default().check(&Keywords, &Keywords).unwrap();
        assert_eq!(
            none.settle(None, &Keywords).unwrap_err().to_string(),
            "invalid load = missing: must be p0=P or contact_area=A"
        );
    }

    #[test]
    fn a_magnification_from_the_scene_is_named_as_its_key() {
        let table = SolveScene {
            zeta: Some(8.0),
            p0: Some(0.1),
            ..SolveScene::default()
        };
        let flags = Flags::default();
        let settled = SolveArgs::default()
            .check(&flags, &flags)
            .unwrap()
            .settle(Some(&table), &flags)
            .unwrap();
        let Err(e) = settled.run(&rough(), Origin::Array, &flags, |_, _| {
            ControlFlow::Continue(())
        }) else {
            panic!("solved beyond zeta_max");
        };
        assert_eq!(
            e.to_string(),
            "invalid solve.zeta = 8: must be in [1, zeta_max = 4]"
        );
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
