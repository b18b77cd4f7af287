//! The registry: which code runs a definition's `experiment = "..."`.
//!
//! [`BUILTIN`] is the one table that names every experiment. Adding an experiment is its
//! module under [`crate::experiments`] (a type implementing [`Experiment`]) and one line
//! here; running, checking and listing follow from the table. A [`Registry`] can also be
//! extended at run time ([`Registry::with`]), which is how the tests register an
//! experiment of their own.

use std::marker::PhantomData;

use super::outcome::Outcome;
use super::plan::PlannedUnit;
use super::runner::{check_experiment, planned_units, run_experiment, RunOptions};
use super::source::Source;
use crate::error::{Error, Result};
use crate::experiments::{
    contact_area, flux, modes, reentry, source, total_energy, transitions, Experiment,
};

/// What the runner needs of an experiment, without its types.
pub trait Entry: Send + Sync {
    /// Runs a definition of this experiment: its outcome, or `None` for one share of a
    /// sharded run ([`super::runner::Mode`]).
    fn run(&self, source: &Source, opts: &RunOptions) -> Result<Option<Outcome>>;
    /// Checks a definition of this experiment (both scenes) without running it.
    fn check(&self, source: &Source) -> Result<()>;
    /// The jobs a run of the definition with `opts` would run, with their costs.
    fn jobs(&self, source: &Source, opts: &RunOptions) -> Result<Vec<PlannedUnit>>;
}

/// The registry's entry for the experiment type `E`: runs, checks and plans a definition
/// through `E`'s [`Experiment`] implementation. It holds no data, only the type.
pub struct EntryOf<E>(PhantomData<fn() -> E>);

impl<E> EntryOf<E> {
    /// The entry (a constant, so that [`BUILTIN`] can hold a `'static` reference to it).
    pub const NEW: Self = EntryOf(PhantomData);
}

impl<E: Experiment> Entry for EntryOf<E> {
    fn run(&self, source: &Source, opts: &RunOptions) -> Result<Option<Outcome>> {
        run_experiment::<E>(source, opts)
    }

    fn check(&self, source: &Source) -> Result<()> {
        check_experiment::<E>(source)
    }

    fn jobs(&self, source: &Source, opts: &RunOptions) -> Result<Vec<PlannedUnit>> {
        planned_units::<E>(source, opts)
    }
}

/// Every built-in experiment, by the name definitions give in `experiment = "..."`.
pub const BUILTIN: &[(&str, &dyn Entry)] = &[
    ("contact_area", &EntryOf::<contact_area::ContactArea>::NEW),
    ("diffusion", &EntryOf::<transitions::Diffusion>::NEW),
    ("drift", &EntryOf::<transitions::Drift>::NEW),
    ("flux", &EntryOf::<flux::Flux>::NEW),
    ("mode_frozen", &EntryOf::<modes::ModeFrozen>::NEW),
    ("mode_onset", &EntryOf::<modes::ModeOnset>::NEW),
    ("reentry", &EntryOf::<reentry::Reentry>::NEW),
    ("source", &EntryOf::<source::BoundarySource>::NEW),
    ("total_energy", &EntryOf::<total_energy::TotalEnergy>::NEW),
];

/// Experiments by name.
pub struct Registry {
    entries: Vec<(String, Box<dyn Entry>)>,
}

/// An entry of [`BUILTIN`] in a [`Registry`]: the `'static` entry borrowed, so that the
/// built-in experiments and those added at run time ([`Registry::with`]) are boxed alike.
struct BuiltinEntry(&'static dyn Entry);

impl Entry for BuiltinEntry {
    fn run(&self, source: &Source, opts: &RunOptions) -> Result<Option<Outcome>> {
        self.0.run(source, opts)
    }

    fn check(&self, source: &Source) -> Result<()> {
        self.0.check(source)
    }

    fn jobs(&self, source: &Source, opts: &RunOptions) -> Result<Vec<PlannedUnit>> {
        self.0.jobs(source, opts)
    }
}

impl Registry {
    /// The built-in experiments ([`BUILTIN`]).
    pub fn builtin() -> Self {
        Self {
            entries: BUILTIN
                .iter()
                .map(|&(name, e)| {
                    (
                        name.to_string(),
                        Box::new(BuiltinEntry(e)) as Box<dyn Entry>,
                    )
                })
                .collect(),
        }
    }

    /// This registry with experiment `E` under `name` (replacing one of that name).
    pub fn with<E: Experiment + 'static>(mut self, name: &str) -> Self {
        self.entries.retain(|(n, _)| n != name);
        self.entries
            .push((name.to_string(), Box::new(EntryOf::<E>::NEW)));
        self
    }

    /// The experiment names, in registration order.
    pub fn names(&self) -> Vec<&str> {
        self.entries.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The entry for `source`'s `experiment`; an unknown name is an error that lists the
    /// known ones.
    pub fn entry(&self, source: &Source) -> Result<&dyn Entry> {
        let (_, experiment) = source.header()?;
        self.entries
            .iter()
            .find(|(n, _)| *n == experiment)
            .map(|(_, e)| e.as_ref())
            .ok_or_else(|| {
                Error::bad_file(
                    &source.path,
                    format!(
                        "experiment = \"{experiment}\" is unknown; expected one of {:?}",
                        self.names()
                    ),
                )
            })
    }

    /// Runs `source`: its outcome, or `None` for one share of a sharded run.
    pub fn run(&self, source: &Source, opts: &RunOptions) -> Result<Option<Outcome>> {
        self.entry(source)?.run(source, opts)
    }

    /// The jobs of `source` run with `opts`, with their costs.
    pub fn jobs(&self, source: &Source, opts: &RunOptions) -> Result<Vec<PlannedUnit>> {
        self.entry(source)?.jobs(source, opts)
    }

    /// Checks `source` without running it: its header, the experiment it names, and the
    /// ranges of both of its scenes. Errors name the file, the scene's table and the field.
    pub fn check(&self, source: &Source) -> Result<()> {
        self.entry(source)?.check(source)
    }
}

/// Runs `source` with the built-in experiments (every job, to its outcome).
pub fn run(source: &Source, opts: &RunOptions) -> Result<Outcome> {
    Registry::builtin()
        .run(source, opts)?
        .ok_or_else(|| Error::bad_file(&source.path, "a share of a run has no outcome"))
}

/// Checks `source` against the built-in experiments.
pub fn check(source: &Source) -> Result<()> {
    Registry::builtin().check(source)
}
