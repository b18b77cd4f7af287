//! Persson checked on the user's own surface: read the scans, solve their load curves,
//! compare with Persson's predictions and write `surface.json`, `surface.md` and the
//! figures ([`crate::measured`]). The command line's `check-surface` and Python's
//! `check_surface` both call [`check_surface`].

use std::path::Path;

use super::Spelling;
use crate::engine::solver::{Progress, SolverKind};
use crate::error::Result;
use crate::measured::check::{check, CheckOptions, SurfaceCheck};
use crate::measured::page;
use crate::measured::scan::Scan;

/// Reads the scans in `paths` (one surface, several scans).
pub fn read_scans(paths: &[impl AsRef<Path>], s: &dyn Spelling) -> Result<Vec<Scan>> {
    if paths.is_empty() {
        return Err(s.rename(crate::error::Error::invalid(
            "heights",
            "no file",
            "at least one height map (.npy or a text matrix)",
        )));
    }
    paths.iter().map(|p| Scan::read(p.as_ref())).collect()
}

/// Checks the surface of `scans` with `opts`; writes the page and its files into `out`
/// when given. `progress` sees the scan, the solver, the load and every iteration.
pub fn check_surface(
    scans: &[Scan],
    opts: &CheckOptions,
    out: Option<&Path>,
    s: &dyn Spelling,
    progress: &mut dyn FnMut(usize, SolverKind, usize, Progress),
) -> Result<SurfaceCheck> {
    if let Some(dir) = out {
        super::check_out_dir(dir, s)?;
    }
    let result = check(scans, opts, progress).map_err(|e| s.rename(e))?;
    if let Some(dir) = out {
        page::write(&result, dir)?;
    }
    Ok(result)
}
