//! What an outcome measures, read from the typed [`Outcome`]: every statistic with its
//! error bar, and every reading that can flip (a verdict, a check, a claim's result).
//!
//! One function lists the statistics ([`statistics`]) and one the readings ([`readings`]).
//! A part an outcome does not have gives no statistic; a number that is not known (NaN in
//! memory, `null` in the file) is `None`.
//!
//! | key | from |
//! |---|---|
//! | `headline` | `value`, `std_error` |
//! | `detail:KEY` (`detail:KEY@GRID` when `grid` is set) | `details[].value` |
//! | `cross_check:SOLVER` | each of `cross_checks` |
//! | `claim:KEY` | `claims[].measured` ([`ClaimOutcome`]) |
//! | `study:STUDY/ROW/COLUMN` | each estimate or number cell of `studies[].rows` ([`Cell`]) |
//!
//! Readings: `verdict`, `reproduced`, `check:KEY` (passed, failed, undecided),
//! `claim:KEY` (its [`ClaimResult`] as the file writes it: `reproduced`,
//! `not_reproduced`, ...), `cross_check:SOLVER` (agrees or disagrees).

use serde::Serialize;

use crate::experiments::study::Cell;
use crate::stats::Estimate;
use crate::validation::measures::Measure;
use crate::validation::Outcome;
#[cfg(doc)]
use crate::validation::{ClaimOutcome, ClaimResult};

/// A statistic of an outcome: a value and its standard error, either possibly unknown.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measured {
    /// The value (`None`: not measured, `null` in the file).
    pub value: Option<f64>,
    /// Its standard error (`None`: no error bar).
    pub std_error: Option<f64>,
}

impl Measured {
    /// A value and an error bar, NaN read as unknown.
    pub fn new(value: f64, std_error: f64) -> Self {
        let known = |x: f64| (!x.is_nan()).then_some(x);
        Self {
            value: known(value),
            std_error: known(std_error),
        }
    }

    /// Whether `self` and `other` are the same numbers bit for bit (both unknown counts as
    /// the same).
    pub fn identical(&self, other: &Measured) -> bool {
        let bits = |x: Option<f64>| x.map(f64::to_bits);
        bits(self.value) == bits(other.value) && bits(self.std_error) == bits(other.std_error)
    }
}

impl From<Estimate> for Measured {
    fn from(e: Estimate) -> Self {
        Self::new(e.value, e.std_error)
    }
}

/// A statistic with its key (see the module's table).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Statistic {
    /// Stable key, the same in every run of the outcome.
    pub key: String,
    /// Its value and error bar.
    #[serde(flatten)]
    pub measured: Measured,
}

/// A reading that can flip between two runs: a verdict, a check, a claim's result.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Reading {
    /// Stable key (see the module's docs).
    pub key: String,
    /// Its value in words.
    pub value: String,
}

/// A study cell as a statistic: an estimate, or a number without an error bar; an empty
/// cell is none.
fn cell(c: &Cell) -> Option<Measured> {
    match *c {
        Cell::Estimate(e) => Some(e.into()),
        Cell::Number(v) => Some(Measured::new(v, f64::NAN)),
        Cell::Empty => None,
    }
}

/// An enum as its file spelling (`"not_reproduced"` -> `not_reproduced`).
fn spelled<T: Serialize>(x: &T) -> String {
    match serde_json::to_value(x) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(v) => v.to_string(),
        Err(_) => String::new(),
    }
}

/// Every statistic of an outcome, in the order of the module's table; keys that repeat
/// within the outcome get `#2`, `#3`, ... so that every key is unique.
pub fn statistics(outcome: &Outcome) -> Vec<Statistic> {
    let mut out: Vec<(String, Measured)> = vec![(
        "headline".into(),
        Measured::new(outcome.value, outcome.std_error),
    )];
    for d in &outcome.details {
        let key = Measure::Detail {
            key: d.key.clone(),
            grid: d.grid,
        };
        out.push((key.to_string(), d.value.into()));
    }
    for c in &outcome.cross_checks {
        out.push((
            format!("cross_check:{}", c.solver),
            Measured::new(c.value, c.std_error),
        ));
    }
    for claim in &outcome.claims {
        if let Some(m) = claim.measured {
            out.push((format!("claim:{}", claim.key), m.into()));
        }
    }
    for study in &outcome.studies {
        for row in &study.rows {
            for (k, c) in row.cells.iter().enumerate() {
                let Some(m) = cell(c) else { continue };
                let column = study
                    .columns
                    .get(k)
                    .map_or_else(|| format!("#{}", k + 1), |c| c.key.clone());
                out.push((format!("study:{}/{}/{column}", study.key, row.key), m));
            }
        }
    }
    unique(out)
        .into_iter()
        .map(|(key, measured)| Statistic { key, measured })
        .collect()
}

/// Every reading of an outcome that can flip; keys made unique as in [`statistics`].
pub fn readings(outcome: &Outcome) -> Vec<Reading> {
    let mut out: Vec<(String, String)> = vec![("verdict".into(), outcome.verdict.to_string())];
    let reproduced = match outcome.reproduced {
        Some(true) => "as the paper",
        Some(false) => "not as the paper",
        None => "inconclusive",
    };
    out.push(("reproduced".into(), reproduced.into()));
    for guard in &outcome.guards {
        let words = match (guard.decided, guard.passed) {
            (false, _) => "undecided",
            (true, true) => "passed",
            (true, false) => "failed",
        };
        out.push((format!("guard:{}", guard.key), words.into()));
    }
    for claim in &outcome.claims {
        out.push((format!("claim:{}", claim.key), spelled(&claim.result)));
    }
    for c in &outcome.cross_checks {
        let words = if c.agrees { "agrees" } else { "disagrees" };
        out.push((format!("cross_check:{}", c.solver), words.into()));
    }
    unique(out)
        .into_iter()
        .map(|(key, value)| Reading { key, value })
        .collect()
}

/// `items` with every repeated key numbered from its second occurrence (`key#2`, ...).
fn unique<T>(items: Vec<(String, T)>) -> Vec<(String, T)> {
    let mut seen: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    items
        .into_iter()
        .map(|(key, v)| {
            let n = seen.entry(key.clone()).or_insert(0);
            *n += 1;
            if *n == 1 {
                (key, v)
            } else {
                (format!("{key}#{n}"), v)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_keys_are_numbered() {
        let items = vec![("a".to_string(), 1), ("b".into(), 2), ("a".into(), 3)];
        let keys: Vec<String> = unique(items).into_iter().map(|(k, _)| k).collect();
        assert_eq!(keys, ["a", "b", "a#2"]);
    }

    #[test]
    fn cells_read_as_estimates_numbers_or_nothing() {
        let e = cell(&Cell::Estimate(Estimate::new(2.0, 0.5))).unwrap();
        assert_eq!((e.value, e.std_error), (Some(2.0), Some(0.5)));
        let n = cell(&Cell::Number(3.0)).unwrap();
        assert_eq!((n.value, n.std_error), (Some(3.0), None));
        assert!(cell(&Cell::Empty).is_none());
        let one = cell(&Cell::Estimate(Estimate::new(1.0, f64::NAN))).unwrap();
        assert_eq!(one.std_error, None, "one realization: no error bar");
    }
}
