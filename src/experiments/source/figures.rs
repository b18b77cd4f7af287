//! The account, the table and the figure of the boundary source: every row, bin width and
//! denominator of the readings of [`super::study`].

use super::stats::{RowStats, SourceStats};
use super::study::{percent, shares, CLAIM, COLUMNS};
use crate::experiments::{figure, Criteria, Table};
use crate::plot::{Axis, Figure, Series, Style};

/// The account, from the numbers: the headline row, then the range over the rows.
pub fn account(runs: &str, criteria: &Criteria, s: &SourceStats) -> String {
    let first = &s.rows[0];
    let zero = first.readings[0];
    let entering = |r: &RowStats| r.readings[0].of_non_contact.value;
    let (lo, hi) = s.rows.iter().fold((&s.rows[0], &s.rows[0]), |(lo, hi), r| {
        (
            if entering(r) < entering(lo) { r } else { lo },
            if entering(r) > entering(hi) { r } else { hi },
        )
    });
    let widest = s
        .rows
        .iter()
        .flat_map(|r| r.readings.last())
        .fold(f64::NAN, |m: f64, r| m.max(r.of_bin.value));
    format!(
        "Over {runs} of each of {} scenes, at {} (a_r = {:.4} at zeta, load fixed) {} of \
         the non-contact at zeta enters contact in the step ({} of the contact, {} of A0), \
         {}. Over the scenes the share of the non-contact entering contact runs from {:.3}% \
         ({}) to {:.3}% ({}). With a zero bin of width up to {} p0/a_r, up to {:.2}% of the \
         bin's points lie above it after the step.{}",
        s.rows.len(),
        first.step.label(),
        first.contact_before.value,
        percent(zero.of_non_contact),
        percent(zero.of_contact),
        percent(zero.of_nominal),
        zero.of_non_contact
            .z_text(0.0, "Persson's absorbing boundary (none)"),
        100.0 * entering(lo),
        lo.step.label(),
        100.0 * entering(hi),
        hi.step.label(),
        first.readings.last().map_or(0.0, |r| r.width),
        100.0 * widest,
        criteria.paper(CLAIM).map_or(String::new(), |p| format!(
            " The paper states about {:.0}% (of all points previously in non-contact).",
            100.0 * p
        )),
    )
}

/// One row per scene row and bin width: the row, the width, `a_r` at zeta, and each share
/// with its standard error.
pub fn table(name: &str, s: &SourceStats) -> Table {
    let mut columns = vec![
        "hurst",
        "contact_area",
        "zeta",
        "dzeta",
        "bin_width",
        "a_r_before",
    ];
    let errors: Vec<String> = COLUMNS.iter().map(|c| format!("{}_se", c.0)).collect();
    for (c, e) in COLUMNS.iter().zip(&errors) {
        columns.push(c.0);
        columns.push(e);
    }
    let mut table = Table::new(name, &columns);
    for row in &s.rows {
        let st = &row.step;
        for r in &row.readings {
            let mut values = vec![
                st.hurst,
                st.contact_area,
                st.zeta,
                st.dzeta,
                r.width,
                row.contact_before.value,
            ];
            for e in shares(r) {
                values.extend([e.value, e.std_error]);
            }
            table.push(values);
        }
    }
    table
}

/// The share of the non-contact that lies above the bin after the step, against the bin's
/// width, one series per row, with the paper's value as a line.
pub fn non_contact_figure(criteria: &Criteria, s: &SourceStats) -> Figure {
    let mut fig = figure(
        "non_contact_share",
        "Points of the zero bin above it after one step, share of the non-contact at zeta",
        Axis::linear("bin width w (p0/a_r at zeta)"),
        Axis::log("share of the non-contact at zeta"),
    );
    for row in &s.rows {
        fig.series.push(Series::with_errors(
            row.step.label(),
            Style::LinePoints,
            row.readings
                .iter()
                .map(|r| (r.width, r.of_non_contact.value, r.of_non_contact.std_error)),
        ));
    }
    if let Some(p) = criteria.paper(CLAIM) {
        let widths = s.rows[0].readings.iter().map(|r| r.width);
        let (lo, hi) = (
            widths.clone().fold(f64::NAN, f64::min),
            widths.fold(f64::NAN, f64::max),
        );
        fig.series.push(Series::xy(
            "the paper's 'about 1%'",
            Style::Dashed,
            [(lo, p), (hi, p)],
        ));
    }
    fig
}
