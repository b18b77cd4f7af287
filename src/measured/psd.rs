//! A measured surface's own statistics: its rms height and slope, the moments of its
//! height distribution, and its power spectrum, as shells for Persson's theory, radially
//! averaged for the page, and as the slope tensor that says how isotropic it is.
//!
//! Conventions ([`crate::conventions`], section 2), for a scan of `R x C` points (rows x
//! columns) with pixel `a`: `h~(q) = (R C)^-1 sum_r h(r) e^(-i q.r)` with the physical
//! wavevectors `q = 2 pi (mx / (C a), my / (R a))`, so that `mean(h^2) = sum_q |h~(q)|^2`;
//! the isotropic power spectrum is `C(q) = A / (2 pi)^2 <|h~(q)|^2>` with the scan's area
//! `A = R C a^2` (units: length^4), so that `h_rms^2 = integral C(q) d^2q`. A square scan
//! is the case `R = C`; on a rectangle the wavevectors are not on one square lattice, and
//! the shells group the modes of equal `|q|` exactly: `|q|^2` is proportional to the
//! integer `mx^2 R'^2 + my^2 C'^2` (`R' = R / g`, `C' = C / g`, `g` their greatest common
//! divisor).
//!
//! A periodic scan (square) is transformed as it is (its mean removed), on the grid of
//! the solver, so that Persson's theory sees the modes `solve --heights` solves. A
//! measured, non-periodic scan is first detrended (its least-squares plane removed: the
//! tilt of the sample) and then multiplied by a separable Hann window `w(x) w(y)`,
//! `w(x) = sin^2(pi (x + 1/2) / N)` along each side, scaled by `8/3` so that the window
//! keeps the mean square (`mean(w^2) = 3/8` per axis): the step at the edges of a
//! non-periodic map would otherwise leak power `~ q^-2` into every wavevector (the usual
//! remedy; Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017)). The
//! contact problem is solved on the detrended heights, not the windowed ones.
//!
//! What says whether the theory applies: the skewness and the excess kurtosis of the
//! heights (0 for Gaussian heights), the anisotropy `sqrt(l_min / l_max)` of the slope
//! tensor `sum_q q q^T |h~(q)|^2` (1 for an isotropic spectrum, near 0 for stripes), and
//! the log-log slope of `C(q)` over the highest octave below the Nyquist wavevector
//! `pi / a` (`-2 (1 + H)`, between -4 and -2, for a self-affine surface; near 0 for an
//! instrument's white-noise floor).

use std::collections::BTreeMap;

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::engine::spectrum::{Shell, ShellSpectrum};
use crate::engine::surface::Surface;
use crate::error::{Error, Result};
use crate::stats::{Bins, Histogram};

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

/// The shape of a scan: rows and columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shape {
    /// Rows (points along axis 0).
    pub rows: usize,
    /// Columns (points along axis 1).
    pub cols: usize,
}

impl Shape {
    /// Points of the scan.
    pub fn points(&self) -> usize {
        self.rows * self.cols
    }

    /// The longer side.
    pub fn longer(&self) -> usize {
        self.rows.max(self.cols)
    }

    /// Whether rows equal columns.
    pub fn is_square(&self) -> bool {
        self.rows == self.cols
    }
}

impl std::fmt::Display for Shape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} x {}", self.rows, self.cols)
    }
}

/// A scan's statistics and spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanSpectrum {
    /// How the edges were treated.
    pub boundary: Boundary,
    /// The scan's shape.
    pub shape: Shape,
    /// The heights the contact problem is solved on (grid units: divided by the pixel
    /// size), detrended for a free boundary, as they are for a periodic one.
    pub heights: Vec<f64>,
    /// The spectrum in shells, grid units, `lambda_l` the scan's longer side.
    pub shells: ShellSpectrum,
    /// Rms height of the detrended heights (the scan's length unit).
    pub h_rms: f64,
    /// Rms slope from finite differences of the detrended heights (dimensionless).
    pub slope_rms: f64,
    /// Rms slope from the spectrum, `sqrt(sum_q q^2 |h~|^2)`, the `g_bar` of Persson's
    /// theory (dimensionless).
    pub slope_rms_spectral: f64,
    /// Skewness of the detrended heights.
    pub skewness: f64,
    /// Excess kurtosis of the detrended heights.
    pub kurtosis: f64,
    /// `sqrt(l_min / l_max)` of the slope tensor (1: isotropic).
    pub anisotropy: f64,
    /// Log-log slope of `C(q)` over the highest octave below the Nyquist wavevector
    /// (`None` when fewer than two bins lie there).
    pub high_q_slope: Option<f64>,
    /// The radially averaged `C(q)`, in the scan's units.
    pub radial: Vec<RadialBin>,
}

/// One mode of the half spectrum: its wavevector (grid units), `|h~|^2` and its weight in
/// sums over the full spectrum (1 or 2), and whether it lies on a Nyquist row or column.
#[derive(Debug, Clone, Copy)]
struct Mode {
    qx: f64,
    qy: f64,
    power: f64,
    weight: f64,
    nyquist: bool,
}

impl ScanSpectrum {
    /// The statistics of a `shape` scan with pixel size `pixel` (heights and pixel in one
    /// length unit). A periodic scan must be square (the solvers' periodic grid is).
    pub fn new(heights: &[f64], shape: Shape, pixel: f64, boundary: Boundary) -> Result<Self> {
        let scaled: Vec<f64> = heights.iter().map(|h| h / pixel).collect();
        let (level, modes, shells) = match boundary {
            Boundary::Periodic => periodic_modes(&scaled, shape)?,
            Boundary::Free => {
                let level = remove_plane(&scaled, shape);
                let (modes, shells) = window_modes(&hann(&level, shape), shape)?;
                (level, modes, shells)
            }
        };
        let centred = remove_mean(&level);
        let moments = Moments::of(&centred);
        let h_rms = pixel * moments.rms;
        let slope_rms = finite_difference_slope(&centred, shape, boundary);
        let slope_rms_spectral = shells.rms_gradient(f64::INFINITY);
        let radial = radial_average(&modes, shape, pixel);
        let high_q_slope = high_q_slope(&radial, pixel);
        Ok(Self {
            boundary,
            shape,
            heights: level,
            shells,
            h_rms,
            slope_rms,
            slope_rms_spectral,
            skewness: moments.skewness,
            kurtosis: moments.kurtosis,
            anisotropy: anisotropy(&modes),
            high_q_slope,
            radial,
        })
    }
}

/// One mode of a scan's spectrum in the scan's units, as the radial average sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModePower {
    /// `|q|` (1 / length).
    pub q: f64,
    /// `C = A / (2 pi)^2 |h~(q)|^2` of this mode alone (length^4).
    pub c: f64,
    /// The modes of the full spectrum it stands for (1 or 2: `q` and `-q`).
    pub weight: f64,
}

/// Every mode of a scan's half spectrum, transformed as [`ScanSpectrum::new`] transforms
/// it (a periodic scan as it is, a free one detrended and Hann-windowed), without `q = 0`
/// and the Nyquist rows and columns (as the radial average leaves them out), in the
/// scan's units: what [`crate::measured::stitch`] bins on a grid of its own.
pub fn scan_modes(
    heights: &[f64],
    shape: Shape,
    pixel: f64,
    boundary: Boundary,
) -> Result<Vec<ModePower>> {
    let scaled: Vec<f64> = heights.iter().map(|h| h / pixel).collect();
    let modes = match boundary {
        Boundary::Periodic => periodic_modes(&scaled, shape)?.1,
        Boundary::Free => window_modes(&hann(&remove_plane(&scaled, shape), shape), shape)?.0,
    };
    let area = shape.points() as f64 / (2.0 * std::f64::consts::PI).powi(2);
    Ok(modes
        .into_iter()
        .filter(|m| !m.nyquist)
        .map(|m| ModePower {
            q: m.qx.hypot(m.qy) / pixel,
            c: area * m.power * pixel.powi(4),
            weight: m.weight,
        })
        .collect())
}

/// A periodic scan's heights as `solve --heights` takes them (the surface of its modes up
/// to the shortest wavelength present), its half spectrum and its shells on the grid.
fn periodic_modes(scaled: &[f64], shape: Shape) -> Result<(Vec<f64>, Vec<Mode>, ShellSpectrum)> {
    if !shape.is_square() {
        return Err(Error::invalid(
            "periodic",
            format!("a {shape} scan"),
            "a square scan (the periodic solvers' grid is square; a rectangular scan is \
             solved with a free boundary, without --periodic)",
        ));
    }
    let grid = Grid::new(shape.rows, 1.0)?;
    let fft = Fft2::new(&grid);
    let surface = Surface::from_heights(grid.clone(), scaled, None)?;
    let level = surface.heights_at(surface.zeta_max(), &fft);
    let mut spec = fft.new_spectrum();
    fft.forward(&level, &mut spec);
    let shells = ShellSpectrum::from_modes(&grid, &spec, grid.length());
    let dq = grid.dq();
    let modes = spec
        .iter()
        .enumerate()
        .filter(|&(s, _)| s != 0)
        .map(|(s, h)| {
            let (mx, my) = grid.wavevector(s);
            Mode {
                qx: dq * mx as f64,
                qy: dq * my as f64,
                power: h.norm_sqr(),
                weight: grid.weight_of(s),
                nyquist: grid.is_nyquist(s),
            }
        })
        .collect();
    Ok((level, modes, shells))
}

/// The half spectrum of a (windowed) rectangular scan in grid units, and its shells of
/// equal `|q|` (see the module docs), the grid's integer shells ([`Grid::k2_wide`]).
fn window_modes(h: &[f64], shape: Shape) -> Result<(Vec<Mode>, ShellSpectrum)> {
    let Shape { rows, cols } = shape;
    let (grid, spec) = half_spectrum(h, shape)?;
    let two_pi = 2.0 * std::f64::consts::PI;
    let mut modes = Vec::with_capacity(grid.modes());
    let mut acc: BTreeMap<u64, (u32, f64)> = BTreeMap::new();
    for (s, h) in spec.iter().enumerate().skip(1) {
        let (mx, my) = grid.wavevector(s);
        let weight = grid.weight_of(s);
        let power = h.norm_sqr();
        modes.push(Mode {
            qx: two_pi * mx as f64 / cols as f64,
            qy: two_pi * my as f64 / rows as f64,
            power,
            weight,
            nyquist: grid.is_nyquist(s),
        });
        if power == 0.0 {
            continue;
        }
        let e = acc.entry(grid.k2_wide(s)).or_insert((0, 0.0));
        e.0 += weight as u32;
        e.1 += weight * power;
    }
    let lambda_l = shape.longer() as f64;
    let q_l = two_pi / lambda_l;
    let dq = grid.dq();
    let shells = acc
        .into_iter()
        .map(|(key, (count, h2))| {
            let q = dq * (key as f64).sqrt();
            Shell {
                // The integer of `|q|^2` (saturated where it exceeds the field: a label).
                k2: u32::try_from(key).unwrap_or(u32::MAX),
                q,
                zeta: q / q_l,
                modes: count,
                h2,
                q2h2: q * q * h2,
            }
        })
        .collect();
    Ok((modes, ShellSpectrum { q_l, shells }))
}

/// The grid of a `shape` scan (grid units) and the half spectrum of `h` on it, by the
/// engine's transform ([`Fft2::forward`]: `h~ = (R C)^-1 sum h e^(-i q.r)`).
pub(super) fn half_spectrum(h: &[f64], shape: Shape) -> Result<(Grid, Vec<Complex64>)> {
    let grid = Grid::rectangle(shape.rows, shape.cols, 1.0)?;
    let fft = Fft2::new(&grid);
    let mut spec = fft.new_spectrum();
    fft.forward(h, &mut spec);
    Ok((grid, spec))
}

fn remove_mean(h: &[f64]) -> Vec<f64> {
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    h.iter().map(|v| v - mean).collect()
}

/// `h` minus its least-squares plane `c + a x + b y` (coordinates centred, so the three
/// coefficients decouple).
fn remove_plane(h: &[f64], shape: Shape) -> Vec<f64> {
    let Shape { rows, cols } = shape;
    let centre = |n: usize| 0.5 * (n as f64 - 1.0);
    let (cx, cy) = (centre(cols), centre(rows));
    let sum_sq = |n: usize, c: f64| (0..n).map(|k| (k as f64 - c).powi(2)).sum::<f64>();
    let sxx = sum_sq(cols, cx) * rows as f64;
    let syy = sum_sq(rows, cy) * cols as f64;
    let (mut sx, mut sy, mut s) = (0.0, 0.0, 0.0);
    for (k, &v) in h.iter().enumerate() {
        sx += v * ((k % cols) as f64 - cx);
        sy += v * ((k / cols) as f64 - cy);
        s += v;
    }
    let (a, b, c) = (sx / sxx, sy / syy, s / h.len() as f64);
    h.iter()
        .enumerate()
        .map(|(k, &v)| v - c - a * ((k % cols) as f64 - cx) - b * ((k / cols) as f64 - cy))
        .collect()
}

/// The Hann window along one side of `n` points.
fn hann_side(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| {
            (std::f64::consts::PI * (k as f64 + 0.5) / n as f64)
                .sin()
                .powi(2)
        })
        .collect()
}

/// The separable Hann window, scaled to keep the mean square.
fn hann(h: &[f64], shape: Shape) -> Vec<f64> {
    let (wy, wx) = (hann_side(shape.rows), hann_side(shape.cols));
    h.iter()
        .enumerate()
        .map(|(k, &v)| v * wy[k / shape.cols] * wx[k % shape.cols] * HANN_NORM)
        .collect()
}

/// Rms, skewness and excess kurtosis of centred values.
struct Moments {
    rms: f64,
    skewness: f64,
    kurtosis: f64,
}

impl Moments {
    fn of(centred: &[f64]) -> Self {
        let n = centred.len() as f64;
        let m = |k: i32| centred.iter().map(|v| v.powi(k)).sum::<f64>() / n;
        let (m2, m3, m4) = (m(2), m(3), m(4));
        let (skewness, kurtosis) = if m2 > 0.0 {
            (m3 / m2.powf(1.5), m4 / (m2 * m2) - 3.0)
        } else {
            (0.0, 0.0)
        };
        Self {
            rms: m2.sqrt(),
            skewness,
            kurtosis,
        }
    }
}

/// Rms slope `sqrt(mean(|grad h|^2))` from differences between neighbours (grid units, so
/// dimensionless): wrapping around for a periodic scan, inside the window for a free one.
fn finite_difference_slope(h: &[f64], shape: Shape, boundary: Boundary) -> f64 {
    let Shape { rows, cols } = shape;
    let wrap = boundary == Boundary::Periodic;
    let (mut sum, mut count) = (0.0, 0usize);
    for i in 0..rows {
        for j in 0..cols {
            let v = h[i * cols + j];
            if wrap || j + 1 < cols {
                sum += (h[i * cols + (j + 1) % cols] - v).powi(2);
                count += 1;
            }
            if wrap || i + 1 < rows {
                sum += (h[((i + 1) % rows) * cols + j] - v).powi(2);
                count += 1;
            }
        }
    }
    // Two directions: mean square of each difference, summed.
    (2.0 * sum / count as f64).sqrt()
}

/// `sqrt(l_min / l_max)` of the slope tensor `sum_q q q^T |h~|^2` (1 for a flat scan).
fn anisotropy(modes: &[Mode]) -> f64 {
    let (mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0);
    for m in modes {
        let w = m.weight * m.power;
        xx += w * m.qx * m.qx;
        xy += w * m.qx * m.qy;
        yy += w * m.qy * m.qy;
    }
    let mean = 0.5 * (xx + yy);
    let spread = (0.25 * (xx - yy).powi(2) + xy * xy).sqrt();
    let (hi, lo) = (mean + spread, (mean - spread).max(0.0));
    if hi > 0.0 {
        (lo / hi).sqrt()
    } else {
        1.0
    }
}

/// Bins per decade of `q` in the radial average.
const BINS_PER_DECADE: f64 = 10.0;

/// The radially averaged `C(q) = A / (2 pi)^2 <|h~|^2>` in log-spaced bins (Nyquist rows
/// and columns left out), converted from grid units to the scan's (`q / pixel`,
/// `C pixel^4`).
fn radial_average(modes: &[Mode], shape: Shape, pixel: f64) -> Vec<RadialBin> {
    let q_min = 2.0 * std::f64::consts::PI / shape.longer() as f64;
    let averaged = || modes.iter().filter(|m| !m.nyquist);
    let top = averaged().map(|m| m.qx.hypot(m.qy)).fold(0.0, f64::max);
    let bins = Bins::log10_up_to(q_min, BINS_PER_DECADE, top);
    // Per bin: sums of |q| and of the power, and the modes, each weighted.
    let mut sums = Histogram::<(f64, f64, u32)>::new(bins);
    for m in averaged() {
        let q = m.qx.hypot(m.qy);
        let bin = sums.at(q);
        bin.0 += m.weight * q;
        bin.1 += m.weight * m.power;
        bin.2 += m.weight as u32;
    }
    let area = shape.points() as f64 / (2.0 * std::f64::consts::PI).powi(2);
    sums.into_cells()
        .into_iter()
        .filter(|s| s.2 > 0)
        .map(|(sq, sh, count)| RadialBin {
            q: sq / f64::from(count) / pixel,
            c: area * sh / f64::from(count) * pixel.powi(4),
            modes: count,
        })
        .collect()
}

/// The least-squares slope of `log C` against `log q` over the bins between half the
/// Nyquist wavevector `pi / pixel` and the Nyquist wavevector.
fn high_q_slope(radial: &[RadialBin], pixel: f64) -> Option<f64> {
    let nyquist = std::f64::consts::PI / pixel;
    let (ln_q, ln_c): (Vec<f64>, Vec<f64>) = radial
        .iter()
        .filter(|b| b.q >= 0.5 * nyquist && b.q <= nyquist && b.c > 0.0)
        .map(|b| (b.q.ln(), b.c.ln()))
        .unzip();
    crate::stats::LineFit::fit(&ln_q, &ln_c).map(|f| f.slope.value)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::surface::{Surface, SurfaceModel};

    fn square(n: usize) -> Shape {
        Shape { rows: n, cols: n }
    }

    #[test]
    fn a_tilted_plane_is_removed_entirely() {
        let shape = Shape { rows: 12, cols: 20 };
        let h: Vec<f64> = (0..shape.points())
            .map(|k| 3.0 + 0.2 * (k % 20) as f64 - 0.7 * (k / 20) as f64)
            .collect();
        let s = ScanSpectrum::new(&h, shape, 0.5, Boundary::Free).unwrap();
        assert!(s.heights.iter().all(|v| v.abs() < 1e-12));
        assert!(s.h_rms < 1e-12 && s.slope_rms < 1e-12);
    }

    #[test]
    fn a_periodic_scan_keeps_its_own_spectrum_and_units() {
        // A generated surface (unit rms gradient) read back as a periodic scan with pixel
        // 0.25: the spectral slope is the generator's, h_rms scales with the pixel, and
        // integral C d^2q gives back h_rms^2.
        let surface = Surface::generate(&SurfaceModel::new(64, 0.8, 64.0, 4.0, 5)).unwrap();
        let fft = Fft2::new(surface.grid());
        let h: Vec<f64> = surface
            .heights_at(f64::INFINITY, &fft)
            .iter()
            .map(|v| v * 0.25)
            .collect();
        let s = ScanSpectrum::new(&h, square(64), 0.25, Boundary::Periodic).unwrap();
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
        // A generated surface is isotropic and Gaussian.
        assert!(s.anisotropy > 0.8, "{}", s.anisotropy);
        assert!(s.skewness.abs() < 0.5 && s.kurtosis.abs() < 1.0);
        // Rectangles are solved with a free boundary only.
        let e = ScanSpectrum::new(
            &h[..64 * 32],
            Shape { rows: 32, cols: 64 },
            1.0,
            Boundary::Periodic,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("periodic") && e.contains("32 x 64"), "{e}");
    }

    #[test]
    fn the_window_keeps_the_spectrum_of_a_rough_window_near_the_periodic_one() {
        // A 128^2 window cut from a 256^2 periodic surface: its windowed spectral slope is
        // close to the whole surface's (the window removes the edge leak); so is that of a
        // 128 x 96 window, whose shells hold its modes in physical wavevectors.
        let surface = Surface::generate(&SurfaceModel::new(256, 0.8, 128.0, 4.0, 2)).unwrap();
        let fft = Fft2::new(surface.grid());
        let full = surface.heights_at(f64::INFINITY, &fft);
        for shape in [
            square(128),
            Shape {
                rows: 96,
                cols: 128,
            },
            Shape {
                rows: 128,
                cols: 75,
            },
        ] {
            let window: Vec<f64> = (0..shape.points())
                .map(|k| full[(k / shape.cols) * 256 + k % shape.cols])
                .collect();
            let s = ScanSpectrum::new(&window, shape, 1.0, Boundary::Free).unwrap();
            assert!(
                (s.slope_rms_spectral - 1.0).abs() < 0.1,
                "{shape}: {}",
                s.slope_rms_spectral
            );
            assert!((s.slope_rms - 1.0).abs() < 0.15, "{shape}: {}", s.slope_rms);
            // Every mode is in one shell: the shells' modes are the spectrum's.
            let modes: u32 = s.shells.shells.iter().map(|s| s.modes).sum();
            assert_eq!(modes as usize, shape.points() - 1, "{shape}");
            // The rough surface's spectrum falls at high q (no noise floor).
            assert!(
                s.high_q_slope.unwrap() < -2.0,
                "{shape}: {:?}",
                s.high_q_slope
            );
        }
    }

    #[test]
    fn stripes_white_noise_and_particles_are_measured() {
        let shape = Shape { rows: 64, cols: 80 };
        // Stripes along x: every slope along y.
        let stripes: Vec<f64> = (0..shape.points())
            .map(|k| (0.7 * (k / 80) as f64).sin() + 0.3 * (1.9 * (k / 80) as f64).cos())
            .collect();
        let s = ScanSpectrum::new(&stripes, shape, 1.0, Boundary::Free).unwrap();
        assert!(s.anisotropy < 0.1, "{}", s.anisotropy);
        // White noise: a flat spectrum.
        let mut x = 1u64;
        let noise: Vec<f64> = (0..shape.points())
            .map(|_| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (x >> 11) as f64 / 2f64.powi(53) - 0.5
            })
            .collect();
        let s = ScanSpectrum::new(&noise, shape, 1.0, Boundary::Free).unwrap();
        assert!(s.high_q_slope.unwrap().abs() < 0.5, "{:?}", s.high_q_slope);
        assert!(s.anisotropy > 0.8);
        // A few tall particles on a flat: skewed, heavy tails.
        let mut particles = vec![0.0; shape.points()];
        for k in [100, 1700, 3000] {
            particles[k] = 5.0;
        }
        let s = ScanSpectrum::new(&particles, shape, 1.0, Boundary::Free).unwrap();
        assert!(
            s.skewness > 10.0 && s.kurtosis > 100.0,
            "{} {}",
            s.skewness,
            s.kurtosis
        );
    }
}
