//! The measure a claim names ([`Measure`]): where in a run its number is. A definition
//! writes it as text, parsed once when the definition loads:
//!
//! * `headline`: the validation's statistic;
//! * `detail:KEY`, or `detail:KEY@N` for the detail measured on the `N x N` grid of a
//!   resolution study; the key is typed ([`DetailKey`]: a stem and the values that pick
//!   one member of a family, as the load in `share_ar0.14`), so that a value written
//!   otherwise (`share_ar0.140`) names the same detail;
//! * `study:STUDY/ROW/COLUMN`: a cell of a [`crate::experiments::study::Study`];
//! * `cross_check:SOLVER`: another solver's headline.
//!
//! A form that is none of these, a grid that is not a count, or a solver that does not
//! exist is refused at load; the text a measure prints ([`std::fmt::Display`]) is its
//! canonical form, the text it was read from when that writes each value as Rust prints
//! it (as every shipped definition does), so the register's hashes and the outcomes'
//! records are unchanged.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::engine::solver::SolverKind;
use crate::experiments::DetailKey;

/// The forms a measure takes, as error messages list them.
pub const FORMS: &str = "headline, detail:KEY[@N], study:STUDY/ROW/COLUMN or cross_check:SOLVER";

/// Where a claim's number is.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Measure {
    /// The validation's statistic.
    Headline,
    /// A detail of the run, on the `grid x grid` grid where it names one.
    Detail {
        /// The detail's key.
        key: DetailKey,
        /// Points per side of the grid, for a step of a resolution study.
        grid: Option<usize>,
    },
    /// A cell of a study.
    Study {
        /// The study's key.
        study: String,
        /// The row's key.
        row: String,
        /// The column's key.
        column: String,
    },
    /// Another solver's headline.
    CrossCheck(SolverKind),
}

impl Measure {
    /// The detail `key` on no particular grid.
    pub fn detail(key: impl Into<DetailKey>) -> Self {
        Measure::Detail {
            key: key.into(),
            grid: None,
        }
    }

    /// The measure with what picks one row or grid left out: `detail:KEY` for a detail,
    /// `study:STUDY` for a study (an optional part of a scene gives whole details and
    /// studies); `None` for the headline and a cross-check.
    pub fn family(&self) -> Option<String> {
        match self {
            Measure::Detail { key, .. } => Some(format!("detail:{key}")),
            Measure::Study { study, .. } => Some(format!("study:{study}")),
            Measure::Headline | Measure::CrossCheck(_) => None,
        }
    }
}

impl FromStr for Measure {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let refused = |why: &str| format!("measure {text:?}: {why}; a measure is one of {FORMS}");
        let (kind, rest) = text.split_once(':').unwrap_or((text, ""));
        match kind {
            "headline" if rest.is_empty() => Ok(Measure::Headline),
            "detail" if !rest.is_empty() => match rest.split_once('@') {
                None => Ok(Measure::detail(rest)),
                Some((key, grid)) => match grid.parse::<usize>() {
                    Ok(n) if !key.is_empty() && n > 0 => Ok(Measure::Detail {
                        key: key.into(),
                        grid: Some(n),
                    }),
                    _ => Err(refused("a grid size >= 1 after '@' in detail:KEY@N")),
                },
            },
            "study" => {
                let parts: Vec<&str> = rest.splitn(3, '/').collect();
                match parts[..] {
                    [s, r, c] if !s.is_empty() && !r.is_empty() && !c.is_empty() => {
                        Ok(Measure::Study {
                            study: s.into(),
                            row: r.into(),
                            column: c.into(),
                        })
                    }
                    _ => Err(refused(
                        "a study, a row and a column in study:STUDY/ROW/COLUMN",
                    )),
                }
            }
            "cross_check" => SolverKind::from_name(rest)
                .map(Measure::CrossCheck)
                .ok_or_else(|| {
                    refused(&format!(
                        "the cross-check of a solver, {}",
                        SolverKind::listed()
                    ))
                }),
            _ => Err(refused("not a form of measure")),
        }
    }
}

impl TryFrom<String> for Measure {
    type Error = String;

    fn try_from(text: String) -> Result<Self, String> {
        text.parse()
    }
}

impl From<Measure> for String {
    fn from(m: Measure) -> String {
        m.to_string()
    }
}

impl fmt::Display for Measure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Measure::Headline => write!(f, "headline"),
            Measure::Detail { key, grid: None } => write!(f, "detail:{key}"),
            Measure::Detail { key, grid: Some(n) } => write!(f, "detail:{key}@{n}"),
            Measure::Study { study, row, column } => write!(f, "study:{study}/{row}/{column}"),
            Measure::CrossCheck(s) => write!(f, "cross_check:{}", s.name()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_reads_back_as_written() {
        for text in [
            "headline",
            "detail:share_ar0.14",
            "detail:kappa_on_grid@512",
            "study:asymptote_law/mode/k1",
            "study:one_percent_readings/H0.5_a0.01_z63_w0.01/non_contact",
            "cross_check:cg",
        ] {
            let m: Measure = text.parse().unwrap();
            assert_eq!(m.to_string(), text);
            let json = serde_json::to_string(&m).unwrap();
            assert_eq!(json, format!("\"{text}\""));
            assert_eq!(serde_json::from_str::<Measure>(&json).unwrap(), m);
        }
        assert_eq!(
            "detail:k@64".parse::<Measure>().unwrap(),
            Measure::Detail {
                key: "k".into(),
                grid: Some(64)
            }
        );
    }

    #[test]
    fn a_malformed_measure_is_refused_with_the_forms() {
        for (text, why) in [
            ("headlines", "not a form"),
            ("headline:x", "not a form"),
            ("detail:", "not a form"),
            ("detail:k@", "grid size"),
            ("detail:k@0", "grid size"),
            ("detail:k@n", "grid size"),
            ("study:a/b", "a row and a column"),
            ("study:a//c", "a row and a column"),
            ("cross_check:lbfgs", "gfmd"),
            ("", "not a form"),
        ] {
            let e = text.parse::<Measure>().unwrap_err();
            assert!(e.contains(why) && e.contains(FORMS), "{text}: {e}");
        }
    }

    #[test]
    fn a_family_leaves_out_the_row_and_the_grid() {
        let m: Measure = "detail:k@64".parse().unwrap();
        assert_eq!(m.family().as_deref(), Some("detail:k"));
        let m: Measure = "study:s/r/c".parse().unwrap();
        assert_eq!(m.family().as_deref(), Some("study:s"));
        assert_eq!(Measure::Headline.family(), None);
    }
}
