//! The check's outputs: `surface.json` (the [`SurfaceCheck`] as it is), `surface.md` (a
//! page for people) and its figures under `figures/` ([`super::figures`]): the power
//! spectrum, the contact-area curve, the pressure distribution and the elastic energy,
//! each beside Persson's original and corrected predictions. Every file is written
//! atomically.
//!
//! Numbers are written with three significant digits in engineering notation
//! ([`super::units::eng`]), lengths with their unit, pressures in units of `E*` and, with
//! a modulus, in pascals. In every figure a series keeps its colour: the headline
//! simulation first, then Persson's original and corrected theory, then the cross-check.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::check::{
    CurvePoint, SurfaceCheck, CROSS_CHECK_MIN_S, CROSS_CHECK_TIME, RULE, SOLVER_AGREEMENT,
};
use super::fill::{Fill, MAX_FILLED_SHARE};
use super::psd::Boundary;
use super::spikes::SPIKE_RMS;
use super::units::{eng, length, percent, SQUARE_PIXEL_TOLERANCE};
use super::warnings::{CONTACT_PRESSURE, LIMITS};
use crate::error::Result;

pub use super::figures::figures;
use super::figures::{area_of, energy_of, energy_unit, unit};
use crate::stats::Estimate;
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
fn mean_text(m: &Estimate) -> String {
    if m.has_error() {
        format!("{} ± {}", eng(m.value), eng(m.std_error))
    } else {
        format!("{} (one scan: no error bar)", eng(m.value))
    }
}

/// The page.
pub fn markdown(c: &SurfaceCheck) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Persson's theory on a measured surface\n");
    header(&mut s, c);
    missing(&mut s, c);
    warnings(&mut s, c);
    spikes(&mut s, c);
    failures(&mut s, c);
    verdicts(&mut s, c);
    surface(&mut s, c);
    super::resolved::cutoff(&mut s, c);
    curve(&mut s, c);
    super::resolved::pixel_error(&mut s, c);
    distribution(&mut s, c);
    energy(&mut s, c);
    reentry(&mut s, c);
    solvers(&mut s, c);
    let _ = writeln!(
        s,
        "## Files\n\n`surface.json` holds every number of this page; `solves.jsonl` one line \
         per solve, written as each ended; the figures are in `figures/` as SVG and PNG. \
         Scans: {}.",
        c.scans
            .iter()
            .map(|p| format!("`{p}`"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    s
}

fn header(s: &mut String, c: &SurfaceCheck) {
    let scans = c.scans.len();
    let [a, b] = c.pixel_sides;
    let pixel = if a == b {
        format!("pixel size {}", length(c.pixel_size, c.unit.as_deref()))
    } else {
        format!(
            "pixel size {} (the geometric mean of the sides given, {} x {}, which differ by \
             less than the {}% taken as square)",
            length(c.pixel_size, c.unit.as_deref()),
            eng(a),
            eng(b),
            100.0 * SQUARE_PIXEL_TOLERANCE
        )
    };
    let pressures = match c.modulus {
        Some(e) => format!(
            "pressures in units of the contact modulus E* and in pascals with E* = {} Pa",
            eng(e)
        ),
        None => "pressures in units of the contact modulus E*".to_string(),
    };
    let _ = writeln!(
        s,
        "{} of {} x {} points (rows x columns), {pixel}, heights and lengths in {}, {} \
         boundary; {pressures}. Persson's theory is evaluated on each scan's own spectrum. \
         Solved with {}{}, residual tolerance {}.\n",
        if scans == 1 {
            "One scan".to_string()
        } else {
            format!("{scans} scans (realizations of one surface)")
        },
        c.rows,
        c.cols,
        unit(c),
        match c.boundary {
            Boundary::Periodic => "periodic",
            Boundary::Free => "free (non-periodic)",
        },
        c.solver.name().to_uppercase(),
        c.cross_check.map_or(String::new(), |k| format!(
            ", cross-checked with {}",
            k.name().to_uppercase()
        )),
        eng(c.tol)
    );
}

fn missing(s: &mut String, c: &SurfaceCheck) {
    let points = c.rows * c.cols;
    let filled: Vec<String> = c
        .scans
        .iter()
        .zip(&c.filled)
        .filter(|(_, &k)| k > 0)
        .map(|(name, &k)| {
            format!(
                "`{name}`: {k} of {points} points ({})",
                percent(k as f64 / points as f64)
            )
        })
        .collect();
    if filled.is_empty() {
        let _ = writeln!(s, "Every point of every scan was measured.\n");
    } else {
        let _ = writeln!(
            s,
            "**Undefined points filled** by harmonic interpolation from their neighbours \
             (the discrete Laplace equation solved on them, the measured points fixed; at \
             most {}% of a scan is filled): {}.\n",
            100.0 * MAX_FILLED_SHARE,
            filled.join("; ")
        );
    }
    debug_assert!(c.fill == Fill::Interpolate || filled.is_empty());
}

fn warnings(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(s, "## Warnings\n");
    if c.warnings.is_empty() {
        let _ = writeln!(s, "None: no threshold below is crossed.\n");
    } else {
        for w in &c.warnings {
            let _ = writeln!(s, "- **{}**: {}.", w.name, w.message);
        }
        s.push('\n');
    }
    let thresholds: Vec<String> = LIMITS
        .iter()
        .map(|l| format!("{} {} (`{}`)", l.statistic, l.condition(), l.name))
        .collect();
    let _ = writeln!(s, "Thresholds: {}.\n", thresholds.join("; "));
}

/// The scans' spikes and outliers, and at each load the share of the contact points on
/// them: a contact carried by spikes is the spikes' tips, not the surface's.
fn spikes(s: &mut String, c: &SurfaceCheck) {
    if c.outliers.iter().all(|o| o.count == 0 && o.despiked == 0) {
        return;
    }
    let _ = writeln!(
        s,
        "## Spikes and outliers\n\nFound before the solves: points farther than {} rms \
         heights from the mean height (none is expected of Gaussian heights). {}\n",
        SPIKE_RMS,
        match c.despike {
            Some(k) => format!(
                "Despiking was asked: points farther than {k} robust deviations from the \
                 median of their eight neighbours were replaced by harmonic interpolation \
                 before the check."
            ),
            None => "Despiking (off by default) would replace them before the check.".into(),
        }
    );
    for (scan, o) in c.scans.iter().zip(&c.outliers) {
        let _ = writeln!(s, "- `{scan}`: {}.", o.summary());
        let carried: Vec<String> = c
            .loads
            .iter()
            .zip(&o.contact_share)
            .filter_map(|(p0, share)| {
                share
                    .filter(|&x| x > 0.0)
                    .map(|x| format!("{} of the contact at p0 = {} E*", percent(x), eng(*p0)))
            })
            .collect();
        if o.count > 0 {
            let _ = writeln!(
                s,
                "  Contact points on them: {}.",
                if carried.is_empty() {
                    "none at any load solved".to_string()
                } else {
                    carried.join("; ")
                }
            );
        }
    }
    s.push('\n');
}

fn failures(s: &mut String, c: &SurfaceCheck) {
    if c.failures.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "## Solves that failed\n\nThe curve keeps the loads that every scan's {} solve \
         reached. Every solve has a budget of {} iterations; a cross-check solve also gets \
         {} times the headline solve's time at its load (at least {} s).\n",
        c.solver.name(),
        c.max_iterations,
        CROSS_CHECK_TIME,
        CROSS_CHECK_MIN_S
    );
    for f in &c.failures {
        let _ = writeln!(
            s,
            "- `{}`, {} ({}): {}",
            f.scan,
            f.solver.name(),
            if f.headline {
                "headline"
            } else {
                "cross-check"
            },
            f.message
        );
    }
    s.push('\n');
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
    let u = unit(c);
    let _ = writeln!(
        s,
        "## The surface\n\n| statistic | value |\n|---|---|\n| rms height ({u}) | {} |\n| \
         rms slope (finite differences) | {} |\n| rms slope from the spectrum (Persson's \
         g) | {} |\n| skewness of the heights | {} |\n| excess kurtosis of the heights | {} \
         |\n| spectral isotropy sqrt(l_min / l_max) | {} |\n| log-log slope of C(q), highest \
         octave | {} |\n\nSpectrum: {}.\n\n![power spectrum](figures/psd.png)\n",
        mean_text(&st.h_rms),
        mean_text(&st.slope_rms),
        mean_text(&st.slope_rms_spectral),
        mean_text(&st.skewness),
        mean_text(&st.kurtosis),
        mean_text(&st.anisotropy),
        st.high_q_slope
            .map_or("— (too few bins)".to_string(), |m| mean_text(&m)),
        c.spectrum_method
    );
}

/// A load curve's table on the page: what it shows and where the numbers come from.
struct CurveTable {
    /// Section heading and the text under it.
    heading: &'static str,
    note: String,
    /// The quantity's symbol and unit in the column heads.
    symbol: String,
    /// The factor from the JSON's numbers to the table's.
    factor: f64,
    /// [value, error, cross-check, Persson, corrected] of a point.
    pick: fn(&CurvePoint) -> [Option<f64>; 5],
    /// The ratio to Persson and its verdict.
    ratio: fn(&CurvePoint) -> (&Estimate, Verdict),
    /// The figure's file stem and caption.
    figure: (&'static str, &'static str),
}

fn curve_table(s: &mut String, c: &SurfaceCheck, t: &CurveTable) {
    let num = |v: Option<f64>| v.map_or_else(|| "—".into(), |v| eng(t.factor * v));
    let sym = &t.symbol;
    let pa = c.modulus.is_some();
    let mut head = vec!["p0 / E*".to_string()];
    if pa {
        head.push("p0 (Pa)".into());
    }
    head.push(format!("{sym}, {}", c.solver.name()));
    if let Some(k) = c.cross_check {
        head.push(format!("{sym}, {}", k.name()));
    }
    head.extend([
        "Persson".to_string(),
        "Persson, corrected".into(),
        "ratio to Persson".into(),
        "verdict".into(),
    ]);
    let _ = writeln!(
        s,
        "## {}\n\n{}| {} |\n|{}",
        t.heading,
        t.note,
        head.join(" | "),
        "---|".repeat(head.len())
    );
    let mut marked = false;
    for p in &c.curve {
        let [value, error, cross, persson, corrected] = (t.pick)(p);
        let (ratio, verdict) = (t.ratio)(p);
        let mut row = vec![format!(
            "{}{}",
            eng(p.p0),
            if p.past_yield { " ‡" } else { "" }
        )];
        marked |= p.past_yield;
        if pa {
            row.push(p.p0_pa.map_or("—".into(), eng));
        }
        row.push(format!(
            "{}{}",
            num(value),
            error.map_or(String::new(), |e| format!(" ± {}", num(Some(e))))
        ));
        if c.cross_check.is_some() {
            row.push(num(cross));
        }
        row.extend([
            num(persson),
            num(corrected),
            mean_text(ratio),
            verdict.to_string(),
        ]);
        let _ = writeln!(s, "| {} |", row.join(" | "));
    }
    if marked {
        let _ = writeln!(
            s,
            "\n‡ far past the yield of any material: the mean pressure in contact p0 / a_r \
             is {} E*.",
            CONTACT_PRESSURE.condition()
        );
    }
    let _ = writeln!(s, "\n![{}](figures/{}.png)\n", t.figure.1, t.figure.0);
}
fn curve(s: &mut String, c: &SurfaceCheck) {
    curve_table(
        s,
        c,
        &CurveTable {
            heading: "Contact area",
            note: if c.curve.iter().any(|p| p.pixel.is_some()) {
                "The ratio to Persson sets the theory against the contact area extrapolated \
                 to a vanishing pixel (next section).\n\n"
                    .into()
            } else {
                String::new()
            },
            symbol: "a_r".into(),
            factor: 1.0,
            pick: area_of,
            ratio: |p| (&p.area_ratio, p.area_verdict),
            figure: ("contact_area", "contact area"),
        },
    );
}

fn distribution(s: &mut String, c: &SurfaceCheck) {
    let Some(d) = &c.pressure_distribution else {
        let _ = writeln!(
            s,
            "## Pressure distribution\n\nNo load was solved: no distribution.\n"
        );
        return;
    };
    let _ = writeln!(
        s,
        "## Pressure distribution\n\nAt p0 = {} E*{}: the rms pressure over Persson's is \
         {} ({}). The histogram counts every point of the window, so that it integrates to \
         the contact area, as Persson's Pr(p) does (the delta function at p = 0 left \
         out).\n\n![pressure distribution](figures/pressure_distribution.png)\n",
        eng(d.p0),
        c.modulus
            .map_or(String::new(), |e| format!(" ({} Pa)", eng(d.p0 * e))),
        mean_text(&d.rms_ratio),
        d.verdict
    );
}

fn energy(s: &mut String, c: &SurfaceCheck) {
    let (energy_unit, factor) = energy_unit(c);
    let what = match c.boundary {
        Boundary::Periodic => "the energy of the pressure's fluctuation p - p0",
        Boundary::Free => {
            "free boundary: the work of the contact pressure on the half-space beyond that \
             of a flat punch of the window's shape at the same load, which a finite window \
             needs and an infinite surface has not"
        }
    };
    curve_table(
        s,
        c,
        &CurveTable {
            heading: "Elastic energy",
            note: format!("Per unit area, in {energy_unit} ({what}).\n\n"),
            symbol: format!("E_el ({energy_unit})"),
            factor,
            pick: energy_of,
            ratio: |p| (&p.energy_ratio, p.energy_verdict),
            figure: ("elastic_energy", "elastic energy"),
        },
    );
}

fn reentry(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(s, "## Re-entry over magnification\n");
    let Some(r) = &c.reentry else {
        let _ = writeln!(s, "Not measured (no load solved, or not asked for).\n");
        return;
    };
    let _ = writeln!(
        s,
        "The first scan's spectrum truncated at zeta_max = {} (lambda_s = L / {}, L the \
         longer side: four points of the sweep's {} x {} grid), every one of its {} shells \
         added one at a time at p0 = {} E*, each solve warm-started from the last, as the \
         c_reentry validation sweeps its surfaces: of the {} points in contact at zeta_max \
         (a_r = {}), **{}** had been out of contact at a lower magnification (Persson's \
         theory: 0); {} left contact after the first shell and came back. {} solver \
         iterations, {} s.{}\n",
        r.zeta_max,
        r.zeta_max,
        r.grid[0],
        r.grid[1],
        r.shells,
        eng(r.p0),
        r.contact_points,
        eng(r.a_r),
        eng(r.share),
        eng(r.share_after_first),
        r.iterations,
        eng(r.wall_s),
        r.failed
            .as_ref()
            .map_or(String::new(), |m| format!(" The sweep stopped early: {m}."))
    );
}

fn solvers(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(
        s,
        "## Solvers\n\n| solver | iterations | largest residual | failed solves | wall time (s) \
         |\n|---|---|---|---|---|"
    );
    for w in &c.solvers {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            w.solver.name(),
            w.iterations,
            eng(w.max_residual),
            w.failed,
            eng(w.wall_s)
        );
    }
    if let Some(agree) = c.solvers_agree {
        let _ = writeln!(
            s,
            "\nThe two solvers {} (contact area and energy within {}% at every load and \
             scan both solved).",
            if agree { "agree" } else { "DISAGREE" },
            100.0 * SOLVER_AGREEMENT
        );
    }
    s.push('\n');
}
