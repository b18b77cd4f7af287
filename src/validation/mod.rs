//! Named validations: each of Persson's assumptions as a reduced experiment with a verdict.
//!
//! What it may use: [`crate::experiments`] and everything below it; nothing above
//! (report, commands).
//!
//! A validation is a declarative file (`validations/<name>.toml`, see [`Definition`]) that
//! names an experiment (the code that runs it, looked up in the [`registry`]), the
//! statistic, Persson's prediction, the paper's finding and the rule for the verdict, and
//! holds two scenes: `reduced` (small, run by `cargo test`) and `full` (paper scale, run
//! from the command line).
//!
//! The [`runner`] splits the scene into the experiment's jobs, runs them in parallel,
//! keeps every finished job's result on disk at once ([`store`]; an interrupted ensemble
//! resumes where it stopped with `--resume`), and turns the experiment's conclusion into
//! an [`Outcome`] with a verdict computed from the data ([`VerdictRule::judge`]), written
//! as `<name>.json`, `<name>.csv` and figures.
//!
//! * [`definition`]: verdict rule, the paper's finding, the two scenes;
//! * [`claims`]: the paper's quantitative statements as data, each decided by one rule;
//! * [`measures`]: where a claim finds its numbers, and the check at load that each measure
//!   a claim names is one its experiment declares;
//! * [`phrase`]: the paper's wordings, each with the one rule it maps to;
//! * [`unit`](mod@unit): what a claim's measure is, and the tolerance each phrase takes on it;
//! * [`register`]: every rule a claim has been decided under, and its amendments;
//! * [`source`]: the built-in definitions and definition folders;
//! * [`outcome`]: the record of a run;
//! * [`store`]: job results and checkpoints on disk;
//! * [`segments`]: the wall time of a job resumed from its checkpoints;
//! * [`runner`]: running one experiment's definition;
//! * [`registry`]: the table of experiments;
//! * [`shard`] and [`plan`]: runs split into shares over many machines (a scheduler's job
//!   array over a shared output folder) and merged into the outcomes of one run;
//! * [`audit`]: stored job results recomputed with this build and compared byte for byte.

pub mod audit;
mod claim_outcome;
pub mod claims;
mod conclusion;
pub mod definition;
mod interval;
mod judge;
pub mod measure;
pub mod measures;
pub mod outcome;
mod pending;
pub mod phrase;
pub mod plan;
pub mod register;
pub mod registry;
pub mod runner;
pub mod segments;
pub mod shard;
pub mod source;
pub mod store;
pub mod unit;

pub use claims::{ClaimOutcome, ClaimResult, ClaimSpec};
pub use definition::{Definition, PaperFinding, Scale, Verdict, VerdictRule};
pub use outcome::Outcome;
pub use registry::{check, run, Registry};
pub use runner::{Mode, RunOptions};
pub use source::Source;

// The outcome's secondary statistics and checks are the experiments' own records.
pub use crate::experiments::{Detail, DetailKey, Guard};
