//! The page of a line-scan check: `surface.json` (the [`LineCheck`], the synthesized
//! surfaces' fields with `line` beside them), `surface.md` (the profiles, their spectrum
//! and its conversion, Persson on the converted spectrum, then the synthesized surfaces'
//! check, headed as such) and the figures, `figures/line_psd` among them.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::abel::Uncertain;
use super::check::{LineCheck, LineFindings};
use crate::error::Result;
use crate::measured::units::eng;
use crate::plot::{Axis, Figure, Series, Style};

/// Writes `surface.json`, `surface.md` and the figures into `dir`; returns the files.
pub fn write(check: &LineCheck, dir: &Path) -> Result<Vec<PathBuf>> {
    // The synthesized surfaces' page and figures, then this check's JSON and page over it.
    let mut files = crate::measured::page::write(&check.surface, dir)?;
    files.extend(crate::plot::render(&figure(check), &dir.join("figures"))?);
    let json = serde_json::to_vec_pretty(check).expect("checks serialise");
    crate::io::write_atomic(&dir.join("surface.json"), &json)?;
    let md = markdown(check);
    crate::io::write_atomic(&dir.join("surface.md"), md.as_bytes())?;
    Ok(files)
}

/// The page: the line scans' section, then the synthesized surfaces' check.
pub fn markdown(c: &LineCheck) -> String {
    let l = &c.line;
    let u = c.surface.unit.as_deref().unwrap_or("length unit");
    let mut s = String::new();
    let _ = writeln!(s, "# Persson's theory on line scans\n");
    let _ = writeln!(
        s,
        "**The contact was simulated on {} isotropic surfaces of {side} x {side} points \
         synthesized with the spectrum the profiles imply (random phases, one per seed; the \
         error bars come from them), not on the measured profiles.** A profile holds no \
         contact area of its own: its spectrum, converted under the assumption of an \
         isotropic surface, is all that reaches the theory and the simulation.\n",
        l.seeds,
        side = l.synthesized_side
    );
    profiles(&mut s, l, u);
    conversion(&mut s, l, u);
    persson(&mut s, c);
    let page = crate::measured::page::markdown(&c.surface);
    let body = page
        .strip_prefix("# Persson's theory on a measured surface\n")
        .unwrap_or(&page);
    let _ = write!(
        s,
        "\n# The check on the synthesized surfaces\n\nThe surfaces below are the synthesized \
         ones (\"scans\"), not measurements.\n{body}"
    );
    s
}

/// The profiles: their sources and statistics.
fn profiles(s: &mut String, l: &LineFindings, u: &str) {
    let sources: Vec<String> = l
        .sources
        .iter()
        .map(|(name, k)| format!("`{name}` ({k} profile{})", if *k == 1 { "" } else { "s" }))
        .collect();
    let _ = writeln!(
        s,
        "## The profiles\n\n{} profile(s) of {} points, spacing {} {u} (length {} {u}), {}: \
         {}.\n\n| statistic | value |\n|---|---|\n| rms height ({u}) | {} |\n| rms slope \
         along the profiles (finite differences) | {} |\n| rms slope along the profiles \
         (spectrum) | {} |\n| rms slope of the converted surface (Persson's g, profile's \
         band) | {} (sqrt 2 x along: {}) |\n| skewness of the heights | {} |\n| excess \
         kurtosis of the heights | {} |\n| log-log slope of C1D, highest octave (the tail) \
         | {} |\n",
        l.profiles,
        l.points,
        eng(l.pixel_size),
        eng(l.pixel_size * l.points as f64),
        match l.boundary {
            crate::measured::psd::Boundary::Periodic => "periodic",
            crate::measured::psd::Boundary::Free => "measured windows (free boundary)",
        },
        sources.join(", "),
        eng(l.h_rms),
        eng(l.slope_rms),
        eng(l.slope_rms_spectral),
        eng(l.slope_rms_converted),
        eng(std::f64::consts::SQRT_2 * l.slope_rms_spectral),
        eng(l.skewness),
        eng(l.kurtosis),
        l.tail_slope
            .map_or("— (does not fall: truncated)".into(), eng)
    );
}

/// The conversion of the profiles' spectrum to the surface's, bin by bin.
fn conversion(s: &mut String, l: &LineFindings, u: &str) {
    let _ = writeln!(
        s,
        "## From the profiles' spectrum to the surface's\n\nMethod: {}.\n\n| q (1/{u}) | \
         C1D ({u}^3) | C (2D, {u}^4) | share from the tail past the cutoff | uncertain |\n\
         |---|---|---|---|---|",
        l.method
    );
    for (b, c2) in l.spectrum.iter().zip(&l.converted) {
        let why = match c2.uncertain {
            None => "",
            Some(Uncertain::Cutoff) => "near the cutoff: rests on the extrapolated tail",
            Some(Uncertain::FewModes) => "few modes (lowest q)",
            Some(Uncertain::NotPositive) => "not positive: left out",
        };
        let _ = writeln!(
            s,
            "| {} | {} ± {} | {} ± {} | {} | {why} |",
            eng(b.q),
            eng(b.c),
            eng(b.std_error),
            eng(c2.c),
            eng(c2.std_error),
            if c2.tail_share.is_finite() {
                format!("{:.1}%", 100.0 * c2.tail_share)
            } else {
                "—".into()
            }
        );
    }
    let _ = writeln!(
        s,
        "\nThe conversion is uncertain near the profile's cutoff, where the Abel integral is \
         truncated and rests on the tail extrapolated past it, and at the lowest q, where a \
         bin holds few modes; those bins are marked, and drawn apart in the figure.\n\n\
         ![line spectrum](figures/line_psd.png)\n"
    );
}

/// Persson's theory on the converted spectrum beside the synthesized surfaces' curve.
fn persson(s: &mut String, c: &LineCheck) {
    let l = &c.line;
    let _ = writeln!(
        s,
        "## Persson's theory on the converted spectrum\n\nOver the profile's whole band \
         (2 pi / L to pi / a), beside the synthesized surfaces' own (whose side {side} \
         points {} the wavelengths longer than {side} pixels).\n\n| p0 / E* | a_r Persson \
         (converted, whole band) | corrected | a_r simulated (synthesized) | a_r Persson \
         (synthesized) |\n|---|---|---|---|---|",
        if l.synthesized_side < l.points {
            "leaves out"
        } else {
            "keeps"
        },
        side = l.synthesized_side
    );
    for p in &l.persson {
        let sim = c.surface.curve.iter().find(|q| q.p0 == p.p0);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            eng(p.p0),
            eng(p.a_r_persson),
            eng(p.a_r_persson_corrected),
            sim.map_or("— (not solved)".into(), |q| match q.a_r_std_error {
                Some(e) => format!("{} ± {}", eng(q.a_r), eng(e)),
                None => eng(q.a_r),
            }),
            sim.map_or("—".into(), |q| eng(q.a_r_persson)),
        );
    }
}

/// The profiles' spectrum, the converted one (certain and uncertain bins apart) and the
/// synthesized surfaces' radial average.
pub fn figure(c: &LineCheck) -> Figure {
    let l = &c.line;
    let u = c.surface.unit.as_deref().unwrap_or("length unit");
    let certain = |b: &&super::abel::ConvertedBin| b.uncertain.is_none();
    let mut series = vec![
        Series::with_errors(
            "C1D(q), profiles",
            Style::Points,
            l.spectrum.iter().map(|b| (b.q, b.c, b.std_error)),
        ),
        Series::with_errors(
            "C(q), converted",
            Style::Points,
            l.converted
                .iter()
                .filter(certain)
                .map(|b| (b.q, b.c, b.std_error)),
        ),
        Series::with_errors(
            "C(q), converted: uncertain",
            Style::Points,
            l.converted
                .iter()
                .filter(|b| !certain(b) && b.c > 0.0)
                .map(|b| (b.q, b.c, b.std_error)),
        ),
        Series::xy(
            "C(q), synthesized surfaces",
            Style::Line,
            c.surface.statistics.psd.iter().map(|b| (b.q, b.c)),
        ),
    ];
    if let Some(across) = &l.spectrum_across {
        series.push(Series::xy(
            "C1D(q), profiles across",
            Style::Dashed,
            across.iter().map(|b| (b.q, b.c)),
        ));
    }
    Figure {
        name: "line_psd".into(),
        title: "Line scans: the profiles' spectrum and the surface's it implies".into(),
        x: Axis::log(format!("q (1/{u})")),
        y: Axis::log(format!("C1D ({u}^3), C ({u}^4)")),
        y2: None,
        series,
    }
}
