//! The scorecard's table (one row per validation), and the cells it shares with the
//! sections.

use std::fmt::Write as _;

use super::format::{duration, md, num, or_dash, pm, table};
use super::golden::GoldenMatch;
use super::outcomes::{grid_cell, seeds_cell};
use super::{anchor, reproduced_cell, verdict_cell, Scorecard};
use crate::validation::{Outcome, Scale};

/// The columns of the scorecard's table.
const COLUMNS: [&str; 14] = [
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
];

impl Scorecard<'_> {
    pub(super) fn table(&self, s: &mut String) {
        let _ = writeln!(s, "## Scorecard\n");
        let rows: Vec<Vec<String>> = self
            .loaded
            .iter()
            .zip(self.golden)
            .map(|(l, g)| table_row(&l.outcome, g))
            .collect();
        s.push_str(&table(&COLUMNS, &rows));
        let _ = writeln!(
            s,
            "\nVerdict rule (per validation: significance z, resolution r): **violated** when \
             |measured − Persson| > z · error; **holds** when the whole interval measured ± \
             z · error lies within Persson ± r; **inconclusive** otherwise. \"Reproduced\" \
             requires the paper's verdict, the paper's range (overlapped by measured ± z · \
             error), every check of the paper's finding and every claim that is evidence \
             (consistency checks and statements the paper makes two ways take no part); \
             \"contradicted\" when the verdict is conclusive and any of them fails; \"not \
             established\" otherwise (the verdict inconclusive, or a check or claim the data \
             do not decide: the claims named not established). \"Grid\" lists points \
             per side (all refinements); \"solver residual\" is the largest residual of all \
             solves.\n"
        );
    }
}

/// One validation's row, in the order of [`COLUMNS`].
fn table_row(o: &Outcome, g: &GoldenMatch) -> Vec<String> {
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
        format!("{} ({})", or_dash(o.paper_value, num), o.paper_verdict),
        verdict_cell(o.verdict),
        reproduced_cell(o),
        md(&g.cell()),
        grid_cell(&o.scene),
        seeds_cell(&o.scene),
        duration(o.wall_s),
        num(o.max_residual),
    ]
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

/// Each other solver's value of the headline statistic and whether it agrees with the
/// headline's, one after the other.
pub(super) fn cross_check_cell(o: &Outcome) -> String {
    if o.cross_checks.is_empty() {
        return "not run".into();
    }
    let cells: Vec<String> = o
        .cross_checks
        .iter()
        .map(|c| {
            format!(
                "{} {}, {}",
                c.solver.to_uppercase(),
                headline(c.value, c.std_error),
                if c.agrees { "agrees" } else { "**DISAGREES**" }
            )
        })
        .collect();
    cells.join("; ")
}
