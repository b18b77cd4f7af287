//! The page of a surface checked across scales: `scales.json` (the [`ScalesCheck`] as it
//! is), `scales.md`, its figures under `figures/` (each scan's spectrum over its band and
//! the stitched one, `scales_psd`; each areal scan's simulated contact area beside
//! Persson on its band and on the whole surface, `scales_contact_area`), and each areal
//! scan's own check page in `scan-<k>/` ([`crate::measured::page`]). Numbers as the
//! single-scan page writes them ([`crate::measured::units::eng`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::{Kind, ScaleFindings, ScalesCheck};
use crate::error::Result;
use crate::measured::units::{eng, length, percent};
use crate::plot::{Axis, Figure, Series, Style};

/// The folder of scan `k`'s own check page.
pub fn scan_dir(k: usize) -> String {
    format!("scan-{k}")
}

/// Writes `scales.json`, `scales.md`, the figures and each areal scan's page into `dir`;
/// returns the files.
///
/// # Errors
///
/// If a file cannot be written.
pub fn write(c: &ScalesCheck, dir: &Path) -> Result<Vec<PathBuf>> {
    let json = serde_json::to_vec_pretty(c).expect("checks serialise");
    let json_path = dir.join("scales.json");
    crate::io::write_atomic(&json_path, &json)?;
    let mut files = vec![json_path];
    for figure in figures(c) {
        files.extend(crate::plot::render(&figure, &dir.join("figures"))?);
    }
    for (k, s) in c.scans.iter().enumerate() {
        if let Some(check) = &s.check {
            files.extend(crate::measured::page::write(check, &dir.join(scan_dir(k)))?);
        }
    }
    let md = dir.join("scales.md");
    crate::io::write_atomic(&md, markdown(c).as_bytes())?;
    files.push(md);
    Ok(files)
}

fn unit(c: &ScalesCheck) -> &str {
    c.unit.as_deref().unwrap_or("length unit")
}

/// The figures: the spectra, and the contact areas of the areal scans.
pub fn figures(c: &ScalesCheck) -> Vec<Figure> {
    let u = unit(c);
    let mut psd: Vec<Series> = c
        .scans
        .iter()
        .zip(&c.stitched.scans)
        .map(|(s, bins)| {
            Series::xy(
                s.label.clone(),
                Style::Points,
                bins.iter().map(|b| (b.q, b.c)),
            )
        })
        .collect();
    psd.push(Series::xy(
        "stitched",
        Style::Line,
        c.stitched.bins.iter().map(|b| (b.q, b.c)),
    ));
    let mut area = Vec::new();
    for s in &c.scans {
        let Some(rows) = &s.comparison else { continue };
        area.push(Series::with_errors(
            format!("{}: simulation", s.label),
            Style::Points,
            rows.iter()
                .map(|r| (r.p0, r.a_r, r.a_r_std_error.unwrap_or(f64::NAN))),
        ));
        area.push(Series::xy(
            format!("{}: Persson, its band", s.label),
            Style::Dashed,
            rows.iter().map(|r| (r.p0, r.a_r_persson_band)),
        ));
        area.push(Series::xy(
            format!("{}: Persson, whole surface", s.label),
            Style::Line,
            rows.iter().map(|r| (r.p0, r.a_r_persson_whole)),
        ));
    }
    let mut figures = vec![Figure {
        name: "scales_psd".into(),
        title: "Each scan's power spectrum over its reliable band, and the stitched one".into(),
        x: Axis::log(format!("q (1/{u})")),
        y: Axis::log(format!("C(q) ({u}^4)")),
        y2: None,
        series: psd,
    }];
    if !area.is_empty() {
        figures.push(Figure {
            name: "scales_contact_area".into(),
            title: "Contact area of each areal scan: simulated, Persson on its band and on \
                    the whole surface"
                .into(),
            x: Axis::log("p0 / E*"),
            y: Axis::log("a_r"),
            y2: None,
            series: area,
        });
    }
    figures
}

/// The page.
pub fn markdown(c: &ScalesCheck) -> String {
    let mut s = String::new();
    let u = c.unit.as_deref();
    let _ = writeln!(
        s,
        "# Persson's theory on a surface measured at several scales\n\n{} scans of one \
         surface, lengths in {} (scans in other units converted). Their spectra are \
         stitched into the surface's, Persson's theory is evaluated on it (the whole \
         surface) and on each scan's band, and each areal scan's contact is simulated alone \
         and set against both.\n",
        c.scans.len(),
        unit(c)
    );
    scans(&mut s, c);
    gaps(&mut s, c);
    let _ = writeln!(
        s,
        "## The stitched spectrum\n\n{}.\n\nOver the whole surface (wavevectors {} to {} \
         1/{}): rms height {}, rms slope {} (Persson's `g_bar`).\n\n![spectra](figures/scales_psd.svg)\n",
        c.method,
        eng(c.stitched.band.lo),
        eng(c.stitched.band.hi),
        unit(c),
        length(c.h_rms, u),
        eng(c.slope_rms)
    );
    for (k, f) in c.scans.iter().enumerate() {
        comparison(&mut s, k, f);
    }
    whole(&mut s, c);
    let _ = writeln!(
        s,
        "## Files\n\n`scales.json` holds every number of this page (`stitched.bins`: the \
         stitched spectrum; `stitched.scans`: each scan's on the same bins); each areal \
         scan's own check is in `scan-<k>/` (`surface.md`, `surface.json`); the figures are \
         in `figures/`."
    );
    s
}

fn scans(s: &mut String, c: &ScalesCheck) {
    let u = c.unit.as_deref();
    let _ = writeln!(
        s,
        "## The scans\n\n| scan | source | kind | points | pixel (given) | pixel | reliable band, \
         wavelengths | rms slope of the stitched spectrum over the band |\n|---|---|---|---|---|---|---|---|"
    );
    for f in &c.scans {
        let two_pi = 2.0 * std::f64::consts::PI;
        let _ = writeln!(
            s,
            "| {} | `{}` | {} | {} | {} {} | {} | {} to {} | {} |",
            f.label,
            f.source,
            match f.kind {
                Kind::Map => "height map",
                Kind::Line => "line scans",
            },
            match f.kind {
                Kind::Map => format!("{} x {}", f.shape[0], f.shape[1]),
                Kind::Line => format!("{} x {} (profiles x points)", f.shape[0], f.shape[1]),
            },
            eng(f.pixel_given),
            f.unit_given.as_deref().unwrap_or(""),
            length(f.pixel_size, u),
            length(two_pi / f.band.lo, u),
            length(two_pi / f.band.hi, u),
            eng(f.slope_rms_band)
        );
    }
    let _ = writeln!(
        s,
        "\nA scan's reliable band runs from its longest wavelength (its side; four times \
         the lowest wavevector for a measured window, whose Hann window mixes its lowest \
         modes) down to wavelengths of four pixels (half its Nyquist wavevector, where \
         the instrument's lateral resolution and aliasing act first). Line scans count \
         only the bins of their converted spectrum the conversion does not mark \
         uncertain.\n"
    );
}

fn gaps(s: &mut String, c: &ScalesCheck) {
    let u = c.unit.as_deref();
    let two_pi = 2.0 * std::f64::consts::PI;
    if c.stitched.gaps.is_empty() {
        let _ = writeln!(s, "The bands overlap: the stitched spectrum has no gap.\n");
        return;
    }
    for g in &c.stitched.gaps {
        let _ = writeln!(
            s,
            "**A gap**: no scan resolves the wavelengths from {} down to {} (q from {} to \
             {} 1/{}); the stitched spectrum is interpolated in log-log across it, and \
             Persson's theory on the whole surface leans on that interpolation there. \
             Measure a scan that spans it.\n",
            length(two_pi / g.from, u),
            length(two_pi / g.to, u),
            eng(g.from),
            eng(g.to),
            unit(c)
        );
    }
}

fn comparison(s: &mut String, k: usize, f: &ScaleFindings) {
    let Some(rows) = &f.comparison else {
        return;
    };
    let _ = writeln!(
        s,
        "## {}: simulated, against Persson on its band and on the whole surface\n\n\
         The contact of this scan alone (its own page: `{}/surface.md`), beside Persson's \
         original theory on the scan's own spectrum (every mode it holds), on the stitched \
         spectrum over its reliable band, and on the whole surface.\n\n\
         | p0 / E* | a_r simulated | Persson, its spectrum | Persson, stitched over its band \
         | Persson, whole surface | corrected, whole surface | whole / band |\n\
         |---|---|---|---|---|---|---|",
        f.label,
        super::page::scan_dir(k)
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {}{} | {} | {} | {} | {} | {} |",
            eng(r.p0),
            eng(r.a_r),
            r.a_r_std_error
                .map_or(String::new(), |e| format!(" ± {}", eng(e))),
            eng(r.a_r_persson_scan),
            eng(r.a_r_persson_band),
            eng(r.a_r_persson_whole),
            eng(r.a_r_persson_whole_corrected),
            eng(r.whole_over_band)
        );
    }
    if let (Some(lo), Some(hi)) = (rows.first(), rows.last()) {
        let _ = writeln!(
            s,
            "\nThe scales this scan does not resolve remove {} of Persson's contact area \
             on its band at the lowest load, {} at the highest.\n",
            percent(1.0 - lo.whole_over_band),
            percent(1.0 - hi.whole_over_band)
        );
    }
}

fn whole(s: &mut String, c: &ScalesCheck) {
    let _ = writeln!(
        s,
        "## Persson on the whole surface\n\n| p0 / E* | a_r Persson | corrected |\n|---|---|---|"
    );
    for p in &c.whole {
        let _ = writeln!(
            s,
            "| {} | {} | {} |",
            eng(p.p0),
            eng(p.a_r_persson),
            eng(p.a_r_persson_corrected)
        );
    }
    s.push('\n');
}
