//! One hard-wall problem: a model, substrate heights and the mean pressure, with the
//! length scale its residual is measured in, the gap, and the fields of a cold start.

use crate::engine::field;
use crate::engine::grid::Grid;
use crate::error::{check_positive, Error, Result};

use super::model::Model;

/// The gap `g = u - h` between the elastic surface at `u` and the substrate at `h`
/// (negative where the surface penetrates the substrate).
#[inline]
pub fn gap(u: f64, h: f64) -> f64 {
    u - h
}

/// One hard-wall problem: a model, substrate heights and the mean pressure.
#[derive(Debug, Clone, Copy)]
pub struct ContactProblem<'a> {
    /// The elastic model.
    pub model: &'a Model,
    /// Substrate heights `h(r)` at the magnification being solved.
    pub heights: &'a [f64],
    /// Mean pressure `p0` over the grid (for a free boundary, over the doubled grid: the
    /// window's mean pressure times the window's share of the grid).
    pub p0: f64,
    /// Length scale `ell` of the residual (see [`super::residual`]).
    pub length_scale: f64,
    /// Standard deviation of the heights (tamaas's error measure divides by it).
    pub heights_std: f64,
}

impl<'a> ContactProblem<'a> {
    /// Checks the inputs and prepares the problem.
    ///
    /// # Errors
    ///
    /// If `p0` is not positive and finite, the heights are not one per grid point, a height
    /// is not finite, or their spread overflows.
    pub fn new(model: &'a Model, heights: &'a [f64], p0: f64) -> Result<Self> {
        check_positive("p0", p0)?;
        if heights.len() != model.grid.points() {
            return Err(Error::invalid(
                "heights",
                format!("{} values", heights.len()),
                format!("rows x cols = {} values", model.grid.points()),
            ));
        }
        // A free boundary's statistics are the window's (the floor outside it is no surface).
        let window: Vec<f64>;
        let (heights_seen, side) = match model.window {
            None if model.grid.is_square() => (heights, model.grid.length()),
            None => {
                let area = model.grid.points() as f64;
                (heights, area.sqrt() * model.grid.spacing())
            }
            Some((rows, cols)) => {
                let n = model.grid.cols();
                window = heights
                    .chunks(n)
                    .take(rows)
                    .flat_map(|r| &r[..cols])
                    .copied()
                    .collect();
                let side = ((rows * cols) as f64).sqrt();
                (&window[..], side * model.grid.spacing())
            }
        };
        // One pass for the mean (finite exactly when every height is, barring overflow),
        // one for the spread; the finiteness check runs only to name the bad input.
        let mean = field::mean(heights_seen);
        if !mean.is_finite() && !field::all_finite(heights_seen) {
            return Err(Error::invalid(
                "heights",
                "a non-finite value",
                "finite numbers (no NaN or infinity)",
            ));
        }
        let rms = field::std_dev_about(heights_seen, mean);
        if !rms.is_finite() {
            return Err(Error::invalid(
                "heights",
                format!("a spread that overflows (mean {mean:e})"),
                "heights whose squares are finite",
            ));
        }
        let flat_scale = p0 * side / (std::f64::consts::PI * model.halfspace.e_star());
        let length_scale = if rms > 1e-12 * flat_scale {
            rms
        } else {
            flat_scale
        };
        Ok(Self {
            model,
            heights,
            p0,
            length_scale,
            heights_std: rms,
        })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.model.grid
    }

    /// The pressure of a cold start: uniform under the wall (all of a periodic grid, the
    /// window of a free boundary) with mean `p0`, 0 elsewhere.
    pub fn cold_pressure(&self, p: &mut [f64]) {
        match self.model.window {
            None => p.fill(self.p0),
            Some(_) => {
                let under =
                    self.p0 * self.model.grid.points() as f64 / self.model.wall_points() as f64;
                for (k, v) in p.iter_mut().enumerate() {
                    *v = if self.model.under_wall(k) { under } else { 0.0 };
                }
            }
        }
    }

    /// The displacement of a cold start: on the wall where there is one; on the free
    /// surface outside a free-boundary window, level with the window's mean height.
    pub fn cold_displacement(&self, u: &mut [f64]) {
        u.copy_from_slice(self.heights);
        if self.model.window.is_some() {
            let (sum, count) = self
                .heights
                .iter()
                .enumerate()
                .filter(|(k, _)| self.model.under_wall(*k))
                .fold((0.0, 0usize), |(s, c), (_, h)| (s + h, c + 1));
            let level = sum / count as f64;
            for (k, v) in u.iter_mut().enumerate() {
                if !self.model.under_wall(k) {
                    *v = level;
                }
            }
        }
    }
}
