//! The paper's claims as data: every quantitative statement of the paper that a validation
//! tests, with its place in the paper, the paper's value as printed, the measure it is set
//! against and the rule that decides it (`[[claims]]` in `validations/<name>.toml`).
//!
//! One function decides every claim, [`ClaimSpec::judge`], through the decision rule of
//! every verdict and check ([`crate::stats::decide`]): a claim is a statement about the
//! interval `value +- z std_error` of its measure, `z` the validation's significance
//! unless the claim states its own. The result is reproduced, not reproduced, undecided
//! (no error bar), not measured (the measure is absent, or the claim says why it cannot be
//! measured here), or not judged at this scale (a magnitude the paper states for its own
//! scene, shown but not judged on the reduced scene).
//!
//! The rules ([`Rule`]):
//!
//! * `near = r`: the paper's value within a relative tolerance `r` or `z` standard errors,
//!   `|v - P| <= z s + r |P|`;
//! * `above = t`, `below = t`: the interval lies above (below) `t`, a sign or a strict
//!   bound: `v - z s > t` (`v + z s < t`);
//! * `at_most = t`, `at_least = t`: the interval reaches `t` or below (above), a bound the
//!   measurement must not contradict: `v - z s <= t` (`v + z s >= t`);
//! * `within = [lo, hi]`: the interval overlaps `[lo, hi]`;
//! * `exceeds = "MEASURE"`: an ordering, the difference of the two measures above 0.
//!
//! A measure names where the number is: `headline`, `detail:KEY` (or `detail:KEY@N` for
//! the detail measured on the `N x N` grid), `study:STUDY/ROW/COLUMN` (a cell of a
//! [`Study`]) or `cross_check:SOLVER`.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::experiments::study::{self, Study};
use crate::experiments::Detail;
use crate::stats::{decide, Claim, Decision, Estimate};

/// How a claim is decided from its measure's interval `value +- z std_error`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Rule {
    /// Within a relative tolerance of the paper's value, or `z` standard errors.
    Near(f64),
    /// Above a threshold (a sign, or a strict bound).
    Above(f64),
    /// Below a threshold.
    Below(f64),
    /// Not contradicting an upper bound.
    AtMost(f64),
    /// Not contradicting a lower bound.
    AtLeast(f64),
    /// Overlapping a range.
    Within((f64, f64)),
    /// Larger than another measure.
    Exceeds(String),
    /// Away from a value: the interval excludes it (a statement that a law is violated,
    /// without a direction).
    Differs(f64),
}

/// One statement of the paper: `[[claims]]` in a definition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClaimSpec {
    /// Stable identifier, unique within the validation.
    pub key: String,
    /// The statement, as the paper prints it (quoted or closely paraphrased).
    pub statement: String,
    /// Where: equation, figure, section, and the lines of the paper's source.
    pub place: String,
    /// The paper's value as printed ("~62%", "> 0", "within 3%").
    pub paper: String,
    /// The paper's value as a number, where it states one.
    #[serde(default)]
    pub value: Option<f64>,
    /// The measure it is compared with (absent: not measured, see `not_measured`).
    #[serde(default)]
    pub measure: Option<String>,
    /// The rule.
    pub rule: Rule,
    /// The paper's scene, where it differs from the validation's.
    #[serde(default)]
    pub scene: Option<String>,
    /// The reading taken where the paper leaves the method open, with the line that
    /// implies it (fixed from the text, before the value is seen).
    #[serde(default)]
    pub reading: Option<String>,
    /// Why the claim is not measured here (with no measure).
    #[serde(default)]
    pub not_measured: Option<String>,
    /// Whether the reduced scene judges it: false for a magnitude the paper states for its
    /// own, larger scene (the reduced value is shown, not judged).
    #[serde(default = "yes")]
    pub reduced: bool,
    /// Significance in standard errors, if not the validation's.
    #[serde(default)]
    pub significance: Option<f64>,
}

fn yes() -> bool {
    true
}

/// What a claim's measurement says.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClaimResult {
    /// The measurement reproduces the statement.
    Reproduced,
    /// It contradicts it.
    NotReproduced,
    /// No error bar (one realization), so the rule cannot decide.
    Undecided,
    /// There is nothing to measure it with here.
    NotMeasured,
    /// A magnitude of the paper's scene, measured on the reduced scene: shown, not judged.
    NotJudgedAtThisScale,
}

impl ClaimResult {
    /// The result in words, as the tables print it.
    pub fn text(self) -> &'static str {
        match self {
            ClaimResult::Reproduced => "yes",
            ClaimResult::NotReproduced => "no",
            ClaimResult::Undecided => "undecided",
            ClaimResult::NotMeasured => "not measured",
            ClaimResult::NotJudgedAtThisScale => "not judged (reduced scene)",
        }
    }

    /// Its part in the validation's reproduction: passed, failed or undecided; `None`
    /// where it takes no part (not measured, not judged at this scale).
    pub fn decision(self) -> Option<Decision> {
        match self {
            ClaimResult::Reproduced => Some(Decision::Passed),
            ClaimResult::NotReproduced => Some(Decision::Failed),
            ClaimResult::Undecided => Some(Decision::Undecided),
            ClaimResult::NotMeasured | ClaimResult::NotJudgedAtThisScale => None,
        }
    }
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
    /// The paper's value as a number.
    pub paper_value: Option<f64>,
    /// The measure (empty when not measured).
    pub measure: String,
    /// The paper's scene, where it differs.
    pub scene: Option<String>,
    /// The reading taken.
    #[serde(default)]
    pub reading: Option<String>,
    /// The rule.
    pub rule: Rule,
    /// The measurement (absent when not measured).
    pub measured: Option<Estimate>,
    /// The result.
    pub result: ClaimResult,
    /// Why not measured or not judged, where that is the result.
    pub why: Option<String>,
}

/// Where a claim finds its numbers: a run's headline, details, studies and cross-checks.
pub struct Measures<'a> {
    /// The headline statistic.
    pub headline: Estimate,
    /// The secondary statistics.
    pub details: &'a [Detail],
    /// The studies.
    pub studies: &'a [Study],
    /// The other solvers' headlines: (solver, estimate).
    pub cross_checks: Vec<(String, Estimate)>,
}

impl Measures<'_> {
    /// The estimate a measure names, if the run has it.
    pub fn get(&self, measure: &str) -> Option<Estimate> {
        let (kind, rest) = measure.split_once(':').unwrap_or((measure, ""));
        match kind {
            "headline" => Some(self.headline),
            "detail" => {
                let (key, grid) = match rest.split_once('@') {
                    Some((k, g)) => (k, g.parse::<usize>().ok()),
                    None => (rest, None),
                };
                self.details
                    .iter()
                    .find(|d| d.key == key && (grid.is_none() || d.grid == grid))
                    .map(|d| d.value)
            }
            "study" => {
                let mut parts = rest.splitn(3, '/');
                let (s, r, c) = (parts.next()?, parts.next()?, parts.next()?);
                study::find(self.studies, s)?.cell(r, c)?.estimate()
            }
            "cross_check" => self
                .cross_checks
                .iter()
                .find(|(s, _)| s == rest)
                .map(|(_, e)| *e),
            _ => None,
        }
    }
}

/// Checks a measure's form: one of the kinds above.
fn check_measure(field: &str, measure: &str) -> Result<()> {
    let (kind, rest) = measure.split_once(':').unwrap_or((measure, ""));
    let ok = match kind {
        "headline" => rest.is_empty(),
        "detail" | "cross_check" => !rest.is_empty(),
        "study" => rest.splitn(3, '/').filter(|p| !p.is_empty()).count() == 3,
        _ => false,
    };
    if ok {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            measure,
            "headline, detail:KEY[@N], study:STUDY/ROW/COLUMN or cross_check:SOLVER",
        ))
    }
}

impl ClaimSpec {
    /// Checks the claim's fields; errors name the claim and the field.
    pub fn validate(&self) -> Result<()> {
        let field = |f: &str| format!("claims.{}.{f}", self.key);
        if self.key.is_empty() {
            return Err(Error::invalid("claims.key", "\"\"", "a non-empty key"));
        }
        match (&self.measure, &self.not_measured) {
            (Some(m), None) => check_measure(&field("measure"), m)?,
            (None, Some(_)) => {}
            (Some(_), Some(_)) => {
                return Err(Error::invalid(
                    &field("not_measured"),
                    "a reason beside a measure",
                    "either a measure or a reason why there is none",
                ))
            }
            (None, None) => {
                return Err(Error::invalid(
                    &field("measure"),
                    "none",
                    "a measure, or not_measured with the reason",
                ))
            }
        }
        match &self.rule {
            Rule::Near(r) if !(r.is_finite() && *r >= 0.0) => {
                return Err(Error::invalid(
                    &field("rule.near"),
                    r,
                    "a relative tolerance >= 0",
                ))
            }
            Rule::Near(_) if self.value.is_none() => {
                return Err(Error::invalid(
                    &field("value"),
                    "none",
                    "the paper's value, which rule `near` compares with",
                ))
            }
            // Refused when lo > hi or either is not a number.
            Rule::Within((lo, hi)) if lo.partial_cmp(hi).is_none_or(|o| o.is_gt()) => {
                return Err(Error::invalid(
                    &field("rule.within"),
                    format!("[{lo}, {hi}]"),
                    "a range [lo, hi] with lo <= hi",
                ))
            }
            Rule::Exceeds(m) => check_measure(&field("rule.exceeds"), m)?,
            _ => {}
        }
        if let Some(z) = self.significance {
            if !(z.is_finite() && z >= 0.0) {
                return Err(Error::invalid(
                    &field("significance"),
                    z,
                    "a number of standard errors >= 0",
                ));
            }
        }
        Ok(())
    }

    /// Judges the claim on a run (of the reduced scene when `reduced_scene`), at the
    /// validation's significance `z` unless the claim states its own: the one rule of every
    /// claim.
    pub fn judge(&self, measures: &Measures, reduced_scene: bool, z: f64) -> ClaimOutcome {
        let z = self.significance.unwrap_or(z);
        let measured = self.measure.as_deref().and_then(|m| measures.get(m));
        let (result, why) = match (&self.measure, measured) {
            (None, _) => (ClaimResult::NotMeasured, self.not_measured.clone()),
            (Some(m), None) => (
                ClaimResult::NotMeasured,
                Some(format!("this run has no {m}")),
            ),
            (Some(_), Some(_)) if reduced_scene && !self.reduced => (
                ClaimResult::NotJudgedAtThisScale,
                Some("a magnitude of the paper's scene: judged on the full scene".into()),
            ),
            (Some(_), Some(e)) => match self.decide(e, measures, z) {
                Decision::Passed => (ClaimResult::Reproduced, None),
                Decision::Failed => (ClaimResult::NotReproduced, None),
                Decision::Undecided => (
                    ClaimResult::Undecided,
                    Some("no error bar (one realization) or no value".into()),
                ),
            },
        };
        ClaimOutcome {
            key: self.key.clone(),
            statement: self.statement.clone(),
            place: self.place.clone(),
            paper: self.paper.clone(),
            paper_value: self.value,
            measure: self.measure.clone().unwrap_or_default(),
            scene: self.scene.clone(),
            reading: self.reading.clone(),
            rule: self.rule.clone(),
            measured,
            result,
            why,
        }
    }

    /// The rule applied to the measured estimate `e`.
    fn decide(&self, e: Estimate, measures: &Measures, z: f64) -> Decision {
        let claim = match &self.rule {
            Rule::Near(r) => {
                let target = self.value.unwrap_or(f64::NAN);
                Claim::Near {
                    target,
                    tolerance: r * target.abs(),
                }
            }
            Rule::Above(t) => Claim::Above(*t),
            Rule::Below(t) => Claim::Below(*t),
            Rule::AtMost(t) => return !decide(e, Claim::Above(*t), z),
            Rule::AtLeast(t) => return !decide(e, Claim::Below(*t), z),
            Rule::Within((lo, hi)) => Claim::Overlaps(*lo, *hi),
            Rule::Differs(t) => return !decide(e, Claim::Overlaps(*t, *t), z),
            Rule::Exceeds(other) => {
                return match measures.get(other) {
                    Some(o) => decide(Estimate::difference(e, o), Claim::Above(0.0), z),
                    None => Decision::Undecided,
                }
            }
        };
        decide(e, claim, z)
    }
}

/// Checks a definition's claims: each valid, keys unique.
pub fn validate_claims(claims: &[ClaimSpec]) -> Result<()> {
    for (k, c) in claims.iter().enumerate() {
        c.validate()?;
        if claims[..k].iter().any(|o| o.key == c.key) {
            return Err(Error::invalid("claims.key", &c.key, "a key used once"));
        }
    }
    Ok(())
}

/// The claims' part in a validation's reproduction, in three-valued logic: every judged
/// claim (reproduced, not reproduced or undecided).
pub fn decision(claims: &[ClaimOutcome]) -> Decision {
    Decision::all(claims.iter().filter_map(|c| c.result.decision()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(rule: Rule, value: Option<f64>) -> ClaimSpec {
        ClaimSpec {
            key: "k".into(),
            statement: "s".into(),
            place: "p".into(),
            paper: "~62%".into(),
            value,
            measure: Some("headline".into()),
            rule,
            scene: None,
            reading: None,
            not_measured: None,
            reduced: true,
            significance: None,
        }
    }

    fn measures(headline: Estimate) -> Measures<'static> {
        Measures {
            headline,
            details: &[],
            studies: &[],
            cross_checks: vec![("cg".into(), Estimate::new(0.5, 0.01))],
        }
    }

    fn result(rule: Rule, value: Option<f64>, e: Estimate) -> ClaimResult {
        spec(rule, value).judge(&measures(e), false, 3.0).result
    }

    #[test]
    fn a_share_far_from_the_papers_value_is_not_reproduced() {
        let near = || Rule::Near(0.1);
        let e = |v| Estimate::new(v, 0.006);
        assert_eq!(
            result(near(), Some(0.62), e(0.644)),
            ClaimResult::Reproduced
        );
        assert_eq!(
            result(near(), Some(0.62), e(0.20)),
            ClaimResult::NotReproduced
        );
        // Within 10% plus three standard errors, not beyond.
        assert_eq!(result(near(), Some(1.0), e(0.882)), ClaimResult::Reproduced);
        assert_eq!(
            result(near(), Some(1.0), e(0.88)),
            ClaimResult::NotReproduced
        );
        // No error bar: undecided, whatever the value.
        let one = Estimate::new(0.62, f64::NAN);
        assert_eq!(result(near(), Some(0.62), one), ClaimResult::Undecided);
    }

    #[test]
    fn signs_bounds_ranges_and_orderings_read_the_interval() {
        let e = Estimate::new(1.0, 0.1);
        assert_eq!(result(Rule::Above(0.6), None, e), ClaimResult::Reproduced);
        assert_eq!(
            result(Rule::Above(0.8), None, e),
            ClaimResult::NotReproduced
        );
        assert_eq!(result(Rule::Below(1.4), None, e), ClaimResult::Reproduced);
        // A bound the interval reaches is not contradicted; one it misses is.
        assert_eq!(result(Rule::AtMost(0.8), None, e), ClaimResult::Reproduced);
        assert_eq!(
            result(Rule::AtMost(0.6), None, e),
            ClaimResult::NotReproduced
        );
        assert_eq!(result(Rule::AtLeast(1.2), None, e), ClaimResult::Reproduced);
        assert_eq!(
            result(Rule::AtLeast(1.4), None, e),
            ClaimResult::NotReproduced
        );
        assert_eq!(
            result(Rule::Within((1.2, 2.0)), None, e),
            ClaimResult::Reproduced
        );
        // Away from a value only when the interval excludes it.
        assert_eq!(result(Rule::Differs(0.6), None, e), ClaimResult::Reproduced);
        assert_eq!(
            result(Rule::Differs(1.2), None, e),
            ClaimResult::NotReproduced
        );
        let exceeds = |m: &str| Rule::Exceeds(m.into());
        assert_eq!(
            result(exceeds("cross_check:cg"), None, e),
            ClaimResult::Reproduced
        );
        assert_eq!(
            result(exceeds("cross_check:fire"), None, e),
            ClaimResult::Undecided
        );
    }

    #[test]
    fn unmeasured_and_reduced_claims_take_no_part() {
        let mut s = spec(Rule::Near(0.1), Some(0.62));
        s.reduced = false;
        let m = measures(Estimate::new(0.2, 0.01));
        let reduced = s.judge(&m, true, 3.0);
        assert_eq!(reduced.result, ClaimResult::NotJudgedAtThisScale);
        assert_eq!(reduced.measured, Some(Estimate::new(0.2, 0.01)));
        assert_eq!(s.judge(&m, false, 3.0).result, ClaimResult::NotReproduced);
        s.measure = Some("detail:absent".into());
        let absent = s.judge(&m, false, 3.0);
        assert_eq!(absent.result, ClaimResult::NotMeasured);
        assert!(absent.why.as_ref().unwrap().contains("detail:absent"));
        assert_eq!(decision(std::slice::from_ref(&absent)), Decision::Passed);
        let failed = ClaimOutcome {
            result: ClaimResult::NotReproduced,
            ..absent
        };
        assert_eq!(decision(&[reduced, failed]), Decision::Failed);
    }

    #[test]
    fn bad_claims_are_refused_naming_the_field() {
        let refused = |s: ClaimSpec, field: &str| {
            let e = validate_claims(&[s]).unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        };
        refused(spec(Rule::Near(0.1), None), "claims.k.value");
        refused(spec(Rule::Near(-0.1), Some(1.0)), "claims.k.rule.near");
        refused(spec(Rule::Within((2.0, 1.0)), None), "claims.k.rule.within");
        let mut s = spec(Rule::Above(0.0), None);
        s.measure = Some("study:a/b".into());
        refused(s.clone(), "claims.k.measure");
        s.measure = None;
        refused(s.clone(), "claims.k.measure");
        s.not_measured = Some("why".into());
        assert!(validate_claims(&[s.clone()]).is_ok());
        s.measure = Some("headline".into());
        refused(s, "claims.k.not_measured");
        let a = spec(Rule::Above(0.0), None);
        let e = validate_claims(&[a.clone(), a]).unwrap_err().to_string();
        assert!(e.contains("claims.key"), "{e}");
    }
}
