//! The validations (`persson-check validate`, Python's `validate`, `plan` and `merge`):
//! which definitions, checked before anything runs; their jobs with estimated costs and
//! shares (the plan, [`crate::validation::plan`]); the merge of the job results that
//! shares stored; and the run, one definition after the other, where one failure does not
//! stop the others.

use std::path::{Path, PathBuf};

use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};
use crate::validation::plan::Plan;
use crate::validation::source::{builtin_sources, select, sources_in, Source};
use crate::validation::{Mode, Outcome, Registry, RunOptions, Scale};

use super::Spelling;

/// The definitions named (all when `names` is empty), from the folder `dir` (at least one
/// `*.toml` there) or the built-in copies of `validations/`.
///
/// # Errors
///
/// If `dir` cannot be read or holds no `*.toml` file, a definition cannot be read, or a
/// name in `names` is none of the definitions'.
pub fn definitions(dir: Option<&Path>, names: &[String], s: &dyn Spelling) -> Result<Vec<Source>> {
    let sources = match dir {
        Some(dir) => {
            let sources = sources_in(dir)?;
            if sources.is_empty() {
                return Err(Error::invalid(
                    &s.name("dir"),
                    format!("{} (no *.toml files)", dir.display()),
                    "a folder of validation definitions (*.toml)",
                ));
            }
            sources
        }
        None => builtin_sources(),
    };
    select(sources, names)
}

/// Checks every definition (header, experiment, both scenes' ranges) before any runs:
/// bad input writes nothing.
///
/// # Errors
///
/// The first definition's error: its header, experiment or a scene's range.
pub fn check(registry: &Registry, sources: &[Source]) -> Result<()> {
    sources.iter().try_for_each(|source| registry.check(source))
}

/// The options of a run: reduced or `full` scenes, into `out`, continuing from the job
/// results there (`resume`), with progress bars or not, with the `solvers` given (the first
/// for the headline, each other for a cross-check; none: [`RunOptions::DEFAULT_SOLVERS`]),
/// every job to its outcome.
pub fn run_options(
    full: bool,
    out: PathBuf,
    resume: bool,
    progress: bool,
    solvers: &[SolverKind],
) -> RunOptions {
    RunOptions {
        scale: if full { Scale::Full } else { Scale::Reduced },
        out,
        resume,
        progress,
        solvers: if solvers.is_empty() {
            RunOptions::DEFAULT_SOLVERS.to_vec()
        } else {
            solvers.to_vec()
        },
        mode: Mode::All,
    }
}

/// The jobs of `sources` run with `opts`, with their estimated costs, split into `shards`
/// shares when given.
///
/// # Errors
///
/// If a definition's jobs cannot be made (its scene is out of range).
pub fn plan(
    registry: &Registry,
    sources: &[Source],
    opts: &RunOptions,
    shards: Option<usize>,
) -> Result<Plan> {
    let mut units = Vec::new();
    for source in sources {
        units.extend(registry.jobs(source, opts)?);
    }
    Ok(Plan::new(units, shards))
}

/// Sets `opts` to merge the job results the shares stored under `opts.out`, once every
/// job of `plan` has a result there under its job key (computed by this commit, unless
/// `accept_other_commit`: see [`Plan::check_merge`]); nothing is written otherwise. With
/// `partial`, the optional parts of a scene whose jobs lack results are left out and
/// recorded as pending.
///
/// # Errors
///
/// If a job of `plan` has no result under `opts.out` (one of an optional part is allowed
/// with `partial`), or one computed by another commit unless `accept_other_commit`
/// ([`Plan::check_merge`]).
pub fn merge(
    plan: &Plan,
    accept_other_commit: bool,
    partial: bool,
    opts: &mut RunOptions,
) -> Result<()> {
    plan.check_merge(accept_other_commit, partial)?;
    opts.mode = Mode::Merge {
        other_commits_accepted: accept_other_commit,
        partial,
    };
    Ok(())
}

/// Runs the definitions in turn while `proceed()` says so (it is asked before each):
/// each definition's outcome (`None` for a share of a sharded run) or its error.
pub fn run(
    registry: &Registry,
    sources: &[Source],
    opts: &RunOptions,
    proceed: &dyn Fn() -> bool,
) -> Vec<(PathBuf, Result<Option<Outcome>>)> {
    let mut results = Vec::new();
    for source in sources {
        if !proceed() {
            break;
        }
        results.push((source.path.clone(), registry.run(source, opts)));
    }
    results
}
