//! A probe for changes to the FIRE solver that must not change its numerics: the solves of
//! the GFMD probe ([`crate::gfmd_bits::probe`]: cold, warm, a load search and a sweep of a
//! few shells, two failing solves) by FIRE. Run before and after a change and compare:
//!
//! `cargo test --test suite fire_bits -- --ignored --nocapture`

use persson_check::engine::solver::Fire;

use crate::gfmd_bits::probe;

#[test]
#[ignore = "a probe: prints digests to compare before and after a change"]
fn fire_bits() {
    probe(&|| Box::new(Fire::default()), "FIRE_BITS_OUT");
}
