//! Two folders of outcomes compared statistic by statistic: `compare BASE NEW`.
//!
//! For every statistic both folders' outcomes have ([`statistics::statistics`]), the
//! difference in combined standard errors,
//!
//! `z = (x_new - x_base) / sqrt(s_base^2 + s_new^2)`,
//!
//! with the error bars each side has (a side without one adds nothing; neither side with
//! one gives no `z`). Two statistics equal bit for bit, error bars included, are
//! "identical". A reading that differs between the sides (verdict, reproduction, a check,
//! a claim's result, a cross-check's agreement: [`statistics::readings`]) is a flip.
//! Outcomes, statistics and readings present on one side only are listed. The comparison
//! fails when some `|z|` exceeds the threshold or something flips.
//!
//! The outcomes are read as [`Outcome`]s: a file that looks like one (it has `name`,
//! `statistic` and `verdict`) but does not read as one is an error naming it.

pub mod statistics;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::Value;

use self::statistics::{readings, Measured};
use super::format::{md, pm, push_table};
use crate::error::{Error, Result};
use crate::validation::Outcome;

/// The default threshold of `|z|`.
pub const Z_THRESHOLD: f64 = 3.0;

/// One statistic found on both sides.
#[derive(Debug, Clone, Serialize)]
pub struct Compared {
    /// The outcome (`name`).
    pub outcome: String,
    /// The statistic's key.
    pub key: String,
    /// Its value and error bar in BASE.
    pub base: Measured,
    /// Its value and error bar in NEW.
    pub new: Measured,
    /// Equal bit for bit, error bars included.
    pub identical: bool,
    /// `new - base`, when both values are known.
    pub difference: Option<f64>,
    /// The difference in combined standard errors, when an error bar is known.
    pub z: Option<f64>,
    /// `|z|` above the threshold.
    pub beyond: bool,
}

/// A reading that flipped.
#[derive(Debug, Clone, Serialize)]
pub struct Flip {
    /// The outcome.
    pub outcome: String,
    /// The reading's key.
    pub key: String,
    /// Its value in BASE.
    pub base: String,
    /// Its value in NEW.
    pub new: String,
}

/// Something present on one side only.
#[derive(Debug, Clone, Serialize)]
pub struct OneSide {
    /// The outcome.
    pub outcome: String,
    /// The statistic's or reading's key (`None`: the whole outcome).
    pub key: Option<String>,
    /// "base" or "new".
    pub side: &'static str,
}

/// The comparison of two folders of outcomes.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// The BASE folder.
    pub base: PathBuf,
    /// The NEW folder.
    pub new: PathBuf,
    /// The threshold of `|z|`.
    pub z_threshold: f64,
    /// Outcomes on both sides, by name.
    pub outcomes: Vec<String>,
    /// Every statistic on both sides.
    pub statistics: Vec<Compared>,
    /// Every flip.
    pub flips: Vec<Flip>,
    /// Outcomes, statistics and readings on one side only.
    pub one_side: Vec<OneSide>,
    /// The comparison in one paragraph.
    pub summary: String,
    /// Nothing beyond the threshold and nothing flipped.
    pub passed: bool,
}

/// The outcomes (`<name>.json` holding `name`, `statistic` and `verdict`) directly in
/// `dir`, by name; other JSON files are skipped. `flag` names the folder in errors.
pub fn read_folder(dir: &Path, flag: &str) -> Result<BTreeMap<String, Outcome>> {
    if !dir.is_dir() {
        return Err(Error::invalid(
            flag,
            dir.display(),
            "an existing folder of outcomes (<name>.json)",
        ));
    }
    let mut out = BTreeMap::new();
    for entry in std::fs::read_dir(dir).map_err(|e| Error::io(dir, e))? {
        let path = entry.map_err(|e| Error::io(dir, e))?.path();
        if !(path.is_file() && path.extension().is_some_and(|x| x == "json")) {
            continue;
        }
        let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, e))?;
        let value: Value = serde_json::from_slice(&bytes)
            .map_err(|e| Error::bad_file(&path, format!("not valid JSON ({e})")))?;
        let is_outcome = ["name", "statistic", "verdict"]
            .iter()
            .all(|k| value.get(k).is_some());
        if !is_outcome {
            continue;
        }
        let outcome: Outcome = serde_json::from_value(value)
            .map_err(|e| Error::bad_file(&path, format!("not an outcome ({e})")))?;
        out.insert(outcome.name.clone(), outcome);
    }
    if out.is_empty() {
        return Err(Error::invalid(
            flag,
            format!("{} (no outcomes in it)", dir.display()),
            "a folder of outcomes (<name>.json), as written by `validate --out`",
        ));
    }
    Ok(out)
}

/// Compares the outcomes of the folders `base` and `new`; `|z|` above `z_threshold` fails.
pub fn compare(base: &Path, new: &Path, z_threshold: f64) -> Result<Comparison> {
    if !(z_threshold.is_finite() && z_threshold > 0.0) {
        return Err(Error::invalid("--z", z_threshold, "a finite number > 0"));
    }
    let b = read_folder(base, "BASE")?;
    let n = read_folder(new, "NEW")?;
    let mut c = Comparison {
        base: base.to_path_buf(),
        new: new.to_path_buf(),
        z_threshold,
        outcomes: Vec::new(),
        statistics: Vec::new(),
        flips: Vec::new(),
        one_side: Vec::new(),
        summary: String::new(),
        passed: true,
    };
    for name in b.keys().filter(|k| !n.contains_key(*k)) {
        c.one_side.push(OneSide {
            outcome: name.clone(),
            key: None,
            side: "base",
        });
    }
    for name in n.keys().filter(|k| !b.contains_key(*k)) {
        c.one_side.push(OneSide {
            outcome: name.clone(),
            key: None,
            side: "new",
        });
    }
    for (name, bo) in &b {
        let Some(no) = n.get(name) else { continue };
        c.outcomes.push(name.clone());
        compare_outcome(name, bo, no, z_threshold, &mut c);
    }
    c.passed = !c.statistics.iter().any(|s| s.beyond) && c.flips.is_empty();
    c.summary = summary(&c);
    Ok(c)
}

/// The statistics and readings of one outcome on both sides, into `c`.
fn compare_outcome(
    name: &str,
    base: &Outcome,
    new: &Outcome,
    z_threshold: f64,
    c: &mut Comparison,
) {
    let bs = statistics::statistics(base);
    let ns: BTreeMap<String, Measured> = statistics::statistics(new)
        .into_iter()
        .map(|s| (s.key, s.measured))
        .collect();
    for s in &bs {
        match ns.get(&s.key) {
            Some(n) => c
                .statistics
                .push(compared(name, &s.key, s.measured, *n, z_threshold)),
            None => c.one_side.push(one_side(name, &s.key, "base")),
        }
    }
    for key in ns.keys().filter(|k| !bs.iter().any(|s| &s.key == *k)) {
        c.one_side.push(one_side(name, key, "new"));
    }
    let br = readings(base);
    let nr: BTreeMap<String, String> = readings(new)
        .into_iter()
        .map(|r| (r.key, r.value))
        .collect();
    for r in &br {
        match nr.get(&r.key) {
            Some(v) if *v != r.value => c.flips.push(Flip {
                outcome: name.to_string(),
                key: r.key.clone(),
                base: r.value.clone(),
                new: v.clone(),
            }),
            Some(_) => {}
            None => c.one_side.push(one_side(name, &r.key, "base")),
        }
    }
    for key in nr.keys().filter(|k| !br.iter().any(|r| &r.key == *k)) {
        c.one_side.push(one_side(name, key, "new"));
    }
}

fn one_side(outcome: &str, key: &str, side: &'static str) -> OneSide {
    OneSide {
        outcome: outcome.to_string(),
        key: Some(key.to_string()),
        side,
    }
}

/// One statistic on both sides: identical, or its difference and `z`.
pub fn compared(
    outcome: &str,
    key: &str,
    base: Measured,
    new: Measured,
    z_threshold: f64,
) -> Compared {
    let identical = base.identical(&new);
    let difference = match (base.value, new.value) {
        (Some(b), Some(n)) if !identical => Some(n - b),
        (Some(_), Some(_)) => Some(0.0),
        _ => None,
    };
    let variance: Option<f64> = [base.std_error, new.std_error]
        .into_iter()
        .flatten()
        .filter(|s| s.is_finite())
        .map(|s| s * s)
        .reduce(|a, b| a + b);
    let z = match (identical, difference, variance) {
        (true, _, _) => Some(0.0),
        // Equal values whose error bars changed have not moved.
        (false, Some(d), Some(v)) => Some(if d == 0.0 { 0.0 } else { d / v.sqrt() }),
        _ => None,
    };
    Compared {
        outcome: outcome.to_string(),
        key: key.to_string(),
        base,
        new,
        identical,
        difference,
        z,
        beyond: z.is_some_and(|z| z.abs() > z_threshold),
    }
}

/// The comparison in one paragraph: what was compared and what moved or flipped.
fn summary(c: &Comparison) -> String {
    let count = |f: &dyn Fn(&Compared) -> bool| c.statistics.iter().filter(|s| f(s)).count();
    let identical = count(&|s| s.identical);
    let beyond = count(&|s| s.beyond);
    let within = count(&|s| !s.identical && !s.beyond && s.z.is_some());
    let no_bar = count(&|s| !s.identical && s.z.is_none());
    let sides = |side: &str, whole: bool| {
        c.one_side
            .iter()
            .filter(|o| o.side == side && o.key.is_none() == whole)
            .count()
    };
    let mut s = format!(
        "{} outcome{} on both sides, {} statistics: {identical} identical, {within} moved \
         within {} standard errors, {beyond} moved beyond, {no_bar} changed without an error \
         bar; {} reading{} flipped.",
        c.outcomes.len(),
        plural(c.outcomes.len()),
        c.statistics.len(),
        c.z_threshold,
        c.flips.len(),
        plural(c.flips.len()),
    );
    let (ob, on) = (sides("base", true), sides("new", true));
    let (kb, kn) = (sides("base", false), sides("new", false));
    if ob + on + kb + kn > 0 {
        let _ = write!(
            s,
            " On one side only: {ob} outcome{} and {kb} statistic{} or reading{} in BASE, \
             {on} outcome{} and {kn} in NEW.",
            plural(ob),
            plural(kb),
            plural(kb),
            plural(on)
        );
    }
    s
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

fn shown(m: &Measured) -> String {
    pm(m.value.unwrap_or(f64::NAN), m.std_error.unwrap_or(f64::NAN))
}

fn z_cell(s: &Compared) -> String {
    match (s.identical, s.z) {
        (true, _) => "identical".into(),
        (false, Some(z)) if s.beyond => format!("**{z:+.1}**"),
        (false, Some(z)) => format!("{z:+.1}"),
        (false, None) => match s.difference {
            Some(d) => format!("no error bar (difference {})", super::format::num(d)),
            None => "no error bar (a value on one side only)".into(),
        },
    }
}

impl Comparison {
    /// The comparison as Markdown: the summary, what moved beyond the threshold, the
    /// flips, what is on one side only, then every statistic by outcome.
    pub fn markdown(&self) -> String {
        let mut s = format!(
            "# Comparison of `{}` (BASE) with `{}` (NEW)\n\n**Summary.** {}\n\n",
            self.base.display(),
            self.new.display(),
            md(&self.summary)
        );
        let _ = writeln!(
            s,
            "{}\n",
            if self.passed {
                format!(
                    "Nothing moved beyond {} standard errors and nothing flipped.",
                    self.z_threshold
                )
            } else {
                format!(
                    "**Failed:** {} statistic{} moved beyond {} standard errors, {} reading{} \
                     flipped.",
                    self.statistics.iter().filter(|c| c.beyond).count(),
                    plural(self.statistics.iter().filter(|c| c.beyond).count()),
                    self.z_threshold,
                    self.flips.len(),
                    plural(self.flips.len())
                )
            }
        );
        let row = |c: &Compared| {
            vec![
                format!("`{}`", c.outcome),
                format!("`{}`", c.key),
                shown(&c.base),
                shown(&c.new),
                z_cell(c),
            ]
        };
        let header = ["outcome", "statistic", "BASE", "NEW", "z"];
        let beyond: Vec<Vec<String>> = self
            .statistics
            .iter()
            .filter(|c| c.beyond)
            .map(row)
            .collect();
        if !beyond.is_empty() {
            let _ = writeln!(s, "## Moved beyond {} standard errors\n", self.z_threshold);
            push_table(&mut s, &header, &beyond);
        }
        if !self.flips.is_empty() {
            s.push_str("## Flipped\n\n");
            let rows: Vec<Vec<String>> = self
                .flips
                .iter()
                .map(|f| {
                    vec![
                        format!("`{}`", f.outcome),
                        format!("`{}`", f.key),
                        md(&f.base),
                        md(&f.new),
                    ]
                })
                .collect();
            push_table(&mut s, &["outcome", "reading", "BASE", "NEW"], &rows);
        }
        if !self.one_side.is_empty() {
            s.push_str("## On one side only\n\n");
            for o in &self.one_side {
                let side = if o.side == "base" { "BASE" } else { "NEW" };
                let _ = match &o.key {
                    None => writeln!(s, "- outcome `{}`: only in {side}", o.outcome),
                    Some(k) => writeln!(s, "- `{}` `{k}`: only in {side}", o.outcome),
                };
            }
            s.push('\n');
        }
        s.push_str("## Every statistic\n\n");
        for name in &self.outcomes {
            let rows: Vec<Vec<String>> = self
                .statistics
                .iter()
                .filter(|c| &c.outcome == name)
                .map(|c| row(c)[1..].to_vec())
                .collect();
            let _ = writeln!(s, "### `{name}`\n");
            push_table(&mut s, &header[1..], &rows);
        }
        s
    }

    /// Writes the Markdown to `out` and the JSON beside it (`out` with `.json`); the two
    /// paths.
    pub fn write(&self, out: &Path) -> Result<(PathBuf, PathBuf)> {
        let json_path = out.with_extension("json");
        if json_path == out {
            return Err(Error::invalid(
                "--out",
                out.display(),
                "a Markdown file name (the JSON is written beside it with .json)",
            ));
        }
        crate::io::write_atomic(out, self.markdown().as_bytes())?;
        let json = serde_json::to_vec_pretty(self).expect("comparisons serialise");
        crate::io::write_atomic(&json_path, &json)?;
        Ok((out.to_path_buf(), json_path))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(value: f64, std_error: Option<f64>) -> Measured {
        Measured {
            value: Some(value),
            std_error,
        }
    }

    #[test]
    fn z_is_the_difference_in_combined_standard_errors() {
        let c = compared("o", "k", m(1.0, Some(0.3)), m(3.0, Some(0.4)), 3.0);
        assert!(!c.identical);
        assert!((c.z.unwrap() - 4.0).abs() < 1e-12, "{:?}", c.z);
        assert!(c.beyond);
        // One side's error bar alone.
        let c = compared("o", "k", m(1.0, None), m(1.5, Some(0.25)), 3.0);
        assert!((c.z.unwrap() - 2.0).abs() < 1e-12 && !c.beyond);
        // No error bar: no z, never beyond.
        let c = compared("o", "k", m(1.0, None), m(2.0, None), 3.0);
        assert_eq!((c.z, c.difference, c.beyond), (None, Some(1.0), false));
        // Identical, bit for bit; -0.0 is not 0.0.
        assert!(compared("o", "k", m(1.0, None), m(1.0, None), 3.0).identical);
        assert!(!compared("o", "k", m(0.0, None), m(-0.0, None), 3.0).identical);
    }
}
