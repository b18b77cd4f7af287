//! A converged solution: the fields, how they were reached, and the quantities read from
//! them (contact area, gap, elastic energy, displacement spectrum).

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::engine::field;

use super::model::Model;
use super::problem::gap;
use super::residual::Residual;

/// A converged solution: fields, and how it was reached.
#[derive(Debug, Clone)]
pub struct ContactSolution {
    /// Contact pressure `p(r) >= 0`.
    pub pressure: Vec<f64>,
    /// Displacement `u(r)` of the elastic surface, rigid shift included.
    pub displacement: Vec<f64>,
    /// Mean pressure `p0`.
    pub p0: f64,
    /// How the solution was reached.
    pub stats: SolveStats,
}

/// How a solution was reached.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct SolveStats {
    /// Solver name.
    pub solver: &'static str,
    /// Iterations (GFMD: time steps) used.
    pub iterations: usize,
    /// Residual of the returned fields.
    pub residual: Residual,
    /// Wall time of the solve, seconds.
    pub wall_s: f64,
    /// Whether the solve started from a previous solution.
    pub warm: bool,
}

impl ContactSolution {
    /// Relative contact area: the fraction of points with `p > 0`.
    pub fn contact_area(&self) -> f64 {
        field::positive_fraction(&self.pressure)
    }

    /// Gap `g = u - h` ([`gap`]), clipped at 0 (a converged solution penetrates only by
    /// rounding).
    pub fn gap(&self, heights: &[f64]) -> Vec<f64> {
        self.displacement
            .iter()
            .zip(heights)
            .map(|(&u, &h)| gap(u, h).max(0.0))
            .collect()
    }

    /// Mean gap `mean(u - h)`, clipped at 0 point by point as in [`Self::gap`].
    pub fn mean_gap(&self, heights: &[f64]) -> f64 {
        field::sum_zip(&self.displacement, heights, |u, h| gap(u, h).max(0.0))
            / heights.len() as f64
    }

    /// Elastic energy per unit area, `(1/2) mean[(p - p0) u]` (see [`crate::engine::elastic`]).
    pub fn elastic_energy(&self) -> f64 {
        0.5 * field::sum_zip(&self.pressure, &self.displacement, |p, u| (p - self.p0) * u)
            / self.pressure.len() as f64
    }

    /// Displacement spectrum `u~(q)`.
    pub fn displacement_spectrum(&self, model: &Model) -> Vec<Complex64> {
        let mut spec = model.fft.new_spectrum();
        model.fft.forward(&self.displacement, &mut spec);
        spec
    }
}
