//! Surfaces with the converted spectrum: the isotropic 2D surfaces on which the contact
//! of a line scan is simulated, and the shells on which Persson's theory is evaluated.
//!
//! A synthesized surface is a periodic `n x n` map with the profiles' spacing `a`,
//! `h~(q) = sqrt(C(q) (2 pi / (n a))^2) xi(q)` with random phases (`|xi| = 1`, so each
//! realization's spectrum is the converted one exactly; [`crate::engine::surface`]), one
//! realization per seed. `C(q)` is the converted spectrum ([`super::abel`]) interpolated
//! in log-log between its positive bins, held at its first bin's value below it (a
//! roll-off: no power is invented at wavelengths the profile does not hold), extended
//! with the tail's power law above its last bin, and zero beyond the profile's Nyquist
//! wavevector `pi / a` (a circular cutoff: isotropic). With `n` below the profile's length,
//! the wavelengths longer than `n a` are left out of the synthesized surfaces.
//!
//! Persson's theory on the whole converted spectrum, over the profile's band
//! `2 pi / L <= q <= pi / a` ([`shells`]): the lattice of an `N x N` surface of the
//! profile's length, in annuli of width `2 pi / L` holding `2 pi k` modes each (the
//! continuum's count), each mode with `|h~|^2 = C(q) (2 pi / L)^2`.

use std::path::PathBuf;

use super::abel::{Converted, LogLog};
use crate::engine::spectrum::ShellSpectrum;
use crate::engine::surface::{Amplitudes, Surface};
use crate::engine::tolerance::ZETA_SLACK;
use crate::error::{Error, Result};
use crate::measured::psd::Shape;
use crate::measured::scan::Scan;

/// The converted spectrum as a function of `|q|` (the scan's units; module docs).
#[derive(Debug, Clone)]
pub struct Isotropic {
    table: LogLog,
    first: (f64, f64),
    nyquist: f64,
}

impl Isotropic {
    /// The spectrum of `converted` for profiles of spacing `pixel`.
    pub fn new(converted: &Converted, pixel: f64) -> Result<Self> {
        let nodes = converted.table();
        let Some(&first) = nodes.first() else {
            return Err(Error::invalid(
                "heights",
                "line scans whose converted spectrum has no positive bin",
                "rough profiles (a spectrum with power)",
            ));
        };
        Ok(Self {
            table: LogLog::new(&nodes, converted.tail_slope),
            first,
            nyquist: std::f64::consts::PI / pixel,
        })
    }

    /// `C(q)` (length^4).
    pub fn at(&self, q: f64) -> f64 {
        if q > self.nyquist * (1.0 + ZETA_SLACK) || q <= 0.0 {
            0.0
        } else if q <= self.first.0 {
            self.first.1
        } else {
            self.table.at(q)
        }
    }
}

/// `seeds` surfaces of side `side` with spectrum `c` and pixel `pixel`, as scans (heights
/// in the profiles' unit), named `synthesized, seed k`.
pub fn synthesize(c: &Isotropic, pixel: f64, side: usize, seeds: u64) -> Result<Vec<Scan>> {
    let dq = 2.0 * std::f64::consts::PI / side as f64;
    // Grid units: q_grid = q a, C_grid = C / a^4, |h~_grid|^2 = C_grid dq_grid^2.
    let power = |q_grid: f64| c.at(q_grid / pixel) / pixel.powi(4) * dq * dq;
    (1..=seeds)
        .map(|seed| {
            let surface = Surface::generate_tabulated(side, &power, seed, Amplitudes::RandomPhase)?;
            let fft = crate::engine::fft::Fft2::new(surface.grid());
            let heights = surface
                .heights_at(f64::INFINITY, &fft)
                .into_iter()
                .map(|h| h * pixel)
                .collect();
            Ok(Scan {
                shape: Shape {
                    rows: side,
                    cols: side,
                },
                heights,
                source: PathBuf::from(format!("synthesized, seed {seed}")),
                filled: 0,
            })
        })
        .collect()
}

/// The shells of the converted spectrum over the profile's band, in grid units (lengths
/// over the pixel) as [`crate::measured::theory::Theory`] takes them (module docs).
pub fn shells(c: &Isotropic, pixel: f64, points: usize) -> ShellSpectrum {
    let dq = 2.0 * std::f64::consts::PI / points as f64;
    crate::measured::theory::annuli(dq, 1..=points / 2, |k| c.at(dq * k as f64 / pixel), pixel)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measured::line::abel::ConvertedBin;

    fn power_law(hurst: f64) -> Converted {
        Converted {
            bins: (0..30)
                .map(|i| {
                    let q = 0.05 * 10f64.powf(i as f64 / 10.0);
                    ConvertedBin {
                        q,
                        c: q.powf(-2.0 - 2.0 * hurst),
                        std_error: 0.0,
                        tail_share: 0.0,
                        uncertain: None,
                    }
                })
                .collect(),
            tail_slope: Some(-1.0 - 2.0 * hurst),
        }
    }

    #[test]
    fn a_synthesized_surface_has_the_spectrum_it_was_given() {
        // Pixel 0.5: q runs to pi / 0.5. The synthesized surface's radial spectrum, read
        // back as a periodic scan, is the table's within rounding (random phases).
        let pixel = 0.5;
        let c = Isotropic::new(&power_law(0.8), pixel).unwrap();
        let scans = synthesize(&c, pixel, 64, 2).unwrap();
        assert_eq!(scans.len(), 2);
        assert_ne!(scans[0].heights, scans[1].heights);
        let s = crate::measured::psd::ScanSpectrum::new(
            &scans[0].heights,
            scans[0].shape,
            pixel,
            crate::measured::psd::Boundary::Periodic,
        )
        .unwrap();
        for b in s
            .radial
            .iter()
            .filter(|b| b.q < 0.9 * std::f64::consts::PI / pixel)
        {
            assert!(
                (b.c / c.at(b.q) - 1.0).abs() < 0.15,
                "q {}: {} vs {}",
                b.q,
                b.c,
                c.at(b.q)
            );
        }
        // Persson's g_bar^2 = integral q^2 C d^2q over the band, from the shells.
        let shells = shells(&c, pixel, 4096);
        let g2: f64 = shells.shells.iter().map(|s| s.q2h2).sum();
        let (lo, hi) = (
            2.0 * std::f64::consts::PI / (4096.0 * pixel),
            std::f64::consts::PI / pixel,
        );
        // integral 2 pi q^3 q^(-3.6) dq = 2 pi (hi^0.4 - 0.05^0.4) / 0.4 above the first
        // bin (0.05), and C held at C(0.05) below it: 2 pi 0.05^4 / 4 C(0.05).
        let held = 0.05f64.powf(0.4) / 4.0;
        let want = 2.0 * std::f64::consts::PI * ((hi.powf(0.4) - 0.05f64.powf(0.4)) / 0.4 + held);
        assert!(lo < 0.05);
        assert!((g2 / want - 1.0).abs() < 0.02, "{g2} vs {want}");
    }
}
