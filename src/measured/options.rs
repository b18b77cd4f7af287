//! How a surface is checked ([`CheckOptions`]), and the check of the options and the
//! scans before any work ([`validate`]): square pixels, a tolerance the solvers accept,
//! loads in range and each once, unit and modulus in range, an iteration budget of at
//! least one, a despiking threshold in range, periodic scans square, every scan of one
//! shape and every point measured or filled.

use serde::{Deserialize, Serialize};

use super::fill::Fill;
use super::psd::Boundary;
use super::scan::{Scan, MIN_SIDE};
use super::units::{check_unit, square_pixel};
use crate::engine::solver::SolverKind;
use crate::error::{check_positive, Error, Result};

/// The iteration budget of every solve unless one is given: a cold CG solve of a measured
/// scan takes some tens to a few hundred iterations, and its stagnation safeguards act
/// after 200 iterations without progress; a solve still short of its
/// tolerance after this many is recorded as failed, with its state, and the check goes on.
pub const MAX_ITERATIONS: usize = 1000;

/// The residual tolerance of every solve unless one is given (looser than the
/// validations' 1e-8: a scan's curve is read to the digits its page prints).
pub const CHECK_TOL: f64 = 1e-6;

/// The headline solver unless one is given: CG, the fastest on a measured scan's free
/// window (its cross-check is GFMD, the first other solver of
/// [`SolverKind::ALL`]).
pub const CHECK_SOLVER: SolverKind = SolverKind::Cg;

/// How a surface is checked.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckOptions {
    /// Pixel sides in the heights' length unit: along axis 0 (between rows) and axis 1
    /// (between columns); equal within [`super::units::SQUARE_PIXEL_TOLERANCE`].
    pub pixel_size: [f64; 2],
    /// The heights' length unit (`None`: unnamed).
    pub unit: Option<String>,
    /// Periodic scans, or measured windows with a free boundary.
    pub boundary: Boundary,
    /// Loads `p0 / E*` (none: the defaults of [`super::theory::default_areas`]).
    pub loads: Option<Vec<f64>>,
    /// The headline solver.
    pub solver: SolverKind,
    /// Also solve with a second solver: the first of [`SolverKind::ALL`] other than the
    /// headline one.
    pub cross_check: bool,
    /// Cross-check every load (else [`super::curves::CROSS_CHECKED_LOADS`] of them).
    pub cross_check_all: bool,
    /// Residual tolerance of every solve.
    pub tol: f64,
    /// Whether the points a scan lacks are filled ([`super::fill`]).
    pub fill: Fill,
    /// The contact modulus `E*` in pascals, for pressures in pascals beside `p0 / E*`.
    pub modulus: Option<f64>,
    /// Whether the re-entry share over magnification is measured
    /// ([`super::reentry`]).
    pub reentry: bool,
    /// The iteration budget of every solve ([`MAX_ITERATIONS`] by default).
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    /// Replace the spikes beyond this many robust deviations before solving
    /// ([`super::spikes::despike`]; `None`: keep every point).
    #[serde(default)]
    pub despike: Option<f64>,
    /// Whether every load is also solved on the scan coarsened by 2 (and 4), for the
    /// contact area extrapolated to a vanishing pixel ([`super::pixel`]).
    #[serde(default = "yes")]
    pub extrapolate: bool,
    /// Whether each scan is cut at its shortest reliable wavelength: the noise floor's
    /// onset, or the tip's radius where given ([`super::cutoff`]).
    #[serde(default = "yes")]
    pub cutoff: bool,
    /// The radius of the instrument's tip, in the heights' unit (`None`: not given).
    #[serde(default)]
    pub tip_radius: Option<f64>,
}

fn yes() -> bool {
    true
}

fn default_max_iterations() -> usize {
    MAX_ITERATIONS
}

impl Default for CheckOptions {
    fn default() -> Self {
        Self {
            pixel_size: [1.0, 1.0],
            unit: None,
            boundary: Boundary::Free,
            loads: None,
            solver: CHECK_SOLVER,
            cross_check: true,
            cross_check_all: false,
            tol: CHECK_TOL,
            fill: Fill::None,
            modulus: None,
            reentry: true,
            max_iterations: MAX_ITERATIONS,
            despike: None,
            extrapolate: true,
            cutoff: true,
            tip_radius: None,
        }
    }
}

/// The solver that cross-checks `solver`: the first of [`SolverKind::ALL`] other than it.
/// The list starts with the paper's method, so every other headline is checked against
/// it, and the paper's method against the next solver of the list (GFMD and CG check each
/// other; a solver added to the list is checked against GFMD).
pub(super) fn other(solver: SolverKind) -> SolverKind {
    SolverKind::ALL
        .into_iter()
        .find(|&s| s != solver)
        .expect("the list holds more than one solver")
}

/// Checks the options and the scans (before any work); returns the pixel size.
pub fn validate(scans: &[Scan], opts: &CheckOptions) -> Result<f64> {
    let pixel = square_pixel(opts.pixel_size)?;
    crate::engine::solver::SolveOptions::with_tol(opts.tol).validate()?;
    if opts.max_iterations == 0 {
        return Err(Error::invalid(
            "max_iterations",
            0,
            "at least 1 iteration per solve",
        ));
    }
    if let Some(k) = opts.despike {
        super::spikes::check_threshold(k)?;
    }
    if let Some(r) = opts.tip_radius {
        check_positive("tip_radius", r)?;
        if !opts.cutoff {
            return Err(Error::invalid(
                "tip_radius",
                r,
                "left out with no cutoff (the tip's radius sets a cutoff)",
            ));
        }
    }
    if let Some(given) = &opts.loads {
        super::theory::check_loads(given)?;
        crate::error::check_once("loads", given)?;
    }
    if let Some(unit) = &opts.unit {
        check_unit(unit)?;
    }
    if let Some(modulus) = opts.modulus {
        check_positive("modulus", modulus)?;
    }
    let Some(first) = scans.first() else {
        return Err(Error::invalid(
            "heights",
            "no scan",
            "at least one height map",
        ));
    };
    if first.shape.rows.min(first.shape.cols) < MIN_SIDE {
        return Err(Error::invalid(
            "heights",
            format!(
                "{} of {} points (rows x columns)",
                first.source.display(),
                first.shape
            ),
            format!(
                "a height map of at least {MIN_SIDE} x {MIN_SIDE} points: a smaller one \
                 holds too few contact points to draw a contact curve (a few at the lowest \
                 loads, its area moving in steps of one point)"
            ),
        ));
    }
    if opts.boundary == Boundary::Periodic && !first.shape.is_square() {
        return Err(Error::invalid(
            "periodic",
            format!("a {} scan (rows x columns)", first.shape),
            "square scans (the periodic solvers' grid is square): solve a rectangular \
             scan with a free boundary (without periodic), or crop it to a square",
        ));
    }
    for s in scans {
        if s.shape != first.shape {
            return Err(Error::bad_file(
                &s.source,
                format!(
                    "{} points (rows x columns), the first scan ({}) has {}: scans of one \
                     surface share their shape",
                    s.shape,
                    first.source.display(),
                    first.shape
                ),
            ));
        }
        let missing = s.missing();
        if let Some((row, col)) = missing.first {
            return Err(Error::bad_file(
                &s.source,
                format!(
                    "{} of {} heights are undefined, the first at row {row}, column {col}: \
                     fill them first (see measured::fill)",
                    missing.count,
                    s.heights.len()
                ),
            ));
        }
    }
    Ok(pixel)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// GFMD and CG check each other, as they always have; every solver of the list is
    /// checked by another one.
    #[test]
    fn every_solver_is_cross_checked_by_another() {
        assert_eq!(other(SolverKind::Gfmd), SolverKind::Cg);
        assert_eq!(other(SolverKind::Cg), SolverKind::Gfmd);
        for kind in SolverKind::ALL {
            assert_ne!(other(kind), kind, "{}", kind.name());
        }
    }
}
