//! A study of an outcome ([`crate::experiments::study`]) as the scorecard shows it: its
//! title and description, one table row per study row (estimates with their error bars,
//! percentages where the column says so), then the notes drawn from the rows.

use std::fmt::Write as _;

use super::format::{md, pm, prose, push_rows, sig};
use crate::experiments::study::{Cell, Column, Study};

/// Every study of an outcome, in order.
pub fn studies(s: &mut String, studies: &[Study]) {
    for study in studies {
        section(s, study);
    }
}

/// One study: title, description, table, notes.
fn section(s: &mut String, study: &Study) {
    let _ = write!(s, "**{}**", md(&study.title));
    if !study.about.is_empty() {
        let _ = write!(s, " ({})", prose(&study.about));
    }
    let _ = writeln!(s, "\n");
    let mut header: Vec<&str> = vec![""];
    header.extend(study.columns.iter().map(|c| c.label.as_str()));
    push_rows(s, &header, &study.rows, |r| {
        let mut row = vec![md(&r.label)];
        row.extend(study.columns.iter().zip(&r.cells).map(|(c, v)| cell(c, v)));
        row
    });
    for note in &study.notes {
        let _ = writeln!(s, "{}\n", prose(note));
    }
}

/// A cell as text: `value ± error`, scaled to % where the column is a percentage.
pub fn cell(column: &Column, cell: &Cell) -> String {
    let scale = if column.percent { 100.0 } else { 1.0 };
    match *cell {
        Cell::Estimate(e) => pm(scale * e.value, scale * e.std_error),
        Cell::Number(v) => sig(scale * v, 4),
        Cell::Empty => "—".into(),
    }
}
