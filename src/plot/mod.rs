//! Figures: what to draw ([`Figure`], [`Raster`], [`Waterfall`]) apart from how it is drawn ([`render`]).
//!
//! Experiments describe their figures as data; the runner renders each to SVG and PNG.
//! Keeping the description plain data lets tests check a figure's content without pixels.

mod intervals;
mod render;
mod waterfall;

pub use intervals::{IntervalChart, IntervalRow};
pub use render::{render, render_intervals, render_raster, render_waterfall, significant};
pub use waterfall::{CutPanel, Waterfall};

use serde::{Deserialize, Serialize};

/// An axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Axis {
    /// Label, with units.
    pub label: String,
    /// Logarithmic scale.
    pub log: bool,
    /// Fixed range (default: fitted to the data).
    pub range: Option<(f64, f64)>,
}

impl Axis {
    /// A linear axis.
    pub fn linear(label: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            log: false,
            range: None,
        }
    }

    /// A logarithmic axis.
    pub fn log(label: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            log: true,
            range: None,
        }
    }

    /// The same axis with a fixed range.
    pub fn with_range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Style {
    /// Solid line.
    Line,
    /// Dashed line.
    Dashed,
    /// Markers (with error bars where points carry errors).
    Points,
    /// Markers joined by a line.
    LinePoints,
}

/// Which vertical axis a series belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Side {
    /// The left axis.
    #[default]
    Left,
    /// The right (secondary) axis.
    Right,
}

/// A data point, optionally with a symmetric error bar in `y`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate.
    pub y: f64,
    /// Standard error of `y`.
    pub err: Option<f64>,
}

/// A labelled series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Drawing style.
    pub style: Style,
    /// Axis.
    pub side: Side,
    /// Points (non-finite points are skipped when drawing).
    pub points: Vec<Point>,
}

impl Series {
    /// A series from `(x, y)` pairs.
    pub fn xy(
        label: impl Into<String>,
        style: Style,
        xy: impl IntoIterator<Item = (f64, f64)>,
    ) -> Self {
        Self {
            label: label.into(),
            style,
            side: Side::Left,
            points: xy
                .into_iter()
                .map(|(x, y)| Point { x, y, err: None })
                .collect(),
        }
    }

    /// A series from `(x, y, err)` triples.
    pub fn with_errors(
        label: impl Into<String>,
        style: Style,
        xye: impl IntoIterator<Item = (f64, f64, f64)>,
    ) -> Self {
        Self {
            label: label.into(),
            style,
            side: Side::Left,
            points: xye
                .into_iter()
                .map(|(x, y, e)| Point { x, y, err: Some(e) })
                .collect(),
        }
    }

    /// The same series on the right axis.
    pub fn on_right(mut self) -> Self {
        self.side = Side::Right;
        self
    }
}

/// A chart: series against one horizontal and one or two vertical axes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Figure {
    /// File stem (the renderer writes `<name>.svg` and `<name>.png`).
    pub name: String,
    /// Title.
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Left vertical axis.
    pub y: Axis,
    /// Right vertical axis, for series with [`Side::Right`].
    pub y2: Option<Axis>,
    /// The series.
    pub series: Vec<Series>,
}

/// An image: one colour per grid point (contact maps), with a legend.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Raster {
    /// File stem (the renderer writes `<name>.png`).
    pub name: String,
    /// Title.
    pub title: String,
    /// Pixels per side.
    pub n: usize,
    /// Row-major colour index per pixel, into `palette`.
    pub pixels: Vec<u8>,
    /// Colours and their legend labels.
    pub palette: Vec<([u8; 3], String)>,
}
