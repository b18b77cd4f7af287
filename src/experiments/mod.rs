//! Experiments: the measurements behind the validations, one module per thing measured.
//!
//! What it may use: [`crate::engine`], [`crate::persson`], [`crate::stats`],
//! [`crate::plot`] (figure descriptions) and [`crate::io`]; nothing above (validations,
//! report, commands).

pub mod contact_area;
pub mod modes;
pub mod reentry;
pub mod total_energy;
pub mod transitions;
