//! A claim judged ([`ClaimOutcome`]): an entry of `claims` in `<name>.json`, with its
//! three-valued result ([`ClaimResult`]: reproduced, contradicted, not established; or not
//! measured, or not judged at this scale), what it counts as ([`ClaimKind`]), and the
//! claims' part in a validation's decision ([`decision`], [`deciding`]).

use serde::{Deserialize, Serialize};

use super::interval::{normal_z, realizations_needed};
use super::phrase::{Phrase, Rule};
use super::unit::Unit;
use crate::stats::{Decision, Estimate, Region};

/// What a measure's error bar measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    /// The spread over realizations: more realizations shrink it as 1/sqrt(n).
    #[default]
    Realizations,
    /// The scatter of points about a fitted law: more realizations do not shrink it.
    Fit,
}

/// A change of a claim's rule after an outcome existed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Amendment {
    /// The first characters of the registered hash of the rule it replaces.
    pub from: String,
    /// Why, in words.
    pub reason: String,
}

/// What a claim's measurement says.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClaimResult {
    /// The data establish the statement.
    Reproduced,
    /// The data exclude it.
    #[serde(alias = "not_reproduced")]
    Contradicted,
    /// Neither: the interval reaches both in and out of the statement's region, the test
    /// cannot tell the statement from its alternative, or there is no error bar.
    #[serde(alias = "undecided")]
    NotEstablished,
    /// There is nothing to measure it with here.
    NotMeasured,
    /// A magnitude of the paper's scene, measured on the reduced scene: shown, not judged.
    NotJudgedAtThisScale,
}

/// What kind of statement a claim is, for counting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClaimKind {
    /// Evidence for or against the paper.
    #[default]
    Evidence,
    /// True by construction: a check of the code, not evidence.
    Consistency,
    /// The paper states it two ways: both readings shown, counted apart.
    Inconsistent,
}

impl ClaimResult {
    /// The result in words, as the tables print it.
    pub fn text(self) -> &'static str {
        match self {
            ClaimResult::Reproduced => "reproduced",
            ClaimResult::Contradicted => "contradicted",
            ClaimResult::NotEstablished => "not established",
            ClaimResult::NotMeasured => "not measured",
            ClaimResult::NotJudgedAtThisScale => "not judged (reduced scene)",
        }
    }

    /// Its part in the validation's reproduction: passed, failed or undecided (not
    /// established); `None` where it takes no part (not measured, not judged at this
    /// scale).
    pub fn decision(self) -> Option<Decision> {
        match self {
            ClaimResult::Reproduced => Some(Decision::Passed),
            ClaimResult::Contradicted => Some(Decision::Failed),
            ClaimResult::NotEstablished => Some(Decision::Undecided),
            ClaimResult::NotMeasured | ClaimResult::NotJudgedAtThisScale => None,
        }
    }

    pub(super) fn of(d: Decision) -> Self {
        match d {
            Decision::Passed => ClaimResult::Reproduced,
            Decision::Failed => ClaimResult::Contradicted,
            Decision::Undecided => ClaimResult::NotEstablished,
        }
    }
}

/// Another reading judged: its measure, value and result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReadingOutcome {
    /// The reading, in words.
    pub reading: String,
    /// Its measure.
    pub measure: String,
    /// The measurement (absent when not measured).
    pub measured: Option<Estimate>,
    /// The result under the claim's rule.
    pub result: ClaimResult,
}

/// A claim with its measurement and result: an entry of `claims` in `<name>.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimOutcome {
    /// Stable identifier.
    pub key: String,
    /// The statement as printed.
    pub statement: String,
    /// Where in the paper.
    pub place: String,
    /// The paper's value as printed.
    pub paper: String,
    /// The paper's wording (absent in outcomes written before phrases existed).
    #[serde(default)]
    pub phrase: Option<Phrase>,
    /// The paper's value as a number.
    pub paper_value: Option<f64>,
    /// The measure (empty when not measured).
    pub measure: String,
    /// What the measure is (absent in outcomes written before units existed).
    #[serde(default)]
    pub unit: Option<Unit>,
    /// The realizations behind the measure's error bar, where the scene lists them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub realizations: Option<usize>,
    /// The interval's half width in standard errors: the validation's significance, or
    /// Student's t at the same coverage for fewer than four realizations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interval_z: Option<f64>,
    /// What the error bar measures.
    #[serde(default)]
    pub error: ErrorKind,
    /// The hash of the rule it was decided under (the claim's `rule_sha256`); absent in
    /// outcomes written before the register.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule_sha256: Option<String>,
    /// Why the rule departs from its phrase's, where it does.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub departs: Option<String>,
    /// The rule's amendments, each with its reason.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub amendments: Vec<Amendment>,
    /// The commit of the sample-size plan that set the claim's realizations, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub planned: Option<String>,
    /// The paper's scene, where it differs.
    pub scene: Option<String>,
    /// The reading taken.
    #[serde(default)]
    pub reading: Option<String>,
    /// The rule.
    pub rule: Rule,
    /// The measurement (absent when not measured).
    pub measured: Option<Estimate>,
    /// For an ordering (`exceeds`), the difference of the two measures the rule judged.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub difference: Option<Estimate>,
    /// The result.
    pub result: ClaimResult,
    /// Evidence, a consistency check, or a statement the paper makes two ways.
    #[serde(default)]
    pub kind: ClaimKind,
    /// Why not measured, not judged or not established, and what would decide it; the
    /// reason a consistency check holds by construction; how the paper contradicts
    /// itself.
    pub why: Option<String>,
    /// The other readings, judged by the same rule.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub readings: Vec<ReadingOutcome>,
}

impl ClaimOutcome {
    /// The estimate the rule judged: the measurement, or for an ordering the difference.
    pub fn judged(&self) -> Option<Estimate> {
        self.difference.or(self.measured)
    }

    /// The region the rule asserts for [`ClaimOutcome::judged`].
    pub fn region(&self) -> Option<Region> {
        match &self.rule {
            Rule::Exceeds(_) => Some(Region::above(0.0)),
            r => r.region(self.paper_value),
        }
    }

    /// What would decide a claim the data do not establish, in a few words: the
    /// realizations (a factor, or a count below four), or more loads for a fitted law; for
    /// the page's table.
    pub fn would_decide(&self) -> Option<String> {
        if self.result != ClaimResult::NotEstablished {
            return None;
        }
        let (e, region) = (self.judged()?, self.region()?);
        if !(e.value.is_finite() && e.has_error()) {
            return Some("2 or more realizations".into());
        }
        let margin = region.margin(e.value);
        if !(margin.is_finite() && margin > 0.0) {
            return Some("no count of realizations (on the edge)".into());
        }
        if self.error == ErrorKind::Fit {
            return Some("more loads or targets (a fit's scatter)".into());
        }
        let z = self.interval_z.unwrap_or(3.0);
        Some(match self.realizations {
            Some(n) if n < 4 => {
                let base = normal_z(z, n);
                format!(
                    "{} realizations (now {n})",
                    realizations_needed(e.std_error, n, margin, base)
                )
            }
            _ => format!(
                "{:.1} x the realizations",
                ((z * e.std_error / margin).powi(2)).max(1.0)
            ),
        })
    }

    /// The side of the rule's edge the value lies on, for a claim not established.
    pub fn leans(&self) -> Option<&'static str> {
        let (e, region) = (self.judged()?, self.region()?);
        (self.result == ClaimResult::NotEstablished && e.value.is_finite()).then(|| {
            if region.contains(e.value) {
                "inside"
            } else {
                "outside"
            }
        })
    }
}

/// The claims' part in a validation's reproduction, in three-valued logic: every judged
/// claim that is evidence (reproduced, contradicted or not established); consistency
/// checks and statements the paper makes two ways take no part.
pub fn decision(claims: &[ClaimOutcome]) -> Decision {
    Decision::all(
        claims
            .iter()
            .filter(|c| c.kind == ClaimKind::Evidence)
            .filter_map(|c| c.result.decision()),
    )
}

/// The evidence claims that keep a validation from being reproduced: the contradicted
/// ones if any, else the not established ones.
pub fn deciding(claims: &[ClaimOutcome]) -> Vec<&ClaimOutcome> {
    let evidence = || claims.iter().filter(|c| c.kind == ClaimKind::Evidence);
    let contradicted: Vec<&ClaimOutcome> = evidence()
        .filter(|c| c.result == ClaimResult::Contradicted)
        .collect();
    if contradicted.is_empty() {
        evidence()
            .filter(|c| c.result == ClaimResult::NotEstablished)
            .collect()
    } else {
        contradicted
    }
}
