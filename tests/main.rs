//! The integration tests, as one crate (one binary, linked once): a module per subject,
//! with the helpers they share in [`common`].

mod architecture;
mod audit;
mod bad_input;
mod cg_bits;
mod check_scales;
mod check_surface;
mod claims;
mod code_shape;
mod common;
mod compare;
mod conformance;
mod determinism;
mod fire_bits;
mod free_bits;
mod gfmd_bits;
mod hard_scenes;
mod old_outcomes;
mod one_realization;
mod persson;
mod readers_fuzz;
mod registry;
mod resume;
mod shard;
mod solvers;
mod validations;
