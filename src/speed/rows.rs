//! The study's records: one row type per study, as written to its CSV and to
//! `speed.json`.

use super::*;

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

/// A timed solve: the solution and its wall time (the fastest of the repeats).
type Timed = (ContactSolution, f64);

impl ToleranceRow {
    /// The row of a cold solve at `tol`, its errors measured against `reference`.
    pub(super) fn of(
        solver: SolverKind,
        tol: f64,
        solved: Result<Timed>,
        reference: &Reference,
    ) -> Self {
        let ok = solved.as_ref().ok();
        let area_error = |s: &ContactSolution| (s.contact_area() - reference.contact_area).abs();
        let energy_error = |s: &ContactSolution| {
            ((s.elastic_energy() - reference.elastic_energy) / reference.elastic_energy).abs()
        };
        Self {
            solver,
            tol,
            wall_s: ok.map(|(_, t)| *t),
            iterations: ok.map(|(s, _)| s.stats.iterations),
            residual: ok.map(|(s, _)| s.stats.residual.value()),
            tamaas: ok.map(|(s, _)| s.stats.residual.tamaas),
            area_error: ok.map(|(s, _)| area_error(s)),
            energy_error: ok.map(|(s, _)| energy_error(s)),
            error: solved.err().map(|e| e.to_string()),
        }
    }
}

impl SizeRow {
    /// The row of a cold solve on an `n x n` grid.
    pub(super) fn of(solver: SolverKind, n: usize, solved: Result<Timed>) -> Self {
        let ok = solved.as_ref().ok();
        Self {
            solver,
            n,
            iterations: ok.map(|(s, _)| s.stats.iterations),
            wall_s: ok.map(|(_, t)| *t),
            residual: ok.map(|(s, _)| s.stats.residual.value()),
            error: solved.err().map(|e| e.to_string()),
        }
    }
}

impl ThreadRow {
    /// The row of a solve taking `wall_s` in a pool of `threads`, against `single`, the
    /// time in one thread if known.
    pub(super) fn of(
        solver: SolverKind,
        threads: usize,
        wall_s: Result<f64>,
        single: Option<f64>,
    ) -> Self {
        let ok = wall_s.as_ref().ok().copied();
        Self {
            solver,
            threads,
            wall_s: ok,
            speedup: ok.and_then(|t| single.map(|t1| t1 / t)),
            error: wall_s.err().map(|e| e.to_string()),
        }
    }
}

impl FloorRow {
    /// The row of a cold solve counted in FFT pairs: its iterations, wall time and the
    /// pairs it used.
    pub(super) fn of(
        solver: SolverKind,
        n: usize,
        fft_pair_s: f64,
        counted: Result<(usize, f64, f64)>,
    ) -> Self {
        let ok = counted.as_ref().ok().copied();
        Self {
            solver,
            n,
            fft_pair_s,
            iterations: ok.map(|(it, _, _)| it),
            wall_s: ok.map(|(_, t, _)| t),
            pairs_per_iteration: ok.map(|(it, _, pairs)| pairs / it.max(1) as f64),
            iteration_in_pairs: ok.map(|(it, t, _)| t / (it.max(1) as f64 * fft_pair_s)),
            overhead: ok.map(|(_, t, pairs)| t / (pairs * fft_pair_s)),
            error: counted.err().map(|e| e.to_string()),
        }
    }
}

impl WarmRow {
    /// The row of a cold solve and a warm re-solve after `change`.
    pub(super) fn of(
        solver: SolverKind,
        n: usize,
        change: String,
        solved: Result<(Timed, Timed)>,
    ) -> Self {
        let ok = solved.as_ref().ok();
        Self {
            solver,
            n,
            change,
            cold_iterations: ok.map(|((cold, _), _)| cold.stats.iterations),
            cold_wall_s: ok.map(|((_, tc), _)| *tc),
            warm_iterations: ok.map(|(_, (warm, _))| warm.stats.iterations),
            warm_wall_s: ok.map(|(_, (_, tw))| *tw),
            ratio: ok.map(|((_, tc), (_, tw))| tw / tc),
            error: solved.err().map(|e| e.to_string()),
        }
    }
}
