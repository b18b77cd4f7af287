//! Speed against error: how long each solver takes to reach a given accuracy.
//!
//! One scene ([`crate::conventions`], section 3; H = 0.8, `lambda_l = N/2`, `lambda_s = 8`,
//! `p0 = 0.1`, seed 1), solved by every solver ([`SolverKind::ALL`]), the solvers taking
//! turns row by row (each tolerance, grid or pool size is solved by all of them before
//! the next), so that a change in the machine's load falls on all of them alike:
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
//! [`run`] computes the study; [`SpeedStudy::write`] writes one CSV per study, `speed.json` and
//! the figures; the scorecard ([`crate::report`]) formats it.

mod options;
mod rows;
mod scene;
mod study;
#[cfg(test)]
mod tests;

pub use options::SpeedOptions;
pub use rows::{
    FloorRow, Reference, SizeFit, SizeRow, SpeedStudy, ThreadRow, ToleranceRow, WarmRow,
};
use scene::Scene;

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::engine::contact::{ContactProblem, ContactSolution, Model};
use crate::engine::solver::SolverKind;
use crate::engine::solver::{SolveOptions, Start};
use crate::engine::surface::{Surface, SurfaceModel};
use crate::engine::sweep::shell_steps;
use crate::error::{check_positive, Error, Result};
use crate::plot::{Axis, Figure, Series, Style};
use crate::provenance::Machine;
use crate::stats::{round_sig, LineFit};

/// The solvers compared, in table order: every solver.
pub const SOLVERS: [SolverKind; SolverKind::ALL.len()] = SolverKind::ALL;

/// Runs the study; `progress` receives a line per step.
pub fn run(opts: &SpeedOptions, progress: &mut dyn FnMut(&str)) -> Result<SpeedStudy> {
    opts.validate()?;
    let started_at = crate::provenance::now_utc();
    let timer = Instant::now();
    let scene = Scene::new(opts, opts.n)?;
    let reference = reference(&scene, opts, progress)?;
    let tolerance = tolerance_study(&scene, &reference, opts, progress);
    let sizes = size_study(opts, progress)?;
    let fits = SOLVERS
        .iter()
        .map(|&kind| fit_exponent(kind, &sizes))
        .collect();
    let threads_study = thread_study(&scene, opts, progress)?;
    let (floor, warm) = floor_and_warm_study(opts, progress)?;
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

/// The reference: a tightly converged CG solve of the scene.
fn reference(
    scene: &Scene,
    opts: &SpeedOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<Reference> {
    progress(&format!(
        "reference: cg, N = {}, tol = {:e}",
        opts.n, opts.reference_tol
    ));
    let (solution, wall_s) = scene.solve(SolverKind::Cg, opts.reference_tol)?;
    Ok(Reference {
        solver: SolverKind::Cg,
        tol: opts.reference_tol,
        residual: solution.stats.residual.value(),
        iterations: solution.stats.iterations,
        wall_s,
        contact_area: solution.contact_area(),
        elastic_energy: solution.elastic_energy(),
    })
}

/// Cold solves at each tolerance, solver by solver.
fn tolerance_study(
    scene: &Scene,
    reference: &Reference,
    opts: &SpeedOptions,
    progress: &mut dyn FnMut(&str),
) -> Vec<ToleranceRow> {
    let mut rows = Vec::new();
    for &tol in &opts.tols {
        for kind in SOLVERS {
            progress(&format!(
                "tolerance: {}, N = {}, tol = {tol:e}",
                kind.name(),
                opts.n
            ));
            let solved = scene.timed(kind, tol, opts.repeats);
            rows.push(ToleranceRow::of(kind, tol, solved, reference));
        }
    }
    rows.sort_by_key(|r| r.solver.index());
    rows
}

/// Cold solves on each grid of the size study, solver by solver.
fn size_study(opts: &SpeedOptions, progress: &mut dyn FnMut(&str)) -> Result<Vec<SizeRow>> {
    let scenes: Vec<(usize, Scene)> = opts
        .valid_sizes()
        .iter()
        .map(|&n| Ok((n, Scene::new(opts, n)?)))
        .collect::<Result<_>>()?;
    let mut rows = Vec::new();
    for (n, scene) in &scenes {
        for kind in SOLVERS {
            progress(&format!(
                "size: {}, N = {n}, tol = {:e}",
                kind.name(),
                opts.size_tol
            ));
            let solved = scene.timed(kind, opts.size_tol, opts.repeats);
            rows.push(SizeRow::of(kind, *n, solved));
        }
    }
    rows.sort_by_key(|r| r.solver.index());
    Ok(rows)
}

/// The same cold solve in pools of each size, solver by solver.
fn thread_study(
    scene: &Scene,
    opts: &SpeedOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<ThreadRow>> {
    let mut rows = Vec::new();
    let mut single = [None; SOLVERS.len()];
    for &k in &opts.threads {
        for kind in SOLVERS {
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
            let wall_s = pool
                .install(|| scene.timed(kind, opts.size_tol, opts.repeats))
                .map(|(_, t)| t);
            if let (1, Ok(t)) = (k, &wall_s) {
                single[kind.index()] = Some(*t);
            }
            rows.push(ThreadRow::of(kind, k, wall_s, single[kind.index()]));
        }
    }
    rows.sort_by_key(|r| r.solver.index());
    Ok(rows)
}

/// On each grid of `floor_sizes`: the FFT pair, then each solver's cold solve counted in
/// pairs and its warm re-solves.
fn floor_and_warm_study(
    opts: &SpeedOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<(Vec<FloorRow>, Vec<WarmRow>)> {
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
    Ok((floor, warm))
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

/// The tiny study ([`SpeedOptions::tiny`]), run once per test process: the fixture of the
/// tests of what reads a study (the scorecard), which run nothing themselves.
#[cfg(test)]
pub(crate) fn tiny_study() -> &'static SpeedStudy {
    static STUDY: std::sync::OnceLock<SpeedStudy> = std::sync::OnceLock::new();
    STUDY.get_or_init(|| run(&SpeedOptions::tiny(), &mut |_| {}).expect("the tiny study runs"))
}
