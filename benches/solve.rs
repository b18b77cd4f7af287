//! Hard-wall solves with every solver of [`SolverKind::ALL`], in its order, on the
//! standard scene of the speed study (`src/speed/`): H = 0.8,
//! `lambda_l = N/2`, `lambda_s = 8`, seed 1, `p0 = 0.1` in units of `E* g_bar` (surfaces
//! have unit rms gradient), `tol = 1e-8`.
//!
//! * `cold/<solver>/<N>`, `N = 256, 512, 1024`: one solve from scratch at full resolution,
//!   the cost of a single contact solution;
//! * `warm_shell/<solver>/<N>`, `N = 256, 512, 1024`: the step of a magnification sweep that
//!   validations repeat hundreds of times. The surface is solved at the shell just below
//!   `zeta = 32` (outside the timing), then the next distinct `|q|^2` shell is added and
//!   the warm-started solve is timed. The scene's roughness stops at
//!   `zeta = lambda_l / lambda_s = N/16`, so the shell added is the surface's last one:
//!   `zeta = 32` at `N = 512`, and `zeta = 16` at `N = 256`, where no shell reaches 32;
//! * `warm_load/<solver>/<N>`, `N = 256, 512, 1024`: a warm re-solve after raising the load by 1%,
//!   the step of a load search (`persson_check::engine::load`).
//!
//! Surfaces, models, solvers and warm starts are built once, outside the timed code, and
//! only when a benchmark is selected; each timed iteration is one call of
//! [`Solver::solve`]. A solver is reused between iterations, as a sweep reuses it, so its
//! work buffers are allocated once.

use std::cell::OnceCell;
use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, SamplingMode};
use persson_check::engine::contact::{ContactProblem, ContactSolution, Model};
use persson_check::engine::solver::SolverKind;
use persson_check::engine::solver::{SolveOptions, Solver, Start};
use persson_check::engine::surface::{Surface, SurfaceModel};
use persson_check::engine::sweep::shell_steps;

/// Hurst exponent of the scene.
const HURST: f64 = 0.8;
/// Short-wavelength cutoff, grid spacings (`lambda_l = N/2`).
const LAMBDA_S: f64 = 8.0;
/// Seed of the realization.
const SEED: u64 = 1;
/// Mean pressure, units of `E* g_bar`.
const P0: f64 = 0.1;
/// Requested residual.
const TOL: f64 = 1e-8;
/// Magnification of the added shell in `warm_shell`.
const SHELL_ZETA: f64 = 32.0;
/// Load factor of `warm_load`.
const LOAD_STEP: f64 = 1.01;

/// The realization on an `n x n` grid and its model.
struct Scene {
    surface: Surface,
    model: Model,
}

impl Scene {
    fn new(n: usize) -> Self {
        let params = SurfaceModel::new(n, HURST, n as f64 / 2.0, LAMBDA_S, SEED);
        let surface = Surface::generate(&params).expect("valid scene");
        let model = Model::new(surface.grid().clone(), 1.0).expect("valid model");
        Self { surface, model }
    }

    /// Heights at magnification `zeta` (`f64::INFINITY`: full resolution).
    fn heights(&self, zeta: f64) -> Vec<f64> {
        self.surface.heights_at(zeta, &self.model.fft)
    }

    /// A problem on `heights` at load `p0`.
    fn problem<'a>(&'a self, heights: &'a [f64], p0: f64) -> ContactProblem<'a> {
        ContactProblem::new(&self.model, heights, p0).expect("valid problem")
    }
}

/// The magnifications `(below, added)` of two consecutive shells of `surface`: `added` is
/// the first shell at or above `zeta` (the last shell if the roughness stops below `zeta`),
/// `below` the shell before it.
fn shell_pair(surface: &Surface, zeta: f64) -> (f64, f64) {
    let steps = shell_steps(surface, 0.0, f64::INFINITY);
    assert!(steps.len() >= 2, "the surface has fewer than two shells");
    let i = steps
        .iter()
        .position(|&z| z >= zeta * (1.0 - 1e-12))
        .unwrap_or(steps.len() - 1)
        .max(1);
    (steps[i - 1], steps[i])
}

/// Solver options of every solve.
fn options() -> SolveOptions {
    SolveOptions::with_tol(TOL)
}

fn cold(c: &mut Criterion) {
    let mut group = c.benchmark_group("cold");
    // Flat sampling: every sample runs the same number of solves, so ten samples of the
    // slowest case (GFMD at 1024^2, seconds per solve) cost ten solves.
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_secs(1));
    let opts = options();
    for n in [256, 512, 1024] {
        group.measurement_time(Duration::from_secs(match n {
            256 => 5,
            512 => 8,
            _ => 20,
        }));
        let scene: OnceCell<(Scene, Vec<f64>)> = OnceCell::new();
        for kind in SolverKind::ALL {
            let mut solver = kind.build();
            group.bench_function(BenchmarkId::new(kind.name(), n), |b| {
                let (scene, heights) = scene.get_or_init(|| {
                    let scene = Scene::new(n);
                    let heights = scene.heights(f64::INFINITY);
                    (scene, heights)
                });
                let problem = scene.problem(heights, P0);
                b.iter_batched(
                    || black_box(&problem),
                    |problem| {
                        solver
                            .solve(problem, Start::Cold, &opts)
                            .expect("cold solve converges")
                    },
                    BatchSize::PerIteration,
                )
            });
        }
    }
    group.finish();
}

/// A warm-start benchmark's fixed inputs: the heights and load solved, the solution it
/// starts from, and what changed since that solution (for the log).
struct WarmCase {
    heights: Vec<f64>,
    p0: f64,
    start: ContactSolution,
    step: String,
}

impl WarmCase {
    /// The timed problem.
    fn problem<'a>(&'a self, scene: &'a Scene) -> ContactProblem<'a> {
        scene.problem(&self.heights, self.p0)
    }
}

/// Times, for each solver and grid size, the warm solve of the case that `prepare` builds
/// (with the solver, on first use). Before the timing, one untimed warm solve logs the
/// iterations of the start and of the re-solve to stderr.
fn warm_group(
    c: &mut Criterion,
    name: &str,
    prepare: impl Fn(&Scene, &mut dyn Solver) -> WarmCase,
) {
    let mut group = c.benchmark_group(name);
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    let opts = options();
    for n in [256, 512, 1024] {
        let scene: OnceCell<Scene> = OnceCell::new();
        for kind in SolverKind::ALL {
            let mut solver = kind.build();
            let case: OnceCell<WarmCase> = OnceCell::new();
            group.bench_function(BenchmarkId::new(kind.name(), n), |b| {
                let scene = scene.get_or_init(|| Scene::new(n));
                let case = case.get_or_init(|| {
                    let case = prepare(scene, solver.as_mut());
                    let warm = solver
                        .solve(&case.problem(scene), Start::Warm(&case.start), &opts)
                        .expect("warm solve converges");
                    eprintln!(
                        "{name}/{}/{n}: {}; iterations: start {}, warm re-solve {}",
                        kind.name(),
                        case.step,
                        case.start.stats.iterations,
                        warm.stats.iterations
                    );
                    case
                });
                let problem = case.problem(scene);
                b.iter_batched(
                    || black_box(&case.start),
                    |start| {
                        solver
                            .solve(&problem, Start::Warm(start), &opts)
                            .expect("warm solve converges")
                    },
                    BatchSize::PerIteration,
                )
            });
        }
    }
    group.finish();
}

fn warm_shell(c: &mut Criterion) {
    warm_group(c, "warm_shell", |scene, solver| {
        let (below, added) = shell_pair(&scene.surface, SHELL_ZETA);
        let heights = scene.heights(below);
        let start = solver
            .solve(&scene.problem(&heights, P0), Start::Cold, &options())
            .expect("solve below the shell converges");
        WarmCase {
            heights: scene.heights(added),
            p0: P0,
            start,
            step: format!("shell added at zeta = {added:.4} to the solution at zeta = {below:.4}"),
        }
    });
}

fn warm_load(c: &mut Criterion) {
    warm_group(c, "warm_load", |scene, solver| {
        let heights = scene.heights(f64::INFINITY);
        let start = solver
            .solve(&scene.problem(&heights, P0), Start::Cold, &options())
            .expect("solve at the first load converges");
        WarmCase {
            heights,
            p0: P0 * LOAD_STEP,
            start,
            step: format!("load {P0} -> {}", P0 * LOAD_STEP),
        }
    });
}

criterion_group!(benches, cold, warm_shell, warm_load);
criterion_main!(benches);
