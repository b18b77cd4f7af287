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
pub use super::unit::{Unit, UNITS};
use crate::error::{Error, Result};
use crate::stats::Region;

pub use super::claim_outcome::{
    deciding, decision, Amendment, ClaimKind, ClaimOutcome, ClaimResult, ErrorKind, ReadingOutcome,
};
pub use super::interval::{interval_z, realizations_needed};
use super::measures::declared;
pub use super::measures::{Measure, Measures};
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
    pub measure: Measure,
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
    /// The paper's value as a number, where it states one (for a sign, the reference the
    /// direction is taken from).
    #[serde(default)]
    pub value: Option<f64>,
    /// The measure it is compared with (absent: not measured, see `not_measured`).
    #[serde(default)]
    pub measure: Option<Measure>,
    /// What the measure is: the page prints it in this unit, and the phrase's tolerance is
    /// this unit's ([`Unit`]).
    pub unit: Unit,
    /// Where in the scene the realizations behind the measure's error bar are listed:
    /// paths of seed lists (`seeds`, `low_load_seeds`, `variants.eps16.seeds` for the
    /// variant named eps16, `resolutions.n1024.seeds`, ...); the measure has as many
    /// realizations as the shortest. Default: the scene's `seeds`.
    #[serde(default = "scene_seeds")]
    pub realizations: Vec<String>,
    /// What the error bar measures: the spread over realizations (the default: more
    /// realizations shrink it as 1/sqrt(n)), or the scatter of points about a fitted law
    /// (`fit`: more realizations do not shrink it).
    #[serde(default)]
    pub error: ErrorKind,
    /// Changes of the rule after an outcome existed, each with its reason: the register
    /// (`validations/register.json`) keeps the earlier rules and their verdicts.
    #[serde(default)]
    pub amendments: Vec<Amendment>,
    /// The commit of the sample-size plan (`docs/power-plan.md`) that set this claim's
    /// realizations from its error bar alone, before the planned jobs ran.
    #[serde(default)]
    pub planned: Option<String>,
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

fn scene_seeds() -> Vec<String> {
    vec!["seeds".into()]
}

/// Checks that every measure that the claims judged on a scene name (each claim's own, an
/// ordering's second measure, each other reading's) is one that a run of the scene has by
/// the keys its experiment declares (`keys`); on the reduced scene (`reduced_scene`) the
/// claims it does not judge (`reduced = false`) are left out. `fixed_solver`: the scene
/// fixes its solver, so a run has no cross-checks. Every claim's realizations name seed
/// lists of the scene (`scene`, as run).
///
/// # Errors
///
/// A measure the experiment does not declare, naming the claim and the field and listing
/// the declared keys closest to the one named; a path of realizations the scene does not
/// have.
pub fn check_declared(
    claims: &[ClaimSpec],
    keys: &Keys,
    scene: &serde_json::Value,
    reduced_scene: bool,
    fixed_solver: bool,
) -> Result<()> {
    for c in claims.iter().filter(|c| c.reduced || !reduced_scene) {
        let Some(measure) = &c.measure else { continue };
        for path in &c.realizations {
            if super::measures::realizations_at(scene, path).is_none() {
                return Err(Error::invalid(
                    &format!("claims.{}.realizations", c.key),
                    path,
                    "the path of a seed list of the scene (e.g. seeds, low_load_seeds, \
                     variants.NAME.seeds)",
                ));
            }
        }
        let mut named = vec![("measure".to_string(), measure)];
        if let Rule::Exceeds(other) = &c.rule {
            named.push(("rule.exceeds".into(), other));
        }
        for (k, r) in c.other_readings.iter().enumerate() {
            named.push((format!("other_readings[{k}].measure"), &r.measure));
        }
        for (field, m) in named {
            declared(m, keys, fixed_solver).map_err(|allowed| {
                Error::invalid(&format!("claims.{}.{field}", c.key), m.to_string(), allowed)
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
            (Some(_), None) | (None, Some(_)) => {}
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
        self.validate_rule(&field)?;
        let ordering = matches!(self.rule, Rule::Exceeds(_));
        if self.phrase.needs_value() && self.value.is_none() && !ordering {
            return Err(Error::invalid(
                &field("value"),
                "none",
                format!(
                    "the paper's value (for \"{}\": {}), which the phrase's rule reads",
                    self.phrase.name(),
                    self.phrase.rule_text()
                ),
            ));
        }
        if !self
            .phrase
            .fits(&self.rule, self.value, self.unit, resolution)
            && self.departs.is_none()
        {
            return Err(Error::invalid(
                &field("rule"),
                format!(
                    "{} for phrase \"{}\" on a measure in {}",
                    self.rule.text(),
                    self.phrase.name(),
                    self.unit.name()
                ),
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
        if self.realizations.is_empty() {
            return Err(Error::invalid(
                &field("realizations"),
                "[]",
                "the paths of the scene's seed lists behind the error bar",
            ));
        }
        Ok(())
    }

    /// The rule's own checks: a tolerance, a range, an ordering's measure.
    fn validate_rule(&self, field: &dyn Fn(&str) -> String) -> Result<()> {
        match &self.rule {
            Rule::Near(r) if !(r.is_finite() && *r >= 0.0) => Err(Error::invalid(
                &field("rule.near"),
                r,
                "a relative tolerance >= 0",
            )),
            Rule::Near(_) if self.value.is_none() => Err(Error::invalid(
                &field("value"),
                "none",
                "the paper's value, which rule `near` compares with",
            )),
            // Refused when lo > hi or either is not a number.
            Rule::Within((lo, hi)) | Rule::Outside((lo, hi))
                if lo.partial_cmp(hi).is_none_or(|o| o.is_gt()) =>
            {
                Err(Error::invalid(
                    &field("rule"),
                    format!("[{lo}, {hi}]"),
                    "a range [lo, hi] with lo <= hi",
                ))
            }
            Rule::Differs(t) => Err(Error::invalid(
                &field("rule.differs"),
                t,
                "outside = [x - r, x + r]: a law is violated beyond a band, so that the claim \
                 can be contradicted where the law holds",
            )),
            _ => Ok(()),
        }
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

    /// The rule as it decides, in a fixed form: the phrase, the measure, the region (the
    /// tolerance and unit resolved), the alternative, the significance, the kind and the
    /// reading. The register keeps its hash ([`ClaimSpec::rule_sha256`]).
    pub fn decisive(&self) -> serde_json::Value {
        let region = match &self.rule {
            Rule::Exceeds(other) => format!("{} - {other} in (0, inf)", self.measure_name()),
            r => r
                .region(self.value)
                .map(|g| region_text(&g))
                .unwrap_or_default(),
        };
        serde_json::json!({
            "phrase": self.phrase.name(),
            "measure": self.measure,
            "region": region,
            "alternative": self.alternative.as_ref().map(|a| a.value),
            "significance": self.significance,
            "kind": self.kind(),
            "reading": self.reading,
        })
    }

    /// The SHA-256 (hex) of the rule as it decides ([`ClaimSpec::decisive`]).
    pub fn rule_sha256(&self) -> String {
        use sha2::{Digest, Sha256};
        let text = serde_json::to_string(&self.decisive()).expect("a JSON value serialises");
        Sha256::digest(text.as_bytes())
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect()
    }

    pub(super) fn measure_name(&self) -> String {
        self.measure
            .as_ref()
            .map(Measure::to_string)
            .unwrap_or_default()
    }
}

/// A region in a fixed notation: `[lo, hi]`, `(t, inf)`, `outside [lo, hi]`, `not t`.
fn region_text(r: &Region) -> String {
    match *r {
        Region::Interval {
            lo,
            lo_closed,
            hi,
            hi_closed,
        } => format!(
            "{}{lo}, {hi}{}",
            if lo_closed { "[" } else { "(" },
            if hi_closed { "]" } else { ")" }
        ),
        Region::Outside(lo, hi) => format!("outside [{lo}, {hi}]"),
        Region::Except(t) => format!("not {t}"),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::{Decision, Estimate};
    use crate::validation::measures::PendingPart;

    fn spec(phrase: Phrase, rule: Rule, value: Option<f64>) -> ClaimSpec {
        ClaimSpec {
            key: "k".into(),
            statement: "s".into(),
            place: "p".into(),
            paper: "~62%".into(),
            phrase,
            value,
            measure: Some("headline".parse().unwrap()),
            unit: Unit::Ratio,
            realizations: scene_seeds(),
            error: ErrorKind::Realizations,
            amendments: Vec::new(),
            planned: None,
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
            scene: &serde_json::Value::Null,
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
        let exceeds = |m: &str| Rule::Exceeds(m.parse().unwrap());
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
    fn a_test_whose_interval_holds_the_alternative_does_not_discriminate() {
        // The former reading of "overestimated by ~10%": E_exa / E_c about 0.91, a region
        // that holds 1. An interval that reaches 1 cannot tell the two apart; one that
        // excludes it can.
        let mut s = spec(Phrase::About, Rule::Near(0.1), Some(0.91));
        s.alternative = Some(Alternative {
            value: 1.0,
            what: "a perfect theory".into(),
        });
        let o = s.judge(&measures(Estimate::new(0.935, 0.03)), false, 3.0);
        assert_eq!(o.result, ClaimResult::NotEstablished);
        assert!(o.why.unwrap().contains("does not discriminate"));
        let o = s.judge(&measures(Estimate::new(0.935, 0.001)), false, 3.0);
        assert_eq!(o.result, ClaimResult::Reproduced);
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
            measure: "cross_check:cg".parse().unwrap(),
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
        s.measure = Some("detail:absent".parse().unwrap());
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
        s.measure = Some("detail:a_load_of_the_full_scene".parse().unwrap());
        s.other_readings = vec![OtherReading {
            reading: "at another load".into(),
            measure: "detail:another_load_of_the_full_scene".parse().unwrap(),
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
        s.measure = Some("detail:eps16_share_ar0.14".parse().unwrap());
        let o = s.judge(&m, false, 3.0);
        assert_eq!(o.result, ClaimResult::NotMeasured);
        let why = o.why.unwrap();
        for word in ["pending", "eps16", "2 of 6", "13.0 core-hours"] {
            assert!(why.contains(word), "{word}: {why}");
        }
        // A study cell of the part, a detail on a grid: the part gives them too.
        assert!(pending[0].gives(&"study:variants/eps16_ar0.14/share".parse().unwrap()));
        assert!(pending[0].gives(&"detail:eps16_share_ar0.14@2048".parse().unwrap()));
        assert!(!pending[0].gives(&"detail:eps16_share_ar0.88".parse().unwrap()));
        assert!(!pending[0].gives(&"headline".parse().unwrap()));
        // Any other absent measure reads as before.
        s.measure = Some("detail:absent".parse().unwrap());
        assert!(s
            .judge(&m, false, 3.0)
            .why
            .unwrap()
            .contains("this run has no"));
    }

    #[test]
    fn each_phrase_has_one_rule_per_unit() {
        let fits = |p: Phrase, r: Rule, v: Option<f64>, u: Unit| p.fits(&r, v, u, 0.01);
        assert!(fits(
            Phrase::About,
            Rule::Near(0.1),
            Some(0.62),
            Unit::Fraction
        ));
        assert!(!fits(
            Phrase::About,
            Rule::Near(0.5),
            Some(0.62),
            Unit::Fraction
        ));
        assert!(fits(
            Phrase::Order,
            Rule::Within((0.05, 0.45)),
            Some(0.15),
            Unit::Ratio
        ));
        assert!(!fits(
            Phrase::Order,
            Rule::Within((0.05, 0.3)),
            Some(0.15),
            Unit::Ratio
        ));
        // O(L^x) on an exponent: growth no faster than L^x, within the exponent's band.
        assert!(fits(
            Phrase::Order,
            Rule::AtMost(0.6),
            Some(0.5),
            Unit::Exponent
        ));
        assert!(!fits(
            Phrase::Order,
            Rule::Within((0.5 / 3.0, 1.5)),
            Some(0.5),
            Unit::Exponent
        ));
        // "negligible": two points on a share, 5% on a ratio, the resolution on a number.
        assert!(fits(
            Phrase::Negligible,
            Rule::Within((-0.02, 0.02)),
            Some(0.0),
            Unit::Points
        ));
        assert!(fits(
            Phrase::Negligible,
            Rule::Within((-0.05, 0.05)),
            Some(0.0),
            Unit::Relative
        ));
        assert!(!fits(
            Phrase::Negligible,
            Rule::Within((-0.1, 0.1)),
            Some(0.0),
            Unit::Relative
        ));
        assert!(fits(
            Phrase::Negligible,
            Rule::Within((-0.01, 0.01)),
            Some(0.0),
            Unit::Number
        ));
        assert!(fits(Phrase::All, Rule::AtLeast(0.98), None, Unit::Fraction));
        assert!(!fits(
            Phrase::All,
            Rule::Near(0.1),
            Some(1.0),
            Unit::Fraction
        ));
        assert!(fits(Phrase::Sign, Rule::Below(0.0), Some(0.0), Unit::Ratio));
        // The check is not skipped without the paper's value: a sign needs its reference.
        assert!(!fits(Phrase::Sign, Rule::Below(0.0), None, Unit::Ratio));
        assert!(fits(
            Phrase::Within,
            Rule::AtMost(0.03),
            Some(0.03),
            Unit::Relative
        ));
        assert!(fits(
            Phrase::Violates,
            Rule::Outside((0.9, 1.1)),
            Some(1.0),
            Unit::Exponent
        ));
        // A departure is refused without its reason, accepted with it.
        let mut s = spec(Phrase::About, Rule::Within((0.5, 0.7)), Some(0.62));
        let e = validate_claims(std::slice::from_ref(&s), 0.02)
            .unwrap_err()
            .to_string();
        assert!(e.contains("claims.k.rule") && e.contains("departs"), "{e}");
        s.departs = Some("why".into());
        assert!(validate_claims(&[s], 0.02).is_ok());
        // A law without a band cannot be contradicted: refused.
        let differs = spec(Phrase::Violates, Rule::Differs(1.0), Some(1.0));
        let e = validate_claims(&[differs], 0.02).unwrap_err().to_string();
        assert!(e.contains("claims.k.rule.differs"), "{e}");
    }

    #[test]
    fn an_alternative_is_judged_against_the_data() {
        // c2 about 1.025 (+-10% holds the alternative 1): an interval that excludes 1
        // discriminates; one that holds it does not.
        let mut s = spec(Phrase::About, Rule::Near(0.1), Some(1.025));
        s.alternative = Some(Alternative {
            value: 1.0,
            what: "Persson's c2 = 1".into(),
        });
        let judged = |e| s.judge(&measures(e), false, 3.0);
        assert_eq!(
            judged(Estimate::new(1.0381, 0.0013)).result,
            ClaimResult::Reproduced
        );
        let o = judged(Estimate::new(1.01, 0.01));
        assert_eq!(o.result, ClaimResult::NotEstablished);
        assert!(o.why.unwrap().contains("does not discriminate"));
        assert_eq!(
            judged(Estimate::new(1.5, 0.01)).result,
            ClaimResult::Contradicted
        );
    }

    #[test]
    fn a_violated_law_can_be_contradicted() {
        let mut s = spec(Phrase::Violates, Rule::Outside((0.9, 1.1)), Some(1.0));
        s.unit = Unit::Exponent;
        let r = |v, e| s.judge(&measures(Estimate::new(v, e)), false, 3.0).result;
        assert_eq!(r(0.409, 0.015), ClaimResult::Reproduced);
        assert_eq!(r(1.0, 0.01), ClaimResult::Contradicted);
        assert_eq!(r(1.08, 0.02), ClaimResult::NotEstablished);
    }

    #[test]
    fn few_realizations_widen_the_interval_to_students_t() {
        // Two realizations: +-3 standard errors would hold the mean some 80% of the time;
        // the interval at the same coverage as three normal standard errors is far wider.
        assert!((interval_z(3.0, Some(4)) - 3.0).abs() < 1e-12);
        assert!((interval_z(3.0, None) - 3.0).abs() < 1e-12);
        let two = interval_z(3.0, Some(2));
        let three = interval_z(3.0, Some(3));
        assert!(two > 200.0 && two < 260.0, "{two}");
        assert!(three > 15.0 && three < 25.0 && three < two, "{three}");
        let scene = serde_json::json!({ "seeds": [1, 2], "variants": [{ "name": "v", "seeds": [1, 2, 3, 4] }] });
        let m = Measures {
            scene: &scene,
            ..measures(Estimate::new(0.0, 0.001))
        };
        assert_eq!(m.realizations(&["seeds".into()]), Some(2));
        assert_eq!(m.realizations(&["variants.v.seeds".into()]), Some(4));
        assert_eq!(
            m.realizations(&["variants.v.seeds".into(), "seeds".into()]),
            Some(2)
        );
        assert_eq!(m.realizations(&["nothing".into()]), None);
        // A list's planned realizations count with it.
        let planned = serde_json::json!({ "seeds": [1, 2], "more_seeds": [3] });
        let p = Measures {
            scene: &planned,
            ..measures(Estimate::new(0.0, 0.001))
        };
        assert_eq!(p.realizations(&["seeds".into()]), Some(3));
        // A shift of 0.01 +- 0.001 against +-0.02: established with four realizations,
        // not with two (+-0.23), which say how many would decide it.
        let s = spec(Phrase::Negligible, Rule::Within((-0.02, 0.02)), Some(0.0));
        let o = s.judge(&m, false, 3.0);
        assert_eq!(o.realizations, Some(2));
        assert_eq!(o.result, ClaimResult::NotEstablished);
        let why = o.why.unwrap();
        assert!(
            why.contains("only 2 realizations") && why.contains("Student"),
            "{why}"
        );
        // A fitted law's scatter: no count of realizations is promised.
        let mut fit = s.clone();
        fit.error = ErrorKind::Fit;
        let why = fit.judge(&m, false, 3.0).why.unwrap();
        assert!(
            why.contains("do not shrink") && !why.contains("times"),
            "{why}"
        );
        assert!(realizations_needed(0.001, 2, 0.01, 3.0) >= 4);
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
            "claims.k.rule",
        );
        // A measure of no form is refused as the definition is read, at its line.
        let text = "key = \"k\"\nstatement = \"s\"\nplace = \"p\"\npaper = \"> 0\"\n\
                    phrase = \"sign\"\nvalue = 0.0\nunit = \"ratio\"\n\
                    measure = \"study:a/b\"\nrule = { above = 0.0 }\n";
        let e = toml::from_str::<ClaimSpec>(text).unwrap_err().to_string();
        for word in [
            "measure = \"study:a/b\"",
            "line 8",
            "study:STUDY/ROW/COLUMN",
        ] {
            assert!(e.contains(word), "{word}: {e}");
        }
        assert!(toml::from_str::<ClaimSpec>(&text.replace("a/b", "a/b/c")).is_ok());
        let mut s = spec(Phrase::Sign, Rule::Above(0.0), Some(0.0));
        s.measure = None;
        refused(s.clone(), "claims.k.measure");
        s.not_measured = Some("why".into());
        assert!(validate_claims(&[s.clone()], 0.02).is_ok());
        s.measure = Some("headline".parse().unwrap());
        refused(s, "claims.k.not_measured");
        let a = spec(Phrase::Sign, Rule::Above(0.0), Some(0.0));
        let e = validate_claims(&[a.clone(), a], 0.02)
            .unwrap_err()
            .to_string();
        assert!(e.contains("claims.key"), "{e}");
    }
}
