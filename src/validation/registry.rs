//! The registry: which code runs a definition's `experiment = "..."`.
//!
//! [`BUILTIN`] is the one table that names every experiment. Adding an experiment is its
//! module under [`crate::experiments`] (a type implementing [`Experiment`]) and one line
//! here; running, checking and listing follow from the table. A [`Registry`] can also be
//! extended at run time ([`Registry::with`]), which is how the tests register an
//! experiment of their own.

use std::marker::PhantomData;

use super::definition::Scale;
use super::outcome::Outcome;
use super::plan::PlannedUnit;
use super::runner::{check_experiment, declared_keys, planned_units, run_experiment, RunOptions};
use super::source::Source;
use crate::error::{Error, Result};
use crate::experiments::{
    contact_area, flux, modes, reentry, source, total_energy, transitions, Experiment, Keys,
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
    /// The measures the experiment declares for the definition's scene at `scale`.
    fn keys(&self, source: &Source, scale: Scale) -> Result<Keys>;
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

    fn keys(&self, source: &Source, scale: Scale) -> Result<Keys> {
        declared_keys::<E>(source, scale)
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

    fn keys(&self, source: &Source, scale: Scale) -> Result<Keys> {
        self.0.keys(source, scale)
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

    /// Checks `source` without running it: its header, the experiment it names, the
    /// ranges of both of its scenes and the measures its claims name. Errors name the file,
    /// the scene's table and the field.
    pub fn check(&self, source: &Source) -> Result<()> {
        self.entry(source)?.check(source)
    }

    /// The measures the experiment of `source` declares for its scene at `scale` (detail
    /// keys and studies), once the definition is checked at that scale.
    pub fn keys(&self, source: &Source, scale: Scale) -> Result<Keys> {
        self.entry(source)?.keys(source, scale)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validation::source::builtin_sources;

    /// The shipped definition `name`.
    fn shipped(name: &str) -> Source {
        builtin_sources()
            .into_iter()
            .find(|s| s.path.to_string_lossy() == format!("builtin:{name}"))
            .expect("a shipped definition")
    }

    /// The shipped definition `name` with `from` replaced by `to` (which must occur).
    fn edited(name: &str, from: &str, to: &str) -> Source {
        let s = shipped(name);
        assert!(s.text.contains(from), "{name}: no {from}");
        Source {
            text: s.text.replace(from, to),
            ..s
        }
    }

    /// The error of checking `source`, which must be refused.
    fn refused(source: &Source) -> String {
        check(source).expect_err("a refused definition").to_string()
    }

    #[test]
    fn every_shipped_definition_names_declared_measures() {
        for s in builtin_sources() {
            check(&s).unwrap_or_else(|e| panic!("{}: {e}", s.path.display()));
        }
    }

    #[test]
    fn a_mistyped_key_is_refused_when_the_definition_loads() {
        // A claim's own measure: the field, the key named and the declared keys closest.
        let e = refused(&edited(
            "c_reentry",
            "measure = \"detail:share_ar0.14\"",
            "measure = \"detail:share_ar0.15\"",
        ));
        for word in [
            "[full]",
            "claims.share_ar0.14.measure",
            "detail:share_ar0.15",
            "share_ar0.14",
            "share_ar0.014",
        ] {
            assert!(e.contains(word), "{word}: {e}");
        }
        // An ordering's second measure.
        let e = refused(&edited(
            "contact_area",
            "exceeds = \"detail:c2_fit\"",
            "exceeds = \"detail:c2_fits\"",
        ));
        assert!(e.contains("claims.c1_exceeds_c2.rule.exceeds"), "{e}");
        // Another reading's measure.
        let e = refused(&edited(
            "e_frozen",
            "measure = \"detail:change_ar0.87_zt16\"",
            "measure = \"detail:change_ar0.87_zt32\"",
        ));
        assert!(
            e.contains("claims.frozen_holds_near_full_contact.other_readings[3].measure"),
            "{e}"
        );
        // A grid the scene does not have, a study's column, a cross-check where the scene
        // fixes its solver.
        let e = refused(&edited(
            "contact_area",
            "measure = \"detail:law_deviation\"",
            "measure = \"detail:kappa_on_grid@100\"",
        ));
        assert!(
            e.contains("claims.law_within_10pct.measure") && e.contains("kappa_on_grid@512"),
            "{e}"
        );
        let e = refused(&edited(
            "e_frozen",
            "study:asymptote_law/mode/k1\"",
            "study:asymptote_law/mode/k3\"",
        ));
        assert!(
            e.contains("claims.k1.measure") && e.contains("k1, k2"),
            "{e}"
        );
        let e = refused(&edited(
            "c_source",
            "value = 0.0\nmeasure = \"headline\"\nrule = { above = 0.0 }",
            "value = 0.0\nmeasure = \"cross_check:gfmd\"\nrule = { above = 0.0 }",
        ));
        assert!(
            e.contains("claims.points_re_enter.measure") && e.contains("fixes its solver"),
            "{e}"
        );
    }

    #[test]
    fn a_claim_the_reduced_scene_does_not_judge_needs_the_full_scenes_keys_only() {
        // d_onset's onset at a_r = 0.87 on the zeta_t = 16 band: a load and a band of the
        // full scene alone, named by a claim with `reduced = false`.
        let s = shipped("d_onset");
        let reduced = Registry::builtin().keys(&s, Scale::Reduced).unwrap();
        let full = Registry::builtin().keys(&s, Scale::Full).unwrap();
        let key = "onset_ar0.87_zt16".into();
        assert!(!reduced.has_detail(&key, None));
        assert!(full.has_detail(&key, None));
        // The same measure on a claim the reduced scene judges is refused there.
        let e = refused(&edited(
            "d_onset",
            "measure = \"detail:peak_over_zeta_t\"",
            "measure = \"detail:onset_ar0.87_zt16\"",
        ));
        assert!(
            e.contains("[reduced]") && e.contains("claims.peaks_above_resolution.measure"),
            "{e}"
        );
    }
}
