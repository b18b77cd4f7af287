//! The elastic model: the grid, the half-space, the FFT plans and the elastic operator as
//! the solvers see it.
//!
//! # The elastic operator
//!
//! The solvers see the elastic body only through the [`Model`]: its stiffness and
//! compliance kernels ([`Model::stiffness`], [`Model::compliance`]), the compliance of one
//! point ([`Model::point_compliance`]) and the inverse masses of mass-weighted dynamics
//! ([`Model::inverse_mass`]), all derived from one stiffness table. Another elastic body
//! (a free-boundary half-space: the real-space Green's function of a uniformly loaded
//! pixel on a zero-padded doubled grid, whose transform gives the stiffness table there,
//! with the hard wall only over the original window) is another way of making these items;
//! no solver computes `q E*/2` itself.

use std::sync::OnceLock;

use crate::engine::elastic::HalfSpace;
use crate::engine::fft::{Fft2, Kernel};
use crate::engine::grid::Grid;
use crate::error::{Error, Result};

/// How far below a free-boundary window the floor outside it lies, in units of the
/// window's height range plus its side (see [`Model::pad_heights`]): the elastic
/// displacement under a mean pressure `p0` over a window of side `L` is of order
/// `p0 L / E*`, below `10 L` for the loads accepted.
const FLOOR_DEPTH: f64 = 1000.0;

/// The elastic model on a grid: geometry, material, the FFT plans and the elastic operator
/// as the solvers use it (see "The elastic operator" in the module docs). Plain data, but
/// for the inverse masses, made on first use.
#[derive(Debug)]
pub struct Model {
    /// The grid.
    pub grid: Grid,
    /// The half-space.
    pub halfspace: HalfSpace,
    /// FFT plans for the grid.
    pub fft: Fft2,
    /// The stiffness `q E*/2` as a convolution kernel.
    pub stiffness: Kernel,
    /// The compliance `2 / (q E*)` as a convolution kernel (the stiffness's values, inverted
    /// as they are read).
    pub compliance: Kernel,
    /// The inverse masses, made on first use ([`Model::inverse_mass`]).
    inverse_mass: OnceLock<Kernel>,
    /// For a free boundary, the rows and columns of the window at the grid's origin that
    /// the hard wall covers; `None`: the wall covers the whole (periodic) grid.
    pub window: Option<(usize, usize)>,
}

impl Model {
    /// A periodic model on `grid` with modulus `e_star`.
    ///
    /// # Errors
    ///
    /// If `e_star` is not positive and finite.
    pub fn new(grid: Grid, e_star: f64) -> Result<Self> {
        let halfspace = HalfSpace::new(&grid, e_star)?;
        let fft = Fft2::new(&grid);
        Ok(Self::with_halfspace(grid, halfspace, fft, None))
    }

    /// A free-boundary model for a `window x window` surface: the doubled, zero-padded grid
    /// of [`crate::engine::boussinesq`], the wall over the window only. Heights for it come
    /// from [`Model::pad_heights`].
    ///
    /// # Errors
    ///
    /// As [`Model::free_window`].
    pub fn free_boundary(window: usize, e_star: f64) -> Result<Self> {
        Self::free_window(window, window, e_star)
    }

    /// A free-boundary model for a `rows x cols` surface: the `2 rows x 2 cols` grid,
    /// zero-padded (no image of the window reaches it along either axis), the wall over
    /// the window only.
    ///
    /// # Errors
    ///
    /// If a side of the doubled grid is outside the grid's range ([`Grid::rectangle`]), or
    /// `e_star` is not positive.
    pub fn free_window(rows: usize, cols: usize, e_star: f64) -> Result<Self> {
        let grid = Grid::rectangle(2 * rows, 2 * cols, 1.0)?;
        let fft = Fft2::new(&grid);
        let table = crate::engine::boussinesq::padded_stiffness(&grid, &fft, e_star)?;
        let halfspace = HalfSpace::with_stiffness(e_star, table)?;
        Ok(Self::with_halfspace(
            grid,
            halfspace,
            fft,
            Some((rows, cols)),
        ))
    }

    /// Points under the wall: the window's, or every point of a periodic grid.
    pub fn wall_points(&self) -> usize {
        match self.window {
            None => self.grid.points(),
            Some((rows, cols)) => rows * cols,
        }
    }

    fn with_halfspace(
        grid: Grid,
        halfspace: HalfSpace,
        fft: Fft2,
        window: Option<(usize, usize)>,
    ) -> Self {
        let stiffness = fft.kernel(halfspace.stiffness());
        let compliance = stiffness.inverse();
        Self {
            grid,
            halfspace,
            fft,
            stiffness,
            compliance,
            inverse_mass: OnceLock::new(),
            window,
        }
    }

    /// Whether point `k` (row-major) is under the wall: every point of a periodic model,
    /// the window's of a free-boundary one.
    #[inline]
    pub fn under_wall(&self, k: usize) -> bool {
        match self.window {
            None => true,
            Some((rows, cols)) => {
                let n = self.grid.cols();
                k / n < rows && k % n < cols
            }
        }
    }

    /// The heights of a free-boundary problem on the doubled grid: the window's heights
    /// (`rows x cols`, row-major) at the origin, and outside it a floor so far below them
    /// that no displacement under a load `p0/E* < 10` reaches it (the window's height
    /// range plus a thousand times its longer side). A periodic model takes the heights as
    /// they are.
    ///
    /// # Errors
    ///
    /// If a free-boundary model is given other than `rows x cols` heights.
    pub fn pad_heights(&self, heights: &[f64]) -> Result<Vec<f64>> {
        let Some((rows, cols)) = self.window else {
            return Ok(heights.to_vec());
        };
        if heights.len() != rows * cols {
            return Err(Error::invalid(
                "heights",
                format!("{} values", heights.len()),
                format!("rows x columns = {} values", rows * cols),
            ));
        }
        let lo = heights.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let floor = lo - FLOOR_DEPTH * ((hi - lo) + rows.max(cols) as f64);
        let mut padded = vec![floor; self.grid.points()];
        for (row, src) in padded
            .chunks_mut(self.grid.cols())
            .zip(heights.chunks(cols))
        {
            row[..cols].copy_from_slice(src);
        }
        Ok(padded)
    }

    /// The displacement of a point under unit pressure on that point alone,
    /// `G(0) = N^-2 sum_q 2 / (q E*)`: the diagonal of the compliance in real space.
    pub fn point_compliance(&self) -> f64 {
        let grid = &self.grid;
        let sum: f64 = self
            .halfspace
            .compliance()
            .enumerate()
            .map(|(s, c)| grid.weight_of(s) * c)
            .sum();
        sum / grid.points() as f64
    }

    /// The inverse masses `1/m(q)` of mass-weighted dynamics as a convolution kernel: the
    /// mass of a mode is its stiffness, `m(q) = q E*/2`, so that every free mode
    /// oscillates with one frequency, and the rigid mode `q = 0` has the mass of the
    /// softest non-zero mode (Zhou, Moseler & Müser, PRB 99, 144103 (2019)). Made from the
    /// stiffness table on first use and kept.
    pub fn inverse_mass(&self) -> &Kernel {
        self.inverse_mass.get_or_init(|| {
            let stiffness = self.halfspace.stiffness();
            let k_min = stiffness
                .iter()
                .copied()
                .filter(|&k| k > 0.0)
                .fold(f64::INFINITY, f64::min);
            let table: Vec<f64> = stiffness
                .iter()
                .map(|&k| 1.0 / if k > 0.0 { k } else { k_min })
                .collect();
            self.fft.kernel(&table)
        })
    }
}
