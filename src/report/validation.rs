//! The section of each validation: what it tests and what it found, its account, its
//! studies with their notes, the secondary statistics, the checks of the paper's
//! finding, its figures and tables, and the scene as run.

use std::fmt::Write as _;
use std::path::PathBuf;

use super::format::{duration, json, md, num, or_dash, pm, prose, push_rows, push_table, sig};
use super::golden::GoldenMatch;
use super::outcomes::{grid_cell, seeds_cell, Loaded};
use super::table::headline;
use super::{anchor, reproduced_cell, verdict_cell, Scorecard};
use crate::validation::{Guard, Outcome};

impl Scorecard<'_> {
    pub(super) fn validation(&self, s: &mut String, l: &Loaded, g: &GoldenMatch) {
        let o = &l.outcome;
        let _ = writeln!(s, "<a id=\"{}\"></a>\n", anchor(&o.name));
        let _ = writeln!(s, "## {}: {}\n", md(&o.name), md(&o.title));
        push_table(s, &["", ""], &facts(o, g));
        account(s, o);
        pending(s, o);
        super::study::studies(s, &o.studies);
        details(s, o);
        guards(s, o);
        self.files(s, o);
        scene(s, o);
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
        self.figures(s, &figures);
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

    /// Each figure shown as its PNG, with a link to its SVG where there is one.
    fn figures(&self, s: &mut String, pngs: &[PathBuf]) {
        if pngs.is_empty() {
            return;
        }
        let _ = writeln!(s, "**Figures**\n");
        for png in pngs {
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
}

/// The section's opening table: the assumption, the predictions, the measurement, the
/// verdict, the golden values and the run.
fn facts(o: &Outcome, g: &GoldenMatch) -> Vec<Vec<String>> {
    let fact = |name: &str, text: String| vec![name.to_string(), text];
    vec![
        fact("Assumption", md(&o.assumption)),
        fact("Statistic", md(&o.statistic)),
        fact(
            "Persson predicts",
            format!("{} (value {})", md(&o.persson_text), num(o.persson)),
        ),
        fact(
            "The paper finds",
            format!(
                "{} (value {}; the paper's verdict: {})",
                md(&o.paper),
                o.paper_value.map_or_else(|| "not stated".into(), num),
                o.paper_verdict
            ),
        ),
        fact(
            "Measured",
            format!("{} ({} scene)", headline(o.value, o.std_error), o.scale),
        ),
        fact(
            "Verdict",
            format!(
                "{} (z = {}, resolution {})",
                verdict_cell(o.verdict),
                sig(o.rule.significance, 3),
                sig(o.rule.resolution, 3)
            ),
        ),
        fact("The paper's finding reproduced", reproduced_cell(o)),
        fact("Golden values", md(&golden_text(g))),
        fact(
            "Run",
            format!(
                "grid {}, seeds {}, {} threads, {}, largest solver residual {}",
                grid_cell(&o.scene),
                seeds_cell(&o.scene),
                o.threads,
                duration(o.wall_s),
                num(o.max_residual)
            ),
        ),
    ]
}

/// How the golden values compare with the snapshot, in words.
fn golden_text(g: &GoldenMatch) -> String {
    match g {
        GoldenMatch::Yes(k, path) => format!("yes: {k} values match {}", path.display()),
        GoldenMatch::Differ(d, path) => format!(
            "**no**: {} differ from {}: {}",
            d.len(),
            path.display(),
            d.join("; ")
        ),
        GoldenMatch::FullScene => "n/a: full scenes have no snapshot".into(),
        GoldenMatch::NotChecked(why) => format!("not checked ({why})"),
    }
}

/// The account generated from the numbers.
fn account(s: &mut String, o: &Outcome) {
    if !o.account.trim().is_empty() {
        let _ = writeln!(s, "{}\n", prose(o.account.trim()));
    }
}

/// The optional parts of the scene a merge left out until their jobs are in.
fn pending(s: &mut String, o: &Outcome) {
    let Some(merge) = &o.merge else { return };
    if merge.pending.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "**Pending**: parts of the scene left out of this merge until all their jobs have \
         results; the claims that read them say so.\n"
    );
    let header = ["part", "jobs with results", "the plan's cost of the rest"];
    push_rows(s, &header, &merge.pending, |p| {
        vec![
            md(&p.name),
            format!("{} of {}", p.done, p.jobs),
            format!("{:.1} core-hours", p.core_hours_left),
        ]
    });
}

/// The secondary statistics with Persson's and the paper's values.
fn details(s: &mut String, o: &Outcome) {
    if o.details.is_empty() {
        return;
    }
    let _ = writeln!(s, "**Secondary statistics**\n");
    let header = ["statistic", "measured ± error", "Persson", "paper", "grid"];
    push_rows(s, &header, &o.details, |d| {
        vec![
            prose(&d.name),
            pm(d.value.value, d.value.std_error),
            or_dash(d.persson, num),
            or_dash(o.paper_value_of(d), num),
            or_dash(d.grid, |n| n.to_string()),
        ]
    });
}

/// The implementation guards and the numbers behind each (never part of a verdict).
fn guards(s: &mut String, o: &Outcome) {
    if o.guards.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "**Implementation guards** (laws every run satisfies whatever the physics; never part \
         of a verdict)\n"
    );
    push_rows(s, &["guard", "result", "numbers"], &o.guards, |c| {
        vec![prose(&c.name), guard_result(c).into(), prose(&c.detail)]
    });
}

fn guard_result(c: &Guard) -> &'static str {
    if !c.decided {
        "not decided (1 realization)"
    } else if c.passed {
        "passed"
    } else {
        "**FAILED**"
    }
}

/// The scene as run, folded.
fn scene(s: &mut String, o: &Outcome) {
    let scene = json(&o.scene);
    let _ = writeln!(
        s,
        "<details><summary>Scene as run</summary>\n\n```json\n{scene}\n```\n\n</details>\n"
    );
}
