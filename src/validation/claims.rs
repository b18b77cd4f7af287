//! The paper's claims as data: every checkable statement of the paper that a validation
//! tests, with its place (or places) in the paper, the paper's value as printed, the
//! phrase the paper states it in, the measure it is set against and the rule that decides
//! it (`[[claims]]` in `validations/<name>.toml`).
//!
//! One function decides every claim, [`ClaimSpec::judge`], as a referee would: a claim
//! asserts that its measure lies in a region of values (the rule's), and the interval
//! `value +- z std_error` of the measure, `z` the validation's significance unless the
//! claim states its own, either lies wholly inside it (**reproduced**: the data establish
//! the statement), wholly outside it (**contradicted**: the data exclude it), or neither
//! (**not established**, with what would decide it) ([`crate::stats::establish`]).
//!
//! The rules ([`Rule`]) and their regions:
//!
//! * `near = r`: `[P - r |P|, P + r |P|]`, `P` the paper's value;
//! * `above = t`, `below = t`: `(t, inf)`, `(-inf, t)`: a sign, or a strict bound;
//! * `at_least = t`, `at_most = t`: `[t, inf)`, `(-inf, t]`;
//! * `within = [lo, hi]`: `[lo, hi]`;
//! * `exceeds = "MEASURE"`: the difference of the two measures in `(0, inf)`;
//! * `differs = t`: every value but `t` (a law stated as violated, without a direction);
//!   never contradicted.
//!
//! Each claim states the phrase the paper uses ([`Phrase`]), and each phrase has one rule
//! ([`Phrase::fits`]): a claim whose rule is not its phrase's is refused at load unless it
//! says why it departs (`departs`). A claim may name the alternative its test must be
//! able to exclude (`alternative`: zero for a sign, another scene's value the paper gives,
//! a floor built into the measure); a rule whose region holds the alternative cannot tell
//! the statement from it, and the claim reads not established (does not discriminate). A
//! statement true by construction is a consistency check (`consistency`, with the reason):
//! shown, counted apart, not evidence. Where the paper contradicts itself, one claim
//! carries both readings (`inconsistent`), shown and counted apart. Where the reading
//! decides the verdict, the other readings are judged by the same rule and shown beside it
//! (`other_readings`).
//!
//! A measure names where the number is: `headline`, `detail:KEY` (or `detail:KEY@N` for
//! the detail measured on the `N x N` grid), `study:STUDY/ROW/COLUMN` (a cell of a
//! [`crate::experiments::study::Study`]) or `cross_check:SOLVER`. Beyond its form, each measure a claim judged on a
//! scene names is checked against the keys its experiment declares for that scene
//! ([`crate::experiments::Keys`], [`check_declared`]) when the definition loads: a mistyped
//! key is an error naming the claim and the field, never "not measured".

use serde::{Deserialize, Serialize};

pub use super::phrase::{Phrase, Rule, ABOUT, ORDER, PHRASES};
use crate::error::{Error, Result};
use crate::stats::{establish, Decision, Estimate, Region};

pub use super::measures::Measures;
use super::measures::{check_measure, declared};
use crate::experiments::Keys;

/// A value the claim's test must be able to exclude.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Alternative {
    /// The value.
    pub value: f64,
    /// What it is (another scene's value given by the paper, a floor of the measure).
    pub what: String,
}

/// Another reading of the statement, judged on its own measure by the claim's rule, or by
/// its own where the reading gives the statement another direction (the paper's other
/// wording of it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OtherReading {
    /// The reading, in words.
    pub reading: String,
    /// Its measure.
    pub measure: String,
    /// Its rule, where not the claim's.
    #[serde(default)]
    pub rule: Option<Rule>,
}

/// One statement of the paper: `[[claims]]` in a definition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClaimSpec {
    /// Stable identifier, unique within the validation.
    pub key: String,
    /// The statement, as the paper prints it (quoted or closely paraphrased).
    pub statement: String,
    /// Where: equation, figure, section, and the lines of the paper's source; the places
    /// of one statement (a caption and the text) joined by "; ".
    pub place: String,
    /// The paper's value as printed ("~62%", "> 0", "within 3%").
    pub paper: String,
    /// The paper's wording, which fixes the rule.
    pub phrase: Phrase,
    /// The paper's value as a number, where it states one.
    #[serde(default)]
    pub value: Option<f64>,
    /// The measure it is compared with (absent: not measured, see `not_measured`).
    #[serde(default)]
    pub measure: Option<String>,
    /// The rule.
    pub rule: Rule,
    /// Why the rule departs from its phrase's, where it does.
    #[serde(default)]
    pub departs: Option<String>,
    /// The value the test must be able to exclude.
    #[serde(default)]
    pub alternative: Option<Alternative>,
    /// Why the statement holds by construction: a consistency check, not evidence.
    #[serde(default)]
    pub consistency: Option<String>,
    /// How the paper contradicts itself on this statement (both readings are shown).
    #[serde(default)]
    pub inconsistent: Option<String>,
    /// Other readings, shown beside the verdict.
    #[serde(default)]
    pub other_readings: Vec<OtherReading>,
    /// The paper's scene, where it differs from the validation's.
    #[serde(default)]
    pub scene: Option<String>,
    /// The reading taken where the paper leaves the method open, with the line that
    /// implies it (fixed from the text, before the value is seen).
    #[serde(default)]
    pub reading: Option<String>,
    /// Why the claim is not measured here (with no measure): the run it needs and its
    /// cost.
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

    fn of(d: Decision) -> Self {
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

/// Checks that every measure that the claims judged on a scene name (each claim's own, an
/// ordering's second measure, each other reading's) is one that a run of the scene has by
/// the keys its experiment declares (`keys`); on the reduced scene (`reduced_scene`) the
/// claims it does not judge (`reduced = false`) are left out. `fixed_solver`: the scene
/// fixes its solver, so a run has no cross-checks.
///
/// # Errors
///
/// A measure the experiment does not declare, naming the claim and the field and listing
/// the declared keys closest to the one named.
pub fn check_declared(
    claims: &[ClaimSpec],
    keys: &Keys,
    reduced_scene: bool,
    fixed_solver: bool,
) -> Result<()> {
    for c in claims.iter().filter(|c| c.reduced || !reduced_scene) {
        let Some(measure) = &c.measure else { continue };
        let mut named = vec![("measure".to_string(), measure)];
        if let Rule::Exceeds(other) = &c.rule {
            named.push(("rule.exceeds".into(), other));
        }
        for (k, r) in c.other_readings.iter().enumerate() {
            named.push((format!("other_readings[{k}].measure"), &r.measure));
        }
        for (field, m) in named {
            declared(m, keys, fixed_solver).map_err(|allowed| {
                Error::invalid(&format!("claims.{}.{field}", c.key), m, allowed)
            })?;
        }
    }
    Ok(())
}

impl ClaimSpec {
    /// Checks the claim's fields in a validation of resolution `resolution`; errors name
    /// the claim and the field.
    pub fn validate(&self, resolution: f64) -> Result<()> {
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
        for (k, r) in self.other_readings.iter().enumerate() {
            check_measure(&field(&format!("other_readings[{k}].measure")), &r.measure)?;
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
        if !self.phrase.fits(&self.rule, self.value, resolution) && self.departs.is_none() {
            return Err(Error::invalid(
                &field("rule"),
                format!("{:?} for phrase \"{}\"", self.rule, self.phrase.name()),
                format!(
                    "the phrase's rule, {}, or `departs` saying why not",
                    self.phrase.rule_text()
                ),
            ));
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
        if self.consistency.is_some() && self.inconsistent.is_some() {
            return Err(Error::invalid(
                &field("inconsistent"),
                "beside consistency",
                "a consistency check or a statement the paper makes two ways, not both",
            ));
        }
        Ok(())
    }

    /// What the claim counts as.
    pub fn kind(&self) -> ClaimKind {
        if self.consistency.is_some() {
            ClaimKind::Consistency
        } else if self.inconsistent.is_some() {
            ClaimKind::Inconsistent
        } else {
            ClaimKind::Evidence
        }
    }

    /// Judges the claim on a run (of the reduced scene when `reduced_scene`), at the
    /// validation's significance `z` unless the claim states its own: the one rule of every
    /// claim.
    pub fn judge(&self, measures: &Measures, reduced_scene: bool, z: f64) -> ClaimOutcome {
        let z = self.significance.unwrap_or(z);
        let measured = self.measure.as_deref().and_then(|m| measures.get(m));
        let (result, why) = match (&self.measure, measured) {
            (None, _) => (ClaimResult::NotMeasured, self.not_measured.clone()),
            // Not judged here whether or not the reduced scene has the measure: a load or
            // grid of the paper's own scene often exists at full scale only.
            (Some(_), _) if reduced_scene && !self.reduced => (
                ClaimResult::NotJudgedAtThisScale,
                Some("a magnitude of the paper's scene: judged on the full scene".into()),
            ),
            (Some(m), None) => (
                ClaimResult::NotMeasured,
                Some(match measures.pending.iter().find(|p| p.gives(m)) {
                    Some(p) => p.why(),
                    None => format!("this run has no {m}"),
                }),
            ),
            (Some(_), Some(e)) => self.verdict(e, measures, z),
        };
        let why = match self.kind() {
            ClaimKind::Consistency => Some(join(
                format!(
                    "consistency check: {}",
                    self.consistency.as_deref().unwrap_or("")
                ),
                why,
            )),
            ClaimKind::Inconsistent => Some(join(
                format!(
                    "the paper is inconsistent: {}",
                    self.inconsistent.as_deref().unwrap_or("")
                ),
                why,
            )),
            ClaimKind::Evidence => why,
        };
        let readings = self
            .other_readings
            .iter()
            .map(|r| {
                let measured = measures.get(&r.measure);
                let result = match measured {
                    _ if reduced_scene && !self.reduced => ClaimResult::NotJudgedAtThisScale,
                    None => ClaimResult::NotMeasured,
                    Some(e) => match &r.rule {
                        Some(rule) => {
                            ClaimSpec {
                                rule: rule.clone(),
                                ..self.clone()
                            }
                            .verdict(e, measures, z)
                            .0
                        }
                        None => self.verdict(e, measures, z).0,
                    },
                };
                ReadingOutcome {
                    reading: r.reading.clone(),
                    measure: r.measure.clone(),
                    measured,
                    result,
                }
            })
            .collect();
        ClaimOutcome {
            key: self.key.clone(),
            statement: self.statement.clone(),
            place: self.place.clone(),
            paper: self.paper.clone(),
            phrase: Some(self.phrase),
            paper_value: self.value,
            measure: self.measure.clone().unwrap_or_default(),
            scene: self.scene.clone(),
            reading: self.reading.clone(),
            rule: self.rule.clone(),
            measured,
            result,
            kind: self.kind(),
            why,
            readings,
        }
    }

    /// The rule applied to the measured estimate `e`: the result and, where it is not
    /// established, why and what would decide it.
    fn verdict(&self, e: Estimate, measures: &Measures, z: f64) -> (ClaimResult, Option<String>) {
        let (e, region) = match (&self.rule, self.rule.region(self.value)) {
            (Rule::Exceeds(other), _) => match measures.get(other) {
                Some(o) => (Estimate::difference(e, o), Region::above(0.0)),
                None => {
                    return (
                        ClaimResult::NotEstablished,
                        Some(format!("this run has no {other} to compare with")),
                    )
                }
            },
            (_, Some(r)) => (e, r),
            (_, None) => unreachable!("every rule but an ordering has a region"),
        };
        if let Some(alt) = &self.alternative {
            if region.contains(alt.value) {
                return (
                    ClaimResult::NotEstablished,
                    Some(format!(
                        "does not discriminate: the rule's region also holds the alternative, \
                         {} = {}; a reading that excludes it would decide",
                        alt.what, alt.value
                    )),
                );
            }
        }
        let result = ClaimResult::of(establish(e, region, z));
        let why = (result == ClaimResult::NotEstablished).then(|| decider(e, region, z));
        (result, why)
    }
}

/// What would decide a claim the data do not establish: realizations enough to shrink
/// the interval inside (or outside) the region, if the value held.
fn decider(e: Estimate, region: Region, z: f64) -> String {
    if !(e.value.is_finite() && e.has_error()) {
        return "no error bar (one realization): two or more realizations would decide".into();
    }
    let margin = region.margin(e.value);
    let inside = region.contains(e.value);
    let goal = if inside { "establish" } else { "contradict" };
    if !(margin.is_finite() && margin > 0.0) {
        return "the value lies on the region's edge: no number of realizations decides".into();
    }
    let factor = (z * e.std_error / margin).powi(2);
    format!(
        "the interval +-{z} standard errors reaches both sides of the rule's edge; about \
         {:.1} times the realizations would {goal} it if the value held",
        factor.max(1.0)
    )
}

fn join(head: String, tail: Option<String>) -> String {
    match tail {
        Some(t) => format!("{head}; {t}"),
        None => head,
    }
}

/// Checks a definition's claims in a validation of resolution `resolution`: each valid,
/// keys unique.
pub fn validate_claims(claims: &[ClaimSpec], resolution: f64) -> Result<()> {
    for (k, c) in claims.iter().enumerate() {
        c.validate(resolution)?;
        if claims[..k].iter().any(|o| o.key == c.key) {
            return Err(Error::invalid("claims.key", &c.key, "a key used once"));
        }
    }
    Ok(())
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validation::measures::PendingPart;

    fn spec(phrase: Phrase, rule: Rule, value: Option<f64>) -> ClaimSpec {
        ClaimSpec {
            key: "k".into(),
            statement: "s".into(),
            place: "p".into(),
            paper: "~62%".into(),
            phrase,
            value,
            measure: Some("headline".into()),
            rule,
            departs: None,
            alternative: None,
            consistency: None,
            inconsistent: None,
            other_readings: Vec::new(),
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
            pending: &[],
        }
    }

    fn result(phrase: Phrase, rule: Rule, value: Option<f64>, e: Estimate) -> ClaimResult {
        spec(phrase, rule, value)
            .judge(&measures(e), false, 3.0)
            .result
    }

    #[test]
    fn about_is_established_inside_ten_percent_and_contradicted_outside() {
        let about = |e| result(Phrase::About, Rule::Near(0.1), Some(0.62), e);
        assert_eq!(about(Estimate::new(0.644, 0.0055)), ClaimResult::Reproduced);
        assert_eq!(about(Estimate::new(0.20, 0.006)), ClaimResult::Contradicted);
        // Reaching over the edge: not established, with what would decide it.
        let o = spec(Phrase::About, Rule::Near(0.1), Some(1.0)).judge(
            &measures(Estimate::new(0.934, 0.028)),
            false,
            3.0,
        );
        assert_eq!(o.result, ClaimResult::NotEstablished);
        assert!(o.why.unwrap().contains("times the realizations"));
        let one = Estimate::new(0.62, f64::NAN);
        assert_eq!(about(one), ClaimResult::NotEstablished);
    }

    #[test]
    fn signs_bounds_ranges_and_orderings_have_three_values() {
        let e = Estimate::new(1.0, 0.1);
        let r = |phrase, rule| result(phrase, rule, None, e);
        assert_eq!(
            r(Phrase::MoreThan, Rule::Above(0.6)),
            ClaimResult::Reproduced
        );
        assert_eq!(
            r(Phrase::MoreThan, Rule::Above(0.8)),
            ClaimResult::NotEstablished
        );
        assert_eq!(
            r(Phrase::MoreThan, Rule::Above(1.4)),
            ClaimResult::Contradicted
        );
        assert_eq!(
            r(Phrase::LessThan, Rule::Below(1.4)),
            ClaimResult::Reproduced
        );
        // A bound: established when the whole interval keeps it.
        assert_eq!(
            r(Phrase::Within, Rule::AtMost(1.4)),
            ClaimResult::Reproduced
        );
        assert_eq!(
            r(Phrase::Within, Rule::AtMost(1.2)),
            ClaimResult::NotEstablished
        );
        assert_eq!(
            r(Phrase::Within, Rule::AtMost(0.6)),
            ClaimResult::Contradicted
        );
        assert_eq!(r(Phrase::Sign, Rule::Differs(0.6)), ClaimResult::Reproduced);
        assert_eq!(
            r(Phrase::Sign, Rule::Differs(1.2)),
            ClaimResult::NotEstablished
        );
        let exceeds = |m: &str| Rule::Exceeds(m.into());
        assert_eq!(
            r(Phrase::Sign, exceeds("cross_check:cg")),
            ClaimResult::Reproduced
        );
        assert_eq!(
            r(Phrase::Sign, exceeds("cross_check:fire")),
            ClaimResult::NotEstablished
        );
        // e_frozen's "long wavelengths lose more": the paper's sign at 2.1 standard errors.
        let lose = Estimate::new(-0.186, 0.089);
        assert_eq!(
            result(Phrase::Sign, Rule::Below(0.0), None, lose),
            ClaimResult::NotEstablished
        );
    }

    #[test]
    fn a_test_that_also_passes_the_alternative_does_not_discriminate() {
        // The former reading of "overestimated by ~10%": E_exa / E_c about 0.91, a region
        // that holds 1.
        let mut s = spec(Phrase::About, Rule::Near(0.1), Some(0.91));
        s.alternative = Some(Alternative {
            value: 1.0,
            what: "a perfect theory".into(),
        });
        let o = s.judge(&measures(Estimate::new(0.935, 0.001)), false, 3.0);
        assert_eq!(o.result, ClaimResult::NotEstablished);
        assert!(o.why.unwrap().contains("does not discriminate"));
    }

    #[test]
    fn consistency_checks_and_inconsistent_statements_are_counted_apart() {
        let mut s = spec(Phrase::Sign, Rule::Below(0.0), None);
        s.consistency = Some("an identity".into());
        let o = s.judge(&measures(Estimate::new(1.0, 0.01)), false, 3.0);
        assert_eq!(
            (o.kind, o.result),
            (ClaimKind::Consistency, ClaimResult::Contradicted)
        );
        assert_eq!(decision(std::slice::from_ref(&o)), Decision::Passed);
        assert!(deciding(&[o]).is_empty());
        let mut s = spec(Phrase::Sign, Rule::Below(1.0), None);
        s.inconsistent = Some("caption and text".into());
        s.other_readings = vec![OtherReading {
            reading: "the text".into(),
            measure: "cross_check:cg".into(),
            rule: None,
        }];
        let o = s.judge(&measures(Estimate::new(0.9, 0.01)), false, 3.0);
        assert_eq!(o.kind, ClaimKind::Inconsistent);
        assert_eq!(o.readings[0].result, ClaimResult::Reproduced);
        assert!(o.why.unwrap().starts_with("the paper is inconsistent"));
    }

    #[test]
    fn unmeasured_and_reduced_claims_take_no_part() {
        let mut s = spec(Phrase::About, Rule::Near(0.1), Some(0.62));
        s.reduced = false;
        let m = measures(Estimate::new(0.2, 0.01));
        let reduced = s.judge(&m, true, 3.0);
        assert_eq!(reduced.result, ClaimResult::NotJudgedAtThisScale);
        assert_eq!(reduced.measured, Some(Estimate::new(0.2, 0.01)));
        assert_eq!(s.judge(&m, false, 3.0).result, ClaimResult::Contradicted);
        s.measure = Some("detail:absent".into());
        let absent = s.judge(&m, false, 3.0);
        assert_eq!(absent.result, ClaimResult::NotMeasured);
        assert!(absent.why.as_ref().unwrap().contains("detail:absent"));
        assert_eq!(decision(std::slice::from_ref(&absent)), Decision::Passed);
        let failed = ClaimOutcome {
            result: ClaimResult::Contradicted,
            ..absent
        };
        assert_eq!(decision(&[reduced, failed.clone()]), Decision::Failed);
        assert_eq!(deciding(&[failed]).len(), 1);
    }

    #[test]
    fn a_claim_of_the_full_scene_is_not_judged_on_the_reduced_one_measured_or_not() {
        let mut s = spec(Phrase::About, Rule::Near(0.1), Some(0.62));
        s.reduced = false;
        s.measure = Some("detail:a_load_of_the_full_scene".into());
        s.other_readings = vec![OtherReading {
            reading: "at another load".into(),
            measure: "detail:another_load_of_the_full_scene".into(),
            rule: None,
        }];
        let m = measures(Estimate::new(0.2, 0.01));
        let reduced = s.judge(&m, true, 3.0);
        assert_eq!(reduced.result, ClaimResult::NotJudgedAtThisScale);
        assert_eq!(
            reduced.readings[0].result,
            ClaimResult::NotJudgedAtThisScale
        );
        let full = s.judge(&m, false, 3.0);
        assert_eq!(full.result, ClaimResult::NotMeasured);
        assert_eq!(full.readings[0].result, ClaimResult::NotMeasured);
    }

    #[test]
    fn a_measure_of_a_pending_part_says_it_is_pending() {
        let pending = [PendingPart {
            name: "eps16".into(),
            jobs: 6,
            done: 2,
            core_hours_left: 13.04,
            measures: vec!["detail:eps16_share_ar0.14".into(), "study:variants".into()],
        }];
        let m = Measures {
            pending: &pending,
            ..measures(Estimate::new(0.2, 0.01))
        };
        let mut s = spec(Phrase::About, Rule::Near(0.1), Some(0.62));
        s.measure = Some("detail:eps16_share_ar0.14".into());
        let o = s.judge(&m, false, 3.0);
        assert_eq!(o.result, ClaimResult::NotMeasured);
        let why = o.why.unwrap();
        for word in ["pending", "eps16", "2 of 6", "13.0 core-hours"] {
            assert!(why.contains(word), "{word}: {why}");
        }
        // A study cell of the part, a detail on a grid: the part gives them too.
        assert!(pending[0].gives("study:variants/eps16_ar0.14/share"));
        assert!(pending[0].gives("detail:eps16_share_ar0.14@2048"));
        assert!(!pending[0].gives("detail:eps16_share_ar0.88"));
        assert!(!pending[0].gives("headline"));
        // Any other absent measure reads as before.
        s.measure = Some("detail:absent".into());
        assert!(s
            .judge(&m, false, 3.0)
            .why
            .unwrap()
            .contains("this run has no"));
    }

    #[test]
    fn each_phrase_has_one_rule() {
        let fits = |p: Phrase, r: Rule, v: Option<f64>| p.fits(&r, v, 0.02);
        assert!(fits(Phrase::About, Rule::Near(0.1), Some(0.62)));
        assert!(!fits(Phrase::About, Rule::Near(0.5), Some(0.62)));
        assert!(fits(Phrase::Order, Rule::Within((0.05, 0.45)), Some(0.15)));
        assert!(!fits(Phrase::Order, Rule::Within((0.05, 0.3)), Some(0.15)));
        assert!(!fits(Phrase::Order, Rule::AtMost(0.1), Some(0.1)));
        assert!(fits(Phrase::Negligible, Rule::Within((-0.02, 0.02)), None));
        assert!(fits(Phrase::All, Rule::AtLeast(0.98), None));
        assert!(!fits(Phrase::All, Rule::Near(0.1), Some(1.0)));
        assert!(fits(Phrase::Sign, Rule::Below(0.0), None));
        assert!(fits(Phrase::Within, Rule::AtMost(0.03), Some(0.03)));
        // A departure is refused without its reason, accepted with it.
        let mut s = spec(Phrase::About, Rule::Within((0.5, 0.7)), Some(0.62));
        let e = validate_claims(std::slice::from_ref(&s), 0.02)
            .unwrap_err()
            .to_string();
        assert!(e.contains("claims.k.rule") && e.contains("departs"), "{e}");
        s.departs = Some("why".into());
        assert!(validate_claims(&[s], 0.02).is_ok());
    }

    #[test]
    fn old_results_read_into_the_three_values() {
        let r: ClaimResult = serde_json::from_str("\"not_reproduced\"").unwrap();
        assert_eq!(r, ClaimResult::Contradicted);
        let r: ClaimResult = serde_json::from_str("\"undecided\"").unwrap();
        assert_eq!(r, ClaimResult::NotEstablished);
    }

    #[test]
    fn bad_claims_are_refused_naming_the_field() {
        let refused = |s: ClaimSpec, field: &str| {
            let e = validate_claims(&[s], 0.02).unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        };
        refused(spec(Phrase::About, Rule::Near(0.1), None), "claims.k.value");
        refused(
            spec(Phrase::About, Rule::Near(-0.1), Some(1.0)),
            "claims.k.rule.near",
        );
        refused(
            spec(Phrase::Order, Rule::Within((2.0, 1.0)), None),
            "claims.k.rule.within",
        );
        let mut s = spec(Phrase::Sign, Rule::Above(0.0), None);
        s.measure = Some("study:a/b".into());
        refused(s.clone(), "claims.k.measure");
        s.measure = None;
        refused(s.clone(), "claims.k.measure");
        s.not_measured = Some("why".into());
        assert!(validate_claims(&[s.clone()], 0.02).is_ok());
        s.measure = Some("headline".into());
        refused(s, "claims.k.not_measured");
        let a = spec(Phrase::Sign, Rule::Above(0.0), None);
        let e = validate_claims(&[a.clone(), a], 0.02)
            .unwrap_err()
            .to_string();
        assert!(e.contains("claims.key"), "{e}");
    }
}
