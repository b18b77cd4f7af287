//! The keys of `total_energy`'s details at the headline grid: each built by one function,
//! called where the detail is declared and written ([`super::stats`]).

use crate::experiments::keys::{DetailKey, Tag};

/// The keys of a load's details: both theories' ratios at full resolution, the corrected
/// one's at the lowest magnification, and `S~` over window `w`.
pub(super) fn original_key(a: f64) -> DetailKey {
    DetailKey::new("original").at(Tag::ContactArea, a)
}
pub(super) fn corrected_key(a: f64) -> DetailKey {
    DetailKey::new("corrected").at(Tag::ContactArea, a)
}
pub(super) fn corrected_start_key(a: f64) -> DetailKey {
    DetailKey::new("corrected_start").at(Tag::ContactArea, a)
}
pub(super) fn s_tilde_key(a: f64, w: usize) -> DetailKey {
    DetailKey::new("s_tilde")
        .at(Tag::ContactArea, a)
        .at(Tag::Window, w as f64)
}

/// The key of the corrected ratio at the load nearest `p~0 = 0.1` at the lowest
/// magnification, and at the step nearest each of [`NEAR_P01_ZETAS`] ([`near_p01_key`]).
pub(super) const NEAR_P01_START: &str = "corrected_start_p0.1";
pub(super) const NEAR_P01_ZETAS: [f64; 2] = [2.0, 4.0];
pub(super) fn near_p01_key(zeta: f64) -> DetailKey {
    DetailKey::new("corrected")
        .at(Tag::Pressure, 0.1)
        .at(Tag::Zeta, zeta)
}
/// E_exa / E_c of a load at the step nearest zeta = 2 and 4 (the caption's "low
/// magnification" beyond zeta = 1).
pub(super) fn corrected_at_key(a: f64, zeta: f64) -> DetailKey {
    corrected_key(a).at(Tag::Zeta, zeta)
}
