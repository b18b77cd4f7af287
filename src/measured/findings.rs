//! The check's findings as data: `surface.json` ([`SurfaceCheck`]) and its parts (the load
//! curve, the comparisons with their verdicts, the pressure distribution, the surface's
//! statistics, the failures and the solvers' work), with the rule every comparison is
//! decided by ([`RULE`]). `conclude` draws them from the scans' measurements.

use serde::{Deserialize, Serialize};

use super::cutoff::Cutoff;
use super::fill::Fill;
use super::pixel::PixelEstimate;
use super::psd::{Boundary, RadialBin, Shape};
use super::reentry::Reentry;
use super::warnings::Warning;
use crate::engine::solver::SolverKind;
use crate::stats::Estimate;
use crate::validation::{Verdict, VerdictRule};

/// The rule of every comparison: three standard errors, 10% of Persson's value.
pub const RULE: VerdictRule = VerdictRule {
    significance: 3.0,
    resolution: 0.1,
};

/// Solvers agree when their contact areas and energies differ by less than this, relative.
pub const SOLVER_AGREEMENT: f64 = 0.01;

/// One load of the curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurvePoint {
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// The load in pascals (with `--modulus`).
    pub p0_pa: Option<f64>,
    /// Contact area (headline solver), mean over scans.
    pub a_r: f64,
    /// Its standard error over scans (absent with one scan).
    pub a_r_std_error: Option<f64>,
    /// Contact area by the cross-check solver (absent where it failed).
    pub a_r_cross_check: Option<f64>,
    /// Persson's original theory.
    pub a_r_persson: f64,
    /// Persson's corrected theory.
    pub a_r_persson_corrected: f64,
    /// The pixel's own error: `a_r` on the coarsened scan and extrapolated to a vanishing
    /// pixel ([`super::pixel`]; absent when not asked for, or the scan is too small to
    /// coarsen).
    #[serde(default)]
    pub pixel: Option<PixelEstimate>,
    /// `a_r / a_r,P` over the scans, with `a_r` extrapolated to a vanishing pixel where
    /// [`CurvePoint::pixel`] is there.
    pub area_ratio: Estimate,
    /// The contact-area verdict at this load.
    pub area_verdict: Verdict,
    /// The mean pressure in contact, `p0 / a_r`, in units of `E*`.
    pub contact_pressure: f64,
    /// Whether it is far past the yield of any material
    /// ([`super::warnings::CONTACT_PRESSURE`]).
    pub past_yield: bool,
    /// Elastic energy per unit area (`E*` times the length unit).
    pub energy: f64,
    /// Its standard error over scans.
    pub energy_std_error: Option<f64>,
    /// Energy by the cross-check solver.
    pub energy_cross_check: Option<f64>,
    /// Persson's energy, original theory.
    pub energy_persson: f64,
    /// Persson's energy, corrected theory.
    pub energy_persson_corrected: f64,
    /// `E_el / E_P` over the scans.
    pub energy_ratio: Estimate,
    /// The energy verdict at this load.
    pub energy_verdict: Verdict,
}

/// The pressure distribution at one load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Distribution {
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// Histogram bins: centre in `p / p0`, measured density (per unit `p / p0`, over all
    /// points, so that it integrates to `a_r`), Persson's original and corrected.
    pub bins: Vec<[f64; 4]>,
    /// Rms pressure over Persson's (original), over the scans.
    pub rms_ratio: Estimate,
    /// Its verdict.
    pub verdict: Verdict,
}

/// One comparison's summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// Short name: `contact_area`, `elastic_energy`, `pressure_distribution`.
    pub name: String,
    /// What is compared.
    pub statistic: String,
    /// The verdict over its loads.
    pub verdict: Verdict,
}

/// A solver's work on the surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SolverWork {
    /// The solver.
    pub solver: SolverKind,
    /// Iterations over every load and scan solved.
    pub iterations: usize,
    /// The largest residual of the solves that converged.
    pub max_residual: f64,
    /// Solves that failed.
    pub failed: usize,
    /// Wall time of its curves, seconds.
    pub wall_s: f64,
}

/// A solve that failed: where, and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    /// The scan.
    pub scan: String,
    /// The solver.
    pub solver: SolverKind,
    /// Whether it was the headline solve (else the cross-check).
    pub headline: bool,
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// The solver's message, naming the solver and the load.
    pub message: String,
    /// Wall time spent on it, seconds.
    pub wall_s: f64,
    /// Where the solver stopped (iterations, residual against tol, points in contact),
    /// when it said.
    #[serde(default)]
    pub state: Option<super::body::SolveState>,
}

/// The surface's statistics, means over the scans.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Statistics {
    /// Rms height (length unit), after detrending.
    pub h_rms: Estimate,
    /// Rms slope from finite differences.
    pub slope_rms: Estimate,
    /// Rms slope from the spectrum (Persson's `g_bar`).
    pub slope_rms_spectral: Estimate,
    /// Skewness of the heights.
    pub skewness: Estimate,
    /// Excess kurtosis of the heights.
    pub kurtosis: Estimate,
    /// `sqrt(l_min / l_max)` of the slope tensor.
    pub anisotropy: Estimate,
    /// Log-log slope of `C(q)` over the highest octave (absent where too few bins).
    pub high_q_slope: Option<Estimate>,
    /// The radially averaged power spectrum, mean over scans.
    pub psd: Vec<RadialBin>,
}

/// The scans' short-wavelength cutoffs ([`super::cutoff`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Cutoffs {
    /// Whether a cutoff was asked for (`--no-cutoff` not given).
    pub asked: bool,
    /// The tip's radius given, in the length unit.
    pub tip_radius: Option<f64>,
    /// Each scan's cutoff, where it has one.
    pub scans: Vec<Option<Cutoff>>,
    /// Persson's `g_bar` of the heights solved (after the cutoff), mean over scans.
    pub slope_rms_spectral: Option<Estimate>,
}

/// Everything the check found: `surface.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceCheck {
    /// The scans' files.
    pub scans: Vec<String>,
    /// Rows of every scan.
    pub rows: usize,
    /// Columns of every scan.
    pub cols: usize,
    /// The pixel size used (the geometric mean of the sides given).
    pub pixel_size: f64,
    /// The pixel sides given, along axis 0 and axis 1.
    pub pixel_sides: [f64; 2],
    /// The length unit (absent: unnamed).
    pub unit: Option<String>,
    /// The contact modulus in pascals, when given.
    pub modulus: Option<f64>,
    /// The boundary.
    pub boundary: Boundary,
    /// How missing points were treated.
    pub fill: Fill,
    /// Points filled by interpolation, per scan.
    pub filled: Vec<usize>,
    /// How the spectrum was taken.
    pub spectrum_method: String,
    /// The surface's statistics, as measured (before any cutoff).
    pub statistics: Statistics,
    /// The short-wavelength cutoffs, and the slope of the heights solved.
    #[serde(default)]
    pub cutoff: Cutoffs,
    /// Where the scan lies outside what the theory assumes.
    pub warnings: Vec<Warning>,
    /// The headline solver.
    pub solver: SolverKind,
    /// The cross-check solver, if run.
    pub cross_check: Option<SolverKind>,
    /// Whether the two solvers agree at every load both solved (within
    /// [`SOLVER_AGREEMENT`]).
    pub solvers_agree: Option<bool>,
    /// The loads asked for (`p0 / E*`).
    pub loads: Vec<f64>,
    /// The load curve: the loads every scan's headline solve reached.
    pub curve: Vec<CurvePoint>,
    /// Solves that failed.
    pub failures: Vec<Failure>,
    /// The pressure distribution at the middle load of the curve.
    pub pressure_distribution: Option<Distribution>,
    /// The re-entry share over magnification at the middle load.
    pub reentry: Option<Reentry>,
    /// The comparisons' verdicts.
    pub comparisons: Vec<Comparison>,
    /// The solvers' work.
    pub solvers: Vec<SolverWork>,
    /// Residual tolerance.
    pub tol: f64,
    /// The iteration budget of every solve.
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    /// The despiking threshold in robust deviations, when spikes were replaced.
    #[serde(default)]
    pub despike: Option<f64>,
    /// Each scan's spikes and outliers, and the share of the contact they carry at each
    /// load.
    #[serde(default)]
    pub outliers: Vec<super::spikes::Outliers>,
    /// Wall time of the check, seconds.
    pub wall_s: f64,
}

fn default_max_iterations() -> usize {
    super::options::MAX_ITERATIONS
}

/// The shape of the scans, for callers that hold only the result.
impl SurfaceCheck {
    /// Rows and columns of the scans.
    pub fn shape(&self) -> Shape {
        Shape {
            rows: self.rows,
            cols: self.cols,
        }
    }
}
