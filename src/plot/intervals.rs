//! The description of an interval chart (a forest plot): one row per estimate, each a
//! marker with its interval, all on one axis where a region of interest lies to the right
//! of 0 (the scorecard's claims against their rules, in units of each rule's tolerance).

use serde::{Deserialize, Serialize};

/// One row: a marker at `value` with the interval `value +- half`, in its group.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IntervalRow {
    /// The group the row belongs to (drawn as a heading above its rows).
    pub group: String,
    /// The row's label.
    pub label: String,
    /// Position on the axis.
    pub value: f64,
    /// Half width of the interval (0 for none).
    pub half: f64,
    /// Index of the row's kind into [`IntervalChart::kinds`] (its colour and legend).
    pub kind: usize,
}

/// Rows of intervals on one horizontal axis, grouped, with the region `x > 0` shaded:
/// a row whose interval lies right of 0 lies inside, left of 0 outside, across 0 neither.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IntervalChart {
    /// File stem (the renderer writes `<name>.svg` and `<name>.png`).
    pub name: String,
    /// Title.
    pub title: String,
    /// Label of the horizontal axis.
    pub x_label: String,
    /// The axis range drawn; markers beyond it are drawn at its end as an arrow.
    pub range: (f64, f64),
    /// The kinds of rows, each with its legend label (coloured in this order).
    pub kinds: Vec<String>,
    /// The rows, top to bottom (groups contiguous).
    pub rows: Vec<IntervalRow>,
}
