//! Surfaces and single solves: `surface` (the command line's realization, bit for bit)
//! and `solve` (one contact problem, as `persson-check solve --heights` solves it), with
//! the result as a [`Solution`] whose `summary()` is the command line's `summary.json`.

use numpy::{PyArray2, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use persson_check::tasks::solve::{Origin, Settled, SolveArgs, SolveSummary, Solved};
use persson_check::tasks::surface::{self as surfaces, SurfaceArgs};
use persson_check::tasks::{parse, Keywords};

use crate::conversions::{array2, field, grid_size, record};
use crate::errors::OrRaise;
use crate::worker::run_blocking;

/// The heights of a generated self-affine surface, as an `n x n` float64 array: the same
/// realization, bit for bit, as `persson-check surface --n N --hurst H --lambda-l L
/// --lambda-s S --seed K [--zeta Z] --out h.npy`. Gaussian amplitudes, unit rms gradient at
/// full resolution, grid spacing 1; `zeta` keeps only the modes with |q| <= zeta q_l
/// (default: all, zeta = lambda_l / lambda_s).
#[pyfunction]
#[pyo3(signature = (n, hurst, lambda_l, lambda_s, seed, zeta=None))]
pub fn surface(
    py: Python<'_>,
    n: i64,
    hurst: f64,
    lambda_l: f64,
    lambda_s: f64,
    seed: &Bound<'_, PyAny>,
    zeta: Option<f64>,
) -> PyResult<Py<PyArray2<f64>>> {
    let n = grid_size(n)?;
    let seed = crate::conversions::seed(seed)?;
    let scene = SurfaceArgs {
        n: Some(n),
        hurst: Some(hurst),
        lambda_l: Some(lambda_l),
        lambda_s: Some(lambda_s),
        seed: Some(seed),
        scene: None,
    }
    .resolve(&Keywords, "given")
    .or_raise()?;
    let h = py
        .detach(|| surfaces::generate(&scene, zeta, &Keywords))
        .or_raise()?;
    array2(py, n, h)
}

/// The result of `solve`: the fields as numpy arrays and the values of `summary.json`.
#[pyclass(frozen, module = "persson_check")]
pub struct Solution {
    /// Contact pressure p(r), n x n (units of E*).
    #[pyo3(get)]
    pressure: Py<PyArray2<f64>>,
    /// Surface displacement u(r) of the elastic body, n x n.
    #[pyo3(get)]
    displacement: Py<PyArray2<f64>>,
    /// Gap g(r) = u(r) - h(r) minus its contact offset, n x n (zero in contact).
    #[pyo3(get)]
    gap: Py<PyArray2<f64>>,
    /// The heights solved against (the input at magnification zeta), n x n.
    #[pyo3(get)]
    heights: Py<PyArray2<f64>>,
    summary: SolveSummary,
}

#[pymethods]
impl Solution {
    /// Points per side.
    #[getter]
    fn n(&self) -> usize {
        self.summary.n
    }

    /// Relative contact area a_r.
    #[getter]
    fn contact_area(&self) -> f64 {
        self.summary.contact_area
    }

    /// Mean pressure p0 (given, or found for the target contact area).
    #[getter]
    fn p0(&self) -> f64 {
        self.summary.p0
    }

    /// Elastic energy per unit area.
    #[getter]
    fn elastic_energy(&self) -> f64 {
        self.summary.elastic_energy
    }

    /// Mean gap.
    #[getter]
    fn mean_gap(&self) -> f64 {
        self.summary.mean_gap
    }

    /// Iterations of the (last) solve.
    #[getter]
    fn iterations(&self) -> usize {
        self.summary.iterations
    }

    /// Solver-independent residual reached.
    #[getter]
    fn residual(&self) -> f64 {
        self.summary.residual
    }

    /// Why the solve stopped: always "converged" (other endings raise SolveError).
    #[getter]
    fn termination(&self) -> String {
        self.summary.termination.to_string()
    }

    /// Solver name, one of `SOLVERS`.
    #[getter]
    fn solver(&self) -> &'static str {
        self.summary.solver
    }

    /// Wall time of the (last) solve, seconds.
    #[getter]
    fn wall_s(&self) -> f64 {
        self.summary.wall_s
    }

    /// Magnification solved at.
    #[getter]
    fn zeta(&self) -> f64 {
        self.summary.zeta
    }

    /// Rms gradient of the heights at zeta.
    #[getter]
    fn rms_gradient(&self) -> f64 {
        self.summary.rms_gradient
    }

    /// p0 / (E* rms_gradient).
    #[getter]
    fn reduced_pressure(&self) -> f64 {
        self.summary.reduced_pressure
    }

    /// Effective modulus (1).
    #[getter]
    fn e_star(&self) -> f64 {
        self.summary.e_star
    }

    /// Tolerance asked for.
    #[getter]
    fn tol(&self) -> f64 {
        self.summary.tol
    }

    /// Solves spent (more than one when a contact area was the target).
    #[getter]
    fn load_solves(&self) -> usize {
        self.summary.load_solves
    }

    /// Where the heights came from ("array").
    #[getter]
    fn source(&self) -> &str {
        &self.summary.source
    }

    /// The residual's parts, as in summary.json's residual_components.
    #[getter]
    fn residual_components<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        record(py, &self.summary.residual_components)
    }

    /// tamaas' error measure of this solution.
    #[getter]
    fn tamaas_error(&self) -> f64 {
        self.summary.tamaas_error
    }

    /// The summary values as a dict with summary.json's keys and values (no arrays).
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        Ok(record(py, &self.summary)?.cast_into::<PyDict>()?)
    }

    fn __repr__(&self) -> String {
        let s = &self.summary;
        format!(
            "Solution(n={}, p0={:.6e}, contact_area={:.6}, elastic_energy={:.6e}, \
             iterations={}, residual={:.2e}, solver={:?}, termination={:?})",
            s.n,
            s.p0,
            s.contact_area,
            s.elastic_energy,
            s.iterations,
            s.residual,
            s.solver,
            s.termination.to_string()
        )
    }
}

/// Solves hard-wall contact of a rigid surface of `heights` (a square, C-contiguous
/// float64 array, grid spacing 1) against an elastic half-space (E* = 1), at mean pressure
/// `p0` or at the load that gives relative contact area `contact_area`, as
/// `persson-check solve --heights h.npy` does. Returns a `Solution`.
///
/// `solver` is one of `SOLVERS`. `lambda_l` is the wavelength that defines
/// zeta = |q| / q_l (default: the box size);
/// `zeta` solves at that magnification (default: full resolution). `threads` sets the
/// worker threads (default: all cores). `progress(iteration, residual)` is called every
/// 16 iterations. The GIL is released during the solve; Ctrl-C stops it and raises
/// KeyboardInterrupt. Bad input raises ValueError; a solve that does not converge raises
/// SolveError.
#[pyfunction]
#[pyo3(signature = (heights, p0=None, contact_area=None, solver=None, tol=None, lambda_l=None, threads=None, zeta=None, max_iter=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn solve(
    py: Python<'_>,
    heights: PyReadonlyArrayDyn<'_, f64>,
    p0: Option<f64>,
    contact_area: Option<f64>,
    solver: Option<&str>,
    tol: Option<f64>,
    lambda_l: Option<f64>,
    threads: Option<i64>,
    zeta: Option<f64>,
    max_iter: Option<i64>,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<Solution> {
    let settled = settle(p0, contact_area, zeta, lambda_l, solver, tol, max_iter)?;
    let (n, values) = field(&heights)?;
    let (solved, gap) = run_blocking(py, threads, progress.as_ref(), |hook| {
        let surface = surfaces::from_heights(n, values, lambda_l)?;
        let solved = settled.run(&surface, Origin::Array, &Keywords, |_, p| hook.iteration(p))?;
        let gap = solved.solution.gap(&solved.heights);
        Ok((solved, gap))
    })?;
    let Solved {
        heights,
        solution,
        summary,
    } = solved;
    Ok(Solution {
        pressure: array2(py, n, solution.pressure)?,
        displacement: array2(py, n, solution.displacement)?,
        gap: array2(py, n, gap)?,
        heights: array2(py, n, heights)?,
        summary,
    })
}

/// The solve request of the keywords `solve` and `sweep` share, checked once and settled
/// on the defaults (no scene file: the keywords are all there is).
#[allow(clippy::too_many_arguments)]
pub(crate) fn settle(
    p0: Option<f64>,
    contact_area: Option<f64>,
    zeta: Option<f64>,
    lambda_l: Option<f64>,
    solver: Option<&str>,
    tol: Option<f64>,
    max_iter: Option<i64>,
) -> PyResult<Settled> {
    let max_iter = max_iter
        .map(|m| parse::integer("max_iter", m, 0, u64::MAX, &Keywords).map(|m| m as usize))
        .transpose()
        .or_raise()?;
    SolveArgs {
        p0,
        contact_area,
        zeta,
        lambda_l,
        solver: solver.map(parse::solver).transpose().or_raise()?,
        tol,
        max_iter,
    }
    .check(&Keywords, &Keywords)
    .and_then(|checked| checked.settle(None, &Keywords))
    .or_raise()
}
