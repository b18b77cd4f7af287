//! Golden snapshots: an outcome's golden values against `golden/<name>.snap`.
//!
//! A snapshot is insta's format: a header between two `---` lines, then the JSON body (an
//! object of numbers). Values are compared after the rounding the experiment already did,
//! with a relative tolerance of [`REL_TOL`] that absorbs float parsing only.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::validation::{Outcome, Scale};

/// Relative tolerance of a golden comparison (float parsing, not physics).
pub const REL_TOL: f64 = 1e-9;

/// How an outcome's golden values compare with its snapshot.
#[derive(Debug, Clone, PartialEq)]
pub enum GoldenMatch {
    /// Every value matches (the number of values, the snapshot).
    Yes(usize, PathBuf),
    /// Some values differ: one line per difference.
    Differ(Vec<String>, PathBuf),
    /// Full-scale outcomes have no snapshot (snapshots hold the reduced scenes).
    FullScene,
    /// No comparison was made, and why.
    NotChecked(String),
}

impl GoldenMatch {
    /// Compares `outcome` with its snapshot in `dir` (if a folder is given).
    pub fn of(outcome: &Outcome, dir: Option<&Path>) -> Self {
        if outcome.scale == Scale::Full {
            return Self::FullScene;
        }
        let Some(dir) = dir else {
            return Self::NotChecked("no golden folder".into());
        };
        let path = dir.join(format!("{}.snap", outcome.name));
        if !path.exists() {
            return Self::NotChecked(format!("no snapshot {}", path.display()));
        }
        match read_snapshot(&path) {
            Ok(snap) => {
                let diffs = compare(&outcome.golden, &snap);
                if diffs.is_empty() {
                    Self::Yes(snap.len(), path)
                } else {
                    Self::Differ(diffs, path)
                }
            }
            Err(e) => Self::NotChecked(format!("unreadable snapshot: {e}")),
        }
    }

    /// The scorecard cell: "yes", "no (k differ: ...)", "n/a (full scene)" or "not checked".
    pub fn cell(&self) -> String {
        match self {
            Self::Yes(..) => "yes".into(),
            Self::Differ(d, _) => {
                let shown: Vec<&str> = d.iter().take(3).map(String::as_str).collect();
                let more = if d.len() > 3 { "; ..." } else { "" };
                format!("no ({} differ: {}{more})", d.len(), shown.join("; "))
            }
            Self::FullScene => "n/a (full scene)".into(),
            Self::NotChecked(_) => "not checked".into(),
        }
    }
}

/// Reads the values of an insta snapshot.
pub fn read_snapshot(path: &Path) -> Result<BTreeMap<String, f64>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let body = snapshot_body(&text)
        .ok_or_else(|| Error::bad_file(path, "no header between two `---` lines"))?;
    let value: serde_json::Value = serde_json::from_str(body)
        .map_err(|e| Error::bad_file(path, format!("body is not JSON: {e}")))?;
    let object = value
        .as_object()
        .ok_or_else(|| Error::bad_file(path, "body must be an object of numbers"))?;
    let mut out = BTreeMap::new();
    for (key, v) in object {
        let x = match v {
            serde_json::Value::Number(n) => n.as_f64(),
            // serde_json writes NaN as null.
            serde_json::Value::Null => Some(f64::NAN),
            _ => None,
        }
        .ok_or_else(|| Error::bad_file(path, format!("{key}: {v} is not a number")))?;
        out.insert(key.clone(), x);
    }
    Ok(out)
}

/// The text after the header (`---` ... `---`).
fn snapshot_body(text: &str) -> Option<&str> {
    let mut offset = 0;
    let mut fences = 0;
    for line in text.split_inclusive('\n') {
        offset += line.len();
        if line.trim_end() == "---" {
            fences += 1;
            if fences == 2 {
                return Some(&text[offset..]);
            }
        } else if fences == 0 && !line.trim().is_empty() {
            return None;
        }
    }
    None
}

/// One line per difference between an outcome's values and a snapshot's.
pub fn compare(outcome: &BTreeMap<String, f64>, snapshot: &BTreeMap<String, f64>) -> Vec<String> {
    let mut diffs = Vec::new();
    for (key, &v) in outcome {
        match snapshot.get(key) {
            None => diffs.push(format!("{key} = {} not in the snapshot", exact(v))),
            Some(&s) if !same(v, s) => {
                diffs.push(format!("{key} = {}, snapshot {}", exact(v), exact(s)))
            }
            Some(_) => {}
        }
    }
    for key in snapshot.keys().filter(|k| !outcome.contains_key(*k)) {
        diffs.push(format!("{key} missing from the outcome"));
    }
    diffs
}

/// A golden value as written (every digit), "n/a" for NaN.
fn exact(x: f64) -> String {
    if x.is_nan() {
        "n/a".into()
    } else {
        x.to_string()
    }
}

fn same(a: f64, b: f64) -> bool {
    (a.is_nan() && b.is_nan()) || a == b || (a - b).abs() <= REL_TOL * a.abs().max(b.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SNAP: &str = "---\nsource: tests/validations.rs\nexpression: outcome.golden\n---\n\
                        {\n  \"kappa\": 2.221,\n  \"law_deviation\": 0.0829\n}\n";

    #[test]
    fn snapshot_values_are_read_after_the_header() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.snap");
        std::fs::write(&path, SNAP).unwrap();
        let snap = read_snapshot(&path).unwrap();
        assert_eq!(snap.len(), 2);
        assert_eq!(snap["kappa"], 2.221);
        std::fs::write(&path, "{\"kappa\": 1}").unwrap();
        let e = read_snapshot(&path).unwrap_err().to_string();
        assert!(e.contains("x.snap") && e.contains("header"), "{e}");
        std::fs::write(&path, "---\na: b\n---\n{\"kappa\": \"text\"}").unwrap();
        let e = read_snapshot(&path).unwrap_err().to_string();
        assert!(e.contains("kappa") && e.contains("not a number"), "{e}");
    }

    #[test]
    fn comparison_tolerates_parsing_not_changes() {
        let snap = BTreeMap::from([("a".to_string(), 2.221), ("b".to_string(), 0.0829)]);
        let same_values = BTreeMap::from([
            ("a".to_string(), 2.221 * (1.0 + 1e-12)),
            ("b".to_string(), 0.0829),
        ]);
        assert!(compare(&same_values, &snap).is_empty());
        let changed = BTreeMap::from([("a".to_string(), 2.222), ("c".to_string(), 1.0)]);
        let d = compare(&changed, &snap);
        assert_eq!(d.len(), 3, "{d:?}");
        assert!(d[0].contains("a = 2.222, snapshot 2.221"), "{d:?}");
        assert!(d.iter().any(|l| l.contains("c = 1 not in the snapshot")));
        assert!(d.iter().any(|l| l.contains("b missing from the outcome")));
        assert!(same(f64::NAN, f64::NAN));
    }
}
