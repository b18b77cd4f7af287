//! `persson_check._native`: the Rust side of the Python package.
//!
//! Every function here calls the library's tasks ([`persson_check::tasks`]), the same
//! functions the command line calls, so that a solve, its summary, a sweep, the theory and
//! the validations give the same numbers and refuse bad input with the same messages (a
//! flag such as `--p0` named by its keyword `p0`). This crate only converts values,
//! releases the GIL and maps errors:
//!
//! | module | its job |
//! |---|---|
//! | [`errors`] | the library's errors as Python exceptions, in one place |
//! | [`conversions`] | numpy arrays and fields, names, integers, records as dicts |
//! | [`worker`] | the cancellable worker: GIL released, Ctrl-C, progress callbacks |
//! | [`solve`] | `surface`, `solve` and its `Solution` |
//! | [`sweeps`] | `sweep` and its iterator of steps |
//! | [`theory`] | `theory` and the contact-area law |
//! | [`validations`] | `validate`, `plan`, `merge`, `report` |
//! | [`check`] | `check_surface`: Persson on the user's own height maps, and line scans at non-uniform positions resampled; `check_scales`: one surface at several scales |
//!
//! The public signatures, with their defaults, are those of the Python wrappers in
//! `persson_check/__init__.py`, which convert arrays and paths and call these.

mod check;
mod conversions;
mod errors;
mod solve;
mod sweeps;
mod theory;
mod validations;
mod worker;

use pyo3::prelude::*;

use persson_check::tasks::{SolveOptions, SolverKind};

/// Native part of persson_check (use the persson_check package).
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SolveError", m.py().get_type::<errors::SolveError>())?;
    m.add(
        "SOLVERS",
        pyo3::types::PyTuple::new(m.py(), SolverKind::NAMES)?,
    )?;
    // The defaults of `solve` and `sweep`, written once in the library: the wrappers in
    // `persson_check/__init__.py` take them from here.
    m.add("DEFAULT_SOLVER", SolverKind::default().name())?;
    m.add("DEFAULT_TOL", SolveOptions::DEFAULT_TOL)?;
    m.add("DEFAULT_MAX_ITER", SolveOptions::DEFAULT_MAX_ITER)?;
    m.add("CHECK_SURFACE_DEFAULTS", check::defaults(m.py())?)?;
    m.add_class::<solve::Solution>()?;
    m.add_class::<sweeps::Sweep>()?;
    m.add_class::<sweeps::SweepStep>()?;
    m.add_class::<theory::Theory>()?;
    m.add_function(wrap_pyfunction!(solve::surface, m)?)?;
    m.add_function(wrap_pyfunction!(solve::solve, m)?)?;
    m.add_function(wrap_pyfunction!(sweeps::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(theory::theory, m)?)?;
    m.add_function(wrap_pyfunction!(theory::contact_area_law, m)?)?;
    m.add_function(wrap_pyfunction!(validations::validate, m)?)?;
    m.add_function(wrap_pyfunction!(validations::plan, m)?)?;
    m.add_function(wrap_pyfunction!(validations::merge, m)?)?;
    m.add_function(wrap_pyfunction!(validations::report_md, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_surface, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_scales, m)?)?;
    m.add_function(wrap_pyfunction!(check::resample_line_scan, m)?)?;
    Ok(())
}
