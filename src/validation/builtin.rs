//! The experiments this build knows, and the validation definitions shipped with it.
//!
//! The definitions in `validations/` are compiled in, so the command line runs the default
//! validations from any directory; `--dir` reads definitions from a folder instead. A test
//! checks that the compiled-in copies equal the files.

use std::path::{Path, PathBuf};

use super::runner::{check_experiment, run_experiment};
use super::{Outcome, RunOptions, Source};
use crate::error::{Error, Result};

/// Experiment names accepted in a definition's `experiment` key.
pub const EXPERIMENTS: &[&str] = &[
    "contact_area",
    "diffusion",
    "drift",
    "mode_frozen",
    "mode_onset",
    "reentry",
    "total_energy",
];

/// Runs `source` with the experiment named `experiment`.
pub fn dispatch(experiment: &str, source: &Source, opts: &RunOptions) -> Result<Outcome> {
    match experiment {
        "contact_area" => {
            run_experiment::<crate::experiments::contact_area::ContactArea>(source, opts)
        }
        "diffusion" => run_experiment::<crate::experiments::transitions::Diffusion>(source, opts),
        "drift" => run_experiment::<crate::experiments::transitions::Drift>(source, opts),
        "reentry" => run_experiment::<crate::experiments::reentry::Reentry>(source, opts),
        "mode_onset" => run_experiment::<crate::experiments::modes::ModeOnset>(source, opts),
        "mode_frozen" => run_experiment::<crate::experiments::modes::ModeFrozen>(source, opts),
        "total_energy" => {
            run_experiment::<crate::experiments::total_energy::TotalEnergy>(source, opts)
        }
        other => Err(unknown_experiment(source, other)),
    }
}

/// Checks `source` without running it: its header, the experiment it names, and the
/// ranges of both of its scenes. Errors name the file, the scene's table and the field.
pub fn check(source: &Source) -> Result<()> {
    let (_, experiment) = source.header()?;
    match experiment.as_str() {
        "contact_area" => check_experiment::<crate::experiments::contact_area::ContactArea>(source),
        "diffusion" => check_experiment::<crate::experiments::transitions::Diffusion>(source),
        "drift" => check_experiment::<crate::experiments::transitions::Drift>(source),
        "reentry" => check_experiment::<crate::experiments::reentry::Reentry>(source),
        "mode_onset" => check_experiment::<crate::experiments::modes::ModeOnset>(source),
        "mode_frozen" => check_experiment::<crate::experiments::modes::ModeFrozen>(source),
        "total_energy" => check_experiment::<crate::experiments::total_energy::TotalEnergy>(source),
        other => Err(unknown_experiment(source, other)),
    }
}

fn unknown_experiment(source: &Source, experiment: &str) -> Error {
    Error::bad_file(
        &source.path,
        format!("experiment = \"{experiment}\" is unknown; expected one of {EXPERIMENTS:?}"),
    )
}

/// The definitions compiled into this build: `(name, TOML text)`.
pub const DEFINITIONS: &[(&str, &str)] = &[
    (
        "a_diffusion",
        include_str!("../../validations/a_diffusion.toml"),
    ),
    ("b_drift", include_str!("../../validations/b_drift.toml")),
    (
        "c_reentry",
        include_str!("../../validations/c_reentry.toml"),
    ),
    (
        "contact_area",
        include_str!("../../validations/contact_area.toml"),
    ),
    ("d_onset", include_str!("../../validations/d_onset.toml")),
    ("e_frozen", include_str!("../../validations/e_frozen.toml")),
    (
        "total_energy",
        include_str!("../../validations/total_energy.toml"),
    ),
];

/// The compiled-in definitions as sources.
pub fn builtin_sources() -> Vec<Source> {
    DEFINITIONS
        .iter()
        .map(|(name, text)| Source {
            path: PathBuf::from(format!("builtin:{name}")),
            text: text.to_string(),
        })
        .collect()
}

/// Definitions from `dir` (every `*.toml`, sorted by name).
pub fn sources_in(dir: &Path) -> Result<Vec<Source>> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| Error::io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    paths.iter().map(|p| Source::read(p)).collect()
}

/// Selects definitions by name (all when `names` is empty); unknown names are an error
/// that lists the known ones.
pub fn select(sources: Vec<Source>, names: &[String]) -> Result<Vec<Source>> {
    if names.is_empty() {
        return Ok(sources);
    }
    let mut known = Vec::new();
    for s in &sources {
        known.push(s.header()?.0);
    }
    let mut out = Vec::new();
    for name in names {
        match known.iter().position(|k| k == name) {
            Some(i) => out.push(sources[i].clone()),
            None => {
                return Err(Error::invalid(
                    "validation name",
                    name,
                    format!("one of {known:?}"),
                ))
            }
        }
    }
    Ok(out)
}
