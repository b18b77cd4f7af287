//! Rendering of [`Figure`] and [`Raster`] to files.

use std::path::{Path, PathBuf};

use super::{Figure, Raster};
use crate::error::Result;

/// Renders `figure` into `dir` as `<name>.svg` and `<name>.png`; returns the paths.
pub fn render(_figure: &Figure, _dir: &Path) -> Result<Vec<PathBuf>> {
    Ok(Vec::new())
}

/// Renders `raster` into `dir` as `<name>.png`; returns the path.
pub fn render_raster(_raster: &Raster, _dir: &Path) -> Result<Vec<PathBuf>> {
    Ok(Vec::new())
}
