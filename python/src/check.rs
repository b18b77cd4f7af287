//! `check_surface`: Persson's theory checked on the user's own height maps, or line
//! scans, as `persson-check check-surface` checks them (the same library tasks, the same
//! numbers and the same `surface.json`).

use std::ops::ControlFlow;
use std::path::PathBuf;

use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use persson_check::measured::check::{CheckOptions, Event};
use persson_check::measured::fill::Fill;
use persson_check::measured::line::check::LineOptions;
use persson_check::measured::line::profiles::Profiles;
use persson_check::measured::scan::Scan;
use persson_check::tasks::check::{self as task, CheckRequest, Input};
use persson_check::tasks::solve::StopReason;
use persson_check::tasks::{parse, Keywords};

use crate::conversions::record;
use crate::errors::OrRaise;
use crate::worker::{run_logged, Hook};

/// `check_surface`'s defaults as the library writes them (the options' defaults and the
/// line scans'): the Python wrapper's keywords take them from here.
pub fn defaults(py: Python<'_>) -> PyResult<Bound<'_, pyo3::types::PyDict>> {
    use persson_check::measured::line::check::{DEFAULT_SEEDS, DEFAULT_SIDE};
    let opts = CheckOptions::default();
    let d = pyo3::types::PyDict::new(py);
    d.set_item("solver", opts.solver.name())?;
    d.set_item("tol", opts.tol)?;
    d.set_item("max_iterations", opts.max_iterations)?;
    d.set_item("line_side", DEFAULT_SIDE)?;
    d.set_item("line_seeds", DEFAULT_SEEDS)?;
    Ok(d)
}

/// What a check's event tells Python: the progress of a solve (and the answer to stop it
/// once cancelled), and a line per load (and per scan's outliers) among `count` scans.
fn log_event(hook: &Hook, count: usize, e: Event) -> ControlFlow<StopReason> {
    match e {
        Event::Iteration { progress, .. } => hook.iteration(progress),
        Event::Load { .. } | Event::Outliers { .. } => {
            if let Some(line) = task::load_line(count, &e) {
                hook.line(format!("check_surface: {line}"));
            }
            ControlFlow::Continue(())
        }
    }
}

/// An array's name in messages (`heights[i]`), its shape and its values.
type Named = (PathBuf, Vec<usize>, Vec<f64>);

/// Each array's name, shape and values.
fn named(heights: &[PyReadonlyArrayDyn<'_, f64>]) -> PyResult<Vec<Named>> {
    heights
        .iter()
        .enumerate()
        .map(|(i, h)| {
            let values = h
                .as_slice()
                .map_err(|_| PyValueError::new_err("heights must be C-contiguous arrays"))?;
            Ok((
                PathBuf::from(format!("heights[{i}]")),
                h.shape().to_vec(),
                values.to_vec(),
            ))
        })
        .collect()
}

/// The scans as the library's, checked as a file would be (2D, each side in range; NaN
/// where a point is missing), each named `heights[i]` in messages.
fn scans(heights: &[PyReadonlyArrayDyn<'_, f64>]) -> PyResult<Vec<Scan>> {
    named(heights)?
        .into_iter()
        .map(|(name, shape, values)| Scan::from_values(&name, &shape, values).or_raise())
        .collect()
}

/// The line scans of `heights` (a 1D array is a profile; a 2D one, rows of profiles),
/// each named `heights[i]` in messages.
fn profiles(heights: &[PyReadonlyArrayDyn<'_, f64>]) -> PyResult<Profiles> {
    let parts = named(heights)?
        .into_iter()
        .map(|(name, shape, values)| Profiles::from_values(&name, &shape, values, true).or_raise())
        .collect::<PyResult<Vec<_>>>()?;
    Profiles::pool(parts).or_raise()
}

/// The fill named `name` (`"none"`, `"interpolate"`).
fn fill(name: &str) -> PyResult<Fill> {
    Fill::ALL
        .into_iter()
        .find(|f| f.name() == name)
        .ok_or_else(|| {
            let names: Vec<String> = Fill::ALL
                .iter()
                .map(|f| format!("{:?}", f.name()))
                .collect();
            persson_check::Error::invalid("fill", format!("{name:?}"), names.join(" or "))
        })
        .or_raise()
}

/// Checks Persson's theory on the surface of `heights` (a list of 2D float64 arrays, the
/// scans of one surface, NaN where a point is missing) with pixel sides `pixel_size`
/// (between rows, between columns), as `persson-check check-surface` does, and returns
/// the dict of `surface.json`. With `line` (or any 1D array) the arrays are line scans
/// (a 1D array a profile, a 2D one rows of profiles), checked on `line_seeds` surfaces of
/// side `line_side` synthesized with the spectrum they imply. `out` also writes the page and its files there; `verbose`
/// writes one line per load to `sys.stderr` as it ends. The GIL is released; Ctrl-C
/// stops the solve under way.
#[pyfunction]
#[pyo3(signature = (heights, pixel_size, unit, periodic, loads, solver, cross_check, cross_check_all, tol, fill, modulus, reentry, out, threads, progress, verbose, line, line_side, line_seeds, max_iterations, despike, extrapolate, cutoff, tip_radius))]
#[allow(clippy::too_many_arguments)]
pub fn check_surface<'py>(
    py: Python<'py>,
    heights: Vec<PyReadonlyArrayDyn<'py, f64>>,
    pixel_size: (f64, f64),
    unit: Option<String>,
    periodic: bool,
    loads: Option<Vec<f64>>,
    solver: &str,
    cross_check: bool,
    cross_check_all: bool,
    tol: f64,
    fill: &str,
    modulus: Option<f64>,
    reentry: bool,
    out: Option<PathBuf>,
    threads: Option<i64>,
    progress: Option<Bound<'py, PyAny>>,
    verbose: bool,
    line: bool,
    line_side: usize,
    line_seeds: u64,
    max_iterations: usize,
    despike: Option<f64>,
    extrapolate: bool,
    cutoff: bool,
    tip_radius: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let request = CheckRequest {
        pixel_size: Some(vec![pixel_size.0, pixel_size.1]),
        periodic,
        options: CheckOptions {
            unit,
            loads,
            solver: parse::solver(solver).or_raise()?,
            cross_check,
            cross_check_all,
            tol,
            fill: self::fill(fill)?,
            modulus,
            reentry,
            max_iterations,
            despike,
            extrapolate,
            cutoff,
            tip_radius,
            ..CheckOptions::default()
        },
        line: LineOptions {
            side: line_side,
            seeds: line_seeds,
        },
    };
    let input = if line || heights.iter().any(|h| h.ndim() == 1) {
        Input::Line(profiles(&heights)?)
    } else {
        Input::Surface(scans(&heights)?)
    };
    let task = request.task(input, None, &Keywords).or_raise()?;
    let count = task.curves();
    let checked = run_logged(py, threads, progress.as_ref(), verbose, |hook| {
        let mut events = |e: Event| log_event(hook, count, e);
        task.run(out.as_deref(), &Keywords, &mut events)
    })?;
    record(py, &checked)
}

/// One surface at several scales, as `check-surface --scales` checks it
/// ([`persson_check::tasks::scales::check_scales`]): `scans` are `(heights, pixel, unit)`,
/// each with its own pixel and unit (a 1D array, or any with `line`, line scans), named
/// `heights[i]` in messages; the other keywords as [`check_surface`]'s, for every areal
/// scan. Returns the dict of `scales.json`.
#[pyfunction]
#[pyo3(signature = (scans, periodic, loads, solver, cross_check, cross_check_all, tol, fill, modulus, reentry, out, threads, progress, verbose, line, max_iterations, despike, extrapolate, cutoff, tip_radius))]
#[allow(clippy::too_many_arguments)]
pub fn check_scales<'py>(
    py: Python<'py>,
    scans: Vec<(PyReadonlyArrayDyn<'py, f64>, f64, Option<String>)>,
    periodic: bool,
    loads: Option<Vec<f64>>,
    solver: &str,
    cross_check: bool,
    cross_check_all: bool,
    tol: f64,
    fill: &str,
    modulus: Option<f64>,
    reentry: bool,
    out: Option<PathBuf>,
    threads: Option<i64>,
    progress: Option<Bound<'py, PyAny>>,
    verbose: bool,
    line: bool,
    max_iterations: usize,
    despike: Option<f64>,
    extrapolate: bool,
    cutoff: bool,
    tip_radius: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    use persson_check::measured::psd::Boundary;
    use persson_check::measured::scales::{Measured, ScaleScan};
    let opts = CheckOptions {
        boundary: if periodic {
            Boundary::Periodic
        } else {
            Boundary::Free
        },
        loads,
        solver: parse::solver(solver).or_raise()?,
        cross_check,
        cross_check_all,
        tol,
        fill: self::fill(fill)?,
        modulus,
        reentry,
        max_iterations,
        despike,
        extrapolate,
        cutoff,
        tip_radius,
        ..CheckOptions::default()
    };
    let (arrays, given): (Vec<_>, Vec<_>) = scans.into_iter().map(|(a, p, u)| (a, (p, u))).unzip();
    let scans = named(&arrays)?
        .into_iter()
        .zip(given)
        .enumerate()
        .map(|(i, ((name, shape, values), (pixel, unit)))| {
            let measured = if line || shape.len() == 1 {
                Measured::Line(
                    Profiles::pool(vec![
                        Profiles::from_values(&name, &shape, values, true).or_raise()?
                    ])
                    .or_raise()?,
                )
            } else {
                Measured::Map(Scan::from_values(&name, &shape, values).or_raise()?)
            };
            Ok(ScaleScan {
                label: format!("heights[{i}]"),
                measured,
                pixel,
                unit,
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let count = scans.len();
    let checked = run_logged(py, threads, progress.as_ref(), verbose, |hook| {
        let mut events = |e: Event| log_event(hook, count, e);
        persson_check::tasks::scales::check_scales(
            scans,
            &opts,
            out.as_deref(),
            &Keywords,
            &mut events,
        )
    })?;
    record(py, &checked)
}

/// A line scan at non-uniform positions `x` (heights `h`, the array named `name` in
/// messages) resampled onto as many evenly spaced points by the library
/// ([`persson_check::tasks::check::resample_profile`]): `(heights, spacing, warning)`.
#[pyfunction]
pub fn resample_line_scan(
    name: &str,
    x: Vec<f64>,
    h: Vec<f64>,
) -> PyResult<(Vec<f64>, f64, String)> {
    let r = task::resample_profile(name, &x, &h).or_raise()?;
    Ok((r.heights, r.pixel, r.warning))
}
