//! Surfaces: a generated self-affine realization (`persson-check surface`, Python's
//! `surface`), and heights handed over as a field (`solve --heights`, Python's arrays).
//!
//! A realization is the scene's spectrum with Gaussian (or random-phase) amplitudes drawn
//! from the seed ([`crate::engine::surface`]); at magnification `zeta` only the modes with
//! `|q| <= zeta q_l` are kept, so one seed gives the same roughness, bit for bit, at every
//! magnification and from both front ends.

use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::engine::scene::{check_zeta, SurfaceScene};

/// A surface: its heights, its grid and its spectrum.
pub use crate::engine::surface::Surface;
use crate::error::Result;

use super::Spelling;

/// The heights of realization `seed` of `scene` at magnification `zeta` (default: every
/// mode, `zeta = lambda_l / lambda_s`), after checking the scene's ranges and `zeta`.
pub fn generate(
    scene: &SurfaceScene,
    seed: u64,
    zeta: Option<f64>,
    s: &dyn Spelling,
) -> Result<Vec<f64>> {
    scene.validate().map_err(|e| s.rename(e))?;
    let zeta_max = scene.zeta_max();
    let zeta = zeta.unwrap_or(zeta_max);
    check_zeta(zeta, zeta_max).map_err(|e| s.rename(e))?;
    let surface = Surface::generate(&scene.params(seed))?;
    let fft = Fft2::new(surface.grid());
    Ok(surface.heights_at(zeta, &fft))
}

/// The surface of an `n x n` field of heights (grid spacing 1); `lambda_l` is the
/// wavelength that defines `zeta = |q| / q_l` (default: the box size).
pub fn from_heights(n: usize, heights: &[f64], lambda_l: Option<f64>) -> Result<Surface> {
    let grid = Grid::new(n, 1.0)?;
    Surface::from_heights(grid, heights, lambda_l)
}
