//! How a claim is decided ([`ClaimSpec::judge`]): the measure's interval `value +- z
//! std_error` against the rule's region, the alternative first, with Student's t for
//! fewer than four realizations ([`interval_z`]); where the data do not establish the
//! claim, what would decide it (the realizations that would, never from the value's side
//! alone, or more loads for a fitted law).

use super::claim_outcome::ErrorKind;
use super::claim_outcome::{ClaimKind, ClaimOutcome, ClaimResult, ReadingOutcome};
use super::claims::{ClaimSpec, OtherReading, Rule};
use super::interval::{interval_z, realizations_needed};
use super::measures::Measures;
use crate::stats::{establish, Estimate, Region};

impl ClaimSpec {
    /// Judges the claim on a run (of the reduced scene when `reduced_scene`), at the
    /// validation's significance `z` unless the claim states its own: the one rule of every
    /// claim.
    pub fn judge(&self, measures: &Measures, reduced_scene: bool, z: f64) -> ClaimOutcome {
        let n = measures.realizations(&self.realizations);
        let base = self.significance.unwrap_or(z);
        let iv = Interval {
            base,
            z: interval_z(base, n),
            n,
        };
        let z = iv.z;
        let measured = self.measure.as_ref().and_then(|m| measures.get(m));
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
            (Some(_), Some(e)) => self.verdict(e, measures, iv),
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
            .map(|r| self.reading_outcome(r, measures, reduced_scene, iv))
            .collect();
        ClaimOutcome {
            key: self.key.clone(),
            statement: self.statement.clone(),
            place: self.place.clone(),
            paper: self.paper.clone(),
            phrase: Some(self.phrase),
            paper_value: self.value,
            measure: self.measure_name(),
            unit: Some(self.unit),
            realizations: n,
            interval_z: Some(z),
            error: self.error,
            rule_sha256: Some(self.rule_sha256()),
            departs: self.departs.clone(),
            amendments: self.amendments.clone(),
            planned: self.planned.clone(),
            scene: self.scene.clone(),
            reading: self.reading.clone(),
            rule: self.rule.clone(),
            measured,
            difference: match (&self.rule, measured) {
                (Rule::Exceeds(other), Some(e)) => {
                    measures.get(other).map(|o| Estimate::difference(e, o))
                }
                _ => None,
            },
            result,
            kind: self.kind(),
            why,
            readings,
        }
    }

    /// Another reading judged by the claim's rule, or by its own.
    fn reading_outcome(
        &self,
        r: &OtherReading,
        measures: &Measures,
        reduced_scene: bool,
        iv: Interval,
    ) -> ReadingOutcome {
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
                    .verdict(e, measures, iv)
                    .0
                }
                None => self.verdict(e, measures, iv).0,
            },
        };
        ReadingOutcome {
            reading: r.reading.clone(),
            measure: r.measure.to_string(),
            measured,
            result,
        }
    }

    /// The result of the rule on an estimate of what it judges (for an ordering, the
    /// difference of its two measures), at `z` standard errors: what a measurement of this
    /// value would give. The suite walks every claim with one estimate inside its region
    /// and one outside.
    pub fn judge_estimate(&self, e: Estimate, z: f64) -> ClaimResult {
        let region = match &self.rule {
            Rule::Exceeds(_) => Region::above(0.0),
            r => match r.region(self.value) {
                Some(region) => region,
                None => return ClaimResult::NotEstablished,
            },
        };
        let iv = Interval {
            base: z,
            z,
            n: None,
        };
        self.decide_on(e, region, iv).0
    }

    /// The rule applied to the measured estimate `e` with the interval `e +- z s` (`n`
    /// realizations behind it, where known): the result and, where it is not established,
    /// why and what would decide it.
    fn verdict(
        &self,
        e: Estimate,
        measures: &Measures,
        iv: Interval,
    ) -> (ClaimResult, Option<String>) {
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
        self.decide_on(e, region, iv)
    }

    /// The rule's region applied to the estimate it judges, `e` (for an ordering, the
    /// difference of the two measures), with the interval of `iv`: the alternative first,
    /// then the region.
    fn decide_on(
        &self,
        e: Estimate,
        region: Region,
        iv: Interval,
    ) -> (ClaimResult, Option<String>) {
        let z = iv.z;
        if let Some(alt) = &self.alternative {
            let holds_alternative = (e.value - alt.value).abs() <= z * e.std_error;
            if region.contains(alt.value) && e.has_error() && holds_alternative {
                return (
                    ClaimResult::NotEstablished,
                    Some(format!(
                        "does not discriminate: the interval +-{} standard errors also holds \
                         the alternative, {} = {}",
                        short(z),
                        alt.what,
                        alt.value
                    )),
                );
            }
        }
        let result = ClaimResult::of(establish(e, region, z));
        let why =
            (result == ClaimResult::NotEstablished).then(|| decider(e, region, iv, self.error));
        (result, why)
    }
}

/// The interval a claim is judged with: the significance stated (`base`), the half width
/// in standard errors it takes for the realizations behind the measure (`z`), and how many
/// those are (`n`, where the scene lists them).
#[derive(Debug, Clone, Copy)]
struct Interval {
    base: f64,
    z: f64,
    n: Option<usize>,
}

/// A number of standard errors as the texts print it: 3, 19.2, 235.8.
fn short(z: f64) -> String {
    if (z - z.round()).abs() < 1e-9 {
        format!("{}", z.round())
    } else {
        format!("{z:.1}")
    }
}

/// What would decide a claim the data do not establish, never from its value's side
/// alone: for an error over realizations, the realizations that shrink the interval inside
/// (or outside) the region if the value held (Student's t below four realizations); for
/// the scatter about a fitted law, that more realizations would not shrink it.
fn decider(e: Estimate, region: Region, iv: Interval, error: ErrorKind) -> String {
    let (z, n) = (iv.z, iv.n);
    if !(e.value.is_finite() && e.has_error()) {
        return "no error bar (one realization): two or more realizations would decide".into();
    }
    let margin = region.margin(e.value);
    let goal = if region.contains(e.value) {
        "establish"
    } else {
        "contradict"
    };
    if !(margin.is_finite() && margin > 0.0) {
        return "the value lies on the region's edge: no number of realizations decides".into();
    }
    let reaches = format!(
        "the interval +-{} standard errors reaches both sides of the rule's edge",
        short(z)
    );
    if error == ErrorKind::Fit {
        return format!(
            "{reaches}; the error is the scatter of the points about a fitted law, which more \
             realizations do not shrink: more loads or targets would"
        );
    }
    match n {
        Some(n) if n < 4 => {
            let needed = realizations_needed(e.std_error, n, margin, iv.base);
            format!(
                "{reaches} (only {n} realizations: Student's t with {} degree{} of freedom); \
                 about {needed} realizations would {goal} it if the value held",
                n - 1,
                if n == 2 { "" } else { "s" }
            )
        }
        _ => {
            let factor = (z * e.std_error / margin).powi(2);
            format!(
                "{reaches}; about {:.1} times the realizations would {goal} it if the value \
                 held",
                factor.max(1.0)
            )
        }
    }
}

fn join(head: String, tail: Option<String>) -> String {
    match tail {
        Some(t) => format!("{head}; {t}"),
        None => head,
    }
}
