//! The outcome of a validation run: `<name>.json`.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::definition::{Scale, Verdict, VerdictRule};
use crate::experiments::{Check, Detail};

/// The record of one validation run: `<name>.json` ([`crate::conventions`], section 7).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Name.
    pub name: String,
    /// Title.
    pub title: String,
    /// Assumption under test.
    pub assumption: String,
    /// The headline statistic in words.
    pub statistic: String,
    /// The measured headline statistic.
    pub value: f64,
    /// Its standard error.
    pub std_error: f64,
    /// Persson's prediction of the statistic.
    pub persson: f64,
    /// Persson's prediction in words.
    pub persson_text: String,
    /// The paper's finding in words.
    pub paper: String,
    /// The paper's value, if stated.
    pub paper_value: Option<f64>,
    /// The paper's verdict.
    pub paper_verdict: Verdict,
    /// The verdict of this run.
    pub verdict: Verdict,
    /// Whether the run reproduces the paper's finding (`None` when inconclusive).
    pub reproduced: Option<bool>,
    /// The verdict rule used.
    pub rule: VerdictRule,
    /// Scale of the scene.
    pub scale: Scale,
    /// The scene, as run.
    pub scene: serde_json::Value,
    /// Hash of the definition file (SHA-256, hex).
    pub definition_sha256: String,
    /// Wall time of the whole validation, seconds.
    pub wall_s: f64,
    /// Largest solver residual over all solves.
    pub max_residual: f64,
    /// Secondary statistics.
    pub details: Vec<Detail>,
    /// Checks of the paper's finding.
    pub checks: Vec<Check>,
    /// Account generated from the numbers.
    pub account: String,
    /// Golden values.
    pub golden: BTreeMap<String, f64>,
    /// Files written (tables, figures), relative to the output directory.
    pub files: Vec<String>,
    /// Worker threads used.
    pub threads: usize,
    /// The solver of the headline statistic.
    #[serde(default)]
    pub solver: String,
    /// The same statistic from the other solver on the same scene, if it was run.
    #[serde(default)]
    pub cross_check: Option<CrossCheck>,
}

/// The headline statistic measured again with the other solver (same surfaces, loads and
/// tolerance).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CrossCheck {
    /// The solver.
    pub solver: String,
    /// Its value of the statistic.
    pub value: f64,
    /// Its standard error.
    pub std_error: f64,
    /// Whether the two solvers agree within their combined error (see
    /// [`super::runner::agree`]).
    pub agrees: bool,
}
