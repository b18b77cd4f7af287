//! What both transition validations show: the table of the bins, the transition
//! probabilities, the account of the runs, and the pressure axis of their figures.

use super::stats::{mean_of, BinRow};
use super::{TransitionResult, TransitionScene};
use crate::experiments::{figure, Table};
use crate::plot::{Axis, Figure, Series};
use crate::stats::Estimate;

/// Points `(x, y, standard error)` of a figure series.
pub type Points = Vec<(f64, f64, f64)>;

/// One row per analysed bin.
pub fn bin_table(rows: &[BinRow]) -> Table {
    let mut table = Table::new(
        "bins",
        &[
            "bin",
            "pressure",
            "walkers",
            "d_ratio",
            "d_ratio_se",
            "drift",
            "drift_se",
            "width",
            "lost_fraction",
            "suited",
        ],
    );
    for r in rows {
        table.push(vec![
            r.bin as f64,
            r.pressure,
            r.walkers,
            r.ratio.value,
            r.ratio.std_error,
            r.drift.value,
            r.drift.std_error,
            r.width,
            r.lost,
            if r.suited { 1.0 } else { 0.0 },
        ]);
    }
    table
}

/// `(pressure, value, standard error)` of the rows that pass `keep`.
pub fn bin_points(
    rows: &[BinRow],
    keep: impl Fn(&BinRow) -> bool,
    value: impl Fn(&BinRow) -> Estimate,
) -> Points {
    rows.iter()
        .filter(|r| keep(r))
        .map(|r| {
            let e = value(r);
            (r.pressure, e.value, e.std_error)
        })
        .collect()
}

/// The transition probabilities as a table: one row per (old bin, new bin) with counts
/// pooled over realizations and the probability per old bin.
pub fn transition_table(scene: &TransitionScene, results: &[(u64, TransitionResult)]) -> Table {
    let mut table = Table::new(
        "transitions",
        &[
            "old_bin",
            "old_pressure",
            "new_pressure",
            "count",
            "probability",
        ],
    );
    let size = scene.bins + 1;
    let axis = scene.pressure_bins(1.0);
    for row in 0..size {
        let counts: Vec<u64> = (0..size)
            .map(|col| {
                results
                    .iter()
                    .map(|(_, r)| r.histogram[row][col] as u64)
                    .sum()
            })
            .collect();
        let total: u64 = counts.iter().sum();
        if total == 0 {
            continue;
        }
        // Index 0 is out of contact, index b the pressure bin b - 1.
        let centre = |b: usize| if b == 0 { 0.0 } else { axis.centre(b - 1) };
        for (col, &c) in counts.iter().enumerate() {
            if c > 0 {
                table.push(vec![
                    row as f64 - 1.0,
                    centre(row),
                    centre(col),
                    c as f64,
                    c as f64 / total as f64,
                ]);
            }
        }
    }
    table
}

/// The first sentence of both accounts: the runs and the binning.
pub fn common_account(scene: &TransitionScene, results: &[(u64, TransitionResult)]) -> String {
    let a_old = mean_of(results, |r| r.a_r_old);
    let a_new = mean_of(results, |r| r.a_r_new);
    format!(
        "{} were solved at zeta = {} with a_r = {:.4} and again at zeta = {} (a_r = {:.4}); \
         walkers binned by pressure in bins of {} p0/a_r.",
        scene.base().runs(),
        scene.zeta,
        a_old.value,
        scene.zeta + scene.dzeta,
        a_new.value,
        scene.bin_width
    )
}

/// A figure of a quantity (axis label `y`) by pressure bin.
pub fn bin_figure(name: &str, title: &str, y: &str, series: Vec<Series>) -> Figure {
    let mut fig = figure(
        name,
        title,
        Axis::linear("pressure p / (p0 / a_r)"),
        Axis::linear(y),
    );
    fig.series = series;
    fig
}

/// A horizontal line at `y` across the pressure axis, to the last bin's upper edge.
pub fn level(scene: &TransitionScene, y: f64) -> [(f64, f64); 2] {
    let xmax = scene.pressure_bins(1.0).edge(scene.bins);
    [(0.0, y), (xmax, y)]
}
