//! The check of one surface: its scans solved along a load curve by the headline solver
//! (and the other as a cross-check), Persson's predictions on each scan's own spectrum,
//! and a verdict for each comparison. In three parts: the options and the check of the
//! scans before any work ([`super::options`]), the curves run with their time budgets
//! ([`super::curves`]), and the findings that `surface.json` and the page show
//! ([`super::findings`], drawn by `conclude`); gathered here under one name.

pub use super::curves::{check, Event, CROSS_CHECKED_LOADS, CROSS_CHECK_MIN_S, CROSS_CHECK_TIME};
pub use super::findings::{
    Comparison, CurvePoint, Distribution, Failure, SolverWork, Statistics, SurfaceCheck, RULE,
    SOLVER_AGREEMENT,
};
pub use super::options::{validate, CheckOptions};
