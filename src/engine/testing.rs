//! Fixtures of the unit tests (test builds only).

use rustfft::num_complex::Complex64;

use crate::engine::contact::Model;
use crate::engine::grid::Grid;
use crate::engine::surface::{Surface, SurfaceModel};

/// A small rough contact: an `n x n` self-affine surface (Hurst exponent `hurst`,
/// `lambda_l = n/2`, `lambda_s = n/16`, realization `seed`) on a half-space with `E* = 1`.
pub(crate) fn rough_contact(n: usize, hurst: f64, seed: u64) -> (Surface, Model) {
    let params = SurfaceModel::new(n, hurst, n as f64 / 2.0, n as f64 / 16.0, seed);
    let surface = Surface::generate(&params).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    (surface, model)
}

/// The half spectrum of a real `rows x cols` field on `grid` by the direct O(N^4) sum, in
/// the crate's convention (`f~(q) = N^-2 sum_r f(r) exp(-i q.r)`): the independent control
/// of every fast transform.
pub(crate) fn naive_dft(grid: &Grid, field: &[f64]) -> Vec<Complex64> {
    let (rows, cols) = (grid.rows(), grid.cols());
    let mut out = vec![Complex64::new(0.0, 0.0); grid.modes()];
    for (s, o) in out.iter_mut().enumerate() {
        let (mx, my) = grid.wavevector(s);
        let mut acc = Complex64::new(0.0, 0.0);
        for i in 0..rows {
            for j in 0..cols {
                let phase = -2.0
                    * std::f64::consts::PI
                    * (mx as f64 * j as f64 / cols as f64 + my as f64 * i as f64 / rows as f64);
                acc += Complex64::from_polar(field[i * cols + j], phase);
            }
        }
        *o = acc / (rows * cols) as f64;
    }
    out
}
