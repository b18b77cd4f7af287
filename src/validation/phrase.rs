//! The paper's wordings and the one rule each maps to: a claim's [`Phrase`] names how the
//! paper states it ("about x", "O(x)", "negligible", a sign...), its [`Rule`] the region of
//! values it asserts for its measure ([`crate::validation::claims`] decides the claim on
//! that region). The rule of a phrase depends on the paper's value and on the measure's
//! [`Unit`] only ([`Phrase::rules`]): "negligible" is two percentage points on every share
//! and 5% on every ratio, whichever validation states it. The phrase table of
//! `docs/reviewing.md` is written from here.

use super::measure::Measure;
use serde::{Deserialize, Serialize};

use super::unit::{Tolerance, Unit, EXPONENT_BAND};
use crate::stats::Region;

/// How a claim is decided: the region of values it asserts for its measure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Rule {
    /// Within a relative tolerance of the paper's value.
    Near(f64),
    /// Above a threshold (a sign, or a strict bound).
    Above(f64),
    /// Below a threshold.
    Below(f64),
    /// At most a bound.
    AtMost(f64),
    /// At least a bound.
    AtLeast(f64),
    /// In a range.
    Within((f64, f64)),
    /// Outside a band: a law stated as violated, without a direction, is contradicted
    /// where the interval lies inside the band `[lo, hi]` around the law's value.
    Outside((f64, f64)),
    /// Larger than another measure.
    Exceeds(Measure),
    /// Away from a value, with no band: never contradicted, refused when a definition
    /// loads (the outcomes of earlier versions hold it; `outside` replaces it).
    Differs(f64),
}

/// The wordings of the paper, each with one rule ([`Phrase::fits`], [`Phrase::rule_text`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Phrase {
    /// "~x", "about x", "approximately x", or a number printed without a qualifier:
    /// `near = 0.1`.
    About,
    /// "O(x)": the order of magnitude, `within = [x / 3, 3 x]`; on an exponent ("O(L^x)"),
    /// growth no faster than `L^x`: `at_most = x + 0.1`.
    Order,
    /// "within x", "below x", "errors below x": a bound on a magnitude, `at_most = x`, or
    /// `within = [-x, x]` on a signed difference.
    Within,
    /// "negligible", "does not change", "remains the same", "converged", "very good":
    /// `within = [x - r, x + r]` around the paper's value `x` (usually 0), `r` the band of
    /// the measure's unit ([`Unit::band`]).
    Negligible,
    /// "every single", "all": `at_least = 1 - r`, `r` the band of the measure's unit.
    All,
    /// "significantly": an improvement above zero, `above = 0` (or an ordering,
    /// `exceeds`).
    Significantly,
    /// A sign or a direction ("negative", "picks up", "recede", "underestimates"): `above
    /// = t` or `below = t`, or an ordering of two measures, `exceeds`.
    Sign,
    /// "more than x", "larger than x": `above = x`.
    MoreThan,
    /// "less than x", "smaller than x": `below = x`.
    LessThan,
    /// "in violation of", "deviates from" a law, without a direction: `outside = [x - r,
    /// x + r]`, the complement of "negligible".
    Violates,
}

/// Every phrase, in the order of the phrase table in `docs/reviewing.md`.
pub const PHRASES: [Phrase; 10] = [
    Phrase::About,
    Phrase::Order,
    Phrase::Within,
    Phrase::Negligible,
    Phrase::All,
    Phrase::Significantly,
    Phrase::Sign,
    Phrase::MoreThan,
    Phrase::LessThan,
    Phrase::Violates,
];

/// The relative tolerance of "about" ([`Phrase::About`]).
pub const ABOUT: f64 = 0.1;
/// The factor of "O(x)" ([`Phrase::Order`]): `x / 3` to `3 x`.
pub const ORDER: f64 = 3.0;

impl Phrase {
    /// The phrase as the definitions write it.
    pub fn name(self) -> &'static str {
        match self {
            Phrase::About => "about",
            Phrase::Order => "order",
            Phrase::Within => "within",
            Phrase::Negligible => "negligible",
            Phrase::All => "all",
            Phrase::Significantly => "significantly",
            Phrase::Sign => "sign",
            Phrase::MoreThan => "more_than",
            Phrase::LessThan => "less_than",
            Phrase::Violates => "violates",
        }
    }

    /// The paper's wordings of the phrase.
    pub fn wordings(self) -> &'static str {
        match self {
            Phrase::About => {
                "\"~x\", \"about x\", \"approximately x\", a number printed without a qualifier"
            }
            Phrase::Order => "\"O(x)\"",
            Phrase::Within => {
                "\"within x\", \"below x\", \"errors below x\" (a bound on a magnitude)"
            }
            Phrase::Negligible => {
                "\"negligible\", \"does not change\", \"remains the same\", \"converged\", \"very good\""
            }
            Phrase::All => "\"every single\", \"all\"",
            Phrase::Significantly => "\"significantly\"",
            Phrase::Sign => {
                "a sign or a direction: \"negative\", \"picks up\", \"recede\", \"underestimates\""
            }
            Phrase::MoreThan => "\"more than x\", \"larger than x\"",
            Phrase::LessThan => "\"less than x\", \"smaller than x\"",
            Phrase::Violates => "\"in violation of\", \"deviates from\" (no direction)",
        }
    }

    /// The rule in words, as the phrase table in `docs/reviewing.md` states it (`x` the
    /// paper's value, `r` the band of the measure's unit).
    pub fn rule_text(self) -> &'static str {
        match self {
            Phrase::About => "`near = 0.1`: x +- 10% of x, in every unit",
            Phrase::Order => {
                "`within = [x/3, 3x]` (+-0.48 decades); on an exponent, `at_most = x + 0.1`"
            }
            Phrase::Within => "`at_most = x`, or `within = [-x, x]` on a signed difference",
            Phrase::Negligible => "`within = [x - r, x + r]`",
            Phrase::All => "`at_least = 1 - r`",
            Phrase::Significantly => "`above = 0` on the improvement (or `exceeds`)",
            Phrase::Sign => {
                "`above = x` or `below = x` (x the reference, usually 0 or 1), or `exceeds`"
            }
            Phrase::MoreThan => "`above = x`",
            Phrase::LessThan => "`below = x`",
            Phrase::Violates => "`outside = [x - r, x + r]`: the complement of negligible",
        }
    }

    /// Whether the phrase needs the paper's value: every phrase but "significantly" (whose
    /// reference is the improvement's 0) and "all" (whose reference is 1).
    pub fn needs_value(self) -> bool {
        !matches!(self, Phrase::Significantly | Phrase::All)
    }

    /// The rules the phrase gives a claim of paper value `value` whose measure is in
    /// `unit`, in a validation of resolution `resolution` (the band of a number of the
    /// measure's own unit): one rule, or two where the phrase states a bound on a magnitude
    /// or on a signed difference ("within") or a direction either way (a sign). An
    /// ordering of two measures (`exceeds`) fits "significantly" and a sign whatever the
    /// value. Empty where the phrase needs a value and the claim states none.
    pub fn rules(self, value: Option<f64>, unit: Unit, resolution: f64) -> Vec<Rule> {
        let r = unit.band_width(resolution);
        let Some(x) = value.or(match self {
            Phrase::Significantly => Some(0.0),
            Phrase::All => Some(1.0),
            _ => None,
        }) else {
            return Vec::new();
        };
        match self {
            Phrase::About => vec![Rule::Near(ABOUT)],
            Phrase::Order if unit == Unit::Exponent => vec![Rule::AtMost(x + EXPONENT_BAND)],
            Phrase::Order => vec![Rule::Within((x / ORDER, x * ORDER))],
            Phrase::Within => vec![Rule::AtMost(x), Rule::Within((-x, x))],
            Phrase::Negligible => vec![Rule::Within((x - r, x + r))],
            Phrase::All => vec![Rule::AtLeast(x - r)],
            Phrase::Significantly => vec![Rule::Above(0.0), Rule::Below(0.0)],
            Phrase::Sign => vec![Rule::Above(x), Rule::Below(x)],
            Phrase::MoreThan => vec![Rule::Above(x)],
            Phrase::LessThan => vec![Rule::Below(x)],
            Phrase::Violates => vec![Rule::Outside((x - r, x + r))],
        }
    }

    /// The kind of tolerance the phrase takes on `unit`, where it takes one.
    pub fn tolerance(self, unit: Unit, resolution: f64) -> Option<Tolerance> {
        match self {
            Phrase::About => Some(Tolerance::Relative(ABOUT)),
            Phrase::Order if unit == Unit::Exponent => Some(Tolerance::Absolute(EXPONENT_BAND)),
            Phrase::Order => Some(Tolerance::Decades(ORDER.log10())),
            Phrase::Negligible | Phrase::All | Phrase::Violates => Some(unit.band(resolution)),
            _ => None,
        }
    }

    /// Whether `rule` is this phrase's rule for the paper's value `value` on a measure of
    /// `unit` in a validation of resolution `resolution` ([`Phrase::rules`]).
    pub fn fits(self, rule: &Rule, value: Option<f64>, unit: Unit, resolution: f64) -> bool {
        if matches!(rule, Rule::Exceeds(_)) {
            return matches!(self, Phrase::Significantly | Phrase::Sign);
        }
        self.rules(value, unit, resolution)
            .iter()
            .any(|r| r.same_as(rule))
    }
}

impl Rule {
    /// The region the rule asserts, for a claim of paper value `value`; `None` for an
    /// ordering, whose region is that of the difference (`(0, inf)`).
    pub fn region(&self, value: Option<f64>) -> Option<Region> {
        Some(match self {
            Rule::Near(r) => {
                let p = value.unwrap_or(f64::NAN);
                Region::closed(p - r * p.abs(), p + r * p.abs())
            }
            Rule::Above(t) => Region::above(*t),
            Rule::Below(t) => Region::below(*t),
            Rule::AtMost(t) => Region::at_most(*t),
            Rule::AtLeast(t) => Region::at_least(*t),
            Rule::Within((lo, hi)) => Region::closed(*lo, *hi),
            Rule::Outside((lo, hi)) => Region::Outside(*lo, *hi),
            Rule::Differs(t) => Region::Except(*t),
            Rule::Exceeds(_) => return None,
        })
    }

    /// Whether two rules are the same to seven digits (definitions write x / 3 as a
    /// decimal).
    pub fn same_as(&self, other: &Rule) -> bool {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * a.abs().max(b.abs()).max(1e-12);
        match (self, other) {
            (Rule::Near(a), Rule::Near(b))
            | (Rule::Above(a), Rule::Above(b))
            | (Rule::Below(a), Rule::Below(b))
            | (Rule::AtMost(a), Rule::AtMost(b))
            | (Rule::AtLeast(a), Rule::AtLeast(b))
            | (Rule::Differs(a), Rule::Differs(b)) => close(*a, *b),
            (Rule::Within((a, b)), Rule::Within((c, d)))
            | (Rule::Outside((a, b)), Rule::Outside((c, d))) => close(*a, *c) && close(*b, *d),
            (Rule::Exceeds(a), Rule::Exceeds(b)) => a == b,
            _ => false,
        }
    }

    /// The rule in the words of a definition: `near = 0.1`, `within = [lo, hi]`, ...
    pub fn text(&self) -> String {
        match self {
            Rule::Near(r) => format!("near = {r}"),
            Rule::Above(t) => format!("above = {t}"),
            Rule::Below(t) => format!("below = {t}"),
            Rule::AtMost(t) => format!("at_most = {t}"),
            Rule::AtLeast(t) => format!("at_least = {t}"),
            Rule::Within((lo, hi)) => format!("within = [{lo}, {hi}]"),
            Rule::Outside((lo, hi)) => format!("outside = [{lo}, {hi}]"),
            Rule::Exceeds(m) => format!("exceeds = {m}"),
            Rule::Differs(t) => format!("differs = {t}"),
        }
    }
}
