//! The pixel's own error on a contact area: each load re-solved on the scan coarsened by
//! 2 (and by 4 where the scan is large enough), and the contact area extrapolated to a
//! vanishing pixel.
//!
//! **Why first order.** A solve on a grid of pixel `a` decides contact point by point, so
//! the contact area it finds is off by a share of the points along the contact line: the
//! line's length per unit area times a fraction of the pixel. The error is therefore of
//! first order in `a`, `a_r(a) = a_r(0) + c a + O(a^2)`, and Richardson's extrapolation
//! from the pixel and twice the pixel removes its first-order term:
//!
//! `a_r(0) ≈ R(a, 2a) = 2 a_r(a) - a_r(2a)`.
//!
//! Where the scan is large enough for a third level (coarsened by 4), the same rule one
//! level up, `R(2a, 4a) = 2 a_r(2a) - a_r(4a)`, gives the extrapolation's own spread,
//! `|R(a, 2a) - R(2a, 4a)|`, and the order the three levels show,
//! `log2((a_r(4a) - a_r(2a)) / (a_r(2a) - a_r(a)))` (reported, not used: on generated
//! surfaces it scatters between about 1 and 1.5 from one realization to the next).
//!
//! **Coarsening** takes every `f`-th point of the scan ([`coarsen`]): the same heights
//! sampled at `f` times the pixel, in a window of the same size. A scan whose roughness
//! is band-limited at wavelengths above `2 f` pixels (a generated surface with
//! `lambda_s > 2 f a`, or a scan filtered at its short-wavelength cutoff) keeps every one
//! of its modes; roughness finer than that folds onto the coarse grid's wavevectors, and
//! the estimate then mixes the pixel's error with the change of the surface
//! ([`PixelEstimate::folded`]).
//!
//! Measured on generated surfaces (`H = 0.8`, `lambda_l / lambda_s` 6.4 and 12.8, five
//! realizations each, `p0` 0.05 and 0.145 `E* g_bar`, periodic): `a_r` at
//! `lambda_s / a = 5` lies 0.008 to 0.020 above the answer at `lambda_s / a = 20`, and
//! `R(a, 2a)` from `lambda_s / a = 5` lies 0.001 to 0.013 from it, closer in every one of
//! the 15 cases (`tests/check_surface.rs` holds one of them).

use serde::{Deserialize, Serialize};

use super::psd::{Boundary, Shape};
use super::scan::MIN_SIDE;
use crate::engine::spectrum::ShellSpectrum;

/// The coarsening factors of the estimate, finest first.
pub const FACTORS: [usize; 2] = [2, 4];

/// The factors of [`FACTORS`] a `shape` scan can be coarsened by: each side, divided by
/// the factor, at least [`MIN_SIDE`] (the floor on size of every scan); for a periodic
/// scan also a whole number of coarse pixels per side. Only the factors below the first
/// one refused are kept, so the levels are always the pixel, 2 and 4 in that order.
pub fn factors(shape: Shape, boundary: Boundary) -> Vec<usize> {
    FACTORS
        .into_iter()
        .take_while(|&f| {
            let sides = shape.rows / f >= MIN_SIDE && shape.cols / f >= MIN_SIDE;
            let whole = boundary == Boundary::Free || shape.rows % f == 0;
            sides && whole
        })
        .collect()
}

/// Every `factor`-th point of the `shape` heights from the first (row-major), and the
/// coarse shape: `ceil(rows / factor) x ceil(cols / factor)` for a free window, exactly
/// `rows / factor` a side for a periodic scan (whose side [`factors`] keeps divisible).
pub fn coarsen(heights: &[f64], shape: Shape, factor: usize) -> (Vec<f64>, Shape) {
    let coarse = Shape {
        rows: shape.rows.div_ceil(factor),
        cols: shape.cols.div_ceil(factor),
    };
    let values = (0..coarse.rows)
        .flat_map(|i| (0..coarse.cols).map(move |j| heights[i * factor * shape.cols + j * factor]))
        .collect();
    (values, coarse)
}

/// First-order Richardson extrapolation to a vanishing pixel from the values at the pixel
/// and at twice the pixel: `2 fine - coarse`.
pub fn richardson(fine: f64, coarse: f64) -> f64 {
    2.0 * fine - coarse
}

/// The pixel's error at one load: the contact areas at the pixel and coarser, and what
/// they extrapolate to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PixelEstimate {
    /// The contact area at 2 and (where there is a third level) 4 times the pixel, as
    /// `(factor, a_r)`, mean over the scans.
    pub coarse: Vec<(usize, f64)>,
    /// `R(a, 2a)`, the contact area extrapolated to a vanishing pixel, mean over the
    /// scans.
    pub extrapolated: f64,
    /// The extrapolated contact area less the one at the pixel.
    pub difference: f64,
    /// `|R(a, 2a) - R(2a, 4a)|` with a third level, mean over the scans.
    pub spread: Option<f64>,
    /// The order the three levels show, where the two differences share their sign.
    pub order: Option<f64>,
    /// The factors whose coarse grid folds roughness the scan holds (finer than twice
    /// the coarse pixel) onto its wavevectors (see the module docs): with 2 among them
    /// the extrapolation mixes the pixel's error with that change of the surface, with
    /// 4 alone only the spread and the order do.
    #[serde(default)]
    pub folded: Vec<usize>,
}

impl PixelEstimate {
    /// The estimate of one scan from its contact areas at the pixel and at each factor
    /// of [`FACTORS`] kept (`coarse`, in that order; at least the factor 2), and the
    /// shortest wavelength the scan holds, in pixels ([`shortest_wavelength`]).
    pub fn of_levels(fine: f64, coarse: &[(usize, f64)], shortest: f64) -> Option<Self> {
        let &(_, twice) = coarse.first()?;
        let extrapolated = richardson(fine, twice);
        let (spread, order) = match coarse.get(1) {
            Some(&(_, four)) => {
                let spread = (extrapolated - richardson(twice, four)).abs();
                let ratio = (four - twice) / (twice - fine);
                (Some(spread), (ratio > 0.0).then(|| ratio.log2()))
            }
            None => (None, None),
        };
        Some(Self {
            coarse: coarse.to_vec(),
            extrapolated,
            difference: extrapolated - fine,
            spread,
            order,
            folded: coarse
                .iter()
                .map(|&(f, _)| f)
                .filter(|&f| folds(shortest, f))
                .collect(),
        })
    }

    /// The mean of several scans' estimates, level by level over the levels every scan
    /// has (the spread and the order only where every scan shows one).
    pub fn mean(all: &[Self]) -> Option<Self> {
        let first = all.first()?;
        let levels = all.iter().map(|e| e.coarse.len()).min()?;
        let n = all.len() as f64;
        let mean = |f: &dyn Fn(&Self) -> f64| all.iter().map(f).sum::<f64>() / n;
        let mean_of = |f: &dyn Fn(&Self) -> Option<f64>| -> Option<f64> {
            let v: Option<Vec<f64>> = all.iter().map(f).collect();
            v.map(|v| v.iter().sum::<f64>() / n)
        };
        let coarse = (0..levels)
            .map(|k| (first.coarse[k].0, mean(&|e: &Self| e.coarse[k].1)))
            .collect();
        Some(Self {
            coarse,
            extrapolated: mean(&|e| e.extrapolated),
            difference: mean(&|e| e.difference),
            spread: mean_of(&|e| e.spread),
            order: mean_of(&|e| e.order),
            folded: FACTORS
                .into_iter()
                .filter(|f| all.iter().any(|e| e.folded.contains(f)))
                .collect(),
        })
    }
}

/// The shortest wavelength a scan's spectrum holds, in pixels: that of its highest shell
/// whose power per mode is above `1e-16` of the largest (a band-limited surface's empty
/// shells hold the transform's rounding, some `1e-30` of its power).
pub fn shortest_wavelength(shells: &ShellSpectrum) -> f64 {
    let per_mode = |s: &crate::engine::spectrum::Shell| s.h2 / f64::from(s.modes.max(1));
    let top = shells.shells.iter().map(per_mode).fold(0.0, f64::max);
    shells
        .shells
        .iter()
        .rev()
        .find(|s| per_mode(s) > 1e-16 * top)
        .map_or(f64::INFINITY, |s| 2.0 * std::f64::consts::PI / s.q)
}

/// Whether a spectrum whose shortest wavelength present is `shortest` pixels folds onto
/// the grid coarsened by `factor`: its Nyquist wavelength, `2 factor` pixels, is longer.
pub fn folds(shortest: f64, factor: usize) -> bool {
    shortest < 2.0 * factor as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarsening_keeps_every_factor_th_point() {
        let shape = Shape { rows: 4, cols: 6 };
        let h: Vec<f64> = (0..24).map(f64::from).collect();
        let (c, s) = coarsen(&h, shape, 2);
        assert_eq!(s, Shape { rows: 2, cols: 3 });
        assert_eq!(c, vec![0.0, 2.0, 4.0, 12.0, 14.0, 16.0]);
        let (c, s) = coarsen(&h, Shape { rows: 3, cols: 8 }, 4);
        assert_eq!(s, Shape { rows: 1, cols: 2 });
        assert_eq!(c, vec![0.0, 4.0]);
    }

    #[test]
    fn the_factors_stop_at_the_floor_on_size() {
        let sq = |n| Shape { rows: n, cols: n };
        assert_eq!(factors(sq(128), Boundary::Periodic), vec![2, 4]);
        assert_eq!(factors(sq(100), Boundary::Periodic), vec![2]);
        assert_eq!(factors(sq(127), Boundary::Free), vec![2]);
        assert_eq!(factors(sq(63), Boundary::Free), Vec::<usize>::new());
        let wide = Shape {
            rows: 64,
            cols: 512,
        };
        assert_eq!(factors(wide, Boundary::Free), vec![2]);
    }

    #[test]
    fn richardson_removes_a_first_order_error_exactly() {
        // a_r(a) = 0.3 + 0.02 a: exact at every pixel.
        let at = |a: f64| 0.3 + 0.02 * a;
        let e = PixelEstimate::of_levels(at(1.0), &[(2, at(2.0)), (4, at(4.0))], 9.0).unwrap();
        assert!((e.extrapolated - 0.3).abs() < 1e-15);
        assert!(e.folded.is_empty());
        assert!((e.difference + 0.02).abs() < 1e-15);
        assert!(e.spread.unwrap() < 1e-15);
        assert!((e.order.unwrap() - 1.0).abs() < 1e-12);
        // A second-order error shows order 2 and a spread.
        let at = |a: f64| 0.3 + 0.01 * a * a;
        let e = PixelEstimate::of_levels(at(1.0), &[(2, at(2.0)), (4, at(4.0))], 5.0).unwrap();
        assert!((e.order.unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(e.folded, vec![4]);
        assert!(e.spread.unwrap() > 0.0);
        assert!(PixelEstimate::of_levels(0.3, &[], 9.0).is_none());
    }

    #[test]
    fn the_mean_is_taken_level_by_level() {
        let a = PixelEstimate::of_levels(0.30, &[(2, 0.32)], 9.0).unwrap();
        let b = PixelEstimate::of_levels(0.20, &[(2, 0.24)], 2.0).unwrap();
        let m = PixelEstimate::mean(&[a, b]).unwrap();
        assert!((m.extrapolated - 0.22).abs() < 1e-15);
        assert_eq!(m.coarse[0].0, 2);
        assert!((m.coarse[0].1 - 0.28).abs() < 1e-15);
        assert_eq!(m.folded, vec![2]);
        assert_eq!(m.spread, None);
    }

    #[test]
    fn folding_starts_below_twice_the_coarse_pixel() {
        assert!(!folds(5.0, 2));
        assert!(folds(3.9, 2));
        assert!(folds(5.0, 4));
    }
}
