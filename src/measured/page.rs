//! The check's outputs: `surface.json` (the [`SurfaceCheck`] as it is), `surface.md` (a
//! page for people) and its figures under `figures/`: the power spectrum, the
//! contact-area curve, the pressure distribution and the elastic energy, each beside
//! Persson's original and corrected predictions. Every file is written atomically.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::check::{Mean, SurfaceCheck, RULE, SOLVER_AGREEMENT};
use super::psd::Boundary;
use crate::error::Result;
use crate::plot::{Axis, Figure, Series, Style};

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

fn optional(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "—".into(), |v| format!("{v:.digits$}"))
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

fn curve(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(
        s,
        "## Contact area\n\n| p0 / E* | a_r ({}) | a_r ({}) | Persson | Persson, corrected \
         | a_r / Persson | verdict |\n|---|---|---|---|---|---|---|",
        c.solver.name(),
        c.cross_check.map_or("—", |k| k.name())
    );
    for p in &c.curve {
        let _ = writeln!(
            s,
            "| {:.4e} | {:.5}{} | {} | {:.5} | {:.5} | {} | {} |",
            p.p0,
            p.a_r,
            p.a_r_std_error
                .map_or(String::new(), |e| format!(" ± {e:.5}")),
            optional(p.a_r_cross_check, 5),
            p.a_r_persson,
            p.a_r_persson_corrected,
            mean_text(&p.area_ratio, 3),
            p.area_verdict
        );
    }
    let _ = writeln!(s, "\n![contact area](figures/contact_area.png)\n");
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
    let _ = writeln!(
        s,
        "## Elastic energy\n\nPer unit area, in E* times the length unit{}.\n\n| p0 / E* | \
         E_el ({}) | E_el ({}) | Persson | Persson, corrected | E_el / Persson | verdict \
         |\n|---|---|---|---|---|---|---|",
        match c.boundary {
            Boundary::Periodic => " (the energy of the pressure's fluctuation p - p0)",
            Boundary::Free =>
                " (free boundary: the work of the contact pressure on the half-space beyond \
                 that of a flat punch of the window's shape at the same load, which a finite \
                 window needs and an infinite surface has not)",
        },
        c.solver.name(),
        c.cross_check.map_or("—", |k| k.name())
    );
    for p in &c.curve {
        let _ = writeln!(
            s,
            "| {:.4e} | {:.5e} | {} | {:.5e} | {:.5e} | {} | {} |",
            p.p0,
            p.energy,
            p.energy_cross_check
                .map_or_else(|| "—".into(), |e| format!("{e:.5e}")),
            p.energy_persson,
            p.energy_persson_corrected,
            mean_text(&p.energy_ratio, 3),
            p.energy_verdict
        );
    }
    let _ = writeln!(s, "\n![elastic energy](figures/elastic_energy.png)\n");
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

/// The page's figures.
pub fn figures(c: &SurfaceCheck) -> Vec<Figure> {
    let ps = |f: fn(&super::check::CurvePoint) -> f64| -> Vec<(f64, f64)> {
        c.curve.iter().map(|p| (p.p0, f(p))).collect()
    };
    let mut area = vec![
        Series::with_errors(
            format!("simulation ({})", c.solver.name()),
            Style::Points,
            c.curve
                .iter()
                .map(|p| (p.p0, p.a_r, p.a_r_std_error.unwrap_or(f64::NAN))),
        ),
        Series::xy("Persson", Style::Line, ps(|p| p.a_r_persson)),
        Series::xy(
            "Persson, corrected",
            Style::Dashed,
            ps(|p| p.a_r_persson_corrected),
        ),
    ];
    if let Some(k) = c.cross_check {
        let pts: Vec<(f64, f64)> = c
            .curve
            .iter()
            .filter_map(|p| Some((p.p0, p.a_r_cross_check?)))
            .collect();
        // Drawn first, so that the headline's markers stay visible on top of it.
        area.insert(
            0,
            Series::xy(format!("cross-check ({})", k.name()), Style::Points, pts),
        );
    }
    let energy = vec![
        Series::with_errors(
            format!("simulation ({})", c.solver.name()),
            Style::Points,
            c.curve
                .iter()
                .map(|p| (p.p0, p.energy, p.energy_std_error.unwrap_or(f64::NAN))),
        ),
        Series::xy("Persson", Style::Line, ps(|p| p.energy_persson)),
        Series::xy(
            "Persson, corrected",
            Style::Dashed,
            ps(|p| p.energy_persson_corrected),
        ),
    ];
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
