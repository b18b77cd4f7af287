//! The description of a waterfall of cross sections (the paper's figure
//! "reentry_waterfall"): one cut through the same contact at several magnifications, one
//! panel each, top to bottom.

use serde::{Deserialize, Serialize};

/// One cut: the elastic body's surface above, the rough body's below, along the cut.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CutPanel {
    /// Label (the magnification).
    pub label: String,
    /// The elastic body's lower surface (its displacement), one value per point of the cut.
    pub upper: Vec<f64>,
    /// The rough body's upper surface (the heights), one value per point.
    pub lower: Vec<f64>,
    /// Points to mark (re-entered contact), one flag per point.
    pub marked: Vec<bool>,
}

/// A stack of cuts, each drawn with the elastic body on top (filled above `upper`), the
/// rough body below (filled below `lower`) and the gap white; marked points in red.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Waterfall {
    /// File stem (the renderer writes `<name>.svg` and `<name>.png`).
    pub name: String,
    /// Title.
    pub title: String,
    /// Label of the horizontal axis (position along the cut).
    pub x_label: String,
    /// Label of the vertical axes (height).
    pub y_label: String,
    /// Legend of the marks.
    pub mark_label: String,
    /// The panels, top to bottom, all of the same length.
    pub panels: Vec<CutPanel>,
}
