//! `persson_check._native`: the Rust side of the Python package.
//!
//! Every function here calls the `persson_check` library directly (never the command line)
//! and follows the command line's order of checks, so that bad input is refused with the
//! same message, a flag such as `--p0` being named by its keyword `p0`.
//!
//! Long computations run on a worker thread with the GIL released, while the calling
//! thread waits on it and checks for signals every few milliseconds; on Ctrl-C (or an
//! exception from a progress callback) it raises a flag that the solver's per-iteration
//! monitor sees, and the worker stops at its next iteration (see [`Hooked`]).

use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyStopIteration, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use persson_check::engine::contact::{ContactProblem, ContactSolution, Model};
use persson_check::engine::fft::Fft2;
use persson_check::engine::grid::{Grid, MAX_N, MIN_N};
use persson_check::engine::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use persson_check::engine::scene::{check_zeta, SurfaceScene};
use persson_check::engine::solver::{Progress, SolveOptions, Solver, SolverKind, Start};
use persson_check::engine::surface::{Amplitudes, Surface};
use persson_check::engine::sweep::{shell_steps, Sweep as EngineSweep};
use persson_check::error::{check_open, check_positive, Error};
use persson_check::io::npy;
use persson_check::persson::{Broadening, Correction, Prediction};
use persson_check::report::{ReportOptions, SpeedChoice};
use persson_check::speed::SpeedOptions;
use persson_check::validation::plan::{definition_hashes, Plan};
use persson_check::validation::source::{builtin_sources, select, sources_in, Source};
use persson_check::validation::{Mode, Registry, RunOptions, Scale};

create_exception!(
    _native,
    SolveError,
    PyRuntimeError,
    "A solve that stopped before its tolerance (iteration budget, stall at the rounding \
     floor, a non-finite value) or a load search that found no load for the target area."
);

/// The library's error as the Python exception a caller expects.
fn to_py(e: Error) -> PyErr {
    let text = e.to_string();
    match e {
        Error::InvalidInput { .. } | Error::BadFile { .. } => PyValueError::new_err(text),
        Error::Io { .. } => PyOSError::new_err(text),
        Error::NotConverged { .. }
        | Error::NonFinite { .. }
        | Error::LostContact { .. }
        | Error::LoadSearch(_) => SolveError::new_err(text),
    }
}

/// The payload a cancelled solve unwinds with (never printed: `resume_unwind` skips the
/// panic hook).
struct Cancelled;

/// How often the waiting thread looks for signals.
const POLL: Duration = Duration::from_millis(20);

/// What a worker tells the thread that waits for it.
enum Event {
    /// Every 16th iteration of a solve (only when a callback wants it).
    Progress(Progress),
    /// The worker of [`run_blocking`] has finished.
    Done,
    /// A step of a sweep.
    Step(Box<Result<StepData, Failure>>),
}

/// What a worker shares with the thread that waits for it.
#[derive(Clone)]
struct Hook {
    cancel: Arc<AtomicBool>,
    progress: Option<Sender<Event>>,
}

impl Hook {
    /// `solver`, stopped by the cancel flag and reporting its progress.
    fn wrap(&self, solver: Box<dyn Solver + Send>) -> Box<dyn Solver + Send> {
        Box::new(Hooked {
            inner: solver,
            hook: self.clone(),
        })
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// A solver whose monitor stops the solve when the cancel flag is raised (by unwinding
/// with [`Cancelled`] out of the solver's iteration loop, the one point where every
/// solver hands control back) and forwards every 16th iteration's progress.
struct Hooked {
    inner: Box<dyn Solver + Send>,
    hook: Hook,
}

impl Solver for Hooked {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn solve_monitored(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress),
    ) -> persson_check::Result<ContactSolution> {
        if self.hook.cancelled() {
            resume_unwind(Box::new(Cancelled));
        }
        let hook = &self.hook;
        self.inner.solve_monitored(problem, start, opts, &mut |p| {
            if hook.cancelled() {
                resume_unwind(Box::new(Cancelled));
            }
            if p.iteration % 16 == 0 {
                if let Some(tx) = &hook.progress {
                    let _ = tx.send(Event::Progress(p));
                }
            }
            monitor(p);
        })
    }
}

/// Why a worker produced no value.
enum Failure {
    Lib(Error),
    Cancelled,
    Panic(String),
}

fn from_panic(payload: Box<dyn std::any::Any + Send>) -> Failure {
    if payload.is::<Cancelled>() {
        return Failure::Cancelled;
    }
    let text = payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "a panic without a message".to_string());
    Failure::Panic(text)
}

/// A rayon pool of `threads` workers, or `None` for the global pool (all cores).
fn pool(threads: Option<i64>) -> PyResult<Option<rayon::ThreadPool>> {
    match threads {
        None => Ok(None),
        Some(t) if (1..=1024).contains(&t) => rayon::ThreadPoolBuilder::new()
            .num_threads(t as usize)
            .build()
            .map(Some)
            .map_err(|e| PyRuntimeError::new_err(format!("threads: {e}"))),
        Some(t) => Err(to_py(Error::invalid(
            "threads",
            t,
            "an integer in [1, 1024]",
        ))),
    }
}

/// Calls `progress(iteration, residual)`.
fn notify(progress: Option<&Bound<'_, PyAny>>, p: Progress) -> PyResult<()> {
    match progress {
        Some(cb) => cb.call1((p.iteration, p.residual)).map(|_| ()),
        None => Ok(()),
    }
}

/// Runs `work` on a worker thread (inside a pool of `threads` if given) with the GIL
/// released; meanwhile checks for signals and forwards progress to `progress`. Ctrl-C or
/// an exception from `progress` raises the cancel flag and, once the worker has stopped,
/// is raised here.
fn run_blocking<T: Send>(
    py: Python<'_>,
    threads: Option<i64>,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(&Hook) -> persson_check::Result<T> + Send,
) -> PyResult<T> {
    let pool = pool(threads)?;
    let (tx, rx) = mpsc::channel();
    let hook = Hook {
        cancel: Arc::new(AtomicBool::new(false)),
        progress: progress.map(|_| tx.clone()),
    };
    // A Receiver is not Sync: it enters the GIL-free waits through a Mutex.
    let rx = Mutex::new(rx);
    let cancel = hook.cancel.clone();
    std::thread::scope(|scope| {
        let worker = scope.spawn(move || {
            let run = move || work(&hook);
            let result = catch_unwind(AssertUnwindSafe(|| match &pool {
                Some(pool) => pool.install(run),
                None => run(),
            }));
            let _ = tx.send(Event::Done);
            result
        });
        let mut raised: Option<PyErr> = None;
        loop {
            let next = py.detach(|| {
                rx.lock()
                    .expect("only this thread receives")
                    .recv_timeout(POLL)
            });
            match next {
                Ok(Event::Progress(p)) => {
                    if raised.is_none() {
                        if let Err(e) = notify(progress, p) {
                            cancel.store(true, Ordering::Relaxed);
                            raised = Some(e);
                        }
                    }
                }
                Ok(Event::Done) | Err(RecvTimeoutError::Disconnected) => break,
                Ok(Event::Step(_)) => {}
                Err(RecvTimeoutError::Timeout) => {}
            }
            if raised.is_none() {
                if let Err(e) = py.check_signals() {
                    cancel.store(true, Ordering::Relaxed);
                    raised = Some(e);
                }
            }
        }
        let result = py.detach(|| worker.join()).unwrap_or_else(Err);
        let result = match result {
            Ok(r) => r.map_err(Failure::Lib),
            Err(payload) => Err(from_panic(payload)),
        };
        if let Some(e) = raised {
            return Err(e);
        }
        match result {
            Ok(v) => Ok(v),
            Err(Failure::Lib(e)) => Err(to_py(e)),
            Err(Failure::Cancelled) => Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(())),
            Err(Failure::Panic(text)) => Err(PyRuntimeError::new_err(format!(
                "internal error (please report): {text}"
            ))),
        }
    })
}

/// A square float64 field handed over from numpy, checked as the `.npy` reader checks a
/// file; borrowed, not copied.
fn field<'a>(heights: &'a PyReadonlyArrayDyn<'_, f64>) -> PyResult<(usize, &'a [f64])> {
    let shape: Vec<u64> = heights.shape().iter().map(|&d| d as u64).collect();
    let n = npy::check_shape(&shape, MIN_N..=MAX_N).map_err(PyValueError::new_err)?;
    let values = heights
        .as_slice()
        .map_err(|_| PyValueError::new_err("heights must be a C-contiguous array"))?;
    npy::check_finite(values, n).map_err(PyValueError::new_err)?;
    Ok((n, values))
}

/// An `n x n` numpy array that takes over `values` (no copy).
fn array2<'py>(py: Python<'py>, n: usize, values: Vec<f64>) -> PyResult<Py<PyArray2<f64>>> {
    Ok(PyArray1::from_vec(py, values).reshape([n, n])?.unbind())
}

fn solver_kind(name: &str) -> PyResult<SolverKind> {
    match name {
        "cg" => Ok(SolverKind::Cg),
        "gfmd" => Ok(SolverKind::Gfmd),
        other => Err(to_py(Error::invalid(
            "solver",
            format!("{other:?}"),
            "\"cg\" or \"gfmd\"",
        ))),
    }
}

/// A non-negative integer argument (the command line takes these as unsigned).
fn unsigned(field: &str, value: i64, max: u64) -> PyResult<u64> {
    if value >= 0 && (value as u64) <= max {
        Ok(value as u64)
    } else {
        Err(to_py(Error::invalid(
            field,
            value,
            format!("an integer in [0, {max}]"),
        )))
    }
}

/// The heights of a generated self-affine surface, as an `n x n` float64 array: the same
/// realization, bit for bit, as `persson-check surface --n N --hurst H --lambda-l L
/// --lambda-s S --seed K [--zeta Z] --out h.npy`. Gaussian amplitudes, unit rms gradient at
/// full resolution, grid spacing 1; `zeta` keeps only the modes with |q| <= zeta q_l
/// (default: all, zeta = lambda_l / lambda_s).
#[pyfunction]
#[pyo3(signature = (n, hurst, lambda_l, lambda_s, seed, zeta=None))]
fn surface(
    py: Python<'_>,
    n: i64,
    hurst: f64,
    lambda_l: f64,
    lambda_s: f64,
    seed: &Bound<'_, PyAny>,
    zeta: Option<f64>,
) -> PyResult<Py<PyArray2<f64>>> {
    let n = usize::try_from(n).map_err(|_| {
        to_py(Error::invalid(
            "n",
            n,
            format!("an integer in [{MIN_N}, {MAX_N}]"),
        ))
    })?;
    let seed = match seed.extract::<u64>() {
        Ok(s) => s,
        Err(e) if seed.is_instance_of::<pyo3::types::PyInt>() => {
            let _ = e;
            return Err(to_py(Error::invalid(
                "seed",
                seed,
                format!("an integer in [0, {}]", u64::MAX),
            )));
        }
        Err(e) => return Err(e),
    };
    let scene = SurfaceScene {
        n,
        hurst,
        lambda_l,
        lambda_s,
        lambda_r: None,
        amplitudes: Amplitudes::Gaussian,
        rms_gradient: 1.0,
        seed: Some(seed),
    };
    scene.validate().map_err(to_py)?;
    let zeta = zeta.unwrap_or(scene.zeta_max());
    check_zeta(zeta, scene.zeta_max()).map_err(to_py)?;
    let h = py
        .detach(|| {
            let surface = Surface::generate(&scene.params(seed))?;
            let fft = Fft2::new(surface.grid());
            Ok(surface.heights_at(zeta, &fft))
        })
        .map_err(to_py)?;
    array2(py, n, h)
}

/// The result of [`solve`]: the fields as numpy arrays and the summary values of
/// `summary.json`.
#[pyclass(frozen, get_all, module = "persson_check")]
struct Solution {
    /// Contact pressure p(r), n x n (units of E*).
    pressure: Py<PyArray2<f64>>,
    /// Surface displacement u(r) of the elastic body, n x n.
    displacement: Py<PyArray2<f64>>,
    /// Gap g(r) = u(r) - h(r) minus its contact offset, n x n (zero in contact).
    gap: Py<PyArray2<f64>>,
    /// The heights solved against (the input at magnification zeta), n x n.
    heights: Py<PyArray2<f64>>,
    /// Points per side.
    n: usize,
    /// Relative contact area a_r.
    contact_area: f64,
    /// Mean pressure p0 (given, or found for the target contact area).
    p0: f64,
    /// Elastic energy per unit area.
    elastic_energy: f64,
    /// Mean gap.
    mean_gap: f64,
    /// Iterations of the (last) solve.
    iterations: usize,
    /// Solver-independent residual reached.
    residual: f64,
    /// Why the solve stopped: always "converged" (other endings raise SolveError).
    termination: String,
    /// Solver name, "cg" or "gfmd".
    solver: String,
    /// Wall time of the (last) solve, seconds.
    wall_s: f64,
    /// Magnification solved at.
    zeta: f64,
    /// Rms gradient of the heights at zeta.
    rms_gradient: f64,
    /// p0 / (E* rms_gradient).
    reduced_pressure: f64,
    /// Effective modulus (1).
    e_star: f64,
    /// Tolerance asked for.
    tol: f64,
    /// Solves spent (more than one when a contact area was the target).
    load_solves: usize,
    /// The residual's parts, as in summary.json's residual_components.
    residual_components: Py<PyDict>,
    /// tamaas' error measure of this solution.
    tamaas_error: f64,
}

#[pymethods]
impl Solution {
    /// The summary values as a dict with summary.json's keys (no arrays).
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("n", self.n)?;
        d.set_item("p0", self.p0)?;
        d.set_item("contact_area", self.contact_area)?;
        d.set_item("elastic_energy", self.elastic_energy)?;
        d.set_item("mean_gap", self.mean_gap)?;
        d.set_item("residual", self.residual)?;
        d.set_item("iterations", self.iterations)?;
        d.set_item("wall_s", self.wall_s)?;
        d.set_item("solver", &self.solver)?;
        d.set_item("termination", &self.termination)?;
        d.set_item("zeta", self.zeta)?;
        d.set_item("rms_gradient", self.rms_gradient)?;
        d.set_item("reduced_pressure", self.reduced_pressure)?;
        d.set_item("e_star", self.e_star)?;
        d.set_item("tol", self.tol)?;
        d.set_item("load_solves", self.load_solves)?;
        d.set_item(
            "residual_components",
            self.residual_components.bind(py).copy()?,
        )?;
        d.set_item("tamaas_error", self.tamaas_error)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Solution(n={}, p0={:.6e}, contact_area={:.6}, elastic_energy={:.6e}, \
             iterations={}, residual={:.2e}, solver={:?}, termination={:?})",
            self.n,
            self.p0,
            self.contact_area,
            self.elastic_energy,
            self.iterations,
            self.residual,
            self.solver,
            self.termination
        )
    }
}

/// What the worker of [`solve`] hands back.
struct Solved {
    heights: Vec<f64>,
    solution: ContactSolution,
    gap: Vec<f64>,
    mean_gap: f64,
    zeta: f64,
    g_bar: f64,
    solves: usize,
}

/// The load of a solve.
#[derive(Clone, Copy)]
enum Load {
    Pressure(f64),
    Area(f64),
}

/// The load from `p0` / `contact_area`, checked as the command line checks its flags.
fn load(p0: Option<f64>, contact_area: Option<f64>) -> PyResult<Load> {
    match (p0, contact_area) {
        (Some(_), Some(_)) => Err(to_py(Error::invalid(
            "load",
            "both p0 and contact_area",
            "one of p0 or contact_area",
        ))),
        (None, None) => Err(to_py(Error::invalid(
            "load",
            "missing",
            "p0=P or contact_area=A",
        ))),
        (Some(p0), None) => {
            check_positive("p0", p0).map_err(to_py)?;
            Ok(Load::Pressure(p0))
        }
        (None, Some(a)) => {
            check_open("contact_area", a, 0.0, 1.0).map_err(to_py)?;
            Ok(Load::Area(a))
        }
    }
}

/// The first magnification check of the command line (`--zeta` before the surface is
/// known).
fn check_zeta_range(zeta: Option<f64>) -> PyResult<()> {
    match zeta {
        Some(z) if !(z.is_finite() && z >= 1.0) => Err(to_py(Error::invalid(
            "zeta",
            z,
            "in [1, zeta_max = lambda_l / lambda_s]",
        ))),
        _ => Ok(()),
    }
}

/// The surface of a heights array (`lambda_l` sets zeta = |q| / q_l; default: the box).
fn surface_of(n: usize, values: &[f64], lambda_l: Option<f64>) -> persson_check::Result<Surface> {
    let grid = Grid::new(n, 1.0)?;
    Surface::from_heights(grid, values, lambda_l)
}

#[allow(clippy::too_many_arguments)]
fn solve_heights(
    hook: &Hook,
    n: usize,
    values: &[f64],
    load: Load,
    kind: SolverKind,
    opts: SolveOptions,
    lambda_l: Option<f64>,
    zeta: Option<f64>,
) -> persson_check::Result<Solved> {
    let surface = surface_of(n, values, lambda_l)?;
    let zeta_max = surface.zeta_max().max(1.0);
    let zeta = zeta.unwrap_or(zeta_max);
    check_zeta(zeta, zeta_max)?;
    let e_star = 1.0;
    let model = Model::new(surface.grid().clone(), e_star)?;
    let heights = surface.heights_at(zeta, &model.fft);
    let g_bar = surface.rms_gradient(zeta);
    let mut solver = hook.wrap(kind.build());
    let (solution, solves) = match load {
        Load::Pressure(p0) => {
            let problem = ContactProblem::new(&model, &heights, p0)?;
            (solver.solve(&problem, Start::Cold, &opts)?, 1)
        }
        Load::Area(a) => {
            if g_bar <= 0.0 {
                return Err(Error::invalid(
                    "contact_area",
                    a,
                    "reachable: the surface is flat (zero rms gradient), so contact is \
                     complete at any load; give p0 instead",
                ));
            }
            let target = AreaTarget {
                contact_area: a,
                p0_guess: persson_load_guess(a, g_bar.max(1e-300), e_star),
            };
            let found = solve_for_area(
                solver.as_mut(),
                &model,
                &heights,
                target,
                Start::Cold,
                &opts,
                &AreaSearch::default(),
            )?;
            (found.solution, found.solves)
        }
    };
    let gap = solution.gap(&heights);
    let mean_gap = solution.mean_gap(&heights);
    Ok(Solved {
        heights,
        solution,
        gap,
        mean_gap,
        zeta,
        g_bar,
        solves,
    })
}

/// Solves hard-wall contact of a rigid surface of `heights` (a square, C-contiguous
/// float64 array, grid spacing 1) against an elastic half-space (E* = 1), at mean pressure
/// `p0` or at the load that gives relative contact area `contact_area`, as
/// `persson-check solve --heights h.npy` does. Returns a `Solution`.
///
/// `lambda_l` is the wavelength that defines zeta = |q| / q_l (default: the box size);
/// `zeta` solves at that magnification (default: full resolution). `threads` sets the
/// worker threads (default: all cores). `progress(iteration, residual)` is called every
/// 16 iterations. The GIL is released during the solve; Ctrl-C stops it and raises
/// KeyboardInterrupt. Bad input raises ValueError; a solve that does not converge raises
/// SolveError.
#[pyfunction]
#[pyo3(signature = (heights, p0=None, contact_area=None, solver="cg", tol=1e-8, lambda_l=None, threads=None, zeta=None, max_iter=100_000, progress=None))]
#[allow(clippy::too_many_arguments)]
fn solve(
    py: Python<'_>,
    heights: PyReadonlyArrayDyn<'_, f64>,
    p0: Option<f64>,
    contact_area: Option<f64>,
    solver: &str,
    tol: f64,
    lambda_l: Option<f64>,
    threads: Option<i64>,
    zeta: Option<f64>,
    max_iter: i64,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<Solution> {
    // The command line's order: the load, the magnification, lambda_l, the solver
    // options; then the array.
    let load = load(p0, contact_area)?;
    check_zeta_range(zeta)?;
    if let Some(l) = lambda_l {
        check_positive("lambda_l", l).map_err(to_py)?;
    }
    let kind = solver_kind(solver)?;
    let max_iter = unsigned("max_iter", max_iter, u64::MAX)? as usize;
    let opts = SolveOptions { tol, max_iter };
    opts.validate().map_err(to_py)?;
    let (n, values) = field(&heights)?;
    let solved = run_blocking(py, threads, progress.as_ref(), |hook| {
        solve_heights(hook, n, values, load, kind, opts, lambda_l, zeta)
    })?;
    let s = solved.solution;
    let r = s.stats.residual;
    let parts = PyDict::new(py);
    for (k, v) in [
        ("penetration", r.penetration),
        ("complementarity", r.complementarity),
        ("tension", r.tension),
        ("equilibrium", r.equilibrium),
        ("load", r.load),
        ("tamaas", r.tamaas),
    ] {
        parts.set_item(k, v)?;
    }
    Ok(Solution {
        n,
        contact_area: s.contact_area(),
        p0: s.p0,
        elastic_energy: s.elastic_energy(),
        mean_gap: solved.mean_gap,
        iterations: s.stats.iterations,
        residual: r.value(),
        termination: "converged".to_string(),
        solver: s.stats.solver.to_string(),
        wall_s: s.stats.wall_s,
        zeta: solved.zeta,
        rms_gradient: solved.g_bar,
        reduced_pressure: s.p0 / solved.g_bar,
        e_star: 1.0,
        tol,
        load_solves: solved.solves,
        residual_components: parts.unbind(),
        tamaas_error: r.tamaas,
        pressure: array2(py, n, s.pressure)?,
        displacement: array2(py, n, s.displacement)?,
        gap: array2(py, n, solved.gap)?,
        heights: array2(py, n, solved.heights)?,
    })
}

/// One step of a magnification sweep.
#[pyclass(frozen, get_all, module = "persson_check")]
struct SweepStep {
    /// Step number, from 0.
    step: usize,
    /// Magnification of this step.
    zeta: f64,
    /// Mean pressure.
    p0: f64,
    /// Relative contact area.
    contact_area: f64,
    /// Elastic energy per unit area.
    elastic_energy: f64,
    /// Mean gap.
    mean_gap: f64,
    /// Rms gradient of the surface at zeta.
    rms_gradient: f64,
    /// Iterations of this step's solve (warm-started from the previous step).
    iterations: usize,
    /// Solver-independent residual reached.
    residual: f64,
    /// Wall time of this step's solve, seconds.
    wall_s: f64,
    /// Pressure field (only with fields=True, else None).
    pressure: Option<Py<PyArray2<f64>>>,
    /// Gap field (only with fields=True, else None).
    gap: Option<Py<PyArray2<f64>>>,
}

#[pymethods]
impl SweepStep {
    fn __repr__(&self) -> String {
        format!(
            "SweepStep(step={}, zeta={:.6}, p0={:.6e}, contact_area={:.6}, \
             elastic_energy={:.6e}, iterations={})",
            self.step, self.zeta, self.p0, self.contact_area, self.elastic_energy, self.iterations
        )
    }
}

/// A sweep step as the worker sends it.
struct StepData {
    zeta: f64,
    p0: f64,
    contact_area: f64,
    elastic_energy: f64,
    mean_gap: f64,
    rms_gradient: f64,
    iterations: usize,
    residual: f64,
    wall_s: f64,
    fields: Option<(Vec<f64>, Vec<f64>)>,
}

/// The worker's side of a sweep: waits for a request before each step.
struct SweepJob {
    surface: Surface,
    steps: Vec<f64>,
    load: Load,
    kind: SolverKind,
    opts: SolveOptions,
    fields: bool,
}

impl SweepJob {
    fn run(
        self,
        requests: Receiver<()>,
        out: Sender<Event>,
        cancel: Arc<AtomicBool>,
        progress: bool,
    ) {
        let hook = Hook {
            cancel,
            progress: progress.then(|| out.clone()),
        };
        let model = match Model::new(self.surface.grid().clone(), 1.0) {
            Ok(m) => m,
            Err(e) => {
                let _ = out.send(Event::Step(Box::new(Err(Failure::Lib(e)))));
                return;
            }
        };
        let mut sweep = EngineSweep::with_solver(
            &self.surface,
            &model,
            hook.wrap(self.kind.build()),
            self.opts,
        );
        let mut p0 = match self.load {
            Load::Pressure(p0) => Some(p0),
            Load::Area(_) => None,
        };
        for &zeta in &self.steps {
            if requests.recv().is_err() {
                return;
            }
            let step = catch_unwind(AssertUnwindSafe(|| -> persson_check::Result<StepData> {
                match (p0, self.load) {
                    (Some(p0), _) => {
                        sweep.solve_at(zeta, p0)?;
                    }
                    (None, Load::Area(a)) => p0 = Some(sweep.find_load(zeta, a)?),
                    (None, Load::Pressure(_)) => unreachable!("p0 is set for a pressure"),
                }
                let solution = sweep.solution().expect("a solve keeps its solution");
                let heights = sweep.heights();
                let fields = self
                    .fields
                    .then(|| (solution.pressure.clone(), solution.gap(heights)));
                Ok(StepData {
                    zeta,
                    p0: solution.p0,
                    contact_area: solution.contact_area(),
                    elastic_energy: solution.elastic_energy(),
                    mean_gap: solution.mean_gap(heights),
                    rms_gradient: self.surface.rms_gradient(zeta),
                    iterations: solution.stats.iterations,
                    residual: solution.stats.residual.value(),
                    wall_s: solution.stats.wall_s,
                    fields,
                })
            }));
            let (result, stop) = match step {
                Ok(r) => (r.map_err(Failure::Lib), false),
                Err(payload) => (Err(from_panic(payload)), true),
            };
            let msg = Event::Step(Box::new(result));
            if out.send(msg).is_err() || stop {
                return;
            }
        }
    }
}

/// The Python side of a running sweep.
struct SweepState {
    requests: Sender<()>,
    /// In a Mutex only to enter the GIL-free waits (a Receiver is not Sync).
    results: Mutex<Receiver<Event>>,
    next_step: usize,
}

/// Iterator over a magnification sweep: one `SweepStep` per magnification, each solve
/// warm-started from the previous one. Made by `persson_check.sweep(...)`; `len()` is the
/// number of steps, so `tqdm(persson_check.sweep(...))` shows a progress bar.
#[pyclass(frozen, module = "persson_check")]
struct Sweep {
    state: Mutex<Option<SweepState>>,
    cancel: Arc<AtomicBool>,
    zetas: Vec<f64>,
    n: usize,
    progress: Option<Py<PyAny>>,
}

#[pymethods]
impl Sweep {
    fn __iter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    fn __len__(&self) -> usize {
        self.zetas.len()
    }

    /// The magnifications of the steps, in order.
    #[getter]
    fn zetas<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.zetas)
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<SweepStep> {
        // Another thread advancing the same sweep holds the lock; waiting for it here, with
        // the GIL held, could deadlock.
        let Ok(mut guard) = self.state.try_lock() else {
            return Err(PyRuntimeError::new_err(
                "this sweep is being advanced by another thread",
            ));
        };
        let Some(state) = guard.as_mut() else {
            return Err(PyStopIteration::new_err(()));
        };
        if state.requests.send(()).is_err() {
            *guard = None;
            return Err(PyStopIteration::new_err(()));
        }
        let progress = self.progress.as_ref().map(|p| p.bind(py).clone());
        let mut raised: Option<PyErr> = None;
        let result = loop {
            let results = &state.results;
            let next = py.detach(|| results.lock().expect("not poisoned").recv_timeout(POLL));
            match next {
                Ok(Event::Progress(p)) => {
                    if raised.is_none() {
                        if let Err(e) = notify(progress.as_ref(), p) {
                            self.cancel.store(true, Ordering::Relaxed);
                            raised = Some(e);
                        }
                    }
                }
                Ok(Event::Step(r)) => break Some(*r),
                Ok(Event::Done) => {}
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break None,
            }
            if raised.is_none() {
                if let Err(e) = py.check_signals() {
                    self.cancel.store(true, Ordering::Relaxed);
                    raised = Some(e);
                }
            }
        };
        let step = state.next_step;
        state.next_step += 1;
        if let Some(e) = raised {
            *guard = None;
            return Err(e);
        }
        match result {
            None => {
                *guard = None;
                Err(PyStopIteration::new_err(()))
            }
            Some(Ok(d)) => {
                let (pressure, gap) = match d.fields {
                    Some((p, g)) => (Some(array2(py, self.n, p)?), Some(array2(py, self.n, g)?)),
                    None => (None, None),
                };
                Ok(SweepStep {
                    step,
                    zeta: d.zeta,
                    p0: d.p0,
                    contact_area: d.contact_area,
                    elastic_energy: d.elastic_energy,
                    mean_gap: d.mean_gap,
                    rms_gradient: d.rms_gradient,
                    iterations: d.iterations,
                    residual: d.residual,
                    wall_s: d.wall_s,
                    pressure,
                    gap,
                })
            }
            Some(Err(Failure::Lib(e))) => Err(to_py(e)),
            Some(Err(Failure::Cancelled)) => {
                *guard = None;
                Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(()))
            }
            Some(Err(Failure::Panic(text))) => {
                *guard = None;
                Err(PyRuntimeError::new_err(format!(
                    "internal error (please report): {text}"
                )))
            }
        }
    }

    /// Stops the sweep (its worker ends at its next iteration); the iterator is then
    /// exhausted.
    fn close(&self) {
        self.cancel.store(true, Ordering::Relaxed);
        *self.state.lock().expect("not poisoned") = None;
    }

    fn __repr__(&self) -> String {
        format!("Sweep(n={}, steps={})", self.n, self.zetas.len())
    }
}

impl Drop for Sweep {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

/// A magnification sweep of `heights` as an iterator of `SweepStep`: roughness is added one
/// shell at a time (every distinct |q| with zeta_from < zeta <= zeta_to, or the given
/// `zetas`) and each solve starts from the previous solution, at constant `p0`, or at the
/// load found at the first step for `contact_area`. Steps are computed one at a time, as
/// the iterator is advanced, on a worker thread with the GIL released; Ctrl-C stops the
/// running solve. `fields=True` adds each step's pressure and gap arrays.
#[pyfunction]
#[pyo3(signature = (heights, p0=None, contact_area=None, zeta_from=1.0, zeta_to=None, zetas=None, solver="cg", tol=1e-8, lambda_l=None, threads=None, fields=false, max_iter=100_000, progress=None))]
#[allow(clippy::too_many_arguments)]
fn sweep(
    py: Python<'_>,
    heights: PyReadonlyArrayDyn<'_, f64>,
    p0: Option<f64>,
    contact_area: Option<f64>,
    zeta_from: f64,
    zeta_to: Option<f64>,
    zetas: Option<Vec<f64>>,
    solver: &str,
    tol: f64,
    lambda_l: Option<f64>,
    threads: Option<i64>,
    fields: bool,
    max_iter: i64,
    progress: Option<Py<PyAny>>,
) -> PyResult<Sweep> {
    let load = load(p0, contact_area)?;
    if let Some(l) = lambda_l {
        check_positive("lambda_l", l).map_err(to_py)?;
    }
    let kind = solver_kind(solver)?;
    let max_iter = unsigned("max_iter", max_iter, u64::MAX)? as usize;
    let opts = SolveOptions { tol, max_iter };
    opts.validate().map_err(to_py)?;
    let (n, values) = field(&heights)?;
    let surface = surface_of(n, values, lambda_l).map_err(to_py)?;
    let zeta_max = surface.zeta_max().max(1.0);
    let steps = match zetas {
        Some(list) => {
            if list.is_empty() {
                return Err(to_py(Error::invalid(
                    "zetas",
                    "[]",
                    "at least one magnification",
                )));
            }
            for &z in &list {
                check_zeta(z, zeta_max).map_err(|e| to_py(e.with_field("zetas")))?;
            }
            list
        }
        None => {
            check_zeta(zeta_from, zeta_max).map_err(|e| to_py(e.with_field("zeta_from")))?;
            let to = zeta_to.unwrap_or(zeta_max);
            check_zeta(to, zeta_max).map_err(|e| to_py(e.with_field("zeta_to")))?;
            let steps = shell_steps(&surface, zeta_from, to);
            if steps.is_empty() {
                return Err(to_py(Error::invalid(
                    "zeta_to",
                    to,
                    format!("above the first shell with roughness after zeta_from = {zeta_from}"),
                )));
            }
            steps
        }
    };
    let pool = pool(threads)?;
    let cancel = Arc::new(AtomicBool::new(false));
    let (req_tx, req_rx) = mpsc::channel();
    let (out_tx, out_rx) = mpsc::channel();
    let job = SweepJob {
        surface,
        steps: steps.clone(),
        load,
        kind,
        opts,
        fields,
    };
    let flag = cancel.clone();
    let wants_progress = progress.is_some();
    std::thread::Builder::new()
        .name("persson-check sweep".to_string())
        .spawn(move || match pool {
            Some(pool) => pool.install(move || job.run(req_rx, out_tx, flag, wants_progress)),
            None => job.run(req_rx, out_tx, flag, wants_progress),
        })
        .map_err(|e| PyRuntimeError::new_err(format!("could not start the sweep: {e}")))?;
    let _ = py;
    Ok(Sweep {
        state: Mutex::new(Some(SweepState {
            requests: req_tx,
            results: Mutex::new(out_rx),
            next_step: 0,
        })),
        cancel,
        zetas: steps,
        n,
        progress,
    })
}

/// Persson's theory at one load on the spectrum of one surface.
#[pyclass(frozen, module = "persson_check")]
struct Theory {
    prediction: Prediction,
    zeta_max: f64,
}

impl Theory {
    fn at(&self, zeta: Option<f64>) -> f64 {
        zeta.unwrap_or(self.zeta_max)
    }
}

#[pymethods]
impl Theory {
    /// Mean pressure p0.
    #[getter]
    fn p0(&self) -> f64 {
        self.prediction.p0()
    }

    /// "original", or "corrected" (with the correction's gamma in `gamma`).
    #[getter]
    fn variant(&self) -> &'static str {
        match self.prediction.variant() {
            persson_check::persson::Variant::Original => "original",
            persson_check::persson::Variant::Corrected(_) => "corrected",
        }
    }

    /// Magnification of the finest shell (the default zeta of every method).
    #[getter]
    fn zeta_max(&self) -> f64 {
        self.zeta_max
    }

    /// Relative contact area a_r at magnification zeta (default: zeta_max).
    #[pyo3(signature = (zeta=None))]
    fn contact_area(&self, zeta: Option<f64>) -> f64 {
        self.prediction.contact_area(self.at(zeta))
    }

    /// 1 - a_r at zeta (computed with erfc: precise near full contact).
    #[pyo3(signature = (zeta=None))]
    fn non_contact_area(&self, zeta: Option<f64>) -> f64 {
        self.prediction.non_contact_area(self.at(zeta))
    }

    /// Total pressure broadening Dp_tot^2 (original) or Dp_mod,tot^2 (corrected) at zeta.
    #[pyo3(signature = (zeta=None))]
    fn total_broadening(&self, zeta: Option<f64>) -> f64 {
        self.prediction.total_broadening(self.at(zeta))
    }

    /// Correction factor S(a_r) at zeta (1 for the original theory).
    #[pyo3(signature = (zeta=None))]
    fn correction_factor(&self, zeta: Option<f64>) -> f64 {
        self.prediction.correction_factor(self.at(zeta))
    }

    /// Elastic energy per unit area of the modes resolved at zeta.
    #[pyo3(signature = (zeta=None))]
    fn elastic_energy(&self, zeta: Option<f64>) -> f64 {
        self.prediction.elastic_energy(self.at(zeta))
    }

    /// The pressure distribution's density Pr(p, zeta) at each of `p` (the delta function of
    /// weight 1 - a_r at p = 0 is not included; see non_contact_area).
    #[pyo3(signature = (p, zeta=None))]
    fn pressure_density<'py>(
        &self,
        py: Python<'py>,
        p: Vec<f64>,
        zeta: Option<f64>,
    ) -> Bound<'py, PyArray1<f64>> {
        let d = self.prediction.pressure_distribution(self.at(zeta));
        PyArray1::from_vec(py, p.iter().map(|&x| d.density(x)).collect())
    }

    /// The cumulative distribution P(pressure <= p) at each of `p`, the delta at 0 included.
    #[pyo3(signature = (p, zeta=None))]
    fn pressure_cdf<'py>(
        &self,
        py: Python<'py>,
        p: Vec<f64>,
        zeta: Option<f64>,
    ) -> Bound<'py, PyArray1<f64>> {
        let d = self.prediction.pressure_distribution(self.at(zeta));
        PyArray1::from_vec(py, p.iter().map(|&x| d.cdf(x)).collect())
    }

    /// The theory shell by shell, as a dict of equal-length numpy arrays: zeta, q,
    /// broadening, added_broadening, total_broadening, contact_area, non_contact_area,
    /// correction, energy, full_contact_energy.
    fn shells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.prediction.shells();
        let d = PyDict::new(py);
        let col = |f: fn(&persson_check::persson::ShellPrediction) -> f64| {
            PyArray1::from_vec(py, s.iter().map(f).collect())
        };
        d.set_item("zeta", col(|x| x.zeta))?;
        d.set_item("q", col(|x| x.q))?;
        d.set_item("broadening", col(|x| x.broadening))?;
        d.set_item("added_broadening", col(|x| x.added_broadening))?;
        d.set_item("total_broadening", col(|x| x.total_broadening))?;
        d.set_item("contact_area", col(|x| x.contact_area))?;
        d.set_item("non_contact_area", col(|x| x.non_contact_area))?;
        d.set_item("correction", col(|x| x.correction))?;
        d.set_item("energy", col(|x| x.energy))?;
        d.set_item("full_contact_energy", col(|x| x.full_contact_energy))?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Theory(variant={:?}, p0={:.6e}, shells={}, contact_area={:.6})",
            self.variant(),
            self.p0(),
            self.prediction.shells().len(),
            self.contact_area(None)
        )
    }
}

/// Persson's theory at mean pressure `p0` on the spectrum of `heights` (its modes grouped
/// into shells of equal |q|): contact area, pressure distribution, broadening and elastic
/// energy at every magnification. `variant` is "original", "yang_persson" (corrected,
/// gamma = 0.42) or "wang_mueser" (corrected, gamma = 5/9). `lambda_l` defines
/// zeta = |q| / q_l (default: the box size; pass the surface's lambda_l for a generated
/// surface).
#[pyfunction]
#[pyo3(signature = (heights, p0, variant="original", lambda_l=None, e_star=1.0))]
fn theory(
    py: Python<'_>,
    heights: PyReadonlyArrayDyn<'_, f64>,
    p0: f64,
    variant: &str,
    lambda_l: Option<f64>,
    e_star: f64,
) -> PyResult<Theory> {
    check_positive("p0", p0).map_err(to_py)?;
    if let Some(l) = lambda_l {
        check_positive("lambda_l", l).map_err(to_py)?;
    }
    let correction = match variant {
        "original" => None,
        "yang_persson" | "corrected" => Some(Correction::yang_persson()),
        "wang_mueser" => Some(Correction::wang_mueser()),
        other => {
            return Err(to_py(Error::invalid(
                "variant",
                format!("{other:?}"),
                "\"original\", \"yang_persson\" or \"wang_mueser\"",
            )))
        }
    };
    let (n, values) = field(&heights)?;
    py.detach(|| {
        let surface = surface_of(n, values, lambda_l)?;
        let broadening = Broadening::new(&surface.shells(), e_star)?;
        let prediction = match correction {
            None => Prediction::original(&broadening, p0)?,
            Some(c) => Prediction::corrected(&broadening, p0, c)?,
        };
        Ok(Theory {
            zeta_max: surface.zeta_max().max(1.0),
            prediction,
        })
    })
    .map_err(to_py)
}

/// The empirical contact-area law, eq. (contactArea) of the paper, at reduced pressure
/// p0 / (E* g_bar).
#[pyfunction]
fn contact_area_law(p_reduced: f64) -> f64 {
    persson_check::persson::persson_contact_area(p_reduced)
}

/// The definitions named (all when `names` is empty), from `dir` or the built-in copies.
fn definitions(names: Vec<String>, dir: Option<String>) -> persson_check::Result<Vec<Source>> {
    let sources = match dir {
        Some(dir) => {
            let sources = sources_in(std::path::Path::new(&dir))?;
            if sources.is_empty() {
                return Err(Error::invalid(
                    "dir",
                    format!("{dir} (no *.toml files)"),
                    "a folder of validation definitions (*.toml)",
                ));
            }
            sources
        }
        None => builtin_sources(),
    };
    select(sources, &names)
}

/// Names as a list: one string or a list of strings (None: all).
fn name_list(names: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
    match names {
        None => Ok(Vec::new()),
        Some(obj) => match obj.extract::<String>() {
            Ok(one) => Ok(vec![one]),
            Err(_) => obj.extract::<Vec<String>>(),
        },
    }
}

fn run_options(
    out: String,
    full: bool,
    solver: Option<&str>,
    resume: bool,
) -> PyResult<RunOptions> {
    Ok(RunOptions {
        scale: if full { Scale::Full } else { Scale::Reduced },
        out: out.into(),
        resume,
        progress: false,
        solvers: match solver {
            Some(s) => vec![solver_kind(s)?],
            None => RunOptions::BOTH.to_vec(),
        },
        mode: Mode::All,
    })
}

/// JSON text as Python objects (dicts, lists), through the json module.
fn json_to_py<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// Runs the definitions with `opts`; stops between definitions when cancelled.
fn run_definitions(
    hook: &Hook,
    sources: &[Source],
    opts: &RunOptions,
) -> persson_check::Result<Vec<String>> {
    let registry = Registry::builtin();
    for source in sources {
        registry.check(source)?;
    }
    let mut outcomes = Vec::new();
    let mut failed = Vec::new();
    for source in sources {
        if hook.cancelled() {
            resume_unwind(Box::new(Cancelled));
        }
        match registry.run(source, opts) {
            Ok(Some(o)) => outcomes.push(serde_json::to_string(&o).expect("outcomes serialise")),
            Ok(None) => {}
            Err(e) => failed.push(format!("{}: {e}", source.path.display())),
        }
    }
    if failed.is_empty() {
        Ok(outcomes)
    } else {
        Err(Error::invalid(
            "validations",
            format!("{} failed", failed.len()),
            format!("all to run ({})", failed.join("; ")),
        ))
    }
}

/// Runs the named validations (a name or a list; all by default) as
/// `persson-check validate NAMES --out OUT` does, writing the same files into `out`, and
/// returns their outcomes as a list of dicts with the keys of `<name>.json`
/// (`o["name"]`, `o["verdict"]`, `o["reproduced"]`, ...). `full=True` runs the paper-scale
/// scenes; `solver` ("gfmd" or "cg") runs one solver only. The GIL is released while it
/// runs; Ctrl-C takes effect once the validation under way has finished.
#[pyfunction]
#[pyo3(signature = (names=None, out="out".to_string(), full=false, solver=None, resume=false, dir=None, threads=None))]
#[allow(clippy::too_many_arguments)]
fn validate<'py>(
    py: Python<'py>,
    names: Option<&Bound<'py, PyAny>>,
    out: String,
    full: bool,
    solver: Option<&str>,
    resume: bool,
    dir: Option<String>,
    threads: Option<i64>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let names = name_list(names)?;
    let out_path = std::path::PathBuf::from(&out);
    if out_path.exists() && !out_path.is_dir() {
        return Err(to_py(Error::invalid(
            "out",
            out_path.display(),
            "a folder (this path exists and is not one)",
        )));
    }
    let opts = run_options(out, full, solver, resume)?;
    let sources = py.detach(|| definitions(names, dir)).map_err(to_py)?;
    let outcomes = run_blocking(py, threads, None, |hook| {
        run_definitions(hook, &sources, &opts)
    })?;
    outcomes.iter().map(|t| json_to_py(py, t)).collect()
}

/// The jobs of the named validations with their estimated costs (and their shares, with
/// `shards`), as `persson-check validate NAMES --plan` prints them, as a dict. With `out`,
/// the measured time of every finished job there is added.
#[pyfunction]
#[pyo3(signature = (names=None, shards=None, full=false, solver=None, out=None, dir=None))]
fn plan<'py>(
    py: Python<'py>,
    names: Option<&Bound<'py, PyAny>>,
    shards: Option<i64>,
    full: bool,
    solver: Option<&str>,
    out: Option<String>,
    dir: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let names = name_list(names)?;
    let shards = match shards {
        None => None,
        Some(k) if (1..=100_000).contains(&k) => Some(k as usize),
        Some(k) => {
            return Err(to_py(Error::invalid(
                "shards",
                k,
                "an integer in [1, 100000]",
            )))
        }
    };
    let opts = run_options(out.unwrap_or_default(), full, solver, false)?;
    let text = py
        .detach(|| -> persson_check::Result<String> {
            let sources = definitions(names, dir)?;
            let registry = Registry::builtin();
            for source in &sources {
                registry.check(source)?;
            }
            let mut units = Vec::new();
            for source in &sources {
                units.extend(registry.jobs(source, &opts)?);
            }
            let plan = Plan::new(units, shards);
            Ok(serde_json::to_string(&plan).expect("plans serialise"))
        })
        .map_err(to_py)?;
    json_to_py(py, &text)
}

/// Writes the outcomes of the named validations from the job results that shares stored
/// under `out/jobs/`, exactly as `persson-check validate NAMES --merge --out OUT` does,
/// and returns them as a list of dicts. Runs no job; every job's result must be there.
#[pyfunction]
#[pyo3(signature = (names=None, out="out".to_string(), full=false, solver=None, accept_other_commit=false, dir=None))]
fn merge<'py>(
    py: Python<'py>,
    names: Option<&Bound<'py, PyAny>>,
    out: String,
    full: bool,
    solver: Option<&str>,
    accept_other_commit: bool,
    dir: Option<String>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let names = name_list(names)?;
    let mut opts = run_options(out, full, solver, false)?;
    let outcomes = py
        .detach(|| -> persson_check::Result<Vec<String>> {
            let sources = definitions(names, dir)?;
            let registry = Registry::builtin();
            for source in &sources {
                registry.check(source)?;
            }
            let mut units = Vec::new();
            for source in &sources {
                units.extend(registry.jobs(source, &opts)?);
            }
            let plan = Plan::new(units, None);
            plan.check_merge(&definition_hashes(&sources)?, accept_other_commit)?;
            opts.mode = Mode::Merge {
                other_commits_accepted: accept_other_commit,
            };
            let hook = Hook {
                cancel: Arc::new(AtomicBool::new(false)),
                progress: None,
            };
            run_definitions(&hook, &sources, &opts)
        })
        .map_err(to_py)?;
    outcomes.iter().map(|t| json_to_py(py, t)).collect()
}

/// Writes the Markdown scorecard of the outcomes in folder `source`, as
/// `persson-check report --from SOURCE --out OUT` does (`speed=False` is `--no-speed`), and
/// returns a dict: path, validations, attention, files, speed_error.
#[pyfunction(name = "report")]
#[pyo3(signature = (source="out".to_string(), out="scorecard.md".to_string(), golden=None, speed=false, speed_n=256))]
fn report_md<'py>(
    py: Python<'py>,
    source: String,
    out: String,
    golden: Option<String>,
    speed: bool,
    speed_n: i64,
) -> PyResult<Bound<'py, PyDict>> {
    let from = std::path::PathBuf::from(&source);
    if !from.is_dir() {
        return Err(to_py(Error::invalid(
            "source",
            from.display(),
            "an existing folder of outcomes (<name>.json), as written by validate",
        )));
    }
    let out = std::path::PathBuf::from(out);
    if out.is_dir() {
        return Err(to_py(Error::invalid(
            "out",
            out.display(),
            "a file (this path is a folder)",
        )));
    }
    let golden = match golden {
        Some(dir) if std::path::Path::new(&dir).is_dir() => Some(dir.into()),
        Some(dir) => {
            return Err(to_py(Error::invalid(
                "golden",
                dir,
                "an existing folder of <name>.snap files",
            )))
        }
        None => None,
    };
    let speed = if speed {
        let n = unsigned("speed_n", speed_n, MAX_N as u64)? as usize;
        let opts = SpeedOptions::with_n(n);
        opts.validate()
            .map_err(|e| to_py(e.with_field("speed_n")))?;
        SpeedChoice::Run(opts)
    } else {
        SpeedChoice::Skip
    };
    let opts = ReportOptions {
        from,
        out,
        golden,
        speed,
    };
    let summary = py
        .detach(|| persson_check::report::write(&opts, &mut |_| {}))
        .map_err(to_py)?;
    let d = PyDict::new(py);
    d.set_item("path", summary.path.display().to_string())?;
    d.set_item("validations", summary.validations)?;
    d.set_item("attention", summary.attention)?;
    d.set_item(
        "files",
        summary
            .files
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>(),
    )?;
    d.set_item("speed_error", summary.speed_error)?;
    Ok(d)
}

/// Native part of persson_check (use the persson_check package).
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SolveError", m.py().get_type::<SolveError>())?;
    m.add_class::<Solution>()?;
    m.add_class::<Sweep>()?;
    m.add_class::<SweepStep>()?;
    m.add_class::<Theory>()?;
    m.add_function(wrap_pyfunction!(surface, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(theory, m)?)?;
    m.add_function(wrap_pyfunction!(contact_area_law, m)?)?;
    m.add_function(wrap_pyfunction!(validate, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(merge, m)?)?;
    m.add_function(wrap_pyfunction!(report_md, m)?)?;
    Ok(())
}
