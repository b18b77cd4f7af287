//! Validation definitions: the verdict rule, the paper's finding and the two scenes of a
//! validation file (`validations/<name>.toml`).

use std::fmt;

use serde::{Deserialize, Serialize};

use super::claims::ClaimSpec;
use crate::error::{Error, Result};
use crate::experiments::Criteria;
use crate::stats::{decide, Claim, Decision, Estimate};

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
    /// The verdict for `measured` against Persson's `persson`, by the rule of
    /// [`decide`]: violated when the interval `measured +- z error` does not come near
    /// Persson's value, holds when it lies within the resolution of it; inconclusive
    /// otherwise, and without an error bar (one realization).
    pub fn judge(&self, measured: Estimate, persson: f64) -> Verdict {
        let z = self.significance;
        let near = Claim::Near {
            target: persson,
            tolerance: 0.0,
        };
        let within = Claim::Within {
            target: persson,
            resolution: self.resolution,
        };
        match decide(measured, near, z) {
            Decision::Undecided => Verdict::Inconclusive,
            Decision::Failed => Verdict::Violated,
            Decision::Passed if decide(measured, within, z).passed() => Verdict::Holds,
            Decision::Passed => Verdict::Inconclusive,
        }
    }

    /// Whether two estimates of one statistic agree (the two solvers' on the same
    /// realizations): their difference comes within the significance times their
    /// combined standard error of zero. Without an error bar (one realization) the
    /// difference is taken as exact, and they agree when it is within the resolution:
    /// both solvers measured the same surfaces, so what remains is solver error.
    pub fn agree(&self, a: Estimate, b: Estimate) -> bool {
        let zero = |tolerance| Claim::Near {
            target: 0.0,
            tolerance,
        };
        let diff = Estimate::difference(a, b);
        match decide(diff, zero(0.0), self.significance) {
            Decision::Undecided => {
                decide(Estimate::new(diff.value, 0.0), zero(self.resolution), 0.0).passed()
            }
            d => d.passed(),
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
    /// The paper's quantitative statements this validation tests
    /// ([`super::claims`]).
    #[serde(default)]
    pub claims: Vec<ClaimSpec>,
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

    /// The scene of `scale`, to edit.
    pub fn scene_mut(&mut self, scale: Scale) -> &mut S {
        match scale {
            Scale::Reduced => &mut self.reduced,
            Scale::Full => &mut self.full,
        }
    }

    /// What the experiment's conclusion is judged by.
    pub fn criteria(&self) -> Criteria {
        Criteria {
            name: self.name.clone(),
            significance: self.verdict.significance,
            resolution: self.verdict.resolution,
            paper_value: self.paper.value,
            paper: self
                .claims
                .iter()
                .filter_map(|c| Some((c.key.clone(), c.value?)))
                .collect(),
        }
    }
}
