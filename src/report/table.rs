//! The scorecard's table (one row per validation) and the section of each validation.

use std::fmt::Write as _;

use super::format::{duration, md, num, pm, prose, sig, table};
use super::golden::GoldenMatch;
use super::outcomes::{grid_cell, seeds_cell, Loaded};
use super::{anchor, reproduced_cell, verdict_cell, Scorecard};
use crate::validation::{Outcome, Scale};

impl Scorecard<'_> {
    pub(super) fn table(&self, s: &mut String) {
        let _ = writeln!(s, "## Scorecard\n");
        let rows: Vec<Vec<String>> = self
            .loaded
            .iter()
            .zip(self.golden)
            .map(|(l, g)| {
                let o = &l.outcome;
                let scale = if o.scale == Scale::Full {
                    " (full)"
                } else {
                    ""
                };
                vec![
                    format!("[{}](#{}){scale}", md(&o.name), anchor(&o.name)),
                    md(&o.assumption),
                    md(&o.statistic),
                    num(o.persson),
                    measured_cell(o),
                    cross_check_cell(o),
                    format!(
                        "{} ({})",
                        o.paper_value.map_or_else(|| "—".into(), num),
                        o.paper_verdict
                    ),
                    verdict_cell(o.verdict),
                    reproduced_cell(o.reproduced),
                    md(&g.cell()),
                    grid_cell(&o.scene),
                    seeds_cell(&o.scene),
                    duration(o.wall_s),
                    num(o.max_residual),
                ]
            })
            .collect();
        s.push_str(&table(
            &[
                "validation",
                "assumption",
                "statistic",
                "Persson",
                "measured ± error (solver)",
                "cross-check",
                "paper (verdict)",
                "verdict",
                "reproduced",
                "golden match",
                "grid",
                "seeds",
                "wall time",
                "solver residual",
            ],
            &rows,
        ));
        let _ = writeln!(
            s,
            "\nVerdict rule (per validation: significance z, resolution r): **violated** when \
             |measured − Persson| > z · error; **holds** when the whole interval measured ± \
             z · error lies within Persson ± r; **inconclusive** otherwise. \"Reproduced\" \
             requires the paper's verdict, the paper's range and every check of the paper's \
             finding; it is undecided when the verdict is inconclusive. \"Grid\" lists points \
             per side (all refinements); \"solver residual\" is the largest residual of all \
             solves.\n"
        );
    }

    pub(super) fn validation(&self, s: &mut String, l: &Loaded, g: &GoldenMatch) {
        let o = &l.outcome;
        let _ = writeln!(s, "<a id=\"{}\"></a>\n", anchor(&o.name));
        let _ = writeln!(s, "## {}: {}\n", md(&o.name), md(&o.title));
        let golden = match g {
            GoldenMatch::Yes(k, path) => format!("yes: {k} values match {}", path.display()),
            GoldenMatch::Differ(d, path) => {
                format!(
                    "**no**: {} differ from {}: {}",
                    d.len(),
                    path.display(),
                    d.join("; ")
                )
            }
            GoldenMatch::FullScene => "n/a: full scenes have no snapshot".into(),
            GoldenMatch::NotChecked(why) => format!("not checked ({why})"),
        };
        let rows = vec![
            vec!["Assumption".into(), md(&o.assumption)],
            vec!["Statistic".into(), md(&o.statistic)],
            vec![
                "Persson predicts".into(),
                format!("{} (value {})", md(&o.persson_text), num(o.persson)),
            ],
            vec![
                "The paper finds".into(),
                format!(
                    "{} (value {}; the paper's verdict: {})",
                    md(&o.paper),
                    o.paper_value.map_or_else(|| "not stated".into(), num),
                    o.paper_verdict
                ),
            ],
            vec![
                "Measured".into(),
                format!("{} ({} scene)", headline(o.value, o.std_error), o.scale),
            ],
            vec![
                "Verdict".into(),
                format!(
                    "{} (z = {}, resolution {})",
                    verdict_cell(o.verdict),
                    sig(o.rule.significance, 3),
                    sig(o.rule.resolution, 3)
                ),
            ],
            vec![
                "The paper's finding reproduced".into(),
                reproduced_cell(o.reproduced),
            ],
            vec!["Golden values".into(), md(&golden)],
            vec![
                "Run".into(),
                format!(
                    "grid {}, seeds {}, {} threads, {}, largest solver residual {}",
                    grid_cell(&o.scene),
                    seeds_cell(&o.scene),
                    o.threads,
                    duration(o.wall_s),
                    num(o.max_residual)
                ),
            ],
        ];
        s.push_str(&table(&["", ""], &rows));
        s.push('\n');
        if !o.account.trim().is_empty() {
            let _ = writeln!(s, "{}\n", prose(o.account.trim()));
        }
        for note in &o.notes {
            let _ = writeln!(s, "{}\n", prose(note));
        }
        if !o.sensitivity.is_empty() {
            let _ = writeln!(
                s,
                "**Sensitivity of the one-step flux** (one setting moved at a time; % of the \
                 nominal area A0 and of the true contact area Ac at zeta)\n"
            );
            let pct = |e: crate::stats::Estimate| pm(100.0 * e.value, 100.0 * e.std_error);
            let rows: Vec<Vec<String>> = o
                .sensitivity
                .iter()
                .map(|r| {
                    vec![
                        md(&r.parameter),
                        md(&r.label),
                        format!("{}x{}, {}", r.config.n, r.config.n, r.config.solver.name()),
                        pct(r.flux_in),
                        pct(r.flux_out),
                        pct(r.flux_in_of_contact),
                        pct(r.flux_out_of_contact),
                    ]
                })
                .collect();
            s.push_str(&table(
                &[
                    "setting",
                    "value",
                    "grid, solver",
                    "in, % A0",
                    "out, % A0",
                    "in, % Ac",
                    "out, % Ac",
                ],
                &rows,
            ));
            s.push('\n');
        }
        if !o.details.is_empty() {
            let _ = writeln!(s, "**Secondary statistics**\n");
            let rows: Vec<Vec<String>> = o
                .details
                .iter()
                .map(|d| {
                    vec![
                        prose(&d.name),
                        pm(d.value.value, d.value.std_error),
                        d.persson.map_or_else(|| "—".into(), num),
                        d.paper.map_or_else(|| "—".into(), num),
                        d.grid.map_or_else(|| "—".into(), |n| n.to_string()),
                    ]
                })
                .collect();
            s.push_str(&table(
                &["statistic", "measured ± error", "Persson", "paper", "grid"],
                &rows,
            ));
            s.push('\n');
        }
        if !o.checks.is_empty() {
            let _ = writeln!(s, "**Checks of the paper's finding**\n");
            let rows: Vec<Vec<String>> = o
                .checks
                .iter()
                .map(|c| {
                    vec![
                        prose(&c.name),
                        if !c.decided {
                            "not decided (1 realization)".into()
                        } else if c.passed {
                            "passed".into()
                        } else {
                            "**FAILED**".into()
                        },
                        prose(&c.detail),
                    ]
                })
                .collect();
            s.push_str(&table(&["check", "result", "numbers"], &rows));
            s.push('\n');
        }
        self.files(s, o);
        let scene = serde_json::to_string_pretty(&o.scene).unwrap_or_default();
        let _ = writeln!(
            s,
            "<details><summary>Scene as run</summary>\n\n```json\n{scene}\n```\n\n</details>\n"
        );
    }

    /// Figures (PNG shown, SVG linked) and tables of an outcome; missing files are named.
    fn files(&self, s: &mut String, o: &Outcome) {
        let from = &self.opts.from;
        let mut figures = Vec::new();
        let mut others = Vec::new();
        let mut missing = Vec::new();
        for f in &o.files {
            let path = from.join(f);
            if !path.exists() {
                missing.push(f.clone());
                continue;
            }
            match path.extension().and_then(|e| e.to_str()) {
                Some("png") => figures.push(path),
                Some("svg") if path.with_extension("png").exists() => {}
                _ => others.push(path),
            }
        }
        if !figures.is_empty() {
            let _ = writeln!(s, "**Figures**\n");
            for png in &figures {
                let stem = png
                    .file_stem()
                    .map(|x| x.to_string_lossy().to_string())
                    .unwrap_or_default();
                let svg = png.with_extension("svg");
                let svg_link = if svg.exists() {
                    format!(" ([SVG]({}))", self.link_to(&svg))
                } else {
                    String::new()
                };
                let _ = writeln!(s, "![{}]({}){svg_link}\n", md(&stem), self.link_to(png));
            }
        }
        if !others.is_empty() {
            let links: Vec<String> = others
                .iter()
                .map(|p| {
                    let label = p.strip_prefix(from).unwrap_or(p).display().to_string();
                    format!("[{}]({})", md(&label), self.link_to(p))
                })
                .collect();
            let _ = writeln!(s, "**Tables**: {}\n", links.join(", "));
        }
        if !missing.is_empty() {
            let _ = writeln!(
                s,
                "**Missing files** (listed in the outcome, not found in `{}`): {}\n",
                from.display(),
                missing.iter().map(|m| md(m)).collect::<Vec<_>>().join(", ")
            );
        }
    }
}

/// A headline statistic with its error bar, or the plain statement that it has none (one
/// realization).
pub(super) fn headline(value: f64, std_error: f64) -> String {
    if value.is_finite() && !std_error.is_finite() {
        format!("{} (one realization: no error bar)", num(value))
    } else {
        pm(value, std_error)
    }
}

/// The headline with its error bar and the solver that measured it.
pub(super) fn measured_cell(o: &Outcome) -> String {
    if o.solver.is_empty() {
        headline(o.value, o.std_error)
    } else {
        format!(
            "{} ({})",
            headline(o.value, o.std_error),
            o.solver.to_uppercase()
        )
    }
}

/// The other solver's value of the headline statistic and whether the two agree.
pub(super) fn cross_check_cell(o: &Outcome) -> String {
    match &o.cross_check {
        Some(c) => format!(
            "{} {}, {}",
            c.solver.to_uppercase(),
            headline(c.value, c.std_error),
            if c.agrees { "agrees" } else { "**DISAGREES**" }
        ),
        None => "not run".into(),
    }
}
