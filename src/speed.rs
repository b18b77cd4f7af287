//! Speed against error: how long each solver takes to reach a given accuracy.
//!
//! One scene (SPEC section 3; H = 0.8, `lambda_l = N/2`, `lambda_s = 8`, `p0 = 0.1`,
//! seed 1), solved by both solvers ([`SolverKind::Cg`], [`SolverKind::Gfmd`]):
//!
//! * **tolerance**: a tightly converged reference (CG, `tol = 1e-12`), then cold solves at
//!   each tolerance; wall time, iterations, the residual reached, and the errors of the
//!   contact area `|a_r - a_ref|` and of the elastic energy `|E - E_ref| / E_ref` against
//!   the reference;
//! * **size**: iterations against the grid size `N` at one tolerance, with the fitted
//!   exponent of `iterations ~ N^k`. The paper's argument for GFMD in reciprocal space is
//!   that mass weighting lowers critical slowing-down from `O(L^2)` (plain damped dynamics)
//!   to `O(L^(1/2))`;
//! * **threads**: the same solve in rayon pools of 1, 2 (and all available) threads.
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

use crate::contact::{ContactProblem, ContactSolution, Model, SolveOptions, Start};
use crate::error::{check_positive, Error, Result};
use crate::plot::{Axis, Figure, Series, Style};
use crate::provenance::Machine;
use crate::solver::SolverKind;
use crate::stats::LineFit;
use crate::surface::{Surface, SurfaceParams};

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
    /// `1e-4 ... 1e-10`, pools of 1, 2 and all available threads.
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
            .validate(&crate::grid::Grid::new(self.n, 1.0)?)
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
                crate::grid::Grid::new(n, 1.0)
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
    /// Residual reached (the project's, see [`crate::contact::Residual`]).
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
}

/// One prepared scene: the surface's heights and the model.
struct Scene {
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
            model,
            heights,
            p0: opts.p0,
        })
    }

    /// A cold solve with a fresh solver; returns the solution and its wall time.
    fn solve(&self, kind: SolverKind, tol: f64) -> Result<(ContactSolution, f64)> {
        let problem = ContactProblem::new(&self.model, &self.heights, self.p0)?;
        let mut solver = kind.build();
        let timer = Instant::now();
        let solution = solver.solve(&problem, Start::Cold, &SolveOptions::with_tol(tol))?;
        Ok((solution, timer.elapsed().as_secs_f64()))
    }

    /// The fastest of `repeats` cold solves.
    fn timed(&self, kind: SolverKind, tol: f64, repeats: usize) -> Result<(ContactSolution, f64)> {
        let (mut best, mut t) = self.solve(kind, tol)?;
        for _ in 1..repeats {
            let (s, dt) = self.solve(kind, tol)?;
            if dt < t {
                (best, t) = (s, dt);
            }
        }
        Ok((best, t))
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

    /// One CSV with a `study` column: `reference`, `tolerance`, `size`, `threads`.
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
        ])
        .map_err(to_io)?;
        let n = self.options.n.to_string();
        let pool = self.threads.to_string();
        let r = &self.reference;
        w.write_record([
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
        ])
        .map_err(to_io)?;
        for t in &self.tolerance {
            w.write_record([
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
            ])
            .map_err(to_io)?;
        }
        for s in &self.sizes {
            w.write_record([
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
            ])
            .map_err(to_io)?;
        }
        for t in &self.threads_study {
            w.write_record([
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

        let dir = tempfile::tempdir().unwrap();
        let written = study.write(dir.path()).unwrap();
        assert!(written.contains(&dir.path().join("speed.csv")));
        assert!(dir.path().join("speed/speed_error.png").exists());
        assert!(dir.path().join("speed/speed_iterations.svg").exists());
        let csv = std::fs::read_to_string(dir.path().join("speed.csv")).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert!(lines[0].starts_with("study,solver,n,threads,tol"));
        assert_eq!(lines.len(), 1 + 1 + 4 + 4 + 4, "{csv}");
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
