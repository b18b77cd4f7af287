//! The re-entry share over magnification on a scan's own shells: assumption (c) of the
//! validations (`p = 0` absorbs), measured as the `c_reentry` validation measures it
//! (the validation's climbs, [`crate::engine::climb`]), on the scan instead of a generated
//! surface.
//!
//! The scan's spectrum is truncated as that validation truncates its surfaces: at
//! `zeta_max = L / lambda_s` with the long-wavelength cutoff at the scan's longer side
//! `L` and `lambda_s` four points of the grid the sweep is solved on ([`REENTRY_ZETA`],
//! at most a quarter of the scan's points per side). The truncated surface is
//! band-limited, so it is solved on the grid of `4 zeta_max` points along the longer
//! side that holds it exactly (its modes placed on that grid's own wavevectors, a
//! [`Roughness`] of the engine). The engine's [`Sweep`] then adds every distinct shell
//! `|q|` up to `zeta_max` (the scan grid's integer shells, [`Grid::k2_wide`]) one at a
//! time, from the first, at the fixed load of the check's middle load, each solve
//! warm-started from the last: the fixed-load steps of `c_reentry`'s climbs
//! ([`climb_steps`]); the history of every point of the window ([`History`], the validation's own
//! record) gives the share of the points in contact at `zeta_max` that were out of
//! contact at a lower magnification (Persson: 0), and the share that left after the
//! first shell and came back. A free scan is swept on the free boundary, its heights the detrended scan's
//! modes (truncating a non-periodic window's spectrum rings at its edges as the window's
//! periodic images step; the share counts the whole window).

use std::time::Instant;

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use super::body::window_of;
use super::psd::{half_spectrum, Boundary, ScanSpectrum, Shape};
use super::theory::E_STAR;
use crate::engine::climb::{climb_steps, Recorder, Stepped};
use crate::engine::contact::{ContactSolution, Model};
use crate::engine::grid::Grid;
use crate::engine::history::History;
use crate::engine::solver::{SolveOptions, SolverKind};
use crate::engine::sweep::{shell_steps, Roughness, Sweep};
use crate::error::{Error, Result};

/// The magnification the sweep climbs to, `L / lambda_s`: the reduced `c_reentry` scene's
/// `zeta_max` (`lambda_l / lambda_s = 64 / 4`), with the scan's side as `lambda_l`. On a
/// square scan this is some ninety shells, on a grid of 64^2 points: about a second.
pub const REENTRY_ZETA: f64 = 16.0;

/// Points per shortest wavelength on the sweep's grid (the validations' `lambda_s = 4`).
const POINTS_PER_LAMBDA_S: f64 = 4.0;

/// The re-entry share of a scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reentry {
    /// The fixed load, `p0 / E*`.
    pub p0: f64,
    /// The magnification climbed to (`L / lambda_s`).
    pub zeta_max: f64,
    /// Shells added, one at a time.
    pub shells: usize,
    /// The sweep's grid (rows x columns of the window).
    pub grid: [usize; 2],
    /// The contact area at `zeta_max` on the sweep's grid.
    pub a_r: f64,
    /// Points in contact at `zeta_max`.
    pub contact_points: u64,
    /// Of those, the share that was out of contact at a lower magnification (the first
    /// shell included).
    pub share: f64,
    /// Of those, the share that left contact after the first shell and came back.
    pub share_after_first: f64,
    /// Solver iterations of the sweep.
    pub iterations: u64,
    /// Wall time, seconds.
    pub wall_s: f64,
    /// Why the sweep stopped before `zeta_max`, if it did (then the shares are those of
    /// the last shell reached).
    pub failed: Option<String>,
}

/// The modes of `spectrum`'s heights up to `zeta_max`, on the grid that holds them: the
/// sweep's grid, and the modes in increasing shells, each `(shell, index on the sweep's
/// half spectrum, amplitude)`, the shell the scan grid's integer `|k|^2`
/// ([`Grid::k2_wide`]); the amplitudes in the sweep's pixels.
struct Truncated {
    shape: Shape,
    grid: Grid,
    modes: Vec<(u64, usize, Complex64)>,
    /// The scan grid's `|q| / q_l` of shell `k2`, `sqrt(k2) L / L_s`.
    zeta_per_root_k2: f64,
    /// The scan's grid and its longer side (the `lambda_l` of `zeta`), which turn a
    /// magnification into the largest shell it resolves.
    scan_grid: Grid,
    longer: f64,
}

impl Roughness for Truncated {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn modes_at(&self, zeta: f64, out: &mut [Complex64]) {
        let limit = self.scan_grid.shell_limit_wide(zeta, self.longer);
        out.fill(Complex64::default());
        for &(_, at, amplitude) in self.modes.iter().take_while(|m| m.0 <= limit) {
            out[at] = amplitude;
        }
    }

    fn shell_zetas(&self) -> Vec<f64> {
        shells(&self.modes)
            .into_iter()
            .map(|k2| (k2 as f64).sqrt() * self.zeta_per_root_k2)
            .collect()
    }
}

fn truncate(spectrum: &ScanSpectrum, zeta_max: f64) -> Result<Truncated> {
    let longer = spectrum.shape.longer() as f64;
    let coarse = POINTS_PER_LAMBDA_S * zeta_max;
    let side = |n: usize| ((n as f64 * coarse / longer).ceil() as usize).max(4);
    let shape = Shape {
        rows: side(spectrum.shape.rows),
        cols: side(spectrum.shape.cols),
    };
    let sweep_grid = Grid::rectangle(shape.rows, shape.cols, 1.0)?;
    let m = sweep_grid.half_cols();
    // Heights in the sweep's pixels: the scan's pixel over the sweep's.
    let scale = coarse / longer;
    let (grid, spec) = half_spectrum(&spectrum.heights, spectrum.shape)?;
    let limit = grid.shell_limit_wide(zeta_max, longer);
    let mut modes: Vec<(u64, usize, Complex64)> = spec
        .iter()
        .enumerate()
        .skip(1)
        .filter_map(|(s, h)| {
            let k2 = grid.k2_wide(s);
            let (mx, my) = grid.wavevector(s);
            // |mx| <= zeta_max cols / L <= cols' / 4: every mode has its own place.
            let at = wrap(my, shape.rows) * m + mx as usize;
            (k2 <= limit).then_some((k2, at, h * scale))
        })
        .collect();
    modes.sort_by_key(|&(k2, _, _)| k2);
    Ok(Truncated {
        shape,
        grid: sweep_grid,
        modes,
        zeta_per_root_k2: longer / grid.length(),
        longer,
        scan_grid: grid,
    })
}

/// The history of the window's points on a free boundary's padded grid (or of every
/// point of a periodic one), recorded step by step.
struct WindowHistory<'m> {
    history: History,
    model: &'m Model,
    shape: Shape,
}

impl Recorder for WindowHistory<'_> {
    fn record(&mut self, step: usize, _zeta: f64, solution: &ContactSolution) -> Result<()> {
        let pressure = window_of(self.model, self.shape, &solution.pressure);
        self.history.update(step, &pressure);
        Ok(())
    }
}

/// The index of signed wavenumber `m` on a side of `n` points.
fn wrap(m: i64, n: usize) -> usize {
    m.rem_euclid(n as i64) as usize
}

/// The distinct shells of the truncated modes, increasing.
fn shells(modes: &[(u64, usize, Complex64)]) -> Vec<u64> {
    let mut k2: Vec<u64> = modes.iter().map(|&(k, _, _)| k).collect();
    k2.dedup();
    k2
}

/// Sweeps the shells of `spectrum` at load `p0` with `solver` to `tol` (see the module
/// docs). `Ok(Err(message))` is a sweep a solve ended; the error, bad input.
pub fn reentry_share(
    spectrum: &ScanSpectrum,
    p0: f64,
    solver: SolverKind,
    tol: f64,
) -> Result<Reentry> {
    let timer = Instant::now();
    let zeta_max = REENTRY_ZETA.min(spectrum.shape.longer() as f64 / POINTS_PER_LAMBDA_S);
    let truncated = truncate(spectrum, zeta_max)?;
    let shape = truncated.shape;
    let model = match spectrum.boundary {
        Boundary::Periodic => Model::new(Grid::new(shape.rows, 1.0)?, E_STAR)?,
        Boundary::Free => Model::free_window(shape.rows, shape.cols, E_STAR)?,
    };
    let share = shape.points() as f64 / model.grid.points() as f64;
    let steps = shell_steps(&truncated, 0.0, f64::INFINITY);
    let mut window = WindowHistory {
        history: History::new(shape.points(), (f64::INFINITY, f64::INFINITY)),
        model: &model,
        shape,
    };
    let mut sweep = Sweep::new(&truncated, &model, solver, SolveOptions::with_tol(tol));
    let mut reached = Stepped::default();
    let climbed = climb_steps(
        &mut sweep,
        p0 * share,
        &steps,
        Stepped::default(),
        &mut window,
        |_, _, done| {
            reached = *done;
            Ok(())
        },
    );
    let failed = match climbed {
        Ok(_) => None,
        Err(
            e @ (Error::NotConverged { .. } | Error::NonFinite { .. } | Error::LostContact { .. }),
        ) => {
            let zeta = steps[reached.step];
            Some(format!(
                "re-entry sweep, shell {} of {} (zeta = {zeta:.3}): {e}",
                reached.step + 1,
                steps.len()
            ))
        }
        Err(e) => return Err(e),
    };
    let (history, iterations) = (window.history, reached.iterations);
    let (contact_points, reentered, after_first) = history.counts();
    let of = |k: u64| k as f64 / contact_points.max(1) as f64;
    Ok(Reentry {
        p0,
        zeta_max,
        shells: steps.len(),
        grid: [shape.rows, shape.cols],
        a_r: contact_points as f64 / shape.points() as f64,
        contact_points,
        share: of(reentered),
        share_after_first: of(after_first),
        iterations,
        wall_s: timer.elapsed().as_secs_f64(),
        failed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::fft::Fft2;
    use crate::engine::surface::{Surface, SurfaceModel};

    #[test]
    fn the_truncated_surface_keeps_its_modes_on_the_coarse_grid() {
        // A band-limited periodic 64^2 surface (lambda_s = 8: zeta <= 8) truncated at
        // zeta_max = 8 lands on a 32^2 grid with every mode: the coarse heights are the
        // fine ones at every second point, in coarse pixels (half as many per length).
        let surface = Surface::generate(&SurfaceModel::new(64, 0.8, 64.0, 8.0, 4)).unwrap();
        let fft = Fft2::new(surface.grid());
        let h = surface.heights_at(f64::INFINITY, &fft);
        let shape = Shape { rows: 64, cols: 64 };
        let spectrum = ScanSpectrum::new(&h, shape, 1.0, Boundary::Periodic).unwrap();
        let t = truncate(&spectrum, 8.0).unwrap();
        assert_eq!(t.shape, Shape { rows: 32, cols: 32 });
        let fft = Fft2::new(&t.grid);
        let mut spec = fft.new_spectrum();
        t.modes_at(8.0, &mut spec);
        let mut coarse = vec![0.0; t.shape.points()];
        fft.inverse(&spec, &mut coarse, &mut Vec::new());
        for i in 0..32 {
            for j in 0..32 {
                let fine = 0.5 * spectrum.heights[2 * i * 64 + 2 * j];
                assert!((coarse[i * 32 + j] - fine).abs() < 1e-12, "({i}, {j})");
            }
        }
        // The shells are the surface's own, in increasing order, from |k|^2 = 1 to the
        // last below zeta = 8 (|k|^2 = 64).
        let k2 = shells(&t.modes);
        assert!(k2.windows(2).all(|w| w[0] < w[1]));
        assert_eq!((k2[0], *k2.last().unwrap()), (1, 64));
        assert!((8.0 * t.zeta_per_root_k2 - 8.0).abs() < 1e-15);
        // Each shell's magnification resolves that shell and no other.
        let zetas = t.shell_zetas();
        assert_eq!(zetas.len(), k2.len());
        for (&z, &k) in zetas.iter().zip(&k2) {
            assert_eq!(t.scan_grid.shell_limit_wide(z, t.longer), k);
        }
    }

    #[test]
    fn points_leave_and_come_back_as_shells_are_added() {
        // A 64^2 window of a rough surface at a_r about 0.1: some points re-enter (the
        // paper's finding), and the share counts the points in contact at zeta_max.
        let surface = Surface::generate(&SurfaceModel::new(128, 0.8, 64.0, 4.0, 6)).unwrap();
        let fft = Fft2::new(surface.grid());
        let full = surface.heights_at(f64::INFINITY, &fft);
        let shape = Shape { rows: 48, cols: 64 };
        let window: Vec<f64> = (0..shape.points())
            .map(|k| full[(k / 64) * 128 + k % 64])
            .collect();
        let spectrum = ScanSpectrum::new(&window, shape, 1.0, Boundary::Free).unwrap();
        let r = reentry_share(&spectrum, 0.05, SolverKind::Cg, 1e-8).unwrap();
        assert!(r.failed.is_none(), "{:?}", r.failed);
        assert_eq!(r.zeta_max, 16.0);
        assert_eq!(r.grid, [48, 64]);
        assert!(r.shells > 50, "{} shells", r.shells);
        assert!(r.a_r > 0.01 && r.a_r < 0.5, "a_r {}", r.a_r);
        assert!(r.share > 0.0 && r.share <= 1.0, "share {}", r.share);
        assert!(r.share_after_first <= r.share);
    }
}
