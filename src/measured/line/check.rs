//! The check of line scans: the profiles' spectrum ([`super::spectrum`]) converted to the
//! isotropic surface's ([`super::abel`]), Persson's theory on the converted spectrum over
//! the profile's band ([`super::synthesis::shells`]), and the check of a 2D surface
//! ([`crate::measured::check`]) run on surfaces synthesized with it
//! ([`super::synthesis::synthesize`]: random phases, one per seed, the error bars from the
//! seeds), so that the contact is simulated on synthesized surfaces, not on the measured
//! profile. The synthesized surfaces are periodic squares of side
//! `min(LineOptions::side, N)` with the profiles' spacing.
//!
//! Warnings beside the 2D check's ([`crate::measured::warnings`]; the skewness and
//! kurtosis are the profiles', not the synthesized surfaces', which are Gaussian by
//! construction):
//!
//! * **isotropy of the profiles** ([`ISOTROPY`]): with profiles in two directions (the
//!   rows and columns of 2D inputs read as line scans), the larger over the smaller of
//!   their rms slopes; the conversion assumes one spectrum in every direction.
//! * **profile length** ([`PROFILE_LENGTH`]): Persson's contact area with only the
//!   wavelengths longer than a quarter of the profile resolved (`a_r` at `zeta = 4`), at
//!   the lowest load: where it is small, the contact sits on the few highest of the
//!   profile's longest undulations, so wavelengths longer than the profile (which it
//!   cannot show) would change it, and a window of the profile's size holds few contact
//!   patches.

use std::ops::ControlFlow;

use serde::{Deserialize, Serialize};

use super::abel::{convert, ConvertedBin};
use super::profiles::Profiles;
use super::spectrum::{LineBin, ProfileSpectrum};
use super::synthesis::{shells, synthesize, Isotropic};
use crate::engine::grid::MIN_N;
use crate::error::{Error, Result, StopReason};
use crate::measured::check::{check, CheckOptions, Event, SurfaceCheck};
use crate::measured::fill::Fill;
use crate::measured::psd::Boundary;
use crate::measured::scan::MIN_SIDE;
use crate::measured::theory::{Theory, TheoryPoint};
use crate::measured::units::square_pixel;
use crate::measured::warnings::{Limit, Side, Warning, KURTOSIS, SKEWNESS};

/// The side of the synthesized surfaces unless asked (at most the profile's length): a
/// 4096-point profile is checked in seconds on two cores.
pub const DEFAULT_SIDE: usize = 256;

/// Synthesized surfaces (seeds) unless asked: the error bars come from them.
pub const DEFAULT_SEEDS: u64 = 4;

/// The largest side of synthesized surfaces.
pub const MAX_SIDE: usize = 4096;

/// The magnification of the profile length check: wavelengths down to a quarter of it.
pub const LONG_WAVELENGTHS: f64 = 4.0;

/// The isotropy of the profiles in two directions.
pub const ISOTROPY: Limit = Limit {
    name: "profile_isotropy",
    statistic: "the larger over the smaller rms slope of the profiles along the rows and \
                along the columns",
    threshold: 1.2,
    side: Side::Above,
    meaning: "the profiles' spectra differ with direction (a lay, scan lines, a tilt \
              left in one direction); the conversion to a surface's spectrum assumes \
              an isotropic surface",
};

/// The profiles' length against the loads.
pub const PROFILE_LENGTH: Limit = Limit {
    name: "profile_length",
    statistic: "Persson's contact area with only the wavelengths longer than a quarter \
                of the profile resolved (a_r at zeta = 4), at the lowest load",
    threshold: 0.5,
    side: Side::Below,
    meaning: "at this load the contact sits on the few highest of the profile's longest \
              undulations: wavelengths longer than the profile, which it cannot show, \
              would change the contact, and a window of its size holds few contact \
              patches; measure longer profiles, or read the higher loads",
};

/// How line scans are checked, beside [`CheckOptions`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct LineOptions {
    /// Side of the synthesized surfaces (points; at most the profile's length).
    pub side: usize,
    /// Synthesized surfaces, one per seed `1..=seeds`.
    pub seeds: u64,
}

impl Default for LineOptions {
    fn default() -> Self {
        Self {
            side: DEFAULT_SIDE,
            seeds: DEFAULT_SEEDS,
        }
    }
}

impl LineOptions {
    /// Checks the side and the seeds.
    pub fn validate(&self) -> Result<()> {
        if !(MIN_N.max(MIN_SIDE)..=MAX_SIDE).contains(&self.side) {
            return Err(Error::invalid(
                "line_side",
                self.side,
                format!(
                    "the side of the synthesized surfaces, in [{MIN_SIDE}, {MAX_SIDE}] points \
                     (the height maps' floor, measured::scan::MIN_SIDE)"
                ),
            ));
        }
        if !(2..=64).contains(&self.seeds) {
            return Err(Error::invalid(
                "line_seeds",
                self.seeds,
                "synthesized surfaces in [2, 64] (the error bars come from them)",
            ));
        }
        Ok(())
    }
}

/// What the line scans gave, beside the synthesized surfaces' check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineFindings {
    /// The inputs and the profiles each gave.
    pub sources: Vec<(String, usize)>,
    /// Profiles.
    pub profiles: usize,
    /// Points per profile.
    pub points: usize,
    /// Spacing of the points (length unit).
    pub pixel_size: f64,
    /// How the profiles' edges were treated.
    pub boundary: Boundary,
    /// Rms height of the detrended profiles.
    pub h_rms: f64,
    /// Rms slope along the profiles (differences between neighbours).
    pub slope_rms: f64,
    /// Rms slope along the profiles from their spectrum.
    pub slope_rms_spectral: f64,
    /// Skewness of the profiles' heights.
    pub skewness: f64,
    /// Excess kurtosis of the profiles' heights.
    pub kurtosis: f64,
    /// The profiles' spectrum `C1D(q)` (length^3), averaged.
    pub spectrum: Vec<LineBin>,
    /// The spectrum of the profiles across (the columns), when there are some.
    pub spectrum_across: Option<Vec<LineBin>>,
    /// The converted isotropic spectrum `C(q)` (length^4).
    pub converted: Vec<ConvertedBin>,
    /// The log-log slope of `C1D` over the highest octave, extrapolated past the cutoff.
    pub tail_slope: Option<f64>,
    /// Rms slope of the surface of the converted spectrum (Persson's `g_bar`), over the
    /// profile's band; `sqrt 2` times the slope along the profiles for an isotropic one.
    pub slope_rms_converted: f64,
    /// Side of the synthesized surfaces.
    pub synthesized_side: usize,
    /// Synthesized surfaces.
    pub seeds: u64,
    /// Persson's theory on the converted spectrum over the profile's band, at the loads.
    pub persson: Vec<TheoryPoint>,
    /// How the conversion was made, in words.
    pub method: String,
}

/// The check of line scans: the synthesized surfaces' check (`surface.json`'s fields)
/// and what the profiles gave (`line`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineCheck {
    /// The check of the synthesized surfaces, with the profiles' warnings.
    #[serde(flatten)]
    pub surface: SurfaceCheck,
    /// The profiles, their spectra and Persson on the converted spectrum.
    pub line: LineFindings,
}

/// The conversion, in words for the page and the JSON.
pub const METHOD: &str = "profiles detrended (periodic: mean removed) and Hann-windowed as \
    the 2D path does, their 1D spectra averaged in log bins; the isotropic 2D spectrum from \
    the inverse Abel transform C(q) = -(1/pi) int_q^inf C1D'(k) / sqrt(k^2 - q^2) dk (Jacobs, \
    Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017); Persson, Tribol. Lett. \
    54, 99 (2014)), C1D interpolated in log-log and extrapolated past the cutoff with the \
    power law of its highest octave";

/// Checks the options of a line check before any work (as
/// [`crate::measured::check::validate`] checks a surface's): the synthesized surfaces'
/// side and seeds, square pixels, the tolerance, the loads, the unit and the modulus;
/// returns the pixel size.
pub fn validate(opts: &CheckOptions, line: &LineOptions) -> Result<f64> {
    line.validate()?;
    let pixel = square_pixel(opts.pixel_size)?;
    crate::engine::solver::SolveOptions::with_tol(opts.tol).validate()?;
    if let Some(given) = &opts.loads {
        crate::measured::theory::check_loads(given)?;
    }
    if let Some(unit) = &opts.unit {
        crate::measured::units::check_unit(unit)?;
    }
    if let Some(modulus) = opts.modulus {
        crate::error::check_positive("modulus", modulus)?;
    }
    if let Some(k) = opts.despike {
        // The contact is simulated on synthesized surfaces, which have no instrument
        // spikes to remove; despiking them would only cut their Gaussian tails.
        return Err(Error::invalid(
            "despike",
            k,
            "not given for line scans (their contact is simulated on synthesized surfaces)",
        ));
    }
    Ok(pixel)
}

/// Checks the surface of line scans `profiles` (module docs). `events` sees the
/// synthesized surfaces' solves.
pub fn check_line(
    profiles: &Profiles,
    opts: &CheckOptions,
    line: &LineOptions,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<LineCheck> {
    let pixel = validate(opts, line)?;
    let spectrum = ProfileSpectrum::of(profiles, pixel, opts.boundary);
    if spectrum.h_rms == 0.0 {
        return Err(Error::invalid(
            "heights",
            "flat line scans",
            "rough profiles (a spectrum with power)",
        ));
    }
    let converted = convert(&spectrum);
    let isotropic = Isotropic::new(&converted, pixel)?;
    let side = line.side.min(profiles.points);
    let scans = synthesize(&isotropic, pixel, side, line.seeds)?;
    let synthesized = CheckOptions {
        boundary: Boundary::Periodic,
        fill: Fill::None,
        ..opts.clone()
    };
    let mut surface = check(&scans, &synthesized, events)?;
    let band = shells(&isotropic, pixel, profiles.points);
    let theory = Theory::new(&band)?;
    let persson = surface
        .loads
        .iter()
        .map(|&p0| {
            theory.at(p0).map(|t| TheoryPoint {
                p0,
                a_r_persson: t.contact_area,
                a_r_persson_corrected: t.contact_area_corrected,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let across = profiles
        .across
        .as_ref()
        .map(|a| ProfileSpectrum::new(&a.heights, a.points, pixel, opts.boundary, true));
    let mut warnings: Vec<Warning> = [
        SKEWNESS.check(spectrum.skewness),
        KURTOSIS.check(spectrum.kurtosis),
    ]
    .into_iter()
    .flatten()
    .collect();
    if let Some(a) = &across {
        let (x, y) = (spectrum.slope_rms_spectral, a.slope_rms_spectral);
        if x > 0.0 && y > 0.0 {
            warnings.extend(ISOTROPY.check(x.max(y) / x.min(y)));
        }
    }
    if let Some(&lowest) = surface.loads.first() {
        warnings.extend(PROFILE_LENGTH.check(theory.contact_area_at(lowest, LONG_WAVELENGTHS)?));
    }
    // The synthesized surfaces are Gaussian by construction: their moments say nothing.
    surface
        .warnings
        .retain(|w| w.name != SKEWNESS.name && w.name != KURTOSIS.name);
    warnings.append(&mut surface.warnings);
    surface.warnings = warnings;
    surface.spectrum_method = format!(
        "synthesized from line scans ({} profiles of {} points): {}",
        spectrum.profiles, spectrum.points, surface.spectrum_method
    );
    Ok(LineCheck {
        line: LineFindings {
            sources: profiles.sources.clone(),
            profiles: spectrum.profiles,
            points: spectrum.points,
            pixel_size: pixel,
            boundary: opts.boundary,
            h_rms: spectrum.h_rms,
            slope_rms: spectrum.slope_rms,
            slope_rms_spectral: spectrum.slope_rms_spectral,
            skewness: spectrum.skewness,
            kurtosis: spectrum.kurtosis,
            spectrum_across: across.map(|a| a.bins),
            spectrum: spectrum.bins,
            converted: converted.bins,
            tail_slope: converted.tail_slope,
            slope_rms_converted: band.rms_gradient(f64::INFINITY),
            synthesized_side: side,
            seeds: line.seeds,
            persson,
            method: METHOD.to_string(),
        },
        surface,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::fft::Fft2;
    use crate::engine::surface::{Amplitudes, Surface, SurfaceModel};
    use crate::measured::line::abel::Uncertain;
    use crate::measured::psd::{ScanSpectrum, Shape};

    fn heights(p: &SurfaceModel) -> Vec<f64> {
        let s = Surface::generate(p).unwrap();
        s.heights_at(f64::INFINITY, &Fft2::new(s.grid()))
    }

    #[test]
    fn the_rows_of_a_generated_surface_give_back_its_spectrum_within_error_bars() {
        // Random phases: the surface's spectrum is the model's on every mode, and the mean
        // of its periodic rows' spectra is the model summed across them. The conversion
        // gives the model back, within its error bars, where it is not marked uncertain.
        let n = 256;
        let hurst = 0.8;
        let mut p = SurfaceModel::new(n, hurst, n as f64, 2.0, 11);
        p.amplitudes = Amplitudes::RandomPhase;
        let surface = Surface::generate(&p).unwrap();
        let h = surface.heights_at(f64::INFINITY, &Fft2::new(surface.grid()));
        let rows = Profiles::from_values(std::path::Path::new("rows"), &[n, n], h, true).unwrap();
        let spectrum = ProfileSpectrum::of(&rows, 1.0, Boundary::Periodic);
        let converted = convert(&spectrum);
        // The model: C(q) = A / (2 pi)^2 |h~(q)|^2 of any mode, as a power law.
        let (s, _) = surface
            .modes()
            .iter()
            .enumerate()
            .find(|(s, h)| h.norm() > 0.0 && surface.grid().k2(*s) == 100)
            .unwrap();
        let area = (n * n) as f64 / (2.0 * std::f64::consts::PI).powi(2);
        let c10 = area * surface.modes()[s].norm_sqr();
        let q10 = surface.grid().q(s);
        let model = |q: f64| c10 * (q / q10).powf(-2.0 - 2.0 * hurst);
        let mut certain = 0;
        for b in &converted.bins {
            let ratio = b.c / model(b.q);
            eprintln!(
                "q {:.4} C/model {ratio:.4} rel.err {:.4} tail {:.4} {:?}",
                b.q,
                b.std_error / b.c,
                b.tail_share,
                b.uncertain
            );
            if b.uncertain.is_none() {
                certain += 1;
                assert!(
                    (b.c - model(b.q)).abs() <= 3.0 * b.std_error,
                    "q {}: {} vs {} ± {}",
                    b.q,
                    b.c,
                    model(b.q),
                    b.std_error
                );
            }
        }
        // Half a decade in the middle is certain (of two; the lowest bins' error bars
        // count the rows of one map as few independent profiles); the top, near the
        // cutoff, is not.
        assert!(certain >= 5, "{certain} of {}", converted.bins.len());
        assert_eq!(
            converted.bins.last().unwrap().uncertain,
            Some(Uncertain::Cutoff)
        );
    }

    #[test]
    fn a_scan_cut_into_profiles_predicts_its_contact_area_within_its_error_bars() {
        // Four 128^2 windows of a 512^2 surface: Persson's contact area on each window's
        // own 2D spectrum, and on the spectrum converted from its rows. The rows' mean lies
        // within three of the windows' standard errors of theirs, and so do the rms slopes.
        let big = 512;
        let h = heights(&SurfaceModel::new(big, 0.8, 256.0, 4.0, 5));
        let w = 128;
        let loads = [0.01, 0.03, 0.1];
        let (mut own, mut rows) = (vec![vec![]; 4], vec![vec![]; 4]);
        let (mut g_own, mut g_rows) = (vec![], vec![]);
        for k in 0..4 {
            let (r0, c0) = ((k / 2) * 256, (k % 2) * 256);
            let window: Vec<f64> = (0..w * w)
                .map(|i| h[(r0 + i / w) * big + c0 + i % w])
                .collect();
            let shape = Shape { rows: w, cols: w };
            let scan = ScanSpectrum::new(&window, shape, 1.0, Boundary::Free).unwrap();
            let theory = Theory::new(&scan.shells).unwrap();
            g_own.push(scan.slope_rms_spectral);
            let profiles =
                Profiles::from_values(std::path::Path::new("w"), &[w, w], window, true).unwrap();
            let spectrum = ProfileSpectrum::of(&profiles, 1.0, Boundary::Free);
            let iso = Isotropic::new(&convert(&spectrum), 1.0).unwrap();
            let band = shells(&iso, 1.0, w);
            g_rows.push(band.rms_gradient(f64::INFINITY));
            let line = Theory::new(&band).unwrap();
            for &p0 in &loads {
                own[k].push(theory.at(p0).unwrap().contact_area);
                rows[k].push(line.at(p0).unwrap().contact_area);
            }
        }
        let mean_se = |v: &[f64]| {
            let m = v.iter().sum::<f64>() / v.len() as f64;
            let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64;
            (m, (var / v.len() as f64).sqrt())
        };
        let (g2, g2_se) = mean_se(&g_own);
        let (g1, _) = mean_se(&g_rows);
        eprintln!("rms slope: 2D {g2} ± {g2_se}, from rows {g1}");
        assert!(
            (g1 - g2).abs() <= 3.0 * g2_se,
            "rms slope {g1} vs {g2} ± {g2_se}"
        );
        for (i, p0) in loads.iter().enumerate() {
            let (a2, se2) = mean_se(&own.iter().map(|v| v[i]).collect::<Vec<_>>());
            let (a1, se1) = mean_se(&rows.iter().map(|v| v[i]).collect::<Vec<_>>());
            eprintln!("p0 {p0}: a_r 2D {a2} ± {se2}, from rows {a1} ± {se1}");
            assert!(
                (a1 - a2).abs() <= 3.0 * se2,
                "p0 {p0}: {a1} vs {a2} ± {se2}"
            );
        }
    }

    #[test]
    fn a_line_check_runs_on_synthesized_surfaces_and_warns_where_it_should() {
        // Stripes along the rows (every slope across them) cut into rows: the columns
        // disagree with the rows, and the check says so; the synthesized surfaces' contact
        // area rises with the load beside Persson's.
        let n = 128;
        let mut h = heights(&SurfaceModel::new(n, 0.8, 64.0, 4.0, 3));
        for (k, v) in h.iter_mut().enumerate() {
            *v += 3.0 * (0.9 * (k / n) as f64).sin();
        }
        let profiles = Profiles::from_values(std::path::Path::new("s"), &[n, n], h, true).unwrap();
        let opts = CheckOptions {
            loads: Some(vec![0.02, 0.1]),
            cross_check: false,
            reentry: false,
            ..CheckOptions::default()
        };
        let line = LineOptions { side: 64, seeds: 2 };
        let c = check_line(&profiles, &opts, &line, &mut |_| ControlFlow::Continue(())).unwrap();
        let names: Vec<&str> = c.surface.warnings.iter().map(|w| w.name.as_str()).collect();
        assert!(names.contains(&ISOTROPY.name), "{names:?}");
        assert_eq!(c.surface.scans.len(), 2);
        assert_eq!(c.line.synthesized_side, 64);
        assert_eq!(c.surface.curve.len(), 2);
        assert!(c.surface.curve[1].a_r > c.surface.curve[0].a_r);
        assert!(c.surface.curve[0].a_r_std_error.is_some());
        assert_eq!(c.line.persson.len(), 2);
        let md = super::super::page::markdown(&c);
        assert!(md.contains("not on the measured profiles"), "{md}");
        // Bad options name their field.
        for bad in [
            LineOptions { side: 8, seeds: 2 },
            LineOptions { side: 64, seeds: 1 },
        ] {
            let e = check_line(&profiles, &opts, &bad, &mut |_| ControlFlow::Continue(()))
                .unwrap_err()
                .to_string();
            assert!(e.contains("line_side") || e.contains("line_seeds"), "{e}");
        }
    }
}
