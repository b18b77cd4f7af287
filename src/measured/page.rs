//! The check's outputs: `surface.json` (the [`SurfaceCheck`] as it is), `surface.md` (a
//! page for people) and its figures under `figures/`: the power spectrum, the
//! contact-area curve, the pressure distribution and the elastic energy, each beside
//! Persson's original and corrected predictions. Every file is written atomically.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::check::{CurvePoint, Mean, SurfaceCheck, RULE, SOLVER_AGREEMENT};
use super::psd::Boundary;
use crate::error::Result;
use crate::plot::{Axis, Figure, Series, Style};
use crate::validation::Verdict;

/// Writes `surface.json`, `surface.md` and the figures into `dir`; returns the files.
pub fn write(check: &SurfaceCheck, dir: &Path) -> Result<Vec<PathBuf>> {
    let json = serde_json::to_vec_pretty(check).expect("checks serialise");
    let json_path = dir.join("surface.json");
    crate::io::write_atomic(&json_path, &json)?;
    let mut files = vec![json_path];
    let figures_dir = dir.join("figures");
    for figure in figures(check) {
        files.extend(crate::plot::render(&figure, &figures_dir)?);
    }
    let md_path = dir.join("surface.md");
    crate::io::write_atomic(&md_path, markdown(check).as_bytes())?;
    files.push(md_path);
    Ok(files)
}

/// `value ± error`, or the value and "(one scan: no error bar)".
fn mean_text(m: &Mean, digits: usize) -> String {
    match m.std_error {
        Some(e) => format!("{:.*} ± {:.*}", digits, m.value, digits, e),
        None => format!("{:.*} (one scan: no error bar)", digits, m.value),
    }
}

/// The page.
pub fn markdown(c: &SurfaceCheck) -> String {
    let mut s = String::new();
    let scans = c.scans.len();
    let _ = writeln!(s, "# Persson's theory on a measured surface\n");
    let _ = writeln!(
        s,
        "{} of {} x {} points, pixel size {} (heights in the same unit), {} boundary; \
         pressures in units of the contact modulus E*. Persson's theory is evaluated on \
         each scan's own spectrum. Solved with {}{}, residual tolerance {:e}.\n",
        if scans == 1 {
            "One scan".to_string()
        } else {
            format!("{scans} scans (realizations of one surface)")
        },
        c.n,
        c.n,
        c.pixel_size,
        match c.boundary {
            Boundary::Periodic => "periodic",
            Boundary::Free => "free (non-periodic)",
        },
        c.solver.name().to_uppercase(),
        c.cross_check.map_or(String::new(), |k| format!(
            ", cross-checked with {}",
            k.name().to_uppercase()
        )),
        c.tol
    );
    verdicts(&mut s, c);
    surface(&mut s, c);
    curve(&mut s, c);
    distribution(&mut s, c);
    energy(&mut s, c);
    solvers(&mut s, c);
    let _ = writeln!(
        s,
        "## Files\n\n`surface.json` holds every number of this page; the figures are in \
         `figures/` as SVG and PNG. Scans: {}.",
        c.scans
            .iter()
            .map(|p| format!("`{p}`"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    s
}

fn verdicts(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(
        s,
        "## Verdicts\n\nEach comparison is the ratio of the simulation to Persson's \
         original theory, scan by scan; its mean over the scans decides: **violated** when \
         it differs from 1 by more than {} standard errors, **holds** when the interval of \
         {} standard errors lies within 1 ± {}, **inconclusive** otherwise (always so with \
         one scan, which has no error bar). Over the loads: violated when any load is, \
         holds when all hold.\n",
        RULE.significance, RULE.significance, RULE.resolution
    );
    let _ = writeln!(s, "| comparison | statistic | verdict |\n|---|---|---|");
    for k in &c.comparisons {
        let _ = writeln!(s, "| {} | {} | {} |", k.name, k.statistic, k.verdict);
    }
    s.push('\n');
}

fn surface(s: &mut String, c: &SurfaceCheck) {
    let st = &c.statistics;
    let _ = writeln!(
        s,
        "## The surface\n\n| statistic | value |\n|---|---|\n| rms height | {} |\n| rms \
         slope (finite differences) | {} |\n| rms slope from the spectrum (Persson's g) | {} \
         |\n\nSpectrum: {}.\n\n![power spectrum](figures/psd.png)\n",
        mean_text(&st.h_rms, 4),
        mean_text(&st.slope_rms, 4),
        mean_text(&st.slope_rms_spectral, 4),
        c.spectrum_method
    );
}

/// A load curve's table on the page: what it shows and where the numbers come from.
struct CurveTable {
    /// Section heading and the text under it.
    heading: &'static str,
    note: &'static str,
    /// The quantity's symbol in the column heads.
    symbol: &'static str,
    /// Numbers in scientific notation (else fixed).
    scientific: bool,
    /// [value, error, cross-check, Persson, corrected] of a point.
    pick: fn(&CurvePoint) -> [Option<f64>; 5],
    /// The ratio to Persson and its verdict.
    ratio: fn(&CurvePoint) -> (&Mean, Verdict),
    /// The figure's file stem and caption.
    figure: (&'static str, &'static str),
}

fn curve_table(s: &mut String, c: &SurfaceCheck, t: &CurveTable) {
    let num = |v: f64| {
        if t.scientific {
            format!("{v:.5e}")
        } else {
            format!("{v:.5}")
        }
    };
    let _ = writeln!(
        s,
        "## {}\n\n{}| p0 / E* | {sym} ({}) | {sym} ({}) | Persson | Persson, corrected \
         | {sym} / Persson | verdict |\n|---|---|---|---|---|---|---|",
        t.heading,
        t.note,
        c.solver.name(),
        c.cross_check.map_or("—", |k| k.name()),
        sym = t.symbol,
    );
    for p in &c.curve {
        let [value, error, cross, persson, corrected] = (t.pick)(p);
        let (ratio, verdict) = (t.ratio)(p);
        let _ = writeln!(
            s,
            "| {:.4e} | {}{} | {} | {} | {} | {} | {} |",
            p.p0,
            value.map_or_else(|| "—".into(), num),
            error.map_or(String::new(), |e| format!(" ± {}", num(e))),
            cross.map_or_else(|| "—".into(), num),
            persson.map_or_else(|| "—".into(), num),
            corrected.map_or_else(|| "—".into(), num),
            mean_text(ratio, 3),
            verdict
        );
    }
    let _ = writeln!(s, "\n![{}](figures/{}.png)\n", t.figure.1, t.figure.0);
}

/// The contact area's [value, error, cross-check, Persson, corrected].
fn area_of(p: &CurvePoint) -> [Option<f64>; 5] {
    [
        Some(p.a_r),
        p.a_r_std_error,
        p.a_r_cross_check,
        Some(p.a_r_persson),
        Some(p.a_r_persson_corrected),
    ]
}

/// The elastic energy's [value, error, cross-check, Persson, corrected].
fn energy_of(p: &CurvePoint) -> [Option<f64>; 5] {
    [
        Some(p.energy),
        p.energy_std_error,
        p.energy_cross_check,
        Some(p.energy_persson),
        Some(p.energy_persson_corrected),
    ]
}

fn curve(s: &mut String, c: &SurfaceCheck) {
    curve_table(
        s,
        c,
        &CurveTable {
            heading: "Contact area",
            note: "",
            symbol: "a_r",
            scientific: false,
            pick: area_of,
            ratio: |p| (&p.area_ratio, p.area_verdict),
            figure: ("contact_area", "contact area"),
        },
    );
}

fn distribution(s: &mut String, c: &SurfaceCheck) {
    let d = &c.pressure_distribution;
    let _ = writeln!(
        s,
        "## Pressure distribution\n\nAt p0 = {:.4e} E*: the rms pressure over Persson's is \
         {} ({}). The histogram counts every point of the window, so that it integrates to \
         the contact area, as Persson's Pr(p) does (the delta function at p = 0 left \
         out).\n\n![pressure distribution](figures/pressure_distribution.png)\n",
        d.p0,
        mean_text(&d.rms_ratio, 3),
        d.verdict
    );
}

fn energy(s: &mut String, c: &SurfaceCheck) {
    curve_table(
        s,
        c,
        &CurveTable {
            heading: "Elastic energy",
            note: match c.boundary {
                Boundary::Periodic => {
                    "Per unit area, in E* times the length unit (the energy of the \
                     pressure's fluctuation p - p0).\n\n"
                }
                Boundary::Free => {
                    "Per unit area, in E* times the length unit (free boundary: the work of \
                     the contact pressure on the half-space beyond that of a flat punch of \
                     the window's shape at the same load, which a finite window needs and \
                     an infinite surface has not).\n\n"
                }
            },
            symbol: "E_el",
            scientific: true,
            pick: energy_of,
            ratio: |p| (&p.energy_ratio, p.energy_verdict),
            figure: ("elastic_energy", "elastic energy"),
        },
    );
}

fn solvers(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(
        s,
        "## Solvers\n\n| solver | iterations | largest residual | wall time |\n|---|---|---|---|"
    );
    for w in &c.solvers {
        let _ = writeln!(
            s,
            "| {} | {} | {:.2e} | {:.1} s |",
            w.solver.name(),
            w.iterations,
            w.max_residual,
            w.wall_s
        );
    }
    if let Some(agree) = c.solvers_agree {
        let _ = writeln!(
            s,
            "\nThe two solvers {} (contact area and energy within {}% at every load and \
             scan).",
            if agree { "agree" } else { "DISAGREE" },
            100.0 * SOLVER_AGREEMENT
        );
    }
    s.push('\n');
}

/// A load curve's series: the cross-check's points when there are any, joined by a line
/// and drawn first (so that both stay visible where they agree), the headline solver's points with
/// their error bars over scans, and Persson's two predictions; `pick` reads a point's
/// [value, error, cross-check, Persson, corrected].
fn curve_series(c: &SurfaceCheck, pick: fn(&CurvePoint) -> [Option<f64>; 5]) -> Vec<Series> {
    let line = |k: usize| -> Vec<(f64, f64)> {
        c.curve
            .iter()
            .filter_map(|p| Some((p.p0, pick(p)[k]?)))
            .collect()
    };
    let mut series = Vec::new();
    let cross = line(2);
    if let (Some(k), false) = (c.cross_check, cross.is_empty()) {
        series.push(Series::xy(
            format!("cross-check ({})", k.name()),
            Style::LinePoints,
            cross,
        ));
    }
    series.push(Series::with_errors(
        format!("simulation ({})", c.solver.name()),
        Style::Points,
        c.curve.iter().map(|p| {
            let v = pick(p);
            (p.p0, v[0].unwrap_or(f64::NAN), v[1].unwrap_or(f64::NAN))
        }),
    ));
    series.push(Series::xy("Persson", Style::Line, line(3)));
    series.push(Series::xy("Persson, corrected", Style::Dashed, line(4)));
    series
}

/// The page's figures.
pub fn figures(c: &SurfaceCheck) -> Vec<Figure> {
    let area = curve_series(c, area_of);
    let energy = curve_series(c, energy_of);
    let d = &c.pressure_distribution;
    let col = |k: usize| -> Vec<(f64, f64)> { d.bins.iter().map(|b| (b[0], b[k])).collect() };
    vec![
        Figure {
            name: "psd".into(),
            title: "Radially averaged power spectrum".into(),
            x: Axis::log("q (1 / length unit)"),
            y: Axis::log("C(q) (length unit^4)"),
            y2: None,
            series: vec![Series::xy(
                "C(q)",
                Style::LinePoints,
                c.statistics.psd.iter().map(|b| (b.q, b.c)),
            )],
        },
        Figure {
            name: "contact_area".into(),
            title: "Relative contact area against the load".into(),
            x: Axis::log("p0 / E*"),
            y: Axis::log("a_r"),
            y2: None,
            series: area,
        },
        Figure {
            name: "pressure_distribution".into(),
            title: format!("Pressure distribution at p0 = {:.3e} E*", d.p0),
            x: Axis::linear("p / p0"),
            y: Axis::linear("Pr(p / p0)"),
            y2: None,
            series: vec![
                Series::xy(
                    format!("simulation ({})", c.solver.name()),
                    Style::LinePoints,
                    col(1),
                ),
                Series::xy("Persson", Style::Line, col(2)),
                Series::xy("Persson, corrected", Style::Dashed, col(3)),
            ],
        },
        Figure {
            name: "elastic_energy".into(),
            title: "Elastic energy per unit area against the load".into(),
            x: Axis::log("p0 / E*"),
            y: Axis::log("E_el (E* length unit)"),
            y2: None,
            series: energy,
        },
    ]
}
