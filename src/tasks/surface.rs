//! Surfaces: a generated self-affine realization (`persson-check surface`, Python's
//! `surface`), and heights handed over as a field (`solve --heights`, Python's arrays).
//!
//! A realization is the scene's spectrum with Gaussian (or random-phase) amplitudes drawn
//! from the seed ([`crate::engine::surface`]); at magnification `zeta` only the modes with
//! `|q| <= zeta q_l` are kept, so one seed gives the same roughness, bit for bit, at every
//! magnification and from both front ends.

use std::path::Path;

use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::engine::scene::{check_zeta, read_scene};
use crate::error::{Error, Result};

/// A surface (its heights, its grid and its spectrum), the one surface model that
/// generates one, and a scene file (a `[surface]` model and a `[solve]` table).
pub use crate::engine::scene::{Scene, SolveScene};
pub use crate::engine::surface::{Amplitudes, Surface, SurfaceModel};

/// The smallest and largest grid sides.
pub use crate::engine::grid::{MAX_N, MIN_N};

use super::Spelling;

/// A generated surface as a front end asks for it: a scene file, or the model's
/// parameters one by one (Gaussian amplitudes, unit rms gradient, no roll-off); a seed
/// given replaces the scene's.
#[derive(Debug, Clone, Copy, Default)]
pub struct SurfaceArgs<'a> {
    /// A scene file (TOML) with a `[surface]` table.
    pub scene: Option<&'a Path>,
    /// Points per side.
    pub n: Option<usize>,
    /// Hurst exponent, in (0, 1).
    pub hurst: Option<f64>,
    /// Long-wavelength cutoff (grid units), at most `n`.
    pub lambda_l: Option<f64>,
    /// Short-wavelength cutoff (grid units), at least 2.
    pub lambda_s: Option<f64>,
    /// The realization.
    pub seed: Option<u64>,
}

impl SurfaceArgs<'_> {
    /// The scene (read from its file, or made of the parameters given, checked), its
    /// surface's seed set; errors name a parameter through `s`, a missing one as
    /// `missing` says how to give it.
    pub fn resolve(&self, s: &dyn Spelling, missing: &str) -> Result<Scene> {
        let mut scene = match self.scene {
            Some(path) => read_scene(path)?,
            None => {
                let given = |key: &str, value: Option<f64>| {
                    value.ok_or_else(|| Error::invalid(&s.name(key), "missing", missing))
                };
                let n = self
                    .n
                    .ok_or_else(|| Error::invalid(&s.name("n"), "missing", missing))?;
                let surface = SurfaceModel {
                    seed: None,
                    ..SurfaceModel::new(
                        n,
                        given("hurst", self.hurst)?,
                        given("lambda_l", self.lambda_l)?,
                        given("lambda_s", self.lambda_s)?,
                        0,
                    )
                };
                surface.validate().map_err(|e| s.rename(e))?;
                Scene {
                    surface,
                    solve: SolveScene::default(),
                }
            }
        };
        let seed = self.seed.or(scene.surface.seed).ok_or_else(|| {
            Error::invalid(
                "seed",
                "missing",
                format!("given ({} or seed = K in the scene)", s.given("seed", "K")),
            )
        })?;
        scene.surface.seed = Some(seed);
        Ok(scene)
    }
}

/// The surface of a scene resolved by [`SurfaceArgs::resolve`] (its seed set).
pub fn realization(scene: &Scene) -> Result<Surface> {
    Surface::generate(&scene.surface)
}

/// The surface of a `.npy` file of heights (float64, `n x n`); `lambda_l` as in
/// [`from_heights`]. A `lambda_l` beyond the box is named through `s`, anything else as
/// the file.
pub fn read_heights(path: &Path, lambda_l: Option<f64>, s: &dyn Spelling) -> Result<Surface> {
    let field = crate::io::npy::read_field(path, MIN_N..=MAX_N)?;
    from_heights(field.n, &field.values, lambda_l).map_err(|e| match &e {
        Error::InvalidInput { field, .. } if field == "lambda_l" => s.rename(e),
        _ => Error::bad_file(path, e.to_string()),
    })
}

/// The heights of the realization of `scene` (resolved by [`SurfaceArgs::resolve`]: its
/// model checked, its seed set) at magnification `zeta` (default: every mode,
/// `zeta = lambda_l / lambda_s`), after checking `zeta`.
pub fn generate(scene: &Scene, zeta: Option<f64>, s: &dyn Spelling) -> Result<Vec<f64>> {
    let zeta_max = scene.surface.zeta_max();
    let zeta = zeta.unwrap_or(zeta_max);
    check_zeta(zeta, zeta_max).map_err(|e| s.rename(e))?;
    let surface = realization(scene)?;
    let fft = Fft2::new(surface.grid());
    Ok(surface.heights_at(zeta, &fft))
}

/// The surface of an `n x n` field of heights (grid spacing 1); `lambda_l` is the
/// wavelength that defines `zeta = |q| / q_l` (default: the box size).
///
/// # Errors
///
/// If `n` is outside the grid's range, the heights are not `n x n` finite values, or
/// `lambda_l` is out of range.
pub fn from_heights(n: usize, heights: &[f64], lambda_l: Option<f64>) -> Result<Surface> {
    let grid = Grid::new(n, 1.0)?;
    Surface::from_heights(grid, heights, lambda_l)
}
