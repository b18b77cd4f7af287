//! Experiments: the measurements behind the validations, one module per thing measured.
//!
//! What it may use: [`crate::engine`], [`crate::persson`], [`crate::stats`],
//! [`crate::plot`] (figure descriptions, rendered elsewhere) and [`crate::io`]; nothing
//! above it (validations, report, commands).
//!
//! An [`Experiment`]'s scene splits into independent jobs (one realization, or one
//! realization at one load, [`Jobs`]), run one at a time ([`Jobs::run_job`]); the
//! experiment reduces the jobs' results to a [`Conclusion`] in three steps, the same in
//! every experiment ([`Experiment`]): statistics first (pure functions, unit-tested on their
//! own, in a module of statistics), then the findings as data (the headline statistic with
//! its standard error and Persson's value for it, secondary statistics ([`Detail`]),
//! implementation guards ([`Guard`]) and golden values), then a thin builder of the
//! account, tables and figures. The paper's statements are not judged here: each is a
//! claim of the definition, judged once on these findings by
//! [`crate::validation::claims`]. A guard (a counting identity, a conservation law) never
//! enters a verdict; texts print "(no error bar with one realization)" where an error bar
//! would stand.
//!
//! * [`contact_area`]: the contact-area law, `a_r` against `p~0`;
//! * [`transitions`]: assumptions (a) pressure-independent diffusion and (b) no drift;
//! * [`reentry`]: assumption (c), no re-entry into contact;
//! * [`flux`]: assumption (c) in one step, the points that enter and leave contact
//!   between two magnifications (the paper's contact-change figure);
//! * [`source`]: assumption (c) in one step, the share of the zero-pressure bin that
//!   moves into contact (the paper's "about 1%");
//! * [`modes`]: assumptions (d) a mode holds energy only once resolved, (e) and keeps it;
//! * [`total_energy`]: the integrated elastic energy against the original and corrected
//!   theories.
//!
//! The traits are in `experiment.rs`, the findings (criteria, details, checks, tables,
//! the conclusion) in `findings.rs`, the unit tests' reading of the shipped definitions in
//! `shipped.rs`; all are re-exported here.
//!
//! Shared machinery: [`scene`] (the fields every scene repeats, and those of a scene of one
//! step of magnification), [`other_grid`] (the fields of a study's own grid and of its
//! jobs, the Hurst exponent the headline's), [`ensemble`] (the seeds x contact areas job
//! grid and the per-load ensemble statistics), [`climb`] (the fixed-load magnification
//! climb with optional checkpoints), [`contact_change`] (which points entered or left
//! contact in a step, and the maps' packing and colours), [`history`] (every point's
//! contact history over a climb, and the flux over an interval) and [`study`] (the generic
//! table of rows an experiment adds beside its headline); [`keys`] holds the measures an
//! experiment declares for a scene, which claims name.
//! No experiment imports another: what two share lives here.

pub mod climb;
pub mod contact_area;
pub mod declared;
pub use crate::engine::contact_change;
pub mod ensemble;
pub mod flux;
pub use crate::engine::history;
pub mod keys;
pub mod modes;
pub mod other_grid;
pub mod reentry;
pub mod scene;
pub mod source;
pub mod study;
pub mod total_energy;
pub mod transitions;

mod experiment;
mod findings;
#[cfg(test)]
mod shipped;

pub use self::experiment::{keys_of, Experiment, JobContext, JobOf, Jobs, ResultOf, Run, Work};
pub use self::findings::{figure, Conclusion, Criteria, Detail, Guard, Table, UNDECIDED};
pub use self::keys::{DetailKey, Keys};
#[cfg(test)]
pub(crate) use self::shipped::{assert_refused, shipped_scenes, shipped_valid};
