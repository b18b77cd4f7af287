//! The two studies of the one-step flux, each run once with the headline solver's jobs:
//!
//! * `sensitivity/`: the flux again while one setting at a time moves away from a base
//!   configuration, one row each: the plan and its rows (`mod.rs`), one job's solve
//!   (`step.rs`) and the table of [`crate::experiments::study`] (`table.rs`);
//! * `reading/`: those rows read against the paper's one-step flux (`mod.rs`), and the
//!   scorecard's notes on them (`notes.rs`);
//! * `waterfall.rs`: the cross-section waterfall of the paper's figure
//!   "reentry_waterfall", its plan, its run and its figure.

pub mod reading;
pub mod sensitivity;
pub mod waterfall;
