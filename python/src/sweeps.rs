//! Magnification sweeps: `sweep` returns an iterator whose every step is one solve,
//! warm-started from the previous step, computed on a worker thread only when the
//! iterator is advanced (so `tqdm(sweep(...))` shows real progress and a loop that breaks
//! early costs nothing more).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use numpy::{PyArray1, PyArray2, PyReadonlyArrayDyn};
use pyo3::exceptions::{PyRuntimeError, PyStopIteration};
use pyo3::prelude::*;

use persson_check::tasks::solve::Settled;
use persson_check::tasks::surface::{self as surfaces, Surface};
use persson_check::tasks::sweep as task;
use persson_check::tasks::Keywords;

use crate::conversions::{array2, field};
use crate::errors::OrRaise;
use crate::worker::{pool, wait, Event, Failure, Hook};

/// One step of a magnification sweep.
#[pyclass(frozen, get_all, module = "persson_check")]
pub struct SweepStep {
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

impl SweepStep {
    /// Step number `step` from the library's step on an `n x n` grid.
    fn new(py: Python<'_>, step: usize, n: usize, s: task::SweepStep) -> PyResult<Self> {
        let (pressure, gap) = match s.fields {
            Some((p, g)) => (Some(array2(py, n, p)?), Some(array2(py, n, g)?)),
            None => (None, None),
        };
        Ok(SweepStep {
            step,
            zeta: s.zeta,
            p0: s.p0,
            contact_area: s.contact_area,
            elastic_energy: s.elastic_energy,
            mean_gap: s.mean_gap,
            rms_gradient: s.rms_gradient,
            iterations: s.iterations,
            residual: s.residual,
            wall_s: s.wall_s,
            pressure,
            gap,
        })
    }
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

/// The worker's side of a sweep: waits for a request before each step.
struct SweepJob {
    surface: Surface,
    steps: Vec<f64>,
    settled: Settled,
    fields: bool,
}

impl SweepJob {
    fn run(self, requests: Receiver<()>, out: Sender<Event>, hook: Hook) {
        let send = |r: Result<task::SweepStep, Failure>| out.send(Event::Step(Box::new(r)));
        let watched = hook.clone();
        let ran = task::with_run(
            &self.surface,
            &self.settled,
            self.fields,
            move |_, p| watched.iteration(p),
            |run| {
                for &zeta in &self.steps {
                    if requests.recv().is_err() {
                        return;
                    }
                    let result = run.step(zeta).map_err(Failure::from_error);
                    let ends = result.as_ref().is_err_and(Failure::ends_worker);
                    if send(result).is_err() || ends {
                        return;
                    }
                }
            },
        );
        if let Err(e) = ran {
            let _ = send(Err(Failure::Lib(e)));
        }
    }
}

/// The Python side of a running sweep.
struct SweepState {
    requests: Sender<()>,
    /// In a Mutex only to enter the GIL-free waits (a Receiver is not Sync).
    results: Mutex<Receiver<Event>>,
    next_step: usize,
    /// The worker thread, joined once its results end: a panic comes back from it.
    worker: Option<JoinHandle<()>>,
}

impl SweepState {
    /// The end of the sweep once the worker has gone: `StopIteration`, or the internal
    /// error of a worker that panicked.
    fn ended(&mut self, py: Python<'_>) -> PyErr {
        let joined = self.worker.take().map(|w| py.detach(|| w.join()));
        match joined {
            Some(Err(payload)) => Failure::from_panic(payload).into_py(),
            _ => PyStopIteration::new_err(()),
        }
    }
}

/// Iterator over a magnification sweep: one `SweepStep` per magnification, each solve
/// warm-started from the previous one. Made by `persson_check.sweep(...)`; `len()` is the
/// number of steps, so `tqdm(persson_check.sweep(...))` shows a progress bar.
#[pyclass(frozen, module = "persson_check")]
pub struct Sweep {
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
            let end = state.ended(py);
            *guard = None;
            return Err(end);
        }
        let progress = self.progress.as_ref().map(|p| p.bind(py).clone());
        let (result, raised) = wait(
            py,
            &state.results,
            &self.cancel,
            progress.as_ref(),
            |e| match e {
                Event::Step(r) => Some(*r),
                _ => None,
            },
        );
        let step = state.next_step;
        state.next_step += 1;
        if let Some(e) = raised {
            *guard = None;
            return Err(e);
        }
        match result {
            None => {
                let end = state.ended(py);
                *guard = None;
                Err(end)
            }
            Some(Ok(s)) => SweepStep::new(py, step, self.n, s),
            Some(Err(failure)) => {
                if failure.ends_worker() {
                    *guard = None;
                }
                Err(failure.into_py())
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
#[pyo3(signature = (heights, p0=None, contact_area=None, zeta_from=1.0, zeta_to=None, zetas=None, solver=None, tol=None, lambda_l=None, threads=None, fields=false, max_iter=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn sweep(
    heights: PyReadonlyArrayDyn<'_, f64>,
    p0: Option<f64>,
    contact_area: Option<f64>,
    zeta_from: f64,
    zeta_to: Option<f64>,
    zetas: Option<Vec<f64>>,
    solver: Option<&str>,
    tol: Option<f64>,
    lambda_l: Option<f64>,
    threads: Option<i64>,
    fields: bool,
    max_iter: Option<i64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Sweep> {
    let settled = crate::solve::settle(p0, contact_area, None, lambda_l, solver, tol, max_iter)?;
    let (n, values) = field(&heights)?;
    let surface = surfaces::from_heights(n, values, lambda_l).or_raise()?;
    let steps = task::steps(&surface, zetas, zeta_from, zeta_to, &Keywords).or_raise()?;
    let pool = pool(threads)?;
    let cancel = Arc::new(AtomicBool::new(false));
    let (req_tx, req_rx) = mpsc::channel();
    let (out_tx, out_rx) = mpsc::channel();
    let hook = Hook {
        cancel: cancel.clone(),
        progress: progress.is_some().then(|| out_tx.clone()),
        lines: None,
    };
    let job = SweepJob {
        surface,
        steps: steps.clone(),
        settled,
        fields,
    };
    let worker = std::thread::Builder::new()
        .name("persson-check sweep".to_string())
        .spawn(move || match pool {
            Some(pool) => pool.install(move || job.run(req_rx, out_tx, hook)),
            None => job.run(req_rx, out_tx, hook),
        })
        .map_err(|e| PyRuntimeError::new_err(format!("could not start the sweep: {e}")))?;
    Ok(Sweep {
        state: Mutex::new(Some(SweepState {
            requests: req_tx,
            results: Mutex::new(out_rx),
            next_step: 0,
            worker: Some(worker),
        })),
        cancel,
        zetas: steps,
        n,
        progress,
    })
}
