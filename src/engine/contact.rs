//! The hard-wall contact problem, its solution, and the solver-independent residual.
//!
//! Problem ([`crate::conventions`], section 2): find the displacement `u` of the elastic surface and the
//! contact pressure `p` over a rigid substrate of heights `h` such that
//!
//! ```text
//!     g = u - h >= 0,   p >= 0,   p g = 0,   mean(p) = p0,   p~(q) = (q E*/2) u~(q), q != 0.
//! ```
//!
//! # Residual
//!
//! Two solvers reach these conditions from different sides: the constrained conjugate
//! gradient method keeps `u` exactly consistent with `p` and drives the gap to zero inside
//! contact; GFMD keeps the gap exactly zero at the wall and drives the stress outside
//! contact to zero. To compare them at equal accuracy, every solution is judged by the same
//! [`Residual`], computed from the returned `(p, u)` alone. With `ell` the rms height of
//! `h` (or, for a flat substrate, the displacement scale `p0 L / (pi E*)`):
//!
//! | component | definition | measures |
//! |---|---|---|
//! | `penetration` | `max(0, -min g) / ell` | interpenetration anywhere |
//! | `complementarity` | `sum p |g| / (ell sum p)` | gap left where pressure acts |
//! | `tension` | `max(0, -min p) / rms(p)` | adhesive (negative) pressure |
//! | `equilibrium` | `rms(K u + p0 - p) / rms(p)` | stress not balanced by contact, `K = q E*/2` |
//! | `load` | `abs(mean p - p0) / p0` | load balance |
//!
//! The residual is the largest component; a solver stops when it falls below the requested
//! tolerance. The [`Residual::tamaas`] figure, `sum p (g - min g) / (sum p std(h))`, is
//! reported as well so that tolerances here and in tamaas can be put side by side.
//!
//! Each component is written once, as a function of sums over the points
//! ([`Residual::penetration_of`], [`Residual::complementarity_of`],
//! [`Residual::equilibrium_of`], [`Residual::load_of`]): the full residual takes them from
//! the returned fields, and the solvers' cheap estimates from the sums their iterations
//! take anyway (CG: penetration and complementarity from its gap pass; GFMD: equilibrium
//! and load from its stress pass). The gap is [`gap`], also written once.
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

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::engine::elastic::HalfSpace;
use crate::engine::fft::{Fft2, FusedPass, Kernel};
use crate::engine::field;
use crate::engine::grid::Grid;
use crate::error::{check_positive, Error, Result};

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
    pub fn new(grid: Grid, e_star: f64) -> Result<Self> {
        let halfspace = HalfSpace::new(&grid, e_star)?;
        let fft = Fft2::new(&grid);
        Ok(Self::with_halfspace(grid, halfspace, fft, None))
    }

    /// A free-boundary model for a `window x window` surface: the doubled, zero-padded grid
    /// of [`crate::engine::boussinesq`], the wall over the window only. Heights for it come
    /// from [`Model::pad_heights`].
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
    /// Length scale `ell` of the residual (see the module docs).
    pub length_scale: f64,
    /// Standard deviation of the heights (tamaas's error measure divides by it).
    pub heights_std: f64,
}

impl<'a> ContactProblem<'a> {
    /// Checks the inputs and prepares the problem.
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

/// The solver-independent residual (see the module docs). All components are dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct Residual {
    /// Interpenetration, `max(0, -min g) / ell`.
    pub penetration: f64,
    /// Gap where pressure acts, `sum p |g| / (ell sum p)`.
    pub complementarity: f64,
    /// Negative pressure, `max(0, -min p) / rms(p)`.
    pub tension: f64,
    /// Unbalanced stress, `rms(K u + p0 - p) / rms(p)`.
    pub equilibrium: f64,
    /// Load balance, `|mean p - p0| / p0`.
    pub load: f64,
    /// tamaas's error measure, `sum p (g - min g) / (sum p std(h))`.
    pub tamaas: f64,
}

impl Residual {
    /// The residual: the largest component.
    pub fn value(&self) -> f64 {
        self.penetration
            .max(self.complementarity)
            .max(self.tension)
            .max(self.equilibrium)
            .max(self.load)
    }

    /// Interpenetration, `max(0, deepest) / ell`, from the deepest penetration
    /// `deepest = max(-g) = -min g`.
    #[inline]
    pub fn penetration_of(deepest: f64, ell: f64) -> f64 {
        deepest.max(0.0) / ell
    }

    /// Complementarity, `sum p |g| / (ell sum p)` from `p_abs_gap = sum p |g|` and
    /// `sum_p = sum p`; 0 where no pressure acts.
    #[inline]
    pub fn complementarity_of(p_abs_gap: f64, sum_p: f64, ell: f64) -> f64 {
        if sum_p > 0.0 {
            p_abs_gap / (ell * sum_p)
        } else {
            0.0
        }
    }

    /// The rms `sqrt(sum_sq / npts)` of a field from the sum of its squares.
    #[inline]
    pub fn rms_of(sum_sq: f64, npts: f64) -> f64 {
        (sum_sq / npts).sqrt()
    }

    /// Equilibrium, `rms(K u + p0 - p) / rms_p`, from `unbalanced = sum (K u + p0 - p)^2`
    /// over `npts` points and the pressure scale `rms_p`.
    #[inline]
    pub fn equilibrium_of(unbalanced: f64, npts: f64, rms_p: f64) -> f64 {
        Self::rms_of(unbalanced, npts) / rms_p
    }

    /// Load balance, `|mean p - p0| / p0`, from `sum_p = sum p` over `npts` points.
    #[inline]
    pub fn load_of(sum_p: f64, npts: f64, p0: f64) -> f64 {
        (sum_p / npts - p0).abs() / p0
    }

    /// Evaluates the residual of `(p, u)` for `problem`. `spec` (a half spectrum) and
    /// `scratch` (a real field) are work space.
    pub fn evaluate(
        problem: &ContactProblem,
        p: &[f64],
        u: &[f64],
        spec: &mut [Complex64],
        scratch: &mut [f64],
    ) -> Self {
        let h = problem.heights;
        let ell = problem.length_scale;
        let npts = p.len() as f64;
        // The pointwise sums in one sweep; tamaas's `sum p (g - min g)` is
        // `sum p g - min(g) sum p`.
        let s = field::fold_chunks(
            p.len(),
            PointSums::default(),
            #[inline(always)]
            |rg| {
                let mut acc = PointSums::default();
                for ((&pi, &ui), &hi) in p[rg.clone()].iter().zip(&u[rg.clone()]).zip(&h[rg]) {
                    let g = gap(ui, hi);
                    acc.sum_p += pi;
                    acc.p_abs_gap += pi * g.abs();
                    acc.p_gap += pi * g;
                    acc.sum_p2 += pi * pi;
                    acc.min_g = field::nan_min(acc.min_g, g);
                    acc.min_p = field::nan_min(acc.min_p, pi);
                }
                acc
            },
            PointSums::add,
        );
        // Stress balance: K u + p0 - p (the stiffness has no q = 0 mode: p0 is added).
        let model = problem.model;
        let n = model.grid.cols();
        let unbalanced = StressBalance {
            u,
            p,
            p0: problem.p0,
            n,
        };
        let (_, rows) = model
            .fft
            .convolve(&model.stiffness, spec, None, &unbalanced, scratch);
        let unbalanced: f64 = rows.iter().sum();
        let (sum_p, min_g) = (s.sum_p, s.min_g);
        let rms_p = Self::rms_of(s.sum_p2, npts);
        let h_std = problem.heights_std;
        let tamaas = if h_std > 0.0 && sum_p > 0.0 {
            (s.p_gap - min_g * sum_p) / (sum_p * h_std)
        } else {
            0.0
        };
        // Without any pressure, the pressures are measured against the load.
        let rms_p = if rms_p > 0.0 { rms_p } else { problem.p0 };
        Self {
            penetration: Self::penetration_of(-min_g, ell),
            complementarity: Self::complementarity_of(s.p_abs_gap, sum_p, ell),
            tension: (-s.min_p).max(0.0) / rms_p,
            equilibrium: Self::equilibrium_of(unbalanced, npts, rms_p),
            load: Self::load_of(sum_p, npts, problem.p0),
            tamaas,
        }
    }
}

/// The stress balance `K u + p0 - p` as the fused pass of the convolution `K u`: row `i` of
/// `u` generated, the squares of the row's imbalance summed.
struct StressBalance<'a> {
    u: &'a [f64],
    p: &'a [f64],
    p0: f64,
    /// Points in a row, the grid's columns.
    n: usize,
}

impl FusedPass for StressBalance<'_> {
    type Generated = ();
    type Consumed = f64;

    #[inline(always)]
    fn generate(&self, i: usize, x: &mut [f64], _: &mut [f64], _: &[f64]) {
        let n = self.n;
        x.copy_from_slice(&self.u[i * n..(i + 1) * n]);
    }

    #[inline(always)]
    fn consume(&self, i: usize, ku: &[f64], _: &[f64]) -> f64 {
        let n = self.n;
        ku.iter()
            .zip(&self.p[i * n..(i + 1) * n])
            .map(|(&k, &pi)| (k + self.p0 - pi).powi(2))
            .sum::<f64>()
    }
}

/// Sums and minima over the points that the residual needs.
#[derive(Debug, Clone, Copy)]
struct PointSums {
    sum_p: f64,
    p_abs_gap: f64,
    p_gap: f64,
    sum_p2: f64,
    min_g: f64,
    min_p: f64,
}

impl Default for PointSums {
    fn default() -> Self {
        Self {
            sum_p: 0.0,
            p_abs_gap: 0.0,
            p_gap: 0.0,
            sum_p2: 0.0,
            min_g: f64::INFINITY,
            min_p: f64::INFINITY,
        }
    }
}

impl PointSums {
    fn add(self, o: Self) -> Self {
        Self {
            sum_p: self.sum_p + o.sum_p,
            p_abs_gap: self.p_abs_gap + o.p_abs_gap,
            p_gap: self.p_gap + o.p_gap,
            sum_p2: self.sum_p2 + o.sum_p2,
            min_g: field::nan_min(self.min_g, o.min_g),
            min_p: field::nan_min(self.min_p, o.min_p),
        }
    }
}

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
