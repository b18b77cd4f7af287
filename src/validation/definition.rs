//! Validation definitions: the verdict rule, the paper's finding and the two scenes of a
//! validation file (`validations/<name>.toml`).

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::experiments::Criteria;
use crate::stats::Estimate;

/// The verdict on an assumption.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// The measurement agrees with Persson's prediction to within the stated resolution.
    Holds,
    /// The measurement differs from Persson's prediction beyond the stated significance.
    Violated,
    /// The experiment's error bar is too wide to tell.
    Inconclusive,
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Verdict::Holds => "holds",
            Verdict::Violated => "violated",
            Verdict::Inconclusive => "inconclusive",
        })
    }
}

/// How a verdict is reached from `value +- std_error` and Persson's prediction.
///
/// With `z` the significance (in standard errors) and `resolution` the smallest deviation
/// from Persson's value that matters:
///
/// * **violated** when `|value - persson| > z std_error` (the prediction lies outside the
///   confidence interval);
/// * **holds** when the whole interval `value +- z std_error` lies within
///   `persson +- resolution` (an equivalence test);
/// * **inconclusive** otherwise: the interval contains the prediction but is too wide to
///   exclude a deviation of the size that matters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VerdictRule {
    /// Significance `z`, in standard errors (e.g. 3).
    pub significance: f64,
    /// Smallest deviation from Persson's prediction that matters (absolute, in the
    /// statistic's units).
    pub resolution: f64,
}

impl VerdictRule {
    /// The verdict for `measured` against Persson's `persson`.
    pub fn judge(&self, measured: Estimate, persson: f64) -> Verdict {
        let half = self.significance * measured.std_error;
        if !(measured.value.is_finite() && half.is_finite()) {
            return Verdict::Inconclusive;
        }
        let dev = (measured.value - persson).abs();
        if dev > half {
            Verdict::Violated
        } else if dev + half <= self.resolution {
            Verdict::Holds
        } else {
            Verdict::Inconclusive
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        if !(self.significance.is_finite() && self.significance > 0.0) {
            return Err(Error::invalid(
                "verdict.significance",
                self.significance,
                "a number of standard errors > 0",
            ));
        }
        if !(self.resolution.is_finite() && self.resolution > 0.0) {
            return Err(Error::invalid(
                "verdict.resolution",
                self.resolution,
                "a deviation > 0",
            ));
        }
        Ok(())
    }
}

/// What the paper found, and how to tell whether a run reproduces it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperFinding {
    /// The finding in words (with the paper's numbers).
    pub finding: String,
    /// The paper's verdict on the assumption.
    pub verdict: Verdict,
    /// The paper's value of the headline statistic, if it states one.
    #[serde(default)]
    pub value: Option<f64>,
    /// The range of the headline statistic that counts as reproducing the paper.
    #[serde(default)]
    pub range: Option<(f64, f64)>,
}

/// A validation file: the header, and a scene of type `S` at two scales.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Definition<S> {
    /// Unique name (the file stem), e.g. `c_reentry`.
    pub name: String,
    /// The experiment that runs it (see [`super::registry::BUILTIN`]).
    pub experiment: String,
    /// Short title.
    pub title: String,
    /// Persson's assumption under test.
    pub assumption: String,
    /// The headline statistic in words.
    pub statistic: String,
    /// Persson's prediction in words.
    pub persson: String,
    /// Verdict rule.
    pub verdict: VerdictRule,
    /// The paper's finding.
    pub paper: PaperFinding,
    /// Small scene for `cargo test`.
    pub reduced: S,
    /// Paper-scale scene for the command line.
    pub full: S,
}

/// Which of a definition's scenes to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Scale {
    /// The reduced scene.
    Reduced,
    /// The full scene.
    Full,
}

impl fmt::Display for Scale {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Scale::Reduced => "reduced",
            Scale::Full => "full",
        })
    }
}

impl<S> Definition<S> {
    /// The scene at `scale`.
    pub fn scene(&self, scale: Scale) -> &S {
        match scale {
            Scale::Reduced => &self.reduced,
            Scale::Full => &self.full,
        }
    }

    /// What the experiment's conclusion is judged by.
    pub fn criteria(&self) -> Criteria {
        Criteria {
            name: self.name.clone(),
            significance: self.verdict.significance,
            resolution: self.verdict.resolution,
            paper_value: self.paper.value,
        }
    }
}
