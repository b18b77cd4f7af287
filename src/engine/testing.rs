//! Fixtures of the unit tests (test builds only).

use crate::engine::contact::Model;
use crate::engine::surface::{Surface, SurfaceParams};

/// A small rough contact: an `n x n` self-affine surface (Hurst exponent `hurst`,
/// `lambda_l = n/2`, `lambda_s = n/16`, realization `seed`) on a half-space with `E* = 1`.
pub(crate) fn rough_contact(n: usize, hurst: f64, seed: u64) -> (Surface, Model) {
    let params = SurfaceParams::new(n, hurst, n as f64 / 2.0, n as f64 / 16.0, seed);
    let surface = Surface::generate(&params).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    (surface, model)
}
