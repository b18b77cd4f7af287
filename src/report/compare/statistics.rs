//! What an outcome file measures, read as plain JSON: every statistic with its error bar,
//! and every reading that can flip (a verdict, a check, a claim's result).
//!
//! One function lists the statistics ([`statistics`]) and one the readings ([`readings`]);
//! both read `<name>.json` as a [`serde_json::Value`], never as the typed
//! [`crate::validation::Outcome`], so that files written by earlier and later versions
//! (a single `cross_check` or a list `cross_checks`, the flux `sensitivity` rows or generic
//! `studies`, with or without `claims`) read alike. A part an outcome does not have gives no
//! statistic; a number written as `null` (no error bar, not measured) is `None`.
//!
//! | key | from |
//! |---|---|
//! | `headline` | `value`, `std_error` |
//! | `detail:KEY` (`detail:KEY@GRID` when `grid` is set) | `details[].value` |
//! | `cross_check:SOLVER` | `cross_check` or each of `cross_checks` |
//! | `sensitivity:PARAMETER=LABEL/FIELD` | each estimate of each `sensitivity` row |
//! | `claim:KEY` | `claims[].measured` |
//! | `study:STUDY/ROW/COLUMN` | each number or estimate cell of `studies[].rows` |
//!
//! Readings: `verdict`, `reproduced`, `check:KEY` (passed, failed, undecided),
//! `claim:KEY` (its `result`), `cross_check:SOLVER` (agrees or disagrees).

use serde::Serialize;
use serde_json::Value;

/// A statistic of an outcome: a value and its standard error, either possibly unknown.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measured {
    /// The value (`None`: written as `null`, not measured).
    pub value: Option<f64>,
    /// Its standard error (`None`: no error bar).
    pub std_error: Option<f64>,
}

impl Measured {
    /// Whether `self` and `other` are the same numbers bit for bit (both unknown counts as
    /// the same).
    pub fn identical(&self, other: &Measured) -> bool {
        let bits = |x: Option<f64>| x.map(f64::to_bits);
        bits(self.value) == bits(other.value) && bits(self.std_error) == bits(other.std_error)
    }
}

/// A statistic with its key (see the module's table).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Statistic {
    /// Stable key, the same in every version of the outcome.
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

/// A number, or `None` for `null` or anything else.
fn number(v: Option<&Value>) -> Option<f64> {
    v.and_then(Value::as_f64)
}

/// An estimate `{"value": number|null, "std_error": number|null}` (the error may be
/// absent), or `None` when `v` is not one.
fn estimate(v: &Value) -> Option<Measured> {
    let object = v.as_object()?;
    let value = object.get("value")?;
    if !(value.is_number() || value.is_null()) {
        return None;
    }
    Some(Measured {
        value: value.as_f64(),
        std_error: number(object.get("std_error")),
    })
}

/// A study cell as a statistic: a number (no error bar) or an estimate; `None` for text,
/// `null` and anything else.
fn cell(v: &Value) -> Option<Measured> {
    match v {
        Value::Number(n) => Some(Measured {
            value: n.as_f64(),
            std_error: None,
        }),
        _ => estimate(v),
    }
}

/// The string at `key` of `v`, or "" when absent.
fn text<'a>(v: &'a Value, key: &str) -> &'a str {
    v.get(key).and_then(Value::as_str).unwrap_or("")
}

/// The elements of the list at `key` (none when absent or not a list).
fn list<'a>(v: &'a Value, key: &str) -> &'a [Value] {
    v.get(key)
        .and_then(Value::as_array)
        .map(Vec::as_slice)
        .unwrap_or(&[])
}

/// The cross-checks: `cross_check` (one object, or `null`) and the list `cross_checks`.
fn cross_checks(outcome: &Value) -> impl Iterator<Item = &Value> {
    outcome
        .get("cross_check")
        .filter(|c| c.is_object())
        .into_iter()
        .chain(list(outcome, "cross_checks"))
}

/// A detail's key: `key` (the label `name` in files older than stable keys), with
/// `@GRID` when it is one step of a resolution study.
fn detail_key(detail: &Value) -> String {
    let key = match text(detail, "key") {
        "" => text(detail, "name"),
        k => k,
    };
    match detail.get("grid").and_then(Value::as_u64) {
        Some(grid) => format!("detail:{key}@{grid}"),
        None => format!("detail:{key}"),
    }
}

/// Every statistic of an outcome, in the order of the module's table; keys that repeat
/// within the outcome get `#2`, `#3`, ... so that every key is unique.
pub fn statistics(outcome: &Value) -> Vec<Statistic> {
    let mut out: Vec<(String, Measured)> = Vec::new();
    if let Some(headline) = estimate(outcome) {
        out.push(("headline".into(), headline));
    }
    for detail in list(outcome, "details") {
        if let Some(m) = detail.get("value").and_then(estimate) {
            out.push((detail_key(detail), m));
        }
    }
    for check in cross_checks(outcome) {
        if let Some(m) = estimate(check) {
            out.push((format!("cross_check:{}", text(check, "solver")), m));
        }
    }
    for row in list(outcome, "sensitivity") {
        let Some(fields) = row.as_object() else {
            continue;
        };
        let row_key = format!("{}={}", text(row, "parameter"), text(row, "label"));
        for (field, v) in fields {
            if let Some(m) = estimate(v) {
                out.push((format!("sensitivity:{row_key}/{field}"), m));
            }
        }
    }
    for claim in list(outcome, "claims") {
        if let Some(m) = claim.get("measured").and_then(estimate) {
            out.push((format!("claim:{}", text(claim, "key")), m));
        }
    }
    for study in list(outcome, "studies") {
        let columns = list(study, "columns");
        for row in list(study, "rows") {
            for (k, c) in list(row, "cells").iter().enumerate() {
                let Some(m) = cell(c) else { continue };
                let column = columns
                    .get(k)
                    .map(|c| text(c, "key").to_string())
                    .unwrap_or_else(|| format!("#{}", k + 1));
                out.push((
                    format!("study:{}/{}/{column}", text(study, "key"), text(row, "key")),
                    m,
                ));
            }
        }
    }
    unique(out)
        .into_iter()
        .map(|(key, measured)| Statistic { key, measured })
        .collect()
}

/// Every reading of an outcome that can flip; keys made unique as in [`statistics`].
pub fn readings(outcome: &Value) -> Vec<Reading> {
    let mut out: Vec<(String, String)> = Vec::new();
    if let Some(v) = outcome.get("verdict").and_then(Value::as_str) {
        out.push(("verdict".into(), v.into()));
    }
    if let Some(r) = outcome.get("reproduced") {
        let words = match r.as_bool() {
            Some(true) => "reproduced",
            Some(false) => "not reproduced",
            None => "undecided",
        };
        out.push(("reproduced".into(), words.into()));
    }
    for check in list(outcome, "checks") {
        let decided = check
            .get("decided")
            .and_then(Value::as_bool)
            .unwrap_or(true);
        let words = match (decided, check.get("passed").and_then(Value::as_bool)) {
            (false, _) | (true, None) => "undecided",
            (true, Some(true)) => "passed",
            (true, Some(false)) => "failed",
        };
        let key = match text(check, "key") {
            "" => text(check, "name"),
            k => k,
        };
        out.push((format!("check:{key}"), words.into()));
    }
    for claim in list(outcome, "claims") {
        if let Some(result) = claim.get("result").and_then(Value::as_str) {
            out.push((format!("claim:{}", text(claim, "key")), result.into()));
        }
    }
    for check in cross_checks(outcome) {
        if let Some(agrees) = check.get("agrees").and_then(Value::as_bool) {
            let words = if agrees { "agrees" } else { "disagrees" };
            out.push((
                format!("cross_check:{}", text(check, "solver")),
                words.into(),
            ));
        }
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
    use serde_json::json;

    #[test]
    fn lists_every_part_of_old_and_new_outcome_files() {
        let old = json!({
            "value": 0.5, "std_error": 0.01, "verdict": "holds", "reproduced": true,
            "details": [
                {"key": "a", "value": {"value": 1.0, "std_error": null}},
                {"key": "a", "grid": 256, "value": {"value": 2.0, "std_error": 0.1}}
            ],
            "checks": [{"key": "c", "passed": true}, {"key": "d", "passed": false, "decided": false}],
            "cross_check": {"solver": "cg", "value": 0.49, "std_error": 0.01, "agrees": true},
            "sensitivity": [{"parameter": "tol", "label": "1e-4", "value": 1e-4,
                             "flux_in": {"value": 0.2, "std_error": 0.01}, "realizations": 2}]
        });
        let keys: Vec<String> = statistics(&old).into_iter().map(|s| s.key).collect();
        assert_eq!(
            keys,
            [
                "headline",
                "detail:a",
                "detail:a@256",
                "cross_check:cg",
                "sensitivity:tol=1e-4/flux_in"
            ]
        );
        assert_eq!(statistics(&old)[1].measured.std_error, None);
        let listed: Vec<(String, String)> = readings(&old)
            .into_iter()
            .map(|r| (r.key, r.value))
            .collect();
        assert_eq!(
            listed,
            [
                ("verdict".into(), "holds".into()),
                ("reproduced".into(), "reproduced".into()),
                ("check:c".into(), "passed".into()),
                ("check:d".into(), "undecided".into()),
                ("cross_check:cg".into(), "agrees".into()),
            ]
        );
        let new = json!({
            "value": 0.5, "std_error": null, "verdict": "holds", "reproduced": null,
            "cross_check": null,
            "cross_checks": [{"solver": "cg", "value": 0.49, "std_error": 0.01, "agrees": false}],
            "claims": [{"key": "k", "measured": {"value": 3.0, "std_error": 0.2}, "result": "reproduced"},
                       {"key": "m", "measured": null, "result": "not measured"}],
            "studies": [{"key": "s", "columns": [{"key": "label"}, {"key": "x"}, {"key": "y"}],
                         "rows": [{"key": "r", "cells": ["text", 4.0, {"value": 5.0, "std_error": 0.5}]},
                                  {"key": "q", "cells": [null, null, {"value": null, "std_error": null}]}]}]
        });
        let stats = statistics(&new);
        let keys: Vec<&str> = stats.iter().map(|s| s.key.as_str()).collect();
        assert_eq!(
            keys,
            [
                "headline",
                "cross_check:cg",
                "claim:k",
                "study:s/r/x",
                "study:s/r/y",
                "study:s/q/y"
            ]
        );
        assert_eq!(stats[3].measured.value, Some(4.0));
        assert_eq!(stats[5].measured.value, None);
        let r = readings(&new);
        assert!(r.contains(&Reading {
            key: "claim:m".into(),
            value: "not measured".into()
        }));
        assert!(r.contains(&Reading {
            key: "cross_check:cg".into(),
            value: "disagrees".into()
        }));
    }

    #[test]
    fn repeated_keys_are_numbered() {
        let o = json!({"details": [
            {"key": "a", "value": {"value": 1.0}}, {"key": "a", "value": {"value": 2.0}}
        ]});
        let keys: Vec<String> = statistics(&o).into_iter().map(|s| s.key).collect();
        assert_eq!(keys, ["detail:a", "detail:a#2"]);
    }
}
