//! The library's errors as the Python exceptions a caller expects, in one place: bad
//! input is a `ValueError` (the command line's message, the parameter named by its
//! keyword), a file system failure an `OSError`, a solve cancelled by Ctrl-C a
//! `KeyboardInterrupt`, and everything else a solve or a load
//! search can end with (the iteration budget, a stall at the rounding floor, a non-finite
//! value, no load for the target area) a [`SolveError`].

use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;

use persson_check::error::{Error, StopReason};

create_exception!(
    persson_check,
    SolveError,
    PyRuntimeError,
    "A solve that stopped before its tolerance (iteration budget, stall at the rounding \
     floor, a non-finite value) or a load search that found no load for the target area."
);

/// The library's error as the Python exception a caller expects.
pub fn to_py(e: Error) -> PyErr {
    let text = e.to_string();
    match e {
        Error::InvalidInput { .. } | Error::BadFile { .. } => PyValueError::new_err(text),
        Error::Io { .. } => PyOSError::new_err(text),
        // A solve stopped by Ctrl-C (the worker's cancel).
        Error::Stopped {
            reason: StopReason::Cancelled,
            ..
        } => interrupted(),
        // Every other ending is the end of a solve or a load search.
        _ => SolveError::new_err(text),
    }
}

/// A library result as a Python one.
pub trait OrRaise<T> {
    /// The value, or the error as its Python exception.
    fn or_raise(self) -> Result<T, PyErr>;
}

impl<T> OrRaise<T> for persson_check::Result<T> {
    fn or_raise(self) -> Result<T, PyErr> {
        self.map_err(to_py)
    }
}

/// Ctrl-C (or a cancelled worker) as Python's `KeyboardInterrupt`.
pub fn interrupted() -> PyErr {
    PyKeyboardInterrupt::new_err(())
}

/// A panic of the library, which is a bug: a `RuntimeError` that says so.
pub fn internal(text: &str) -> PyErr {
    PyRuntimeError::new_err(format!("internal error (please report): {text}"))
}
