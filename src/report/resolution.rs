//! The statistics measured on several grids (the discretisation error): details with a
//! grid, grouped by their key, as a table and a figure.

use std::fmt::Write as _;
use std::path::PathBuf;

use super::format::{md, num, or_dash, pm, prose, push_table};
use super::outcomes::Loaded;
use super::Scorecard;
use crate::plot::{Axis, Figure, Series, Style};
use crate::validation::{Detail, DetailKey};

/// Secondary statistics of one validation measured on several grids.
#[derive(Debug, Clone)]
pub(super) struct Resolution {
    pub(super) validation: String,
    /// Groups of details with one key (one statistic, several grids), by key, each sorted
    /// by grid.
    pub(super) groups: Vec<(DetailKey, Vec<(usize, Detail)>)>,
    pub(super) figure: Option<PathBuf>,
}

/// Details with a grid, grouped by their key (one statistic measured on several grids).
pub(super) fn resolution_studies(loaded: &[Loaded]) -> Vec<Resolution> {
    let mut out = Vec::new();
    for l in loaded {
        let mut groups: Vec<(DetailKey, Vec<(usize, Detail)>)> = Vec::new();
        for d in &l.outcome.details {
            let Some(n) = d.grid else { continue };
            // The paper's value beside it: its claim's, read from the outcome.
            let d = Detail {
                paper: l.outcome.paper_value_of(d),
                ..d.clone()
            };
            match groups.iter_mut().find(|(k, _)| *k == d.key) {
                Some((_, rows)) => rows.push((n, d)),
                None => groups.push((d.key.clone(), vec![(n, d)])),
            }
        }
        for (_, rows) in &mut groups {
            rows.sort_by_key(|(n, _)| *n);
        }
        if !groups.is_empty() {
            out.push(Resolution {
                validation: l.outcome.name.clone(),
                groups,
                figure: None,
            });
        }
    }
    out
}

pub(super) fn resolution_figure(r: &Resolution) -> Figure {
    let mut fig = Figure {
        name: format!("resolution_{}", r.validation),
        title: format!("{}: statistics measured on several grids", r.validation),
        x: Axis::log("points per side N"),
        y: Axis::linear("measured value"),
        y2: None,
        series: Vec::new(),
    };
    let single = r.groups.len() == 1;
    for (key, rows) in &r.groups {
        fig.series.push(Series::with_errors(
            format!("measured: {key}"),
            Style::LinePoints,
            rows.iter()
                .map(|(n, d)| (*n as f64, d.value.value, d.value.std_error)),
        ));
        let (lo, hi) = (rows[0].0 as f64, rows[rows.len() - 1].0 as f64);
        let common = |f: fn(&Detail) -> Option<f64>| -> Option<f64> {
            let first = f(&rows[0].1)?;
            rows.iter()
                .all(|(_, d)| f(d) == Some(first))
                .then_some(first)
        };
        let label = |who: &str| {
            if single {
                who.to_string()
            } else {
                format!("{who}: {key}")
            }
        };
        if let Some(p) = common(|d| d.persson) {
            fig.series.push(Series::xy(
                label("Persson"),
                Style::Dashed,
                [(lo, p), (hi, p)],
            ));
        }
        if let Some(p) = common(|d| d.paper) {
            fig.series
                .push(Series::xy(label("paper"), Style::Line, [(lo, p), (hi, p)]));
        }
    }
    fig
}

impl Scorecard<'_> {
    pub(super) fn resolution_section(&self, s: &mut String) {
        let _ = writeln!(s, "## Statistic against grid resolution\n");
        if self.resolution.is_empty() {
            let _ = writeln!(
                s,
                "No validation reports a statistic on more than one grid, so the \
                 discretisation error is not shown.\n"
            );
            return;
        }
        let _ = writeln!(
            s,
            "Secondary statistics measured on several grids (same realizations, all lengths \
             scaled with the grid): the change from one grid to the next is the \
             discretisation error the headline values carry or extrapolate away.\n"
        );
        let mut rows = Vec::new();
        for r in self.resolution {
            for (_, group) in &r.groups {
                let mut prev: Option<f64> = None;
                for (n, d) in group {
                    rows.push(vec![
                        md(&r.validation),
                        prose(&d.name),
                        n.to_string(),
                        pm(d.value.value, d.value.std_error),
                        or_dash(prev, |p| num(d.value.value - p)),
                        or_dash(d.persson, num),
                        or_dash(d.paper, num),
                    ]);
                    prev = Some(d.value.value);
                }
            }
        }
        let header = [
            "validation",
            "statistic",
            "grid",
            "measured ± error",
            "change from the previous grid",
            "Persson",
            "paper",
        ];
        push_table(s, &header, &rows);
        for r in self.resolution {
            if let Some(png) = &r.figure {
                let _ = writeln!(
                    s,
                    "![{} against grid resolution]({})\n",
                    md(&r.validation),
                    self.link_to(png)
                );
            }
        }
    }
}
