//! A measured surface's own statistics: its rms height and slope, and its power spectrum,
//! as shells for Persson's theory and radially averaged for the page.
//!
//! Conventions ([`crate::conventions`], section 2): `h~(q) = N^-2 sum_r h(r) e^(-i q.r)`, so
//! that `mean(h^2) = sum_q |h~(q)|^2`; the isotropic power spectrum of a surface of side
//! `L` is `C(q) = (L / 2 pi)^2 <|h~(q)|^2>` (units: length^4), so that
//! `h_rms^2 = integral C(q) d^2q`.
//!
//! A periodic scan is transformed as it is (its mean removed). A measured, non-periodic scan
//! is first detrended (its least-squares plane removed: the tilt of the sample) and then
//! multiplied by a separable Hann window `w(x) w(y)`, `w(x) = sin^2(pi (x + 1/2) / N)`,
//! scaled by `8/3` so that the window keeps the mean square (`mean(w^2) = 3/8` per axis): the
//! step at the edges of a non-periodic map would otherwise leak power `~ q^-2` into every
//! wavevector (the usual remedy; Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5,
//! 013001 (2017)). The contact problem is solved on the detrended heights, not the
//! windowed ones.

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::engine::spectrum::ShellSpectrum;
use crate::engine::surface::Surface;
use crate::error::Result;

/// How a scan's edges are treated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Boundary {
    /// The scan is one period of a periodic surface.
    Periodic,
    /// A measured window of a larger surface: detrended, windowed, free boundary.
    #[default]
    Free,
}

/// Amplitude factor that makes the separable Hann window keep the mean square.
const HANN_NORM: f64 = 8.0 / 3.0;

/// One log-spaced bin of the radially averaged power spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RadialBin {
    /// Mean `|q|` of the bin's modes (1 / length).
    pub q: f64,
    /// `C(q)` (length^4).
    pub c: f64,
    /// Modes averaged (full spectrum).
    pub modes: u32,
}

/// A scan's statistics and spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanSpectrum {
    /// How the edges were treated.
    pub boundary: Boundary,
    /// The heights the contact problem is solved on (grid units: divided by the pixel
    /// size), detrended for a free boundary, as they are for a periodic one.
    pub heights: Vec<f64>,
    /// The spectrum in shells, grid units, `lambda_l = L` (the scan's side).
    pub shells: ShellSpectrum,
    /// Rms height of the detrended heights (the scan's length unit).
    pub h_rms: f64,
    /// Rms slope from finite differences of the detrended heights (dimensionless).
    pub slope_rms: f64,
    /// Rms slope from the spectrum, `sqrt(sum_q q^2 |h~|^2)`, the `g_bar` of Persson's
    /// theory (dimensionless).
    pub slope_rms_spectral: f64,
    /// The radially averaged `C(q)`, in the scan's units.
    pub radial: Vec<RadialBin>,
}

impl ScanSpectrum {
    /// The statistics of an `n x n` scan with pixel size `pixel` (heights and pixel in one
    /// length unit).
    pub fn new(heights: &[f64], n: usize, pixel: f64, boundary: Boundary) -> Result<Self> {
        let grid = Grid::new(n, 1.0)?;
        let scaled: Vec<f64> = heights.iter().map(|h| h / pixel).collect();
        let fft = Fft2::new(&grid);
        // The heights solved on: a periodic scan as `solve --heights` takes it (the
        // surface of its modes up to the shortest wavelength present), a free one without
        // its plane. Statistics are taken without the mean.
        let level = match boundary {
            Boundary::Periodic => {
                let surface = Surface::from_heights(grid.clone(), &scaled, None)?;
                surface.heights_at(surface.zeta_max(), &fft)
            }
            Boundary::Free => remove_plane(&scaled, n),
        };
        let centred = remove_mean(&level);
        let mut modes = fft.new_spectrum();
        match boundary {
            Boundary::Periodic => fft.forward(&level, &mut modes),
            Boundary::Free => fft.forward(&hann(&level, n), &mut modes),
        }
        let shells = ShellSpectrum::from_modes(&grid, &modes, grid.length());
        let h_rms =
            pixel * (centred.iter().map(|h| h * h).sum::<f64>() / centred.len() as f64).sqrt();
        let slope_rms = finite_difference_slope(&centred, n, boundary);
        let slope_rms_spectral = shells.rms_gradient(f64::INFINITY);
        let radial = radial_average(&grid, &modes, pixel);
        Ok(Self {
            boundary,
            heights: level,
            shells,
            h_rms,
            slope_rms,
            slope_rms_spectral,
            radial,
        })
    }
}

fn remove_mean(h: &[f64]) -> Vec<f64> {
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    h.iter().map(|v| v - mean).collect()
}

/// `h` minus its least-squares plane `c + a x + b y` (coordinates centred, so the three
/// coefficients decouple).
fn remove_plane(h: &[f64], n: usize) -> Vec<f64> {
    let centre = 0.5 * (n as f64 - 1.0);
    let coord = |k: usize| k as f64 - centre;
    let s2: f64 = (0..n).map(|k| coord(k).powi(2)).sum::<f64>() * n as f64;
    let (mut sx, mut sy, mut s) = (0.0, 0.0, 0.0);
    for (k, &v) in h.iter().enumerate() {
        sx += v * coord(k % n);
        sy += v * coord(k / n);
        s += v;
    }
    let (a, b, c) = (sx / s2, sy / s2, s / h.len() as f64);
    h.iter()
        .enumerate()
        .map(|(k, &v)| v - c - a * coord(k % n) - b * coord(k / n))
        .collect()
}

/// The separable Hann window, scaled to keep the mean square.
fn hann(h: &[f64], n: usize) -> Vec<f64> {
    let w: Vec<f64> = (0..n)
        .map(|k| {
            (std::f64::consts::PI * (k as f64 + 0.5) / n as f64)
                .sin()
                .powi(2)
        })
        .collect();
    h.iter()
        .enumerate()
        .map(|(k, &v)| v * w[k / n] * w[k % n] * HANN_NORM)
        .collect()
}

/// Rms slope `sqrt(mean(|grad h|^2))` from differences between neighbours (grid units, so
/// dimensionless): wrapping around for a periodic scan, inside the window for a free one.
fn finite_difference_slope(h: &[f64], n: usize, boundary: Boundary) -> f64 {
    let wrap = boundary == Boundary::Periodic;
    let (mut sum, mut count) = (0.0, 0usize);
    for i in 0..n {
        for j in 0..n {
            let v = h[i * n + j];
            if wrap || j + 1 < n {
                sum += (h[i * n + (j + 1) % n] - v).powi(2);
                count += 1;
            }
            if wrap || i + 1 < n {
                sum += (h[((i + 1) % n) * n + j] - v).powi(2);
                count += 1;
            }
        }
    }
    // Two directions: mean square of each difference, summed.
    (2.0 * sum / count as f64).sqrt()
}

/// Bins per decade of `q` in the radial average.
const BINS_PER_DECADE: f64 = 10.0;

/// The radially averaged `C(q) = (L / 2 pi)^2 <|h~|^2>` in log-spaced bins, converted from
/// grid units to the scan's (`q / pixel`, `C pixel^4`).
fn radial_average(grid: &Grid, modes: &[Complex64], pixel: f64) -> Vec<RadialBin> {
    let q_min = grid.dq();
    let bin_of = |q: f64| ((q / q_min).log10() * BINS_PER_DECADE).floor() as usize;
    let mut sums: Vec<(f64, f64, u32)> = Vec::new();
    for (s, h) in modes.iter().enumerate() {
        if s == 0 || grid.is_nyquist(s) {
            continue;
        }
        let q = grid.q(s);
        let b = bin_of(q);
        if sums.len() <= b {
            sums.resize(b + 1, (0.0, 0.0, 0));
        }
        let w = grid.weight_of(s);
        sums[b].0 += w * q;
        sums[b].1 += w * h.norm_sqr();
        sums[b].2 += w as u32;
    }
    let area = (grid.length() / (2.0 * std::f64::consts::PI)).powi(2);
    sums.into_iter()
        .filter(|s| s.2 > 0)
        .map(|(sq, sh, count)| RadialBin {
            q: sq / f64::from(count) / pixel,
            c: area * sh / f64::from(count) * pixel.powi(4),
            modes: count,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::surface::{Surface, SurfaceParams};

    #[test]
    fn a_tilted_plane_is_removed_entirely() {
        let n = 16;
        let h: Vec<f64> = (0..n * n)
            .map(|k| 3.0 + 0.2 * (k % n) as f64 - 0.7 * (k / n) as f64)
            .collect();
        let s = ScanSpectrum::new(&h, n, 0.5, Boundary::Free).unwrap();
        assert!(s.heights.iter().all(|v| v.abs() < 1e-12));
        assert!(s.h_rms < 1e-12 && s.slope_rms < 1e-12);
    }

    #[test]
    fn a_periodic_scan_keeps_its_own_spectrum_and_units() {
        // A generated surface (unit rms gradient) read back as a periodic scan with pixel
        // 0.25: the spectral slope is the generator's, h_rms scales with the pixel, and
        // integral C d^2q gives back h_rms^2.
        let surface = Surface::generate(&SurfaceParams::new(64, 0.8, 64.0, 4.0, 5)).unwrap();
        let fft = Fft2::new(surface.grid());
        let h: Vec<f64> = surface
            .heights_at(f64::INFINITY, &fft)
            .iter()
            .map(|v| v * 0.25)
            .collect();
        let s = ScanSpectrum::new(&h, 64, 0.25, Boundary::Periodic).unwrap();
        assert!(
            (s.slope_rms_spectral - 1.0).abs() < 1e-12,
            "{}",
            s.slope_rms_spectral
        );
        let rms_grid = surface.shells().rms_height(f64::INFINITY);
        assert!((s.h_rms / (0.25 * rms_grid) - 1.0).abs() < 1e-12);
        // Sum of C over the modes times the area per mode (2 pi / L)^2 is the variance.
        let dq = 2.0 * std::f64::consts::PI / (64.0 * 0.25);
        let var: f64 = s
            .radial
            .iter()
            .map(|b| b.c * f64::from(b.modes) * dq * dq)
            .sum();
        // The Nyquist modes are left out of the radial average only.
        assert!(
            (var / s.h_rms.powi(2) - 1.0).abs() < 0.02,
            "{var} vs {}",
            s.h_rms.powi(2)
        );
    }

    #[test]
    fn the_window_keeps_the_spectrum_of_a_rough_window_near_the_periodic_one() {
        // A 128^2 window cut from a 256^2 periodic surface: its windowed spectral slope is
        // close to the whole surface's (the window removes the edge leak).
        let surface = Surface::generate(&SurfaceParams::new(256, 0.8, 128.0, 4.0, 2)).unwrap();
        let fft = Fft2::new(surface.grid());
        let full = surface.heights_at(f64::INFINITY, &fft);
        let window: Vec<f64> = (0..128 * 128)
            .map(|k| full[(k / 128) * 256 + k % 128])
            .collect();
        let s = ScanSpectrum::new(&window, 128, 1.0, Boundary::Free).unwrap();
        assert!(
            (s.slope_rms_spectral - 1.0).abs() < 0.1,
            "{}",
            s.slope_rms_spectral
        );
        assert!((s.slope_rms - 1.0).abs() < 0.15, "{}", s.slope_rms);
    }
}
