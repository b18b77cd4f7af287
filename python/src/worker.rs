//! The cancellable worker: long computations run on a worker thread with the GIL
//! released, while the calling thread waits for it and checks for signals every
//! [`POLL`]. On Ctrl-C (or an exception from a progress callback) it raises a flag that
//! the watch of every solve sees ([`Hook::iteration`]; iteration 0 of every solve comes
//! right after its set-up): the watch answers stop ([`StopReason::Cancelled`]), the solve
//! ends in the library's `Error::Stopped`, which passes through sweeps and load searches
//! to the worker, and the exception is raised once the worker has stopped.

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

use persson_check::error::Error;
use persson_check::tasks::parse::{self, MAX_THREADS};
use persson_check::tasks::solve::{Progress, StopReason};
use persson_check::tasks::sweep::SweepStep;
use persson_check::tasks::Keywords;

use crate::errors::{internal, interrupted, to_py};

/// How often the waiting thread looks for signals.
pub const POLL: Duration = Duration::from_millis(20);

/// Iterations between two progress reports.
const PROGRESS_EVERY: usize = 16;

/// What a worker tells the thread that waits for it.
pub enum Event {
    /// Every [`PROGRESS_EVERY`]th iteration of a solve (only when a callback wants it).
    Progress(Progress),
    /// The worker of [`run_blocking`] has finished.
    Done,
    /// A step of a sweep.
    Step(Box<Result<SweepStep, Failure>>),
    /// A line for Python's `sys.stderr` (only when the caller asked for lines).
    Line(String),
}

/// What a worker shares with the thread that waits for it.
#[derive(Clone)]
pub struct Hook {
    /// Raised to stop the worker.
    pub cancel: Arc<AtomicBool>,
    /// Where progress goes, when a callback wants it.
    pub progress: Option<Sender<Event>>,
    /// Where lines for `sys.stderr` go, when the caller wants them.
    pub lines: Option<Sender<Event>>,
}

impl Hook {
    /// Whether the worker is to stop.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// Sends `text` to be written to Python's `sys.stderr` (a notebook shows it), when the
    /// caller asked for lines.
    pub fn line(&self, text: String) {
        if let Some(tx) = &self.lines {
            let _ = tx.send(Event::Line(text));
        }
    }

    /// A solver's iteration: answers stop ([`StopReason::Cancelled`]) when the worker is
    /// to stop, and forwards every [`PROGRESS_EVERY`]th iteration's progress when a
    /// callback wants it.
    pub fn iteration(&self, p: Progress) -> ControlFlow<StopReason> {
        if self.cancelled() {
            return ControlFlow::Break(StopReason::Cancelled);
        }
        if p.iteration % PROGRESS_EVERY == 0 {
            if let Some(tx) = &self.progress {
                let _ = tx.send(Event::Progress(p));
            }
        }
        ControlFlow::Continue(())
    }
}

/// Why a worker produced no value.
pub enum Failure {
    /// The library's error.
    Lib(Error),
    /// Stopped by the cancel flag.
    Cancelled,
    /// A panic, with its message.
    Panic(String),
}

impl Failure {
    /// The failure of a worker that ended with the library's error `e`: a solve stopped
    /// by the cancel flag is [`Failure::Cancelled`].
    pub fn from_error(e: Error) -> Self {
        match e.stopped() {
            Some(StopReason::Cancelled) => Failure::Cancelled,
            _ => Failure::Lib(e),
        }
    }

    /// The failure of a worker thread that panicked with `payload` (a bug).
    pub fn from_panic(payload: Box<dyn std::any::Any + Send>) -> Self {
        let text = payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "a panic without a message".to_string());
        Failure::Panic(text)
    }

    /// The Python exception: the library's, `KeyboardInterrupt`, or an internal error.
    pub fn into_py(self) -> PyErr {
        match self {
            Failure::Lib(e) => to_py(e),
            Failure::Cancelled => interrupted(),
            Failure::Panic(text) => internal(&text),
        }
    }

    /// Whether the worker has stopped for good (a cancel or a panic, not an error of one
    /// step).
    pub fn ends_worker(&self) -> bool {
        !matches!(self, Failure::Lib(_))
    }
}

/// A rayon pool of `threads` workers, or `None` for the global pool (all cores).
pub fn pool(threads: Option<i64>) -> PyResult<Option<rayon::ThreadPool>> {
    let Some(threads) = threads else {
        return Ok(None);
    };
    let threads = parse::integer("threads", threads, 1, MAX_THREADS, &Keywords).map_err(to_py)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads as usize)
        .build()
        .map(Some)
        .map_err(|e| PyRuntimeError::new_err(format!("threads: {e}")))
}

/// Waits for the worker's events with the GIL released, [`POLL`] at a time: hands
/// progress to `progress`, checks for signals, and returns the first event that `take`
/// keeps (`None` once the worker has gone). Ctrl-C or an exception from `progress` raises
/// `cancel` and is returned beside the event; the wait goes on until the worker answers.
pub fn wait<T>(
    py: Python<'_>,
    events: &Mutex<Receiver<Event>>,
    cancel: &AtomicBool,
    progress: Option<&Bound<'_, PyAny>>,
    mut take: impl FnMut(Event) -> Option<T>,
) -> (Option<T>, Option<PyErr>) {
    let mut raised: Option<PyErr> = None;
    let raise = |e: PyErr, raised: &mut Option<PyErr>| {
        cancel.store(true, Ordering::Relaxed);
        *raised = Some(e);
    };
    loop {
        let next = py.detach(|| events.lock().expect("not poisoned").recv_timeout(POLL));
        match next {
            Ok(Event::Progress(p)) => {
                if let (None, Some(cb)) = (&raised, progress) {
                    if let Err(e) = cb.call1((p.iteration, p.residual)) {
                        raise(e, &mut raised);
                    }
                }
            }
            Ok(Event::Line(text)) => {
                if raised.is_none() {
                    let written = py
                        .import("sys")
                        .and_then(|sys| sys.getattr("stderr"))
                        .and_then(|err| err.call_method1("write", (text + "\n",)));
                    if let Err(e) = written {
                        raise(e, &mut raised);
                    }
                }
            }
            Ok(event) => {
                if let Some(value) = take(event) {
                    return (Some(value), raised);
                }
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => return (None, raised),
        }
        if raised.is_none() {
            if let Err(e) = py.check_signals() {
                raise(e, &mut raised);
            }
        }
    }
}

/// Runs `work` on a worker thread (inside a pool of `threads` if given) with the GIL
/// released; meanwhile checks for signals and forwards progress to `progress`. Ctrl-C or
/// an exception from `progress` stops the worker and, once it has stopped, is raised
/// here.
pub fn run_blocking<T: Send>(
    py: Python<'_>,
    threads: Option<i64>,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(&Hook) -> persson_check::Result<T> + Send,
) -> PyResult<T> {
    run_logged(py, threads, progress, false, work)
}

/// [`run_blocking`], with the lines the worker sends ([`Hook::line`]) written to Python's
/// `sys.stderr` as they come when `lines` is true.
pub fn run_logged<T: Send>(
    py: Python<'_>,
    threads: Option<i64>,
    progress: Option<&Bound<'_, PyAny>>,
    lines: bool,
    work: impl FnOnce(&Hook) -> persson_check::Result<T> + Send,
) -> PyResult<T> {
    let pool = pool(threads)?;
    let (tx, rx) = mpsc::channel();
    let hook = Hook {
        cancel: Arc::new(AtomicBool::new(false)),
        progress: progress.map(|_| tx.clone()),
        lines: lines.then(|| tx.clone()),
    };
    // A Receiver is not Sync: it enters the GIL-free waits through a Mutex.
    let rx = Mutex::new(rx);
    let cancel = hook.cancel.clone();
    std::thread::scope(|scope| {
        // A panic ends the worker thread (its sender goes with it, which ends the wait)
        // and comes back from `join` as an internal error.
        let worker = scope.spawn(move || {
            let run = move || work(&hook);
            let result = match &pool {
                Some(pool) => pool.install(run),
                None => run(),
            };
            let _ = tx.send(Event::Done);
            result
        });
        let (_, raised) = wait(py, &rx, &cancel, progress, |e| {
            matches!(e, Event::Done).then_some(())
        });
        let result = py.detach(|| worker.join());
        if let Some(e) = raised {
            return Err(e);
        }
        match result {
            Ok(r) => r.map_err(|e| Failure::from_error(e).into_py()),
            Err(payload) => Err(Failure::from_panic(payload).into_py()),
        }
    })
}
