//! The validations from Python: `validate`, `plan` and `merge` do what
//! `persson-check validate`, `validate --plan` and `validate --merge` do (the same
//! definitions, checks, plan and files), and `report` what `persson-check report` does.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::PyDict;

use persson_check::error::Error;
use persson_check::report::ReportOptions;
use persson_check::tasks::parse::{self, MAX_SHARDS};
use persson_check::tasks::{check_out_dir, check_out_file, validations as task, Keywords};
use persson_check::validation::source::Source;
use persson_check::validation::{Registry, RunOptions};

use crate::conversions::{name_list, record};
use crate::errors::{to_py, OrRaise};
use crate::worker::{run_blocking, Hook};

/// The options of a run from Python (no progress bars), `solver` a name or a list of
/// names (the first for the headline, each other for a cross-check; None: the default).
fn run_options(
    full: bool,
    out: PathBuf,
    resume: bool,
    solver: Option<&Bound<'_, PyAny>>,
) -> PyResult<RunOptions> {
    let solvers = name_list(solver)?
        .iter()
        .map(|name| parse::solver(name))
        .collect::<persson_check::Result<Vec<_>>>()
        .or_raise()?;
    Ok(task::run_options(full, out, resume, false, &solvers))
}

/// Runs the definitions, checked first, with `opts`; stops between definitions when
/// cancelled. The outcomes, or an error naming every definition that failed.
fn run_definitions(
    hook: &Hook,
    sources: &[Source],
    opts: &RunOptions,
) -> persson_check::Result<Vec<persson_check::validation::Outcome>> {
    let registry = Registry::builtin();
    task::check(&registry, sources)?;
    // Once cancelled, the worker's caller raises `KeyboardInterrupt` whatever this returns.
    let results = task::run(&registry, sources, opts, &|| !hook.cancelled());
    let mut outcomes = Vec::new();
    let mut failed = Vec::new();
    for (path, result) in results {
        match result {
            Ok(Some(o)) => outcomes.push(o),
            Ok(None) => {}
            Err(e) => failed.push(format!("{}: {e}", path.display())),
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
/// scenes; `solver`, a name of `SOLVERS` or a list of them, chooses the solvers (the first
/// for the headline, each other for a cross-check; default "gfmd" and "cg"); `resume=True` reuses the job
/// results already in `out`; `dir` reads the definitions from a folder of `.toml` files.
/// The GIL is released while it runs; Ctrl-C takes effect once the validation under way
/// has finished.
#[pyfunction]
#[pyo3(signature = (names, out, full, solver, resume, dir, threads))]
#[allow(clippy::too_many_arguments)]
pub fn validate<'py>(
    py: Python<'py>,
    names: Option<&Bound<'py, PyAny>>,
    out: PathBuf,
    full: bool,
    solver: Option<&Bound<'py, PyAny>>,
    resume: bool,
    dir: Option<PathBuf>,
    threads: Option<i64>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let names = name_list(names)?;
    check_out_dir(&out, &Keywords).or_raise()?;
    let opts = run_options(full, out, resume, solver)?;
    let sources = py
        .detach(|| task::definitions(dir.as_deref(), &names, &Keywords))
        .or_raise()?;
    let outcomes = run_blocking(py, threads, None, |hook| {
        run_definitions(hook, &sources, &opts)
    })?;
    outcomes.iter().map(|o| record(py, o)).collect()
}

/// The jobs of the named validations with their estimated costs (and their shares, with
/// `shards`), as `persson-check validate NAMES --plan` prints them, as a dict. With `out`,
/// the measured time of every finished job there is added.
#[pyfunction]
#[pyo3(signature = (names=None, shards=None, full=false, solver=None, out=None, dir=None))]
pub fn plan<'py>(
    py: Python<'py>,
    names: Option<&Bound<'py, PyAny>>,
    shards: Option<i64>,
    full: bool,
    solver: Option<&Bound<'py, PyAny>>,
    out: Option<PathBuf>,
    dir: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let names = name_list(names)?;
    let shards = shards
        .map(|k| parse::integer("shards", k, 1, MAX_SHARDS, &Keywords))
        .transpose()
        .or_raise()?;
    let opts = run_options(full, out.unwrap_or_default(), false, solver)?;
    let plan = py
        .detach(|| {
            let sources = task::definitions(dir.as_deref(), &names, &Keywords)?;
            let registry = Registry::builtin();
            task::check(&registry, &sources)?;
            task::plan(&registry, &sources, &opts, shards.map(|k| k as usize))
        })
        .or_raise()?;
    record(py, &plan)
}

/// Writes the outcomes of the named validations from the job results that shares stored
/// under `out/jobs/`, exactly as `persson-check validate NAMES --merge --out OUT` does,
/// and returns them as a list of dicts. Runs no job; every job's result must be there, but
/// for those of a scene's optional parts with `partial` (`--partial`).
#[pyfunction]
#[pyo3(signature = (names, out, full, solver, accept_other_commit, dir, partial))]
#[allow(clippy::too_many_arguments)]
pub fn merge<'py>(
    py: Python<'py>,
    names: Option<&Bound<'py, PyAny>>,
    out: PathBuf,
    full: bool,
    solver: Option<&Bound<'py, PyAny>>,
    accept_other_commit: bool,
    dir: Option<PathBuf>,
    partial: bool,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let names = name_list(names)?;
    let mut opts = run_options(full, out, false, solver)?;
    let outcomes = run_blocking(py, None, None, |hook| {
        let sources = task::definitions(dir.as_deref(), &names, &Keywords)?;
        let registry = Registry::builtin();
        task::check(&registry, &sources)?;
        let plan = task::plan(&registry, &sources, &opts, None)?;
        task::merge(&plan, accept_other_commit, partial, &mut opts)?;
        run_definitions(hook, &sources, &opts)
    })?;
    outcomes.iter().map(|o| record(py, o)).collect()
}

/// Writes the Markdown scorecard of the outcomes in folder `source`, as
/// `persson-check report --from SOURCE --out OUT` does (`golden` is a folder of
/// `<name>.snap` files to compare golden values with; a speed study in `source` is
/// shown), reading `source` only, and returns a dict: path, validations, attention, files.
#[pyfunction(name = "report")]
#[pyo3(signature = (source, out, golden))]
pub fn report_md<'py>(
    py: Python<'py>,
    source: PathBuf,
    out: PathBuf,
    golden: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    if !source.is_dir() {
        return Err(to_py(Error::invalid(
            "source",
            source.display(),
            "an existing folder of outcomes (<name>.json), as written by validate",
        )));
    }
    check_out_file(&out, &Keywords).or_raise()?;
    if let Some(dir) = golden.as_deref().filter(|d| !Path::is_dir(d)) {
        return Err(to_py(Error::invalid(
            "golden",
            dir.display(),
            "an existing folder of <name>.snap files",
        )));
    }
    let opts = ReportOptions {
        from: source,
        out,
        golden,
    };
    let summary = py
        .detach(|| persson_check::report::write(&opts))
        .or_raise()?;
    let d = PyDict::new(py);
    d.set_item("path", summary.path.display().to_string())?;
    d.set_item("validations", summary.validations)?;
    d.set_item("attention", summary.attention)?;
    let files: Vec<String> = summary
        .files
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    d.set_item("files", files)?;
    Ok(d)
}
