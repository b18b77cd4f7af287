//! The two studies of the one-step flux, each run once with the headline solver's jobs:
//!
//! * `sensitivity.rs`: the flux again while one setting at a time moves away from a base
//!   configuration, one row each (a table of [`crate::experiments::study`]);
//! * `reading.rs`: those rows read against the paper's one-step flux, as notes;
//! * `waterfall.rs`: the cross-section waterfall of the paper's figure
//!   "reentry_waterfall", its plan, its run and its figure.

pub mod reading;
pub mod sensitivity;
pub mod waterfall;
