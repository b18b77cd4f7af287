//! The slacks of the geometry: how far apart two magnifications (or wavevectors) may be
//! and still count as one, written once and used by every comparison of that kind.
//!
//! Magnifications are computed in floating point from shells (`zeta = sqrt(k2) L_l / L`),
//! from ladders (`start (end / start)^(k / count)`) and from scenes written in decimal; the
//! same magnification reached two ways may differ in its last bits. A comparison against
//! the end of a range, or between two steps, therefore allows a small relative slack.
//! These are not solver tolerances (those are a solve's options) nor the tolerances of
//! tests; each slack is far below any spacing of the quantities it compares (shells are
//! at least `1 / (2 k2)` apart in relative `|q|^2`; ladders have at most 64 steps per
//! octave) and far above their rounding (`~1e-16` relative).

/// Relative slack on `|k|^2` when deciding whether a shell is resolved at a magnification:
/// a `zeta` computed from a shell's own `|q|` includes that shell despite rounding. Every
/// "is this shell resolved at zeta" decision (grid, surfaces, the spectrum's cutoffs,
/// theory) uses it.
pub const SHELL_SLACK: f64 = 1e-9;

/// Relative slack when a magnification (or a wavevector) is compared with the end of a
/// range: `zeta <= zeta_max (1 + ZETA_SLACK)` counts a `zeta` computed as `zeta_max` as
/// inside, and `zeta > from (1 + ZETA_SLACK)` counts it as not past `from`. Two scenes'
/// ratios of lengths written in decimal (`lambda_l / n`, `lambda_l / lambda_s` of a finer
/// grid against its headline's) are one ratio to this slack too.
pub const ZETA_SLACK: f64 = 1e-12;

/// Relative distance below which two magnification steps are one step: the points of a
/// ladder that close are merged, and a step is found in a ladder to this distance.
pub const STEP_MERGE: f64 = 1e-9;
