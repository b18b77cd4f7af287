//! The solver-independent residual of a pair of fields `(p, u)`.
//!
//! Two solvers reach the conditions of the problem (see [`crate::engine::contact`]) from
//! different sides: the constrained conjugate gradient method keeps `u` exactly consistent
//! with `p` and drives the gap to zero inside contact; GFMD keeps the gap exactly zero at
//! the wall and drives the stress outside contact to zero. To compare them at equal
//! accuracy, every solution is judged by the same [`Residual`], computed from the returned
//! `(p, u)` alone. With `ell` the rms height of `h` (or, for a flat substrate, the
//! displacement scale `p0 L / (pi E*)`):
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

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::engine::fft::FusedPass;
use crate::engine::field;

use super::problem::{gap, ContactProblem};

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
