//! The paper's wordings and the one rule each maps to: a claim's [`Phrase`] names how the
//! paper states it ("about x", "O(x)", "negligible", a sign...), its [`Rule`] the region of
//! values it asserts for its measure ([`crate::validation::claims`] decides the claim on
//! that region). The phrase table of `docs/reviewing.md` is written from here.

use serde::{Deserialize, Serialize};

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
    /// Larger than another measure.
    Exceeds(String),
    /// Away from a value: a law stated as violated, without a direction.
    Differs(f64),
}

/// The wordings of the paper, each with one rule ([`Phrase::fits`], [`Phrase::rule_text`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Phrase {
    /// "~x", "about x", "approximately x", or a number printed without a qualifier:
    /// `near = 0.1`.
    About,
    /// "O(x)": the order of magnitude, `within = [x / 3, 3 x]`.
    Order,
    /// "within x", "below x", "errors below x": a bound on a magnitude, `at_most = x`, or
    /// `within = [-x, x]` on a signed difference.
    Within,
    /// "negligible", "does not change", "remains the same", "converged": `within = [-r,
    /// r]`, `r` the paper's number or else the validation's resolution.
    Negligible,
    /// "every single", "all": `at_least = 1 - r`, `r` the validation's resolution.
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
    /// "in violation of", "deviates from" a law, without a direction: `differs = x`.
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
                "\"negligible\", \"does not change\", \"remains the same\", \"converged\""
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

    /// The rule in words, as the phrase table in `docs/reviewing.md` states it.
    pub fn rule_text(self) -> &'static str {
        match self {
            Phrase::About => "`near = 0.1`: the paper's value +- 10%",
            Phrase::Order => "`within = [x/3, 3x]`",
            Phrase::Within => "`at_most = x`, or `within = [-x, x]` on a signed difference",
            Phrase::Negligible => {
                "`within = [-r, r]`: r the paper's number, else the validation's resolution"
            }
            Phrase::All => "`at_least = 1 - r`: r the validation's resolution",
            Phrase::Significantly => "`above = 0` on the improvement (or `exceeds`)",
            Phrase::Sign => {
                "`above = t` or `below = t` (t the paper's threshold, usually 0), or `exceeds`"
            }
            Phrase::MoreThan => "`above = x`",
            Phrase::LessThan => "`below = x`",
            Phrase::Violates => "`differs = x`: any value but x (never contradicted)",
        }
    }

    /// Whether `rule` is this phrase's rule for the paper's value `value` in a validation
    /// of resolution `resolution`.
    pub fn fits(self, rule: &Rule, value: Option<f64>, resolution: f64) -> bool {
        // Seven digits: definitions write x / 3 as a decimal.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * a.abs().max(b.abs()).max(1e-300);
        let v = value;
        match (self, rule) {
            (Phrase::About, Rule::Near(r)) => close(*r, ABOUT),
            (Phrase::Order, Rule::Within((lo, hi))) => {
                v.is_some_and(|x| close(*lo, x / ORDER) && close(*hi, x * ORDER))
            }
            (Phrase::Within, Rule::AtMost(t)) => v.is_none_or(|x| close(*t, x)),
            (Phrase::Within, Rule::Within((lo, hi))) => {
                close(*lo, -hi) && v.is_none_or(|x| close(*hi, x))
            }
            // The paper's number, where it gives one (a value of 0 is the target, not the
            // width).
            (Phrase::Negligible, Rule::Within((lo, hi))) => {
                close(*lo, -hi) && close(*hi, v.filter(|x| *x > 0.0).unwrap_or(resolution))
            }
            (Phrase::All, Rule::AtLeast(t)) => close(*t, 1.0 - resolution),
            (Phrase::Significantly, Rule::Above(t) | Rule::Below(t)) => *t == 0.0,
            (Phrase::Significantly | Phrase::Sign, Rule::Exceeds(_)) => true,
            (Phrase::Sign, Rule::Above(t) | Rule::Below(t)) => v.is_none_or(|x| close(*t, x)),
            (Phrase::MoreThan, Rule::Above(t)) | (Phrase::LessThan, Rule::Below(t)) => {
                v.is_none_or(|x| close(*t, x))
            }
            (Phrase::Violates, Rule::Differs(t)) => v.is_none_or(|x| close(*t, x)),
            _ => false,
        }
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
            Rule::Differs(t) => Region::Except(*t),
            Rule::Exceeds(_) => return None,
        })
    }
}
