//! The power spectrum of line scans: the one-dimensional `C1D(q)` of the profiles,
//! averaged over them, with its error bar.
//!
//! Conventions ([`crate::conventions`], section 2, in one dimension): a profile of `N`
//! points with spacing `a` and length `L = N a` has `h~(q) = N^-1 sum_x h(x) e^(-i q x)`
//! at `q = 2 pi m / L`, so that `mean(h^2) = sum_q |h~(q)|^2`; its spectrum is
//! `C1D(q) = L / (2 pi) <|h~(q)|^2>` (units: length^3), two-sided, so that
//! `h_rms^2 = integral_{-inf}^{inf} C1D(q) dq`. With the 2D convention of
//! [`crate::measured::psd`] (`C(q) = A / (2 pi)^2 <|h~(q)|^2>`) an isotropic surface's
//! profiles have `C1D(q_x) = integral C(sqrt(q_x^2 + q_y^2)) dq_y` ([`super::abel`]).
//!
//! As the 2D path does ([`crate::measured::psd`]): a measured profile (free boundary) has
//! its least-squares line removed and is multiplied by a Hann window
//! `w(x) = sin^2(pi (x + 1/2) / N)` scaled by `sqrt(8/3)` to keep the mean square; a
//! periodic one has its mean removed. The spectra of the profiles are averaged in
//! log-spaced bins (`BINS_PER_DECADE`), without `q = 0` and the Nyquist mode.
//!
//! Error bar of a bin: the larger of the spread of the profiles' bin means over the square
//! root of their number, and the spectrum of the bin over `sqrt(M P_eff)` (a periodogram
//! ordinate is exponentially distributed: its standard deviation is its mean), with `M`
//! the bin's modes in one profile and `P_eff` the independent profiles: all of them when
//! they come from separate inputs; for neighbouring rows of one map, which share their
//! long wavelengths, `P q a / (2 pi)` (rows further apart than a wavelength are
//! independent), between 1 and `P`.

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use super::profiles::Profiles;
use crate::measured::psd::Boundary;

/// Log-spaced bins per decade of `q`.
pub const BINS_PER_DECADE: f64 = 10.0;

/// One bin of the averaged one-dimensional spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LineBin {
    /// Mean `q` of the bin's modes (1 / length).
    pub q: f64,
    /// `C1D(q)` (length^3), or the converted `C(q)` (length^4) in [`super::abel`].
    pub c: f64,
    /// Its standard error.
    pub std_error: f64,
    /// Modes of the bin in one profile.
    pub modes: u32,
}

/// The averaged spectrum of the profiles and their statistics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProfileSpectrum {
    /// The bins, increasing `q`.
    pub bins: Vec<LineBin>,
    /// Profiles averaged.
    pub profiles: usize,
    /// Points per profile.
    pub points: usize,
    /// Spacing of the points (length unit).
    pub pixel: f64,
    /// Rms height of the detrended profiles (length unit).
    pub h_rms: f64,
    /// Rms slope along the profiles, from differences between neighbours.
    pub slope_rms: f64,
    /// Rms slope along the profiles from their spectrum, `sqrt(sum_q q^2 |h~|^2)`.
    pub slope_rms_spectral: f64,
    /// Skewness of the detrended heights.
    pub skewness: f64,
    /// Excess kurtosis of the detrended heights.
    pub kurtosis: f64,
}

impl ProfileSpectrum {
    /// The spectrum of `profiles` (points `points` apart by `pixel`), whose neighbours
    /// are rows of one map when `rows_of_a_map`.
    pub fn new(
        heights: &[f64],
        points: usize,
        pixel: f64,
        boundary: Boundary,
        rows_of_a_map: bool,
    ) -> Self {
        let n = points;
        let count = heights.len() / n;
        let length = n as f64 * pixel;
        let two_pi = 2.0 * std::f64::consts::PI;
        let top = n.div_ceil(2) - 1; // m = 1..=top, below the Nyquist mode
        let bin_of = |m: usize| (BINS_PER_DECADE * (m as f64).log10()).floor() as usize;
        let bins = bin_of(top.max(1)) + 1;
        let mut modes = vec![0u32; bins];
        let mut q_sum = vec![0.0; bins];
        for m in 1..=top {
            modes[bin_of(m)] += 1;
            q_sum[bin_of(m)] += two_pi * m as f64 / length;
        }
        // Per profile: its bin means.
        let mut per_profile = vec![vec![0.0; bins]; count];
        let (mut m2, mut m3, mut m4, mut slope2, mut slope2_spectral) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let mut planner = rustfft::FftPlanner::<f64>::new();
        let fft = planner.plan_fft_forward(n);
        let window = window(n, boundary);
        for (k, means) in per_profile.iter_mut().enumerate() {
            let level = level(&heights[k * n..(k + 1) * n], boundary);
            for v in &level {
                m2 += v * v;
                m3 += v * v * v;
                m4 += v * v * v * v;
            }
            slope2 += level
                .windows(2)
                .map(|w| ((w[1] - w[0]) / pixel).powi(2))
                .sum::<f64>()
                / (n - 1) as f64;
            let mut data: Vec<Complex64> = level
                .iter()
                .zip(&window)
                .map(|(v, w)| Complex64::new(v * w / n as f64, 0.0))
                .collect();
            fft.process(&mut data);
            for m in 1..=top {
                let power = data[m].norm_sqr();
                means[bin_of(m)] += length / two_pi * power;
                // Both q and -q.
                slope2_spectral += 2.0 * (two_pi * m as f64 / length).powi(2) * power;
            }
            for (b, v) in means.iter_mut().enumerate() {
                if modes[b] > 0 {
                    *v /= f64::from(modes[b]);
                }
            }
        }
        let total = (count * n) as f64;
        let (m2, m3, m4) = (m2 / total, m3 / total, m4 / total);
        let bins = (0..bins)
            .filter(|&b| modes[b] > 0)
            .map(|b| {
                let q = q_sum[b] / f64::from(modes[b]);
                let values: Vec<f64> = per_profile.iter().map(|p| p[b]).collect();
                let c = values.iter().sum::<f64>() / count as f64;
                let spread = if count > 1 {
                    let var =
                        values.iter().map(|v| (v - c).powi(2)).sum::<f64>() / (count - 1) as f64;
                    (var / count as f64).sqrt()
                } else {
                    0.0
                };
                let independent = if rows_of_a_map {
                    (count as f64 * q * pixel / two_pi).clamp(1.0, count as f64)
                } else {
                    count as f64
                };
                let chi2 = c / (f64::from(modes[b]) * independent).sqrt();
                LineBin {
                    q,
                    c,
                    std_error: spread.max(chi2),
                    modes: modes[b],
                }
            })
            .collect();
        Self {
            bins,
            profiles: count,
            points: n,
            pixel,
            h_rms: m2.sqrt(),
            slope_rms: (slope2 / count as f64).sqrt(),
            slope_rms_spectral: (slope2_spectral / count as f64).sqrt(),
            skewness: if m2 > 0.0 { m3 / m2.powf(1.5) } else { 0.0 },
            kurtosis: if m2 > 0.0 { m4 / (m2 * m2) - 3.0 } else { 0.0 },
        }
    }

    /// The spectrum of the profiles of `p` along their rows.
    pub fn of(p: &Profiles, pixel: f64, boundary: Boundary) -> Self {
        Self::new(&p.heights, p.points, pixel, boundary, p.rows_of_a_map)
    }

    /// Length of a profile.
    pub fn length(&self) -> f64 {
        self.points as f64 * self.pixel
    }
}

/// The Hann window scaled to keep the mean square (free), or ones (periodic).
fn window(n: usize, boundary: Boundary) -> Vec<f64> {
    match boundary {
        Boundary::Periodic => vec![1.0; n],
        Boundary::Free => {
            let norm = (8.0f64 / 3.0).sqrt();
            (0..n)
                .map(|k| {
                    norm * (std::f64::consts::PI * (k as f64 + 0.5) / n as f64)
                        .sin()
                        .powi(2)
                })
                .collect()
        }
    }
}

/// A profile less its least-squares line (free) or its mean (periodic).
fn level(h: &[f64], boundary: Boundary) -> Vec<f64> {
    let n = h.len() as f64;
    let mean = h.iter().sum::<f64>() / n;
    if boundary == Boundary::Periodic {
        return h.iter().map(|v| v - mean).collect();
    }
    let centre = 0.5 * (n - 1.0);
    let sxx: f64 = (0..h.len()).map(|k| (k as f64 - centre).powi(2)).sum();
    let sx: f64 = h
        .iter()
        .enumerate()
        .map(|(k, v)| v * (k as f64 - centre))
        .sum();
    let tilt = sx / sxx;
    h.iter()
        .enumerate()
        .map(|(k, v)| v - mean - tilt * (k as f64 - centre))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parseval_holds_and_a_sine_lands_in_its_bin() {
        // A periodic sine of amplitude 2 at m = 6 (alone in its bin) on 256 points, pixel
        // 0.5: h_rms^2 = 2 = integral C1D dq = 2 C1D(q_6) dq (both signs), dq = 2 pi / L,
        // and |h~(q_6)|^2 = 1, so C1D(q_6) = L / (2 pi).
        let (n, pixel) = (256, 0.5);
        let length = n as f64 * pixel;
        let h: Vec<f64> = (0..n)
            .map(|k| 2.0 * (2.0 * std::f64::consts::PI * 6.0 * k as f64 / n as f64).sin())
            .collect();
        let s = ProfileSpectrum::new(&h, n, pixel, Boundary::Periodic, false);
        assert!((s.h_rms - 2f64.sqrt()).abs() < 1e-12);
        let dq = 2.0 * std::f64::consts::PI / length;
        let var: f64 = s
            .bins
            .iter()
            .map(|b| 2.0 * b.c * f64::from(b.modes) * dq)
            .sum();
        assert!((var - 2.0).abs() < 1e-9, "{var}");
        let peak = s.bins.iter().max_by(|a, b| a.c.total_cmp(&b.c)).unwrap();
        assert!((peak.q / (6.0 * dq) - 1.0).abs() < 1e-12 && peak.modes == 1);
        assert!((peak.c / (length / (2.0 * std::f64::consts::PI)) - 1.0).abs() < 1e-12);
        // Rms slope along the profile: amplitude 2 q, over sqrt 2.
        let g = 2.0 * 6.0 * dq / 2f64.sqrt();
        assert!((s.slope_rms_spectral / g - 1.0).abs() < 1e-9);
        // A tilted line is removed entirely by the free boundary's detrending.
        let line: Vec<f64> = (0..n).map(|k| 3.0 + 0.1 * k as f64).collect();
        let s = ProfileSpectrum::new(&line, n, pixel, Boundary::Free, false);
        assert!(s.h_rms < 1e-12 && s.bins.iter().all(|b| b.c < 1e-20));
    }
}
