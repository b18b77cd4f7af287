//! The findings of an experiment as data: what a conclusion is judged by ([`Criteria`]),
//! secondary statistics ([`Detail`]), implementation guards ([`Guard`], never part of a
//! verdict), tables written as CSV ([`Table`])
//! and the [`Conclusion`] that holds them with the headline, figures and studies.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::keys::DetailKey;
use super::study::Study;
use crate::error::{Error, Result};
use crate::plot::{Axis, Figure, Raster, Waterfall};
use crate::stats::{Decision, Estimate};

/// What a conclusion is judged by: the validation's name, its verdict rule's significance
/// and resolution, the paper's value of the headline statistic, and the paper's values of
/// its claims by key (data from the definition, never typed into code).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Criteria {
    /// The validation's name (the stem of its first table).
    pub name: String,
    /// Significance `z`, in standard errors.
    pub significance: f64,
    /// Smallest deviation from Persson's prediction that matters.
    pub resolution: f64,
    /// The paper's value of the headline statistic, if it states one.
    pub paper_value: Option<f64>,
    /// The paper's value of each claim that states one, by the claim's key.
    pub paper: BTreeMap<String, f64>,
}

impl Criteria {
    /// The paper's value of the claim `key`, if the definition states one.
    pub fn paper(&self, key: &str) -> Option<f64> {
        self.paper.get(key).copied()
    }
}

/// A secondary statistic, shown in the validation's section of the scorecard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Detail {
    /// Stable identifier (tests and the report use it, never the label).
    #[serde(default)]
    pub key: DetailKey,
    /// Label, in words.
    pub name: String,
    /// Measurement.
    pub value: Estimate,
    /// Persson's value, if any.
    pub persson: Option<f64>,
    /// The paper's value, if any.
    pub paper: Option<f64>,
    /// Points per side of the grid the value was measured on, when the detail is one step
    /// of a resolution study (one key, measured on several grids).
    #[serde(default)]
    pub grid: Option<usize>,
}

impl Detail {
    /// A detail with key `key` and label `name`, without Persson's or the paper's value.
    pub fn new(key: impl Into<DetailKey>, name: impl Into<String>, value: Estimate) -> Self {
        Self {
            key: key.into(),
            name: name.into(),
            value,
            persson: None,
            paper: None,
            grid: None,
        }
    }

    /// With Persson's value.
    pub fn persson(mut self, v: f64) -> Self {
        self.persson = Some(v);
        self
    }

    /// With the paper's value (if any).
    pub fn paper(mut self, v: Option<f64>) -> Self {
        self.paper = v;
        self
    }

    /// Measured on a grid of `n` points per side.
    pub fn on_grid(mut self, n: usize) -> Self {
        self.grid = Some(n);
        self
    }
}

/// An implementation guard: a law the run must satisfy whatever the physics (a
/// conservation law, a counting identity), shown beside the outcome and never part of a
/// verdict. The paper's statements are judged once, by their claims
/// ([`crate::validation::claims`]), never again here.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Guard {
    /// Stable identifier.
    #[serde(default)]
    pub key: String,
    /// What is checked, in words.
    pub name: String,
    /// Whether it passed (false when not decided).
    pub passed: bool,
    /// The numbers behind it.
    pub detail: String,
    /// Whether the data decide it: false for a guard that needs an error bar when there
    /// is one realization.
    #[serde(default = "decided_default", skip_serializing_if = "is_decided")]
    pub decided: bool,
}

fn decided_default() -> bool {
    true
}

fn is_decided(decided: &bool) -> bool {
    *decided
}

impl Guard {
    /// A guard decided by `decision`, from the one rule of [`crate::stats::decide`]:
    /// passed, failed, or not decided, which the detail says first.
    pub fn new(
        key: impl Into<String>,
        name: impl Into<String>,
        decision: Decision,
        detail: impl Into<String>,
    ) -> Self {
        let detail = detail.into();
        Self {
            key: key.into(),
            name: name.into(),
            passed: decision.passed(),
            decided: decision.is_decided(),
            detail: if decision.is_decided() {
                detail
            } else {
                format!("{UNDECIDED}: {detail}")
            },
        }
    }
}

/// What the detail of a guard the data do not decide starts with.
pub const UNDECIDED: &str = "not decided with 1 realization (no error bar)";

/// A table of numbers, written as CSV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Table {
    /// File stem.
    pub name: String,
    /// Column names.
    pub columns: Vec<String>,
    /// Rows (one value per column).
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table with `columns`.
    pub fn new(name: impl Into<String>, columns: &[&str]) -> Self {
        Self {
            name: name.into(),
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<f64>) {
        assert_eq!(
            row.len(),
            self.columns.len(),
            "a row has one value per column"
        );
        self.rows.push(row);
    }

    /// Writes the table as CSV to `path`, atomically.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let mut w = csv::Writer::from_writer(Vec::new());
        let to_io = |e: csv::Error| Error::io(path, std::io::Error::other(e));
        w.write_record(&self.columns).map_err(to_io)?;
        for row in &self.rows {
            w.write_record(row.iter().map(|&v| cell(v)))
                .map_err(to_io)?;
        }
        let bytes = w
            .into_inner()
            .map_err(|e| Error::io(path, std::io::Error::other(e.to_string())))?;
        crate::io::write_atomic(path, &bytes)
    }
}

/// A CSV cell: the number, or nothing where there is none (NaN: no error bar from one
/// realization, no walkers in a bin).
fn cell(v: f64) -> String {
    if v.is_nan() {
        String::new()
    } else {
        format!("{v}")
    }
}

/// What an experiment concludes from its jobs.
#[derive(Debug, Clone, Default)]
pub struct Conclusion {
    /// The headline statistic.
    pub measured: Option<Estimate>,
    /// Persson's prediction of the headline statistic.
    pub persson: f64,
    /// Secondary statistics.
    pub details: Vec<Detail>,
    /// Implementation guards: never part of a verdict.
    pub guards: Vec<Guard>,
    /// A short account, generated from the numbers (no wall times: it must not depend on
    /// the machine).
    pub account: String,
    /// Values kept as golden snapshots (rounded by the experiment).
    pub golden: BTreeMap<String, f64>,
    /// Tables; the first is written as `<name>.csv`.
    pub tables: Vec<Table>,
    /// Figures.
    pub figures: Vec<Figure>,
    /// Raster images (contact maps).
    pub rasters: Vec<Raster>,
    /// Largest solver residual over all solves.
    pub max_residual: f64,
    /// Studies: tables of rows beside the headline, with their notes.
    pub studies: Vec<Study>,
    /// Waterfalls of cross sections.
    pub waterfalls: Vec<Waterfall>,
}

impl Conclusion {
    /// A conclusion with the headline `measured`, Persson's value of it and the largest
    /// residual of the solves; the rest is added by the experiment.
    pub fn new(measured: Estimate, persson: f64, max_residual: f64) -> Self {
        Self {
            measured: Some(measured),
            persson,
            max_residual,
            ..Default::default()
        }
    }

    /// The detail with key `key`, if any.
    pub fn detail(&self, key: impl Into<DetailKey>) -> Option<&Detail> {
        let key = key.into();
        self.details.iter().find(|d| d.key == key)
    }

    /// The guard with key `key`, if any.
    pub fn guard(&self, key: &str) -> Option<&Guard> {
        self.guards.iter().find(|c| c.key == key)
    }
}

/// A figure with its axes and no series yet (no right axis).
pub fn figure(name: &str, title: impl Into<String>, x: Axis, y: Axis) -> Figure {
    Figure {
        name: name.into(),
        title: title.into(),
        x,
        y,
        y2: None,
        series: Vec::new(),
    }
}
