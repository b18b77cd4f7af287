//! `check_surface`: Persson's theory checked on the user's own height maps, as
//! `persson-check check-surface` checks them (the same library task, the same numbers and
//! the same `surface.json`).

use std::path::PathBuf;

use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use persson_check::measured::check::CheckOptions;
use persson_check::measured::psd::Boundary;
use persson_check::measured::scan::Scan;
use persson_check::tasks::check as task;
use persson_check::tasks::{parse, Keywords};

use crate::conversions::record;
use crate::errors::OrRaise;
use crate::worker::run_blocking;

/// The scans as the library's, checked as a file would be (2D, square, finite), each
/// named `heights[i]` in messages.
fn scans(heights: &[PyReadonlyArrayDyn<'_, f64>]) -> PyResult<Vec<Scan>> {
    heights
        .iter()
        .enumerate()
        .map(|(i, h)| {
            let values = h
                .as_slice()
                .map_err(|_| PyValueError::new_err("heights must be C-contiguous arrays"))?;
            let name = PathBuf::from(format!("heights[{i}]"));
            Scan::from_values(&name, h.shape(), values.to_vec()).or_raise()
        })
        .collect()
}

/// Checks Persson's theory on the surface of `heights` (a list of 2D float64 arrays, the
/// scans of one surface) with pixel size `pixel_size`, as `persson-check check-surface`
/// does, and returns the dict of `surface.json`. `out` also writes the page and its
/// figures there. The GIL is released; Ctrl-C stops the solve under way.
#[pyfunction]
#[pyo3(signature = (heights, pixel_size, periodic, loads, solver, cross_check, tol, out, threads, progress))]
#[allow(clippy::too_many_arguments)]
pub fn check_surface<'py>(
    py: Python<'py>,
    heights: Vec<PyReadonlyArrayDyn<'py, f64>>,
    pixel_size: f64,
    periodic: bool,
    loads: Option<Vec<f64>>,
    solver: &str,
    cross_check: bool,
    tol: f64,
    out: Option<PathBuf>,
    threads: Option<i64>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let solver = parse::solver(solver).or_raise()?;
    let opts = CheckOptions {
        pixel_size,
        boundary: if periodic {
            Boundary::Periodic
        } else {
            Boundary::Free
        },
        loads,
        solver,
        cross_check,
        tol,
    };
    let scans = scans(&heights)?;
    let checked = run_blocking(py, threads, progress.as_ref(), |hook| {
        let mut monitor = |_scan, _solver, _load, p| hook.iteration(p);
        task::check_surface(&scans, &opts, out.as_deref(), &Keywords, &mut monitor)
    })?;
    record(py, &checked)
}
