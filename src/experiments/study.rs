//! Studies: tables of rows an experiment adds beside its headline (a sensitivity study, the
//! readings of a statement the paper leaves open, a resolution ladder), in one generic
//! shape that the outcome stores and the scorecard renders without knowing the experiment.
//!
//! A [`Study`] has stable keys for itself, its columns and its rows, so that a claim of the
//! paper can name one cell as its measure (`study:KEY/ROW/COLUMN`, see
//! [`crate::validation::claims`]) and two runs can be compared cell by cell. A cell is an
//! estimate with its error bar, a plain number, a text or empty ([`Cell`]). Notes are
//! statements drawn from the rows, written from their numbers.

use serde::{Deserialize, Serialize};

use crate::stats::Estimate;

/// One cell of a study's table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Cell {
    /// A value with its standard error (`{"value": .., "std_error": ..}`).
    Estimate(Estimate),
    /// A number without an error bar (a setting, a count, an exact value).
    Number(f64),
    /// Nothing measured here (`null`).
    Empty,
}

impl Cell {
    /// The cell as an estimate: a number is exact (zero error), an empty cell is none.
    pub fn estimate(&self) -> Option<Estimate> {
        match *self {
            Cell::Estimate(e) => Some(e),
            Cell::Number(v) if v.is_finite() => Some(Estimate::new(v, 0.0)),
            _ => None,
        }
    }
}

impl From<Estimate> for Cell {
    fn from(e: Estimate) -> Self {
        Cell::Estimate(e)
    }
}

impl From<f64> for Cell {
    fn from(v: f64) -> Self {
        if v.is_nan() {
            Cell::Empty
        } else {
            Cell::Number(v)
        }
    }
}

impl From<Option<Estimate>> for Cell {
    fn from(e: Option<Estimate>) -> Self {
        e.map_or(Cell::Empty, Cell::Estimate)
    }
}

/// A column: a stable key and a label with its unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Column {
    /// Stable identifier.
    pub key: String,
    /// Label, in words, with the unit.
    pub label: String,
    /// Whether its values are fractions shown as percentages.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub percent: bool,
}

/// A row: a stable key, a label in words, and one cell per column.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// Stable identifier.
    pub key: String,
    /// What the row is, in words.
    pub label: String,
    /// One cell per column of the study.
    pub cells: Vec<Cell>,
}

/// A table of rows beside an experiment's headline.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Study {
    /// Stable identifier.
    pub key: String,
    /// Title, in words.
    pub title: String,
    /// What the rows are and how they were measured.
    #[serde(default)]
    pub about: String,
    /// The columns.
    pub columns: Vec<Column>,
    /// The rows.
    pub rows: Vec<Row>,
    /// Statements drawn from the rows, written from their numbers.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

impl Study {
    /// A study with `columns` as `(key, label)` pairs and no rows yet.
    pub fn new(key: &str, title: impl Into<String>, columns: &[(&str, &str)]) -> Self {
        Self {
            key: key.into(),
            title: title.into(),
            about: String::new(),
            columns: columns
                .iter()
                .map(|&(key, label)| Column {
                    key: key.into(),
                    label: label.into(),
                    percent: false,
                })
                .collect(),
            rows: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// With a description of the rows.
    pub fn about(mut self, about: impl Into<String>) -> Self {
        self.about = about.into();
        self
    }

    /// With the columns `keys` shown as percentages.
    pub fn percent(mut self, keys: &[&str]) -> Self {
        for c in &mut self.columns {
            if keys.contains(&c.key.as_str()) {
                c.percent = true;
            }
        }
        self
    }

    /// Appends a row (one cell per column).
    pub fn push(&mut self, key: impl Into<String>, label: impl Into<String>, cells: Vec<Cell>) {
        let key = key.into();
        assert_eq!(
            cells.len(),
            self.columns.len(),
            "study {}: row {key} has one cell per column",
            self.key
        );
        self.rows.push(Row {
            key,
            label: label.into(),
            cells,
        });
    }

    /// The index of column `key`.
    pub fn column(&self, key: &str) -> Option<usize> {
        self.columns.iter().position(|c| c.key == key)
    }

    /// The row with key `key`.
    pub fn row(&self, key: &str) -> Option<&Row> {
        self.rows.iter().find(|r| r.key == key)
    }

    /// The cell of row `row` in column `column`.
    pub fn cell(&self, row: &str, column: &str) -> Option<Cell> {
        let c = self.column(column)?;
        self.row(row).map(|r| r.cells[c])
    }
}

/// The columns that say what a row ran (its grid, surface, first magnification, load,
/// tolerance and realizations), each key with its one label, so that every study showing
/// a setting names and labels it alike.
pub const SETTINGS: &[(&str, &str)] = &[
    ("n", "points per side"),
    ("hurst", "Hurst exponent"),
    ("lambda_l", "lambda_l (grid units)"),
    ("lambda_s", "lambda_s (grid units)"),
    ("zeta_from", "first magnification (0: the first shell)"),
    ("contact_area", "a_r at zeta_max"),
    ("tol", "residual tolerance"),
    ("realizations", "realizations"),
];

/// Columns as [`Study::new`] takes them: the settings `settings` (keys of [`SETTINGS`], in
/// the order given), then the study's `own`.
///
/// # Panics
///
/// If a key of `settings` is not one of [`SETTINGS`].
pub fn with_settings(
    settings: &[&str],
    own: &[(&'static str, &'static str)],
) -> Vec<(&'static str, &'static str)> {
    let setting = |key: &&str| {
        *SETTINGS
            .iter()
            .find(|(k, _)| k == key)
            .unwrap_or_else(|| panic!("{key} is not a setting of study::SETTINGS"))
    };
    settings
        .iter()
        .map(setting)
        .chain(own.iter().copied())
        .collect()
}

/// The study with key `key` among `studies`.
pub fn find<'a>(studies: &'a [Study], key: &str) -> Option<&'a Study> {
    studies.iter().find(|s| s.key == key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_round_trip_through_json_and_read_as_estimates() {
        let mut s = Study::new("grid", "Grid", &[("n", "points"), ("a_r", "a_r")]);
        s.push(
            "fine",
            "the fine grid",
            vec![1024.0.into(), Estimate::new(0.2, 0.01).into()],
        );
        s.push("none", "nothing", vec![f64::NAN.into(), None.into()]);
        let json = serde_json::to_string(&s).unwrap();
        let back: Study = serde_json::from_str(&json).unwrap();
        assert_eq!(back, s);
        assert_eq!(
            back.cell("fine", "a_r").unwrap().estimate(),
            Some(Estimate::new(0.2, 0.01))
        );
        assert_eq!(
            back.cell("fine", "n").unwrap().estimate(),
            Some(Estimate::new(1024.0, 0.0))
        );
        assert_eq!(back.cell("none", "n"), Some(Cell::Empty));
        assert_eq!(back.cell("none", "a_r").unwrap().estimate(), None);
        assert!(back.cell("fine", "b").is_none() && back.cell("x", "n").is_none());
    }

    #[test]
    fn settings_keep_their_labels_and_order_before_a_study_s_own_columns() {
        let c = with_settings(&["tol", "n"], &[("share", "re-entry share")]);
        assert_eq!(
            c,
            [
                ("tol", "residual tolerance"),
                ("n", "points per side"),
                ("share", "re-entry share")
            ]
        );
    }

    #[test]
    #[should_panic(expected = "not a setting")]
    fn an_unknown_setting_is_refused() {
        with_settings(&["grid"], &[]);
    }

    #[test]
    #[should_panic(expected = "one cell per column")]
    fn a_row_has_one_cell_per_column() {
        let mut s = Study::new("s", "S", &[("a", "a")]);
        s.push("r", "r", vec![]);
    }
}
