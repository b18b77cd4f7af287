//! Speed against error: how long each solver takes to reach a given accuracy.
//!
//! One scene ([`crate::conventions`], section 3; H = 0.8, `lambda_l = N/2`, `lambda_s = 8`,
//! `p0 = 0.1`, seed 1), solved by both solvers ([`SolverKind::Cg`], [`SolverKind::Gfmd`]):
//!
//! * **tolerance**: a tightly converged reference (CG, `tol = 1e-12`), then cold solves at
//!   each tolerance; wall time, iterations, the residual reached, and the errors of the
//!   contact area `|a_r - a_ref|` and of the elastic energy `|E - E_ref| / E_ref` against
//!   the reference;
//! * **size**: iterations against the grid size `N` at one tolerance, with the fitted
//!   exponent of `iterations ~ N^k`. The paper's argument for GFMD in reciprocal space is
//!   that mass weighting lowers critical slowing-down from `O(L^2)` (plain damped dynamics)
//!   to `O(L^(1/2))`;
//! * **threads**: the same solve in rayon pools of 1, 2 (and all available) threads;
//! * **floor**: on each grid of `floor_sizes`, the time of one forward + inverse 2D FFT
//!   pair (the floor of an iteration's cost) and each solver's cold solve in units of it:
//!   the FFT pairs the solve used per iteration (counted by [`crate::engine::fft::Fft2`]), its cost
//!   per iteration in pairs, and the cost of each pair it used (1 would be nothing but
//!   FFTs);
//! * **warm**: on the same grids, each solver re-solving from a converged solution after a
//!   1% load change, and after adding one magnification shell (the last shell at or below
//!   `shell_zeta`, warm-started from the solution one shell lower), against a cold solve of
//!   the same problem.
//!
//! Times are wall-clock times of single runs (the fastest of `repeats`) on whatever machine
//! runs the study, which may be shared with other work: ratios between rows mean more than
//! absolute values. Each study records the [`Machine`] it ran on.
//!
//! [`run`] computes the study; [`SpeedStudy::write`] writes `speed.csv`, `speed.json` and
//! the figures; the scorecard ([`crate::report`]) formats it.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::engine::contact::{ContactProblem, ContactSolution, Model};
use crate::engine::solver::SolverKind;
use crate::engine::solver::{SolveOptions, Start};
use crate::engine::surface::{Surface, SurfaceParams};
use crate::engine::sweep::shell_steps;
use crate::error::{check_positive, Error, Result};
use crate::plot::{Axis, Figure, Series, Style};
use crate::provenance::Machine;
use crate::stats::{round_sig, LineFit};

/// The solvers compared, in table order.
pub const SOLVERS: [SolverKind; 2] = [SolverKind::Cg, SolverKind::Gfmd];

/// What the study runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpeedOptions {
    /// Grid of the tolerance and thread studies.
    pub n: usize,
    /// Grids of the size study (those too small for `lambda_s` are left out).
    pub sizes: Vec<usize>,
    /// Tolerances of the cold solves.
    pub tols: Vec<f64>,
    /// Tolerance of the reference solve (CG).
    pub reference_tol: f64,
    /// Tolerance of the size and thread studies.
    pub size_tol: f64,
    /// Pool sizes of the thread study.
    pub threads: Vec<usize>,
    /// Grids of the floor and warm-start studies.
    pub floor_sizes: Vec<usize>,
    /// Magnification near which the warm-start study adds one shell.
    pub shell_zeta: f64,
    /// Timed solves per row; the fastest counts.
    pub repeats: usize,
    /// Hurst exponent.
    pub hurst: f64,
    /// Short-wavelength cutoff, grid spacings (`lambda_l = N/2`).
    pub lambda_s: f64,
    /// Mean pressure, units of `E*` (surfaces have unit rms gradient).
    pub p0: f64,
    /// Seed of the realization.
    pub seed: u64,
}

impl Default for SpeedOptions {
    fn default() -> Self {
        Self::with_n(256)
    }
}

impl SpeedOptions {
    /// The standard study on an `n x n` grid: sizes `n/4, n/2, n, 2n`, tolerances
    /// `1e-4 ... 1e-10`, pools of 1, 2 and all available threads, floor and warm starts on
    /// `n` and `2n` with one shell added near `zeta = 32`.
    pub fn with_n(n: usize) -> Self {
        let avail = std::thread::available_parallelism()
            .map(|k| k.get())
            .unwrap_or(1);
        let mut threads = vec![1, 2, avail];
        threads.sort_unstable();
        threads.dedup();
        Self {
            n,
            sizes: vec![n / 4, n / 2, n, 2 * n],
            tols: vec![1e-4, 1e-6, 1e-8, 1e-10],
            reference_tol: 1e-12,
            size_tol: 1e-8,
            threads,
            floor_sizes: vec![n, 2 * n],
            shell_zeta: 32.0,
            repeats: 3,
            hurst: 0.8,
            lambda_s: 8.0,
            p0: 0.1,
            seed: 1,
        }
    }

    /// Checks the ranges; errors name the option.
    pub fn validate(&self) -> Result<()> {
        self.params(self.n)
            .spectrum
            .validate(&crate::engine::grid::Grid::new(self.n, 1.0)?)
            .map_err(|e| {
                Error::invalid(
                    "speed n",
                    self.n,
                    format!("a grid that fits the scene ({e})"),
                )
            })?;
        for &tol in self
            .tols
            .iter()
            .chain([&self.reference_tol, &self.size_tol])
        {
            SolveOptions::with_tol(tol).validate()?;
        }
        if self.tols.is_empty() {
            return Err(Error::invalid("speed tols", "[]", "at least one tolerance"));
        }
        if self.threads.contains(&0) {
            return Err(Error::invalid("speed threads", 0, "pool sizes >= 1"));
        }
        if self.repeats == 0 {
            return Err(Error::invalid("speed repeats", 0, ">= 1"));
        }
        for &n in &self.floor_sizes {
            crate::engine::grid::Grid::new(n, 1.0)
                .and_then(|g| self.params(n).spectrum.validate(&g))
                .map_err(|e| {
                    Error::invalid(
                        "speed floor sizes",
                        n,
                        format!("grids that fit the scene ({e})"),
                    )
                })?;
        }
        if !(self.shell_zeta.is_finite() && self.shell_zeta > 1.0) {
            return Err(Error::invalid("speed shell zeta", self.shell_zeta, "> 1"));
        }
        check_positive("speed p0", self.p0)
    }

    fn params(&self, n: usize) -> SurfaceParams {
        SurfaceParams::new(n, self.hurst, n as f64 / 2.0, self.lambda_s, self.seed)
    }

    /// The sizes of the size study whose scene is valid.
    fn valid_sizes(&self) -> Vec<usize> {
        let mut sizes: Vec<usize> = self
            .sizes
            .iter()
            .copied()
            .filter(|&n| {
                crate::engine::grid::Grid::new(n, 1.0)
                    .and_then(|g| self.params(n).spectrum.validate(&g))
                    .is_ok()
            })
            .collect();
        sizes.sort_unstable();
        sizes.dedup();
        sizes
    }
}

/// The reference solution's figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reference {
    /// Solver.
    pub solver: SolverKind,
    /// Tolerance.
    pub tol: f64,
    /// Residual reached.
    pub residual: f64,
    /// Iterations.
    pub iterations: usize,
    /// Wall time, seconds.
    pub wall_s: f64,
    /// Relative contact area.
    pub contact_area: f64,
    /// Elastic energy per unit area.
    pub elastic_energy: f64,
}

/// One cold solve at one tolerance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ToleranceRow {
    /// Solver.
    pub solver: SolverKind,
    /// Requested tolerance.
    pub tol: f64,
    /// Wall time (fastest of the repeats), seconds; `None` when the solve failed.
    pub wall_s: Option<f64>,
    /// Iterations.
    pub iterations: Option<usize>,
    /// Residual reached (the project's, see [`crate::engine::contact::Residual`]).
    pub residual: Option<f64>,
    /// tamaas's error measure of the same solution.
    pub tamaas: Option<f64>,
    /// `|a_r - a_ref|`.
    pub area_error: Option<f64>,
    /// `|E - E_ref| / E_ref`.
    pub energy_error: Option<f64>,
    /// Why the solve failed, if it did.
    pub error: Option<String>,
}

/// Iterations on one grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SizeRow {
    /// Solver.
    pub solver: SolverKind,
    /// Points per side.
    pub n: usize,
    /// Iterations.
    pub iterations: Option<usize>,
    /// Wall time, seconds.
    pub wall_s: Option<f64>,
    /// Residual reached.
    pub residual: Option<f64>,
    /// Why the solve failed, if it did.
    pub error: Option<String>,
}

/// Fitted exponent `k` of `iterations ~ N^k`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SizeFit {
    /// Solver.
    pub solver: SolverKind,
    /// Exponent, when at least two grids converged.
    pub exponent: Option<f64>,
    /// Its standard error, when at least three did.
    pub std_error: Option<f64>,
    /// Grids that entered the fit.
    pub points: usize,
}

/// One solve in a pool of a given size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThreadRow {
    /// Solver.
    pub solver: SolverKind,
    /// Threads in the pool.
    pub threads: usize,
    /// Wall time, seconds.
    pub wall_s: Option<f64>,
    /// Speed-up against the one-thread pool.
    pub speedup: Option<f64>,
    /// Why the solve failed, if it did.
    pub error: Option<String>,
}

/// The cost floor on one grid: one FFT pair, and a cold solve in units of it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorRow {
    /// Solver.
    pub solver: SolverKind,
    /// Points per side.
    pub n: usize,
    /// Wall time of one forward + inverse 2D FFT pair, seconds (fastest batch mean).
    pub fft_pair_s: f64,
    /// Iterations of the cold solve (at the size study's tolerance).
    pub iterations: Option<usize>,
    /// Wall time of the cold solve (fastest of the repeats), seconds.
    pub wall_s: Option<f64>,
    /// FFT pairs the solve used per iteration (refreshes and the final residual included).
    pub pairs_per_iteration: Option<f64>,
    /// Cost of an iteration in FFT pairs, `wall / (iterations fft_pair_s)`.
    pub iteration_in_pairs: Option<f64>,
    /// Cost of each FFT pair the solve used, in FFT pairs, `wall / (pairs fft_pair_s)`:
    /// 1 would be nothing but transforms.
    pub overhead: Option<f64>,
    /// Why the solve failed, if it did.
    pub error: Option<String>,
}

/// A warm re-solve on one grid, against a cold solve of the same problem.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WarmRow {
    /// Solver.
    pub solver: SolverKind,
    /// Points per side.
    pub n: usize,
    /// What changed since the solution the warm solve starts from.
    pub change: String,
    /// Iterations of the cold solve.
    pub cold_iterations: Option<usize>,
    /// Wall time of the cold solve, seconds.
    pub cold_wall_s: Option<f64>,
    /// Iterations of the warm solve.
    pub warm_iterations: Option<usize>,
    /// Wall time of the warm solve, seconds.
    pub warm_wall_s: Option<f64>,
    /// `warm_wall_s / cold_wall_s`.
    pub ratio: Option<f64>,
    /// Why a solve failed, if one did.
    pub error: Option<String>,
}

/// The whole study, as written to `speed.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpeedStudy {
    /// What was run.
    pub options: SpeedOptions,
    /// Where it ran.
    pub machine: Machine,
    /// Threads of the pool the tolerance and size studies ran in.
    pub threads: usize,
    /// Commit of the code that ran it.
    pub commit: String,
    /// Start, RFC 3339 UTC.
    pub started_at: String,
    /// Wall time of the whole study, seconds.
    pub wall_s: f64,
    /// The reference solution.
    pub reference: Reference,
    /// Tolerance study, solver by solver.
    pub tolerance: Vec<ToleranceRow>,
    /// Size study.
    pub sizes: Vec<SizeRow>,
    /// Exponents of the size study.
    pub fits: Vec<SizeFit>,
    /// Thread study.
    pub threads_study: Vec<ThreadRow>,
    /// Floor study (absent in studies written before it existed).
    #[serde(default)]
    pub floor: Vec<FloorRow>,
    /// Warm-start study (absent in studies written before it existed).
    #[serde(default)]
    pub warm: Vec<WarmRow>,
}

/// One prepared scene: the surface, its heights at full resolution, and the model.
struct Scene {
    surface: Surface,
    model: Model,
    heights: Vec<f64>,
    p0: f64,
}

impl Scene {
    fn new(opts: &SpeedOptions, n: usize) -> Result<Self> {
        let surface = Surface::generate(&opts.params(n))?;
        let model = Model::new(surface.grid().clone(), 1.0)?;
        let heights = surface.heights_at(f64::INFINITY, &model.fft);
        Ok(Self {
            surface,
            model,
            heights,
            p0: opts.p0,
        })
    }

    /// A solve of `heights` at `p0` from `start` with a fresh solver; returns the solution
    /// and its wall time.
    fn solve_with(
        &self,
        kind: SolverKind,
        heights: &[f64],
        p0: f64,
        start: Start,
        tol: f64,
    ) -> Result<(ContactSolution, f64)> {
        let problem = ContactProblem::new(&self.model, heights, p0)?;
        let mut solver = kind.build();
        let timer = Instant::now();
        let solution = solver.solve(&problem, start, &SolveOptions::with_tol(tol))?;
        Ok((solution, timer.elapsed().as_secs_f64()))
    }

    /// The fastest of `repeats` solves of `heights` at `p0` from `start`.
    fn timed_with(
        &self,
        kind: SolverKind,
        heights: &[f64],
        p0: f64,
        start: Start,
        tol: f64,
        repeats: usize,
    ) -> Result<(ContactSolution, f64)> {
        let (mut best, mut t) = self.solve_with(kind, heights, p0, start, tol)?;
        for _ in 1..repeats {
            let (s, dt) = self.solve_with(kind, heights, p0, start, tol)?;
            if dt < t {
                (best, t) = (s, dt);
            }
        }
        Ok((best, t))
    }

    /// The fastest of `repeats` cold solves of the scene.
    fn timed(&self, kind: SolverKind, tol: f64, repeats: usize) -> Result<(ContactSolution, f64)> {
        self.timed_with(kind, &self.heights, self.p0, Start::Cold, tol, repeats)
    }

    /// A cold solve of the scene; returns the solution and its wall time.
    fn solve(&self, kind: SolverKind, tol: f64) -> Result<(ContactSolution, f64)> {
        self.solve_with(kind, &self.heights, self.p0, Start::Cold, tol)
    }

    /// Mean wall time of one forward + inverse FFT pair: the fastest of a few batches, each
    /// long enough (about 0.1 s) to be timed reliably.
    fn fft_pair_s(&self) -> f64 {
        let fft = &self.model.fft;
        let mut field = self.heights.clone();
        let mut spec = fft.new_spectrum();
        let mut pair = || {
            fft.forward(&field, &mut spec);
            fft.inverse_in_place(&mut spec, &mut field);
        };
        let timer = Instant::now();
        pair();
        let once = timer.elapsed().as_secs_f64().max(1e-7);
        let per_batch = ((0.1 / once).ceil() as usize).clamp(1, 10_000);
        (0..5)
            .map(|_| {
                let timer = Instant::now();
                for _ in 0..per_batch {
                    pair();
                }
                timer.elapsed().as_secs_f64() / per_batch as f64
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The floor row of one solver: a cold solve counted in FFT pairs.
    fn floor(&self, kind: SolverKind, fft_pair_s: f64, tol: f64, repeats: usize) -> FloorRow {
        let n = self.model.grid.n();
        let before = self.model.fft.transforms();
        let result = self.solve(kind, tol).and_then(|(s, _)| {
            let pairs = (self.model.fft.transforms() - before) as f64 / 2.0;
            let (_, t) = self.timed(kind, tol, repeats)?;
            Ok((s.stats.iterations, t, pairs))
        });
        match result {
            Ok((it, t, pairs)) => FloorRow {
                solver: kind,
                n,
                fft_pair_s,
                iterations: Some(it),
                wall_s: Some(t),
                pairs_per_iteration: Some(pairs / it.max(1) as f64),
                iteration_in_pairs: Some(t / (it.max(1) as f64 * fft_pair_s)),
                overhead: Some(t / (pairs * fft_pair_s)),
                error: None,
            },
            Err(e) => FloorRow {
                solver: kind,
                n,
                fft_pair_s,
                iterations: None,
                wall_s: None,
                pairs_per_iteration: None,
                iteration_in_pairs: None,
                overhead: None,
                error: Some(e.to_string()),
            },
        }
    }

    /// Warm re-solves of one solver: after a 1% load change, and after adding the last
    /// shell at or below `shell_zeta`.
    fn warm(&self, kind: SolverKind, shell_zeta: f64, tol: f64, repeats: usize) -> Vec<WarmRow> {
        let n = self.model.grid.n();
        let row =
            |change: String, r: Result<((ContactSolution, f64), (ContactSolution, f64))>| match r {
                Ok(((cold, tc), (warm, tw))) => WarmRow {
                    solver: kind,
                    n,
                    change,
                    cold_iterations: Some(cold.stats.iterations),
                    cold_wall_s: Some(tc),
                    warm_iterations: Some(warm.stats.iterations),
                    warm_wall_s: Some(tw),
                    ratio: Some(tw / tc),
                    error: None,
                },
                Err(e) => WarmRow {
                    solver: kind,
                    n,
                    change,
                    cold_iterations: None,
                    cold_wall_s: None,
                    warm_iterations: None,
                    warm_wall_s: None,
                    ratio: None,
                    error: Some(e.to_string()),
                },
            };
        let mut rows = Vec::new();
        // Load +1%, from the converged solution at p0.
        let p1 = 1.01 * self.p0;
        let load = self.solve(kind, tol).and_then(|(from, _)| {
            let cold = self.timed_with(kind, &self.heights, p1, Start::Cold, tol, repeats)?;
            let warm =
                self.timed_with(kind, &self.heights, p1, Start::Warm(&from), tol, repeats)?;
            Ok((cold, warm))
        });
        rows.push(row("load +1%".into(), load));
        // One shell: the last at or below shell_zeta, from the solution one shell lower.
        let top = shell_zeta.min(self.surface.zeta_max());
        let steps = shell_steps(&self.surface, 1.0, top);
        match steps.as_slice() {
            [.., below, at] => {
                let h_below = self.surface.heights_at(*below, &self.model.fft);
                let h_at = self.surface.heights_at(*at, &self.model.fft);
                let shell = self
                    .solve_with(kind, &h_below, self.p0, Start::Cold, tol)
                    .and_then(|(from, _)| {
                        let cold =
                            self.timed_with(kind, &h_at, self.p0, Start::Cold, tol, repeats)?;
                        let warm = self.timed_with(
                            kind,
                            &h_at,
                            self.p0,
                            Start::Warm(&from),
                            tol,
                            repeats,
                        )?;
                        Ok((cold, warm))
                    });
                rows.push(row(
                    format!("one shell at zeta = {}", round_sig(*at, 4)),
                    shell,
                ));
            }
            _ => rows.push(row(
                format!("one shell below zeta = {top}"),
                Err(Error::invalid(
                    "speed shell zeta",
                    shell_zeta,
                    "a magnification with at least two shells below it",
                )),
            )),
        }
        rows
    }
}

/// Runs the study; `progress` receives a line per step.
pub fn run(opts: &SpeedOptions, progress: &mut dyn FnMut(&str)) -> Result<SpeedStudy> {
    opts.validate()?;
    let started_at = crate::provenance::now_utc();
    let timer = Instant::now();
    let scene = Scene::new(opts, opts.n)?;

    progress(&format!(
        "reference: cg, N = {}, tol = {:e}",
        opts.n, opts.reference_tol
    ));
    let (ref_sol, ref_t) = scene.solve(SolverKind::Cg, opts.reference_tol)?;
    let reference = Reference {
        solver: SolverKind::Cg,
        tol: opts.reference_tol,
        residual: ref_sol.stats.residual.value(),
        iterations: ref_sol.stats.iterations,
        wall_s: ref_t,
        contact_area: ref_sol.contact_area(),
        elastic_energy: ref_sol.elastic_energy(),
    };

    let mut tolerance = Vec::new();
    for kind in SOLVERS {
        for &tol in &opts.tols {
            progress(&format!(
                "tolerance: {}, N = {}, tol = {tol:e}",
                kind.name(),
                opts.n
            ));
            tolerance.push(match scene.timed(kind, tol, opts.repeats) {
                Ok((s, t)) => ToleranceRow {
                    solver: kind,
                    tol,
                    wall_s: Some(t),
                    iterations: Some(s.stats.iterations),
                    residual: Some(s.stats.residual.value()),
                    tamaas: Some(s.stats.residual.tamaas),
                    area_error: Some((s.contact_area() - reference.contact_area).abs()),
                    energy_error: Some(
                        ((s.elastic_energy() - reference.elastic_energy)
                            / reference.elastic_energy)
                            .abs(),
                    ),
                    error: None,
                },
                Err(e) => ToleranceRow {
                    solver: kind,
                    tol,
                    wall_s: None,
                    iterations: None,
                    residual: None,
                    tamaas: None,
                    area_error: None,
                    energy_error: None,
                    error: Some(e.to_string()),
                },
            });
        }
    }

    let mut sizes = Vec::new();
    let grids = opts.valid_sizes();
    let scenes: Vec<(usize, Scene)> = grids
        .iter()
        .map(|&n| Ok((n, Scene::new(opts, n)?)))
        .collect::<Result<_>>()?;
    for kind in SOLVERS {
        for (n, scene) in &scenes {
            progress(&format!(
                "size: {}, N = {n}, tol = {:e}",
                kind.name(),
                opts.size_tol
            ));
            sizes.push(match scene.timed(kind, opts.size_tol, opts.repeats) {
                Ok((s, t)) => SizeRow {
                    solver: kind,
                    n: *n,
                    iterations: Some(s.stats.iterations),
                    wall_s: Some(t),
                    residual: Some(s.stats.residual.value()),
                    error: None,
                },
                Err(e) => SizeRow {
                    solver: kind,
                    n: *n,
                    iterations: None,
                    wall_s: None,
                    residual: None,
                    error: Some(e.to_string()),
                },
            });
        }
    }
    let fits = SOLVERS
        .iter()
        .map(|&kind| fit_exponent(kind, &sizes))
        .collect();

    let mut threads_study = Vec::new();
    for kind in SOLVERS {
        let mut single = None;
        for &k in &opts.threads {
            progress(&format!(
                "threads: {}, N = {}, {k} thread(s), tol = {:e}",
                kind.name(),
                opts.n,
                opts.size_tol
            ));
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .map_err(|e| {
                    Error::invalid("speed threads", k, format!("a pool rayon can build ({e})"))
                })?;
            let result = pool.install(|| scene.timed(kind, opts.size_tol, opts.repeats));
            let row = match result {
                Ok((_, t)) => {
                    if k == 1 {
                        single = Some(t);
                    }
                    ThreadRow {
                        solver: kind,
                        threads: k,
                        wall_s: Some(t),
                        speedup: single.map(|t1| t1 / t),
                        error: None,
                    }
                }
                Err(e) => ThreadRow {
                    solver: kind,
                    threads: k,
                    wall_s: None,
                    speedup: None,
                    error: Some(e.to_string()),
                },
            };
            threads_study.push(row);
        }
    }

    let mut floor = Vec::new();
    let mut warm = Vec::new();
    for &n in &opts.floor_sizes {
        let scene = Scene::new(opts, n)?;
        progress(&format!("floor: FFT pair, N = {n}"));
        let pair = scene.fft_pair_s();
        for kind in SOLVERS {
            progress(&format!(
                "floor: {}, N = {n}, tol = {:e}",
                kind.name(),
                opts.size_tol
            ));
            floor.push(scene.floor(kind, pair, opts.size_tol, opts.repeats));
            progress(&format!(
                "warm: {}, N = {n}, tol = {:e}",
                kind.name(),
                opts.size_tol
            ));
            warm.extend(scene.warm(kind, opts.shell_zeta, opts.size_tol, opts.repeats));
        }
    }

    Ok(SpeedStudy {
        options: opts.clone(),
        machine: Machine::detect(),
        threads: rayon::current_num_threads(),
        commit: crate::provenance::commit_label(),
        started_at,
        wall_s: timer.elapsed().as_secs_f64(),
        reference,
        tolerance,
        sizes,
        fits,
        threads_study,
        floor,
        warm,
    })
}

/// Least-squares slope of `ln iterations` against `ln N` over the converged grids.
fn fit_exponent(kind: SolverKind, sizes: &[SizeRow]) -> SizeFit {
    let (x, y): (Vec<f64>, Vec<f64>) = sizes
        .iter()
        .filter(|r| r.solver == kind)
        .filter_map(|r| Some(((r.n as f64).ln(), (r.iterations? as f64).max(1.0).ln())))
        .unzip();
    let fit = LineFit::fit(&x, &y);
    SizeFit {
        solver: kind,
        exponent: fit.map(|f| f.slope.value),
        std_error: fit.map(|f| f.slope.std_error).filter(|e| e.is_finite()),
        points: x.len(),
    }
}

impl SpeedStudy {
    /// File names, relative to the study's folder.
    pub const CSV: &'static str = "speed.csv";
    /// The study as JSON (read back by the scorecard).
    pub const JSON: &'static str = "speed.json";
    /// Folder of the figures.
    pub const FIGURES: &'static str = "speed";

    /// Writes `speed.csv`, `speed.json` and the figures (under `speed/`) into `dir`;
    /// returns the paths written.
    pub fn write(&self, dir: &Path) -> Result<Vec<PathBuf>> {
        let mut written = Vec::new();
        let csv_path = dir.join(Self::CSV);
        crate::io::write_atomic(&csv_path, &self.csv_bytes(&csv_path)?)?;
        written.push(csv_path);
        let json_path = dir.join(Self::JSON);
        let json = serde_json::to_vec_pretty(self).expect("the study serialises");
        crate::io::write_atomic(&json_path, &json)?;
        written.push(json_path);
        for figure in self.figures() {
            written.extend(crate::plot::render(&figure, &dir.join(Self::FIGURES))?);
        }
        Ok(written)
    }

    /// Reads a study written by [`SpeedStudy::write`].
    pub fn read(path: &Path) -> Result<Self> {
        let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
        serde_json::from_slice(&bytes).map_err(|e| Error::bad_file(path, e.to_string()))
    }

    /// One CSV with a `study` column: `reference`, `tolerance`, `size`, `threads`, `floor`,
    /// `warm`.
    fn csv_bytes(&self, path: &Path) -> Result<Vec<u8>> {
        let f = |v: Option<f64>| v.map(|x| format!("{x}")).unwrap_or_default();
        let u = |v: Option<usize>| v.map(|x| x.to_string()).unwrap_or_default();
        let mut w = csv::Writer::from_writer(Vec::new());
        let to_io = |e: csv::Error| Error::io(path, std::io::Error::other(e));
        w.write_record([
            "study",
            "solver",
            "n",
            "threads",
            "tol",
            "wall_s",
            "iterations",
            "residual",
            "tamaas_error",
            "area_error",
            "energy_error",
            "speedup",
            "error",
            "fft_pair_s",
            "pairs_per_iteration",
            "iteration_in_pairs",
            "overhead",
            "change",
            "cold_wall_s",
            "cold_iterations",
            "warm_over_cold",
        ])
        .map_err(to_io)?;
        // Rows of the first four studies leave the floor and warm columns empty.
        let pad = |base: [&str; 13]| {
            let mut v: Vec<String> = base.iter().map(|x| x.to_string()).collect();
            v.resize(21, String::new());
            v
        };
        let n = self.options.n.to_string();
        let pool = self.threads.to_string();
        let r = &self.reference;
        w.write_record(pad([
            "reference",
            r.solver.name(),
            &n,
            &pool,
            &format!("{}", r.tol),
            &format!("{}", r.wall_s),
            &r.iterations.to_string(),
            &format!("{}", r.residual),
            "",
            "0",
            "0",
            "",
            "",
        ]))
        .map_err(to_io)?;
        for t in &self.tolerance {
            w.write_record(pad([
                "tolerance",
                t.solver.name(),
                &n,
                &pool,
                &format!("{}", t.tol),
                &f(t.wall_s),
                &u(t.iterations),
                &f(t.residual),
                &f(t.tamaas),
                &f(t.area_error),
                &f(t.energy_error),
                "",
                t.error.as_deref().unwrap_or(""),
            ]))
            .map_err(to_io)?;
        }
        for s in &self.sizes {
            w.write_record(pad([
                "size",
                s.solver.name(),
                &s.n.to_string(),
                &pool,
                &format!("{}", self.options.size_tol),
                &f(s.wall_s),
                &u(s.iterations),
                &f(s.residual),
                "",
                "",
                "",
                "",
                s.error.as_deref().unwrap_or(""),
            ]))
            .map_err(to_io)?;
        }
        for t in &self.threads_study {
            w.write_record(pad([
                "threads",
                t.solver.name(),
                &n,
                &t.threads.to_string(),
                &format!("{}", self.options.size_tol),
                &f(t.wall_s),
                "",
                "",
                "",
                "",
                "",
                &f(t.speedup),
                t.error.as_deref().unwrap_or(""),
            ]))
            .map_err(to_io)?;
        }
        for r in &self.floor {
            w.write_record([
                "floor".to_string(),
                r.solver.name().to_string(),
                r.n.to_string(),
                pool.clone(),
                format!("{}", self.options.size_tol),
                f(r.wall_s),
                u(r.iterations),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                r.error.clone().unwrap_or_default(),
                format!("{}", r.fft_pair_s),
                f(r.pairs_per_iteration),
                f(r.iteration_in_pairs),
                f(r.overhead),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
            ])
            .map_err(to_io)?;
        }
        for r in &self.warm {
            w.write_record([
                "warm".to_string(),
                r.solver.name().to_string(),
                r.n.to_string(),
                pool.clone(),
                format!("{}", self.options.size_tol),
                f(r.warm_wall_s),
                u(r.warm_iterations),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                r.error.clone().unwrap_or_default(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                r.change.clone(),
                f(r.cold_wall_s),
                u(r.cold_iterations),
                f(r.ratio),
            ])
            .map_err(to_io)?;
        }
        let mut bytes = w
            .into_inner()
            .map_err(|e| Error::io(path, std::io::Error::other(e.to_string())))?;
        bytes.flush().map_err(|e| Error::io(path, e))?;
        Ok(bytes)
    }

    /// The study's figures: energy error against time (the contact-area error, quantised in
    /// steps of `1/N^2`, is in the table), and iterations against grid size.
    pub fn figures(&self) -> Vec<Figure> {
        let mut error_fig = Figure {
            name: "speed_error".into(),
            title: format!(
                "Error against wall time, N = {}, cold solves at tolerances {}",
                self.options.n,
                self.options
                    .tols
                    .iter()
                    .map(|t| format!("{t:e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            x: Axis::log("wall time (s)"),
            y: Axis::log("relative energy error |E - E_ref| / E_ref"),
            y2: None,
            series: Vec::new(),
        };
        for kind in SOLVERS {
            let pts: Vec<(f64, f64)> = self
                .tolerance
                .iter()
                .filter(|r| r.solver == kind)
                .filter_map(|r| Some((r.wall_s?, r.energy_error?)))
                .collect();
            error_fig
                .series
                .push(Series::xy(kind.name().to_string(), Style::LinePoints, pts));
        }
        let mut size_fig = Figure {
            name: "speed_iterations".into(),
            title: format!(
                "Iterations against grid size at tolerance {:e} (lambda_l = N/2, lambda_s = {})",
                self.options.size_tol, self.options.lambda_s
            ),
            x: Axis::log("points per side N"),
            y: Axis::log("iterations"),
            y2: None,
            series: Vec::new(),
        };
        for (kind, fit) in SOLVERS.iter().zip(&self.fits) {
            let rows: Vec<(f64, f64)> = self
                .sizes
                .iter()
                .filter(|r| r.solver == *kind)
                .filter_map(|r| Some((r.n as f64, r.iterations? as f64)))
                .collect();
            size_fig.series.push(Series::xy(
                kind.name().to_string(),
                Style::LinePoints,
                rows.clone(),
            ));
            if let (Some(k), Some(&(n0, _))) = (fit.exponent, rows.first()) {
                let last = rows.last().map_or(n0, |r| r.0);
                // The fitted power law through the geometric centre of the points.
                let (lx, ly): (f64, f64) = rows
                    .iter()
                    .fold((0.0, 0.0), |a, r| (a.0 + r.0.ln(), a.1 + r.1.ln()));
                let (cx, cy) = (lx / rows.len() as f64, ly / rows.len() as f64);
                let at = |n: f64| (cy + k * (n.ln() - cx)).exp();
                size_fig.series.push(Series::xy(
                    format!("{}: fit N^{k:.2}", kind.name()),
                    Style::Dashed,
                    [(n0, at(n0)), (last, at(last))],
                ));
            }
        }
        vec![error_fig, size_fig]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smallest study that exercises every part: N = 32, sizes 32 and 64.
    fn tiny() -> SpeedOptions {
        SpeedOptions {
            tols: vec![1e-4, 1e-8],
            reference_tol: 1e-11,
            threads: vec![1, 2],
            floor_sizes: vec![32],
            repeats: 1,
            ..SpeedOptions::with_n(32)
        }
    }

    #[test]
    fn tiny_study_produces_every_row_and_its_files() {
        let opts = tiny();
        let mut lines = Vec::new();
        let study = run(&opts, &mut |l| lines.push(l.to_string())).unwrap();
        // Sizes 8 and 16 cannot hold lambda_s = 8 < lambda_l = N/2: left out.
        assert_eq!(opts.valid_sizes(), vec![32, 64]);
        assert_eq!(study.tolerance.len(), 2 * opts.tols.len());
        assert_eq!(study.sizes.len(), 2 * 2);
        assert_eq!(study.threads_study.len(), 2 * 2);
        assert!(
            lines.iter().any(|l| l.starts_with("reference")),
            "{lines:?}"
        );
        assert!(study.reference.residual <= opts.reference_tol);
        for row in &study.tolerance {
            assert!(row.error.is_none(), "{row:?}");
            let res = row.residual.unwrap();
            assert!(res <= row.tol, "{row:?}");
            // A looser tolerance cannot be closer to the reference than the reference's
            // own accuracy allows, and the energy error is a relative error.
            assert!(row.energy_error.unwrap() < 1.0, "{row:?}");
            assert!(row.wall_s.unwrap() > 0.0);
        }
        // Tighter tolerances are at least as accurate, solver by solver.
        for kind in SOLVERS {
            let e: Vec<f64> = study
                .tolerance
                .iter()
                .filter(|r| r.solver == kind)
                .map(|r| r.energy_error.unwrap())
                .collect();
            assert!(e[1] <= e[0] + 1e-12, "{kind:?}: {e:?}");
            assert!(
                e[1] < 1e-5,
                "{kind:?}: tol 1e-8 gives energy error {}",
                e[1]
            );
        }
        for fit in &study.fits {
            assert_eq!(fit.points, 2);
            assert!(fit.exponent.unwrap().is_finite());
            assert_eq!(fit.std_error, None, "two points give no error bar");
        }
        assert_eq!(study.threads_study[0].speedup, Some(1.0));
        // Floor: CG uses two FFT pairs an iteration (the preconditioner's and the
        // compliance's) and a third when the contact set changed (u = K^-1 p recomputed);
        // GFMD two (the stress and the mass filter); both plus the set-up and the final
        // residual.
        assert_eq!(study.floor.len(), 2);
        for row in &study.floor {
            assert!(row.error.is_none(), "{row:?}");
            let pairs = row.pairs_per_iteration.unwrap();
            assert!((2.0..=3.2).contains(&pairs), "{row:?}");
            assert!(
                row.overhead.unwrap() > 0.0 && row.fft_pair_s > 0.0,
                "{row:?}"
            );
        }
        // Warm starts: a load change and one shell, each solver, never slower in
        // iterations than a cold solve of the same problem.
        assert_eq!(study.warm.len(), 4);
        for row in &study.warm {
            assert!(row.error.is_none(), "{row:?}");
            assert!(
                row.warm_iterations.unwrap() <= row.cold_iterations.unwrap(),
                "{row:?}"
            );
        }
        assert!(study
            .warm
            .iter()
            .any(|r| r.change.starts_with("one shell at zeta = ")));

        let dir = tempfile::tempdir().unwrap();
        let written = study.write(dir.path()).unwrap();
        assert!(written.contains(&dir.path().join("speed.csv")));
        assert!(dir.path().join("speed/speed_error.png").exists());
        assert!(dir.path().join("speed/speed_iterations.svg").exists());
        let csv = std::fs::read_to_string(dir.path().join("speed.csv")).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert!(lines[0].starts_with("study,solver,n,threads,tol"));
        assert_eq!(lines.len(), 1 + 1 + 4 + 4 + 4 + 2 + 4, "{csv}");
        assert!(lines.iter().any(|l| l.starts_with("warm,cg,32,")), "{csv}");
        assert!(
            lines.iter().any(|l| l.starts_with("size,gfmd,64,")),
            "{csv}"
        );
        // serde_json reads floats back to within an ulp or so, not always bit for bit.
        let back = SpeedStudy::read(&dir.path().join("speed.json")).unwrap();
        assert_eq!(back.options, study.options);
        assert_eq!(back.tolerance.len(), study.tolerance.len());
        assert_eq!(back.fits.len(), study.fits.len());
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        assert!(
            rel(
                back.reference.elastic_energy,
                study.reference.elastic_energy
            ) < 1e-14
        );
    }

    #[test]
    fn bad_options_name_the_option() {
        let e = SpeedOptions::with_n(16).validate().unwrap_err().to_string();
        assert!(e.contains("speed n") && e.contains("16"), "{e}");
        let e = SpeedOptions {
            repeats: 0,
            ..SpeedOptions::with_n(64)
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("speed repeats"), "{e}");
    }

    #[test]
    fn exponent_is_the_log_log_slope() {
        let rows: Vec<SizeRow> = [(64, 100), (128, 200), (256, 400)]
            .iter()
            .map(|&(n, it)| SizeRow {
                solver: SolverKind::Cg,
                n,
                iterations: Some(it),
                wall_s: Some(1.0),
                residual: Some(1e-9),
                error: None,
            })
            .collect();
        let fit = fit_exponent(SolverKind::Cg, &rows);
        assert!((fit.exponent.unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(fit.points, 3);
        assert_eq!(fit_exponent(SolverKind::Gfmd, &rows).exponent, None);
    }
}
