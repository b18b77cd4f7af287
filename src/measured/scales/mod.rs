//! One surface measured at several scales (an AFM at nanometre pixels, an optical
//! profilometer at micrometres, a stylus over millimetres): the scans' spectra stitched
//! into the surface's ([`crate::measured::stitch`]), Persson's theory on the stitched
//! spectrum (the whole surface) and on each scan's own band, and each areal scan's contact
//! simulated as a single scan is ([`crate::measured::check`]) and set against both. The
//! comparison shows how much contact the scales a scan does not resolve remove: at a load
//! `p0`, `a_r,P(whole) / a_r,P(band)`, the share of the band's predicted contact area that
//! is left once the other scales' roughness is added.
//!
//! **Units.** Scans in different length units are converted into the first scan's unit
//! (heights and pixel by `metres(unit_i) / metres(unit_0)`, [`super::units::metres`]);
//! scans without a unit must all be without one.
//!
//! **The band a scan resolves reliably** ([`reliable_band`]), from its longest wavelength
//! to its shortest:
//!
//! * long wavelengths: `q_lo = m 2 pi / L` with `L` the scan's longer side; `m = 1` for a
//!   periodic scan, whose modes are the surface's, and `m = 4` ([`LOW_MODES`], the line
//!   scans' same rule, [`crate::measured::line::abel::LOW_MODES`]) for a measured window,
//!   whose Hann window's main lobe mixes each of its lowest modes with two neighbours on
//!   either side, and whose plane removal takes power from the lowest;
//! * short wavelengths: `q_hi = 2 pi / (RELIABLE_PIXELS a)`, wavelengths of at least
//!   [`RELIABLE_PIXELS`] pixels (half the Nyquist wavevector `pi / a`): the octave below
//!   the Nyquist wavevector is where an instrument's lateral resolution (a tip's radius,
//!   an objective's point spread) and the aliasing of shorter wavelengths act first, so
//!   a scan's spectrum is trusted up to half its Nyquist wavevector only; a cutoff known
//!   for the scan (a noise floor, a tip radius, as a shortest reliable wavelength) lowers
//!   `q_hi` further.
//!
//! **What each scan counts** in the stitched average (its modes,
//! [`crate::measured::stitch::Sample`]): an areal scan each mode of its half spectrum
//! (a pair `q, -q` is one independent mode; the weight 1 or 2 of
//! [`super::psd::ModePower`] over 2), divided for a windowed scan by `1.5^2`, the Hann
//! window's equivalent noise bandwidth (1.5 modes along each axis), since neighbouring
//! windowed modes are correlated; a line scan each bin of its converted spectrum that
//! the conversion does not mark uncertain, counting `(C / sigma_C)^2` modes (the modes an
//! exponentially distributed estimate with that relative error rests on). A line scan's
//! band is narrowed to the wavevectors of those bins: beyond them it resolves nothing
//! reliably, and a gap is reported where no other scan does.
//!
//! Its parts: the findings as data and the check here, the page ([`page`]).

pub mod page;

use std::ops::ControlFlow;

use serde::{Deserialize, Serialize};

use super::check::{check, CheckOptions, Event, SurfaceCheck};
use super::cutoff::Cutoff;
use super::line::abel::convert;
use super::line::profiles::Profiles;
use super::line::spectrum::ProfileSpectrum;
use super::psd::{scan_modes, Boundary, ScanSpectrum};
use super::scan::Scan;
use super::stitch::{stitch, Band, Sample, Stitched};
use super::theory::{Theory, TheoryPoint};
use super::units::{check_unit, metres};
use crate::error::{check_positive, Error, Result, StopReason};

/// Wavelengths of fewer pixels than this are left out of a scan's reliable band (module
/// docs): `q_hi = 2 pi / (4 a)`, half the Nyquist wavevector.
pub const RELIABLE_PIXELS: f64 = 4.0;

/// A measured window's reliable band starts this many lowest wavevectors `2 pi / L` up
/// (module docs; the line scans' [`crate::measured::line::abel::LOW_MODES`]).
pub const LOW_MODES: f64 = crate::measured::line::abel::LOW_MODES;

/// The Hann window's equivalent noise bandwidth, in modes along one axis: a windowed
/// scan's mode counts `1 / 1.5^2` of an independent one in the stitched average.
pub const HANN_BANDWIDTH: f64 = 1.5;

/// The band a scan of longer side `side` (length) and pixel `pixel` resolves reliably
/// (module docs); `cutoff`, when known, is its shortest reliable wavelength (a noise
/// floor's or a tip's), which can only narrow the band.
pub fn reliable_band(side: f64, pixel: f64, boundary: Boundary, cutoff: Option<f64>) -> Band {
    let two_pi = 2.0 * std::f64::consts::PI;
    let m = match boundary {
        Boundary::Periodic => 1.0,
        Boundary::Free => LOW_MODES,
    };
    let by_pixels = two_pi / (RELIABLE_PIXELS * pixel);
    let hi = cutoff.map_or(by_pixels, |c| by_pixels.min(two_pi / c));
    Band {
        lo: m * two_pi / side,
        hi,
    }
}

/// What was measured at one scale.
#[derive(Debug, Clone, PartialEq)]
pub enum Measured {
    /// A height map (an areal scan).
    Map(Scan),
    /// Line scans (profiles).
    Line(Profiles),
}

/// One scan of the surface at its scale, as given.
#[derive(Debug, Clone, PartialEq)]
pub struct ScaleScan {
    /// Its name in messages and on the page (`scan[0]`, `heights[1]`), with its file.
    pub label: String,
    /// The heights.
    pub measured: Measured,
    /// Its pixel (the spacing of its points), in its own unit.
    pub pixel: f64,
    /// Its length unit.
    pub unit: Option<String>,
}

/// Which kind a scan is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// A height map.
    Map,
    /// Line scans.
    Line,
}

/// One load of an areal scan's comparison.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScaleRow {
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// The simulated contact area (the scan's headline solver).
    pub a_r: f64,
    /// Its standard error (absent for one scan).
    pub a_r_std_error: Option<f64>,
    /// Persson (original) on the scan's own spectrum, every mode it holds: what the
    /// single-scan check compares with.
    pub a_r_persson_scan: f64,
    /// Persson (original) on the stitched spectrum over the scan's reliable band.
    pub a_r_persson_band: f64,
    /// Persson (original) on the stitched spectrum over the whole surface.
    pub a_r_persson_whole: f64,
    /// Persson (corrected) on the whole surface.
    pub a_r_persson_whole_corrected: f64,
    /// `a_r_persson_whole / a_r_persson_band`: the share of the band's predicted contact
    /// left once the scales the scan does not resolve are added.
    pub whole_over_band: f64,
}

/// What one scan gave.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScaleFindings {
    /// Its name (`scan[0]`, `heights[1]`).
    pub label: String,
    /// Where it came from (its file, or the name given).
    pub source: String,
    /// Height map or line scans.
    pub kind: Kind,
    /// Rows and columns of a map; profiles and points of line scans.
    pub shape: [usize; 2],
    /// Its pixel as given, in its unit.
    pub pixel_given: f64,
    /// Its unit as given.
    pub unit_given: Option<String>,
    /// Its pixel in the surface's unit.
    pub pixel_size: f64,
    /// Its reliable band (1 / the surface's unit).
    pub band: Band,
    /// Rms slope of the stitched spectrum over its band (Persson's `g_bar` there).
    pub slope_rms_band: f64,
    /// The comparison of its simulated contact (areal scans only).
    pub comparison: Option<Vec<ScaleRow>>,
    /// Its own check (areal scans only): `surface.json` of the scan alone.
    pub check: Option<Box<SurfaceCheck>>,
}

/// Everything the check of a surface across scales found: `scales.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScalesCheck {
    /// The surface's length unit (the first scan's).
    pub unit: Option<String>,
    /// The scans, as given.
    pub scans: Vec<ScaleFindings>,
    /// The stitched spectrum, each scan's on its grid, and the gaps.
    pub stitched: Stitched,
    /// Rms height of the stitched spectrum over the whole surface (the surface's unit).
    pub h_rms: f64,
    /// Rms slope of the stitched spectrum over the whole surface.
    pub slope_rms: f64,
    /// Persson on the whole surface at its own default loads (or those asked for).
    pub whole: Vec<TheoryPoint>,
    /// How the spectrum was stitched, in words.
    pub method: String,
    /// Wall time, seconds.
    pub wall_s: f64,
}

/// The stitching rule, in words for the page and the JSON.
pub const METHOD: &str = "each scan's spectrum over its reliable band (from m 2 pi / L, m = 1 \
    periodic and 4 for a windowed scan, up to wavelengths of 4 pixels): areal scans' 2D \
    spectra, line scans' 1D spectra converted by the inverse Abel transform; in log bins of \
    a tenth of a decade, C(b) = sum_i N_i(b) C_i(b) / sum_i N_i(b) with N_i(b) the \
    independent modes of scan i in the bin; interpolated in log-log across gaps";

/// The factor from each scan's unit to the first's, and the surface's unit (module docs).
///
/// # Errors
///
/// If some scans have a unit and others not, a unit's name is malformed, or scans in
/// different units name one not known here (the error names the scan's field).
pub fn unit_factors(scans: &[ScaleScan]) -> Result<(Option<String>, Vec<f64>)> {
    let Some(first) = scans.first() else {
        return Err(Error::invalid("scales", "no scan", "at least two scans"));
    };
    for s in scans {
        if let Some(u) = &s.unit {
            check_unit(u).map_err(|e| e.with_field(&format!("{}.unit", s.label)))?;
        }
    }
    let common = first.unit.clone();
    if scans.iter().all(|s| s.unit == common) {
        return Ok((common, vec![1.0; scans.len()]));
    }
    let known = "a length unit known here (m, mm, µm, um, nm, pm, Å): scans in different \
                 units are converted, and each then needs one";
    let mut factors = Vec::with_capacity(scans.len());
    let base = metres_of(first, known)?;
    for s in scans {
        factors.push(metres_of(s, known)? / base);
    }
    Ok((common, factors))
}

fn metres_of(s: &ScaleScan, known: &str) -> Result<f64> {
    let field = format!("{}.unit", s.label);
    match &s.unit {
        None => Err(Error::invalid(&field, "none", known)),
        Some(u) => metres(u).ok_or_else(|| Error::invalid(&field, u, known)),
    }
}

/// One scan in the surface's unit: its heights scaled by `f`.
fn converted(s: &ScaleScan, f: f64) -> Measured {
    match &s.measured {
        Measured::Map(scan) => Measured::Map(Scan {
            heights: scan.heights.iter().map(|h| h * f).collect(),
            ..scan.clone()
        }),
        Measured::Line(p) => Measured::Line(Profiles {
            heights: p.heights.iter().map(|h| h * f).collect(),
            across: p.across.clone().map(|mut a| {
                a.heights.iter_mut().for_each(|h| *h *= f);
                a
            }),
            ..p.clone()
        }),
    }
}

/// Where a scan came from.
fn source_of(m: &Measured) -> String {
    match m {
        Measured::Map(s) => s.source.display().to_string(),
        Measured::Line(p) => p
            .sources
            .iter()
            .map(|(name, _)| name.as_str())
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// A scan's shape (`[rows, cols]`, or `[profiles, points]`) and its longer side, points.
fn shape_of(m: &Measured) -> ([usize; 2], usize) {
    match m {
        Measured::Map(s) => ([s.shape.rows, s.shape.cols], s.shape.longer()),
        Measured::Line(p) => ([p.count(), p.points], p.points),
    }
}

/// A scan's samples of `C(q)` in the surface's unit, each with its independent modes
/// (module docs).
fn samples(m: &Measured, pixel: f64, boundary: Boundary) -> Result<Vec<Sample>> {
    match m {
        Measured::Map(scan) => {
            let per_mode = 0.5
                / match boundary {
                    Boundary::Periodic => 1.0,
                    Boundary::Free => HANN_BANDWIDTH * HANN_BANDWIDTH,
                };
            Ok(scan_modes(&scan.heights, scan.shape, pixel, boundary)?
                .into_iter()
                .map(|m| Sample {
                    q: m.q,
                    c: m.c,
                    modes: m.weight * per_mode,
                })
                .collect())
        }
        Measured::Line(p) => {
            let spectrum = ProfileSpectrum::of(p, pixel, boundary);
            Ok(convert(&spectrum)
                .bins
                .into_iter()
                .filter(|b| b.uncertain.is_none() && b.c > 0.0 && b.std_error > 0.0)
                .map(|b| Sample {
                    q: b.q,
                    c: b.c,
                    modes: (b.c / b.std_error).powi(2),
                })
                .collect())
        }
    }
}

/// Why line scans without a certain bin in their band are refused.
const NO_CERTAIN_BIN: &str = "line scans whose converted spectrum has a bin the conversion \
    does not mark uncertain within their band (longer or more profiles)";

/// A line scan's band narrowed to the `q` of its certain bins: it resolves nothing
/// reliably beyond them (the conversion marks the lowest and the highest bins uncertain).
fn certain(band: Band, samples: &[Sample]) -> Option<Band> {
    let inside = || samples.iter().map(|s| s.q).filter(|&q| band.holds(q));
    let lo = inside().min_by(f64::total_cmp)?;
    let hi = inside().max_by(f64::total_cmp)?;
    Some(Band { lo, hi })
}

/// Checks the scans before any work: at least two, positive pixels, units that convert.
///
/// # Errors
///
/// As [`unit_factors`], and for fewer than two scans or a pixel that is not positive.
pub fn validate(scans: &[ScaleScan]) -> Result<(Option<String>, Vec<f64>)> {
    if scans.len() < 2 {
        return Err(Error::invalid(
            "scales",
            format!("{} scan(s)", scans.len()),
            "at least two scans of one surface at different scales (one scan is checked \
             alone, without a scan list)",
        ));
    }
    for s in scans {
        check_positive(&format!("{}.pixel_size", s.label), s.pixel)?;
    }
    unit_factors(scans)
}

/// Persson's original and corrected contact areas on `theory` at `loads`.
fn theory_points(theory: &Theory, loads: &[f64]) -> Result<Vec<TheoryPoint>> {
    loads
        .iter()
        .map(|&p0| {
            theory.at(p0).map(|t| TheoryPoint {
                p0,
                a_r_persson: t.contact_area,
                a_r_persson_corrected: t.contact_area_corrected,
            })
        })
        .collect()
}

/// The spectrum side of the check: each scan's band and samples in the surface's unit,
/// stitched.
#[derive(Debug)]
struct Spectra {
    unit: Option<String>,
    scans: Vec<(Measured, f64)>,
    bands: Vec<Band>,
    stitched: Stitched,
}

/// The scans' spectra, converted to one unit, and stitched; `cut` asks each map's
/// short-wavelength cutoff ([`super::cutoff`], with the tip's radius where given), which
/// narrows its reliable band.
fn spectra(scans: &[ScaleScan], boundary: Boundary, cut: Option<Option<f64>>) -> Result<Spectra> {
    let (unit, factors) = validate(scans)?;
    let mut parts = Vec::with_capacity(scans.len());
    let mut converted_scans = Vec::with_capacity(scans.len());
    for (s, f) in scans.iter().zip(&factors) {
        let m = converted(s, *f);
        let pixel = s.pixel * f;
        let (_, side) = shape_of(&m);
        let cutoff = match (&m, cut) {
            (Measured::Map(scan), Some(tip)) => {
                let own = ScanSpectrum::new(&scan.heights, scan.shape, pixel, boundary)?;
                Cutoff::of_scan(&own.radial, &own.shells, pixel, tip).map(|c| c.wavelength)
            }
            _ => None,
        };
        let band = reliable_band(side as f64 * pixel, pixel, boundary, cutoff);
        let samples = samples(&m, pixel, boundary)?;
        let band = match m {
            Measured::Map(_) => band,
            Measured::Line(_) => certain(band, &samples)
                .ok_or_else(|| Error::invalid(&s.label, "line scans", NO_CERTAIN_BIN))?,
        };
        parts.push((band, samples));
        converted_scans.push((m, pixel));
    }
    let stitched = stitch(&parts)?;
    Ok(Spectra {
        unit,
        scans: converted_scans,
        bands: parts.iter().map(|p| p.0).collect(),
        stitched,
    })
}

/// An areal scan's check, its events reported as scan `index`'s.
fn check_one(
    scan: &Scan,
    pixel: f64,
    opts: &CheckOptions,
    index: usize,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<SurfaceCheck> {
    let own = CheckOptions {
        pixel_size: [pixel, pixel],
        ..opts.clone()
    };
    check(std::slice::from_ref(scan), &own, &mut |e| {
        events(match e {
            Event::Outliers { outliers, .. } => Event::Outliers {
                scan: index,
                outliers,
            },
            Event::Iteration {
                solver,
                load,
                progress,
                ..
            } => Event::Iteration {
                scan: index,
                solver,
                load,
                progress,
            },
            Event::Load {
                solver,
                headline,
                load,
                loads,
                outcome,
                ..
            } => Event::Load {
                scan: index,
                solver,
                headline,
                load,
                loads,
                outcome,
            },
        })
    })
}

/// An areal scan's rows: its simulated curve beside Persson on its spectrum, its band
/// and the whole surface.
fn rows(c: &SurfaceCheck, band: &Theory, whole: &Theory) -> Result<Vec<ScaleRow>> {
    c.curve
        .iter()
        .map(|p| {
            let b = band.at(p.p0)?;
            let w = whole.at(p.p0)?;
            Ok(ScaleRow {
                p0: p.p0,
                a_r: p.a_r,
                a_r_std_error: p.a_r_std_error,
                a_r_persson_scan: p.a_r_persson,
                a_r_persson_band: b.contact_area,
                a_r_persson_whole: w.contact_area,
                a_r_persson_whole_corrected: w.contact_area_corrected,
                whole_over_band: w.contact_area / b.contact_area,
            })
        })
        .collect()
}

/// Checks one surface measured at several scales (module docs): `scans` (their missing
/// points already filled or refused), `opts` for every areal scan's check (its pixel
/// sides and unit are each scan's; the boundary is every scan's). `events` sees each
/// areal scan's solves, numbered by the scan's place in `scans`.
///
/// # Errors
///
/// If the scans or the options are refused (before any solve), the stitched spectrum is
/// empty, or a check fails as [`check`] does.
pub fn check_scales(
    scans: &[ScaleScan],
    opts: &CheckOptions,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<ScalesCheck> {
    let timer = std::time::Instant::now();
    let sp = spectra(scans, opts.boundary, opts.cutoff.then_some(opts.tip_radius))?;
    let opts = CheckOptions {
        unit: sp.unit.clone(),
        ..opts.clone()
    };
    for (m, pixel) in &sp.scans {
        if let Measured::Map(scan) = m {
            let own = CheckOptions {
                pixel_size: [*pixel, *pixel],
                ..opts.clone()
            };
            super::check::validate(std::slice::from_ref(scan), &own)?;
        }
    }
    let unit_length = sp.scans.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
    let whole_shells = sp.stitched.shells(sp.stitched.band, unit_length);
    let whole = Theory::new(&whole_shells)?;
    let mut findings = Vec::with_capacity(scans.len());
    for (k, (s, (m, pixel))) in scans.iter().zip(&sp.scans).enumerate() {
        let band_shells = sp.stitched.shells(sp.bands[k], unit_length);
        let (shape, _) = shape_of(m);
        let mut f = ScaleFindings {
            label: s.label.clone(),
            source: source_of(m),
            kind: match m {
                Measured::Map(_) => Kind::Map,
                Measured::Line(_) => Kind::Line,
            },
            shape,
            pixel_given: s.pixel,
            unit_given: s.unit.clone(),
            pixel_size: *pixel,
            band: sp.bands[k],
            slope_rms_band: band_shells.rms_gradient(f64::INFINITY),
            comparison: None,
            check: None,
        };
        if let Measured::Map(scan) = m {
            let c = check_one(scan, *pixel, &opts, k, events)?;
            f.comparison = Some(rows(&c, &Theory::new(&band_shells)?, &whole)?);
            f.check = Some(Box::new(c));
        }
        findings.push(f);
    }
    let loads = super::theory::loads(&whole, opts.loads.as_deref())?;
    Ok(ScalesCheck {
        unit: sp.unit,
        scans: findings,
        h_rms: unit_length * whole_shells.rms_height(f64::INFINITY),
        slope_rms: whole_shells.rms_gradient(f64::INFINITY),
        whole: theory_points(&whole, &loads)?,
        stitched: sp.stitched,
        method: METHOD.to_string(),
        wall_s: timer.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests;
