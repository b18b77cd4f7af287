//! The shortest reliable wavelength of a scan, and the heights filtered there: short-scale
//! data an instrument cannot give are not simulated nor predicted from.
//!
//! Two rules, each giving a wavevector `q_c` above which the scan's modes are dropped (the
//! smaller wins when both apply):
//!
//! * **The noise floor's onset.** A self-affine surface's `C(q)` falls as `q^-2(1+H)`
//!   (log-log slope -2 to -4); white instrument noise is flat (slope 0). Octave-wide
//!   windows of the radial spectrum are fitted from the Nyquist wavevector down, each half
//!   an octave below the last; while a window's log-log slope lies above -1 (the
//!   `noise_floor` warning's threshold, [`super::warnings::NOISE_FLOOR`]), the spectrum
//!   is the floor's. `q_c` is the lower edge of the lowest window of that run that starts
//!   at the top; a scan whose top octave is not flat has no floor and no cutoff from it
//!   (bins below `1e-16` of the largest, a band-limited surface's empty shells holding
//!   the transform's rounding, are left out of the fits).
//! * **The tip's radius** `R`, when the user gives it. A tip of radius `R` follows a
//!   profile only where the profile's curvature stays below `1 / R`. The rms curvature
//!   along a line of the surface resolved up to `q`, from its spectrum (isotropic:
//!   `<cos^4> = 3/8` of `sum q^4 |h~|^2`),
//!
//!   `kappa(q) = sqrt((3/8) sum_{|q'| <= q} q'^4 |h~(q')|^2)`,
//!
//!   grows with `q`; `q_c` is the largest `q` with `kappa(q) <= 1 / R`. Beyond it most of
//!   the valleys are narrower than the tip, which bridges them.
//!
//! **The filter** keeps the modes with `|q| <= q_c` and drops the rest, on the heights
//! the contact is solved on: a periodic scan by its own transform; a measured window
//! (detrended) by the transform of its even mirror image, `2 rows x 2 cols` and
//! periodic without jumps at the edges, cut back to the window. The spectrum and
//! Persson's predictions are then those of the filtered heights.

use serde::{Deserialize, Serialize};

use super::psd::{Boundary, RadialBin, ScanSpectrum, Shape};
use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::engine::spectrum::ShellSpectrum;
use crate::error::Result;

/// Above this log-log slope of `C(q)` an octave of the spectrum is the noise floor's
/// (the `noise_floor` warning's threshold).
pub const FLAT_SLOPE: f64 = -1.0;

/// Why a scan was cut where it was.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reason {
    /// The spectrum flattens into the noise floor above the cutoff; the slope of the
    /// flat octave at the top.
    NoiseFloor {
        /// The log-log slope of the top octave.
        slope: f64,
    },
    /// The rms curvature of the surface resolved to the cutoff reaches that of the tip.
    TipRadius {
        /// The tip's radius, in the heights' unit.
        radius: f64,
    },
}

/// A scan's short-wavelength cutoff.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cutoff {
    /// The cutoff wavevector `q_c` (1 / length, in the scan's unit).
    pub q: f64,
    /// Its wavelength `2 pi / q_c` (the scan's unit).
    pub wavelength: f64,
    /// The same in pixels.
    pub pixels: f64,
    /// Why.
    pub reason: Reason,
}

impl Cutoff {
    fn new(q: f64, pixel: f64, reason: Reason) -> Self {
        let wavelength = 2.0 * std::f64::consts::PI / q;
        Self {
            q,
            wavelength,
            pixels: wavelength / pixel,
            reason,
        }
    }

    /// The cutoff of a scan: the smaller of the noise floor's onset in `radial` (the
    /// scan's radial spectrum, its units) and, with a tip of radius `tip` (the scan's
    /// unit), the tip's from `shells` (grid units: the wavevectors in 1 / pixel);
    /// `None` where neither applies, or the cutoff lies at or beyond the Nyquist
    /// wavevector.
    pub fn of_scan(
        radial: &[RadialBin],
        shells: &ShellSpectrum,
        pixel: f64,
        tip: Option<f64>,
    ) -> Option<Self> {
        let floor = noise_floor(radial, pixel)
            .map(|(q, slope)| Self::new(q, pixel, Reason::NoiseFloor { slope }));
        let tip = tip.and_then(|r| {
            tip_limit(shells, r / pixel)
                .map(|q| Self::new(q / pixel, pixel, Reason::TipRadius { radius: r }))
        });
        let cut = match (floor, tip) {
            (Some(a), Some(b)) => Some(if b.q < a.q { b } else { a }),
            (a, b) => a.or(b),
        }?;
        (cut.q < std::f64::consts::PI / pixel).then_some(cut)
    }
}

/// The cutoff of the scan of `spectrum` (pixel `pixel`, a tip of radius `tip` where
/// given) and the spectrum of its heights filtered there, with its shells above the
/// cutoff dropped (a measured window's taper leaks a trace of power there); `None`
/// where the scan has no cutoff.
pub fn apply(
    spectrum: &ScanSpectrum,
    pixel: f64,
    tip: Option<f64>,
) -> Result<Option<(Cutoff, ScanSpectrum)>> {
    let Some(cut) = Cutoff::of_scan(&spectrum.radial, &spectrum.shells, pixel, tip) else {
        return Ok(None);
    };
    let q_c = cut.q * pixel;
    let kept = filter(&spectrum.heights, spectrum.shape, spectrum.boundary, q_c)?;
    let scaled: Vec<f64> = kept.iter().map(|h| h * pixel).collect();
    let mut filtered = ScanSpectrum::new(&scaled, spectrum.shape, pixel, spectrum.boundary)?;
    let limit = q_c * (1.0 + crate::engine::tolerance::SHELL_SLACK);
    filtered.shells.shells.retain(|s| s.q <= limit);
    Ok(Some((cut, filtered)))
}

/// The noise floor's onset in a radial spectrum of pixel `pixel` (see the module docs):
/// `q_c` and the top octave's slope, or `None` when the top octave is not flat.
pub fn noise_floor(radial: &[RadialBin], pixel: f64) -> Option<(f64, f64)> {
    let nyquist = std::f64::consts::PI / pixel;
    // Bins below 1e-16 of the largest hold the transform's rounding (a band-limited
    // surface's empty shells), not a floor.
    let empty = 1e-16 * radial.iter().map(|b| b.c).fold(0.0, f64::max);
    let slope = |hi: f64| {
        let (q, c): (Vec<f64>, Vec<f64>) = radial
            .iter()
            .filter(|b| b.q >= 0.5 * hi && b.q <= hi && b.c > empty)
            .map(|b| (b.q.ln(), b.c.ln()))
            .unzip();
        crate::stats::LineFit::fit(&q, &c).map(|f| f.slope.value)
    };
    let top = slope(nyquist).filter(|&s| s > FLAT_SLOPE)?;
    let lowest = radial.iter().map(|b| b.q).fold(f64::INFINITY, f64::min);
    let mut edge = 0.5 * nyquist;
    let mut hi = nyquist / std::f64::consts::SQRT_2;
    while 0.5 * hi > lowest && slope(hi).is_some_and(|s| s > FLAT_SLOPE) {
        edge = 0.5 * hi;
        hi /= std::f64::consts::SQRT_2;
    }
    Some((edge, top))
}

/// The tip's limit on `shells` (grid units) for a tip of radius `radius` pixels: the
/// largest shell's `q` with `kappa(q) <= 1 / radius` (see the module docs), `None` when
/// every shell passes (the tip resolves the whole scan).
pub fn tip_limit(shells: &ShellSpectrum, radius: f64) -> Option<f64> {
    let mut sum = 0.0;
    let mut last = None;
    for s in &shells.shells {
        sum += s.q.powi(4) * s.h2;
        if (0.375 * sum).sqrt() * radius > 1.0 {
            // Below the first shell the tip resolves nothing: keep that shell at least.
            return Some(last.unwrap_or(s.q));
        }
        last = Some(s.q);
    }
    None
}

/// The `shape` heights (grid units, detrended for a free boundary) with every mode above
/// `q_c` (1 / pixel) dropped (see the module docs).
pub fn filter(heights: &[f64], shape: Shape, boundary: Boundary, q_c: f64) -> Result<Vec<f64>> {
    let (rows, cols) = (shape.rows, shape.cols);
    let (grid, field) = match boundary {
        Boundary::Periodic => (Grid::new(rows, 1.0)?, heights.to_vec()),
        Boundary::Free => {
            let mirrored: Vec<f64> = (0..2 * rows)
                .flat_map(|i| {
                    let r = if i < rows { i } else { 2 * rows - 1 - i };
                    (0..2 * cols).map(move |j| {
                        let c = if j < cols { j } else { 2 * cols - 1 - j };
                        heights[r * cols + c]
                    })
                })
                .collect();
            (Grid::rectangle(2 * rows, 2 * cols, 1.0)?, mirrored)
        }
    };
    let fft = Fft2::new(&grid);
    let mut spec = fft.new_spectrum();
    fft.forward(&field, &mut spec);
    let limit = q_c * (1.0 + crate::engine::tolerance::SHELL_SLACK);
    for (s, v) in spec.iter_mut().enumerate() {
        if grid.q(s) > limit {
            *v = rustfft::num_complex::Complex64::new(0.0, 0.0);
        }
    }
    let mut out = vec![0.0; grid.points()];
    fft.inverse(&spec, &mut out, &mut Vec::new());
    let wide = grid.cols();
    Ok((0..rows)
        .flat_map(|i| out[i * wide..i * wide + cols].to_vec())
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::surface::{Surface, SurfaceModel};
    use rand::{RngExt as _, SeedableRng};

    fn generated(n: usize, lambda_s: f64) -> Vec<f64> {
        let s = Surface::generate(&SurfaceModel::new(n, 0.8, n as f64 / 2.0, lambda_s, 4)).unwrap();
        s.heights_at(f64::INFINITY, &Fft2::new(s.grid()))
    }

    fn noisy(h: &[f64], rms: f64) -> Vec<f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        h.iter()
            .map(|v| v + rms * 3f64.sqrt() * (2.0 * rng.random::<f64>() - 1.0))
            .collect()
    }

    #[test]
    fn a_self_affine_scan_has_no_floor_and_a_noisy_one_is_cut_where_the_noise_rises() {
        let n = 256;
        let shape = Shape { rows: n, cols: n };
        let clean = generated(n, 2.0);
        // A band-limited surface's empty top octave (rounding only) is no floor.
        let banded = ScanSpectrum::new(&generated(n, 8.0), shape, 1.0, Boundary::Periodic).unwrap();
        assert_eq!(noise_floor(&banded.radial, 1.0), None);
        for boundary in [Boundary::Periodic, Boundary::Free] {
            let s = ScanSpectrum::new(&clean, shape, 1.0, boundary).unwrap();
            assert_eq!(noise_floor(&s.radial, 1.0), None, "{boundary:?}");
            assert!(Cutoff::of_scan(&s.radial, &s.shells, 1.0, None).is_none());
        }
        // White noise of a tenth of the rms height: its flat C(q) crosses the surface's
        // some octaves below the Nyquist wavevector.
        let h_rms = (clean.iter().map(|v| v * v).sum::<f64>() / clean.len() as f64).sqrt();
        let s =
            ScanSpectrum::new(&noisy(&clean, 0.1 * h_rms), shape, 1.0, Boundary::Periodic).unwrap();
        let cut = Cutoff::of_scan(&s.radial, &s.shells, 1.0, None).expect("a floor");
        assert!(matches!(cut.reason, Reason::NoiseFloor { slope } if slope > FLAT_SLOPE));
        // Where the clean surface's spectrum meets the noise's, within an octave.
        let floor = s.radial.last().unwrap().c;
        let clean_s = ScanSpectrum::new(&clean, shape, 1.0, Boundary::Periodic).unwrap();
        let meet = clean_s
            .radial
            .iter()
            .rev()
            .find(|b| b.c > floor)
            .map(|b| b.q)
            .unwrap();
        assert!(
            cut.q > 0.5 * meet && cut.q < 2.0 * meet,
            "{} vs {meet}",
            cut.q
        );
        assert!(cut.pixels > 2.0);
    }

    #[test]
    fn a_blunter_tip_cuts_longer_wavelengths() {
        let n = 128;
        let shape = Shape { rows: n, cols: n };
        let s = ScanSpectrum::new(&generated(n, 2.0), shape, 0.5, Boundary::Periodic).unwrap();
        let q = |r: f64| Cutoff::of_scan(&s.radial, &s.shells, 0.5, Some(r)).map(|c| c.q);
        // The full surface's rms curvature (pixels) sets the radius that resolves it all.
        let kappa = (0.375
            * s.shells
                .shells
                .iter()
                .map(|s| s.q.powi(4) * s.h2)
                .sum::<f64>())
        .sqrt();
        let sharp = 0.5 * 0.9 / kappa;
        assert_eq!(q(sharp), None);
        let (a, b) = (
            q(0.5 * 3.0 / kappa).unwrap(),
            q(0.5 * 30.0 / kappa).unwrap(),
        );
        assert!(b < a, "{b} {a}");
        let tip = Cutoff::of_scan(&s.radial, &s.shells, 0.5, Some(1.5 / kappa)).unwrap();
        assert_eq!(
            tip.reason,
            Reason::TipRadius {
                radius: 1.5 / kappa
            }
        );
        assert!((tip.wavelength - 2.0 * std::f64::consts::PI / tip.q).abs() < 1e-12);
    }

    #[test]
    fn the_filter_drops_exactly_the_modes_above_the_cutoff() {
        let n = 64;
        let shape = Shape { rows: n, cols: n };
        let h = generated(n, 2.0);
        let q_c = 2.0 * std::f64::consts::PI / 8.0;
        let kept = filter(&h, shape, Boundary::Periodic, q_c).unwrap();
        let s = ScanSpectrum::new(&kept, shape, 1.0, Boundary::Periodic).unwrap();
        let top = crate::measured::pixel::shortest_wavelength(&s.shells);
        assert!((8.0..9.0).contains(&top), "{top}");
        // A second pass changes nothing; a cutoff above the Nyquist keeps every point.
        let again = filter(&kept, shape, Boundary::Periodic, q_c).unwrap();
        assert!(kept.iter().zip(&again).all(|(a, b)| (a - b).abs() < 1e-12));
        let all = filter(&h, shape, Boundary::Periodic, 10.0).unwrap();
        assert!(h.iter().zip(&all).all(|(a, b)| (a - b).abs() < 1e-12));
        // A free window: a plane's ramp survives the mirror filter (no jump at the edges),
        // and the shape is kept.
        let shape = Shape { rows: 40, cols: 56 };
        let ramp: Vec<f64> = (0..shape.points()).map(|k| (k % 56) as f64).collect();
        let f = filter(
            &ramp,
            shape,
            Boundary::Free,
            2.0 * std::f64::consts::PI / 8.0,
        )
        .unwrap();
        assert_eq!(f.len(), ramp.len());
        let inner: f64 = (8..32)
            .flat_map(|i| (8..48).map(move |j| i * 56 + j))
            .map(|k| (f[k] - ramp[k]).abs())
            .fold(0.0, f64::max);
        // (A jump at the edges would leave some span / (pi d / 8) at d pixels from it.)
        assert!(inner < 0.25, "{inner}");
    }
}
