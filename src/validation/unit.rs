//! What a claim's measure is ([`Unit`]): a share of points, a difference of two shares, a
//! ratio, a relative change, an exponent, or a number in the measure's own unit. The unit
//! decides how the page prints the measure and the paper's value, and which kind of
//! tolerance a phrase of the paper takes on it ([`Tolerance`], [`Unit::band`]): one
//! tolerance per phrase and kind, so that "negligible" means the same on every share and
//! the same on every ratio.

use serde::{Deserialize, Serialize};

/// The unit of a claim's measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Unit {
    /// A share of a set of points (of the contact, of the non-contact), in [0, 1], printed
    /// in %.
    Fraction,
    /// A share of the nominal area `A0`, in [0, 1], printed in % of A0.
    PercentOfA0,
    /// A difference of two shares, printed in percentage points.
    Points,
    /// A ratio of two like quantities (1 where they are equal).
    Ratio,
    /// A relative deviation or change, `x / y - 1`, printed in %.
    Relative,
    /// The exponent of a power law.
    Exponent,
    /// A number in the measure's own unit (a fitted constant, a count, a distance in grid
    /// spacings, a drift in p0/a_r per unit zeta, a difference of distances): its
    /// tolerances are the validation's resolution, stated in that unit.
    Number,
}

/// Every unit, in the order of the phrase table in `docs/reviewing.md`.
pub const UNITS: [Unit; 7] = [
    Unit::Fraction,
    Unit::PercentOfA0,
    Unit::Points,
    Unit::Ratio,
    Unit::Relative,
    Unit::Exponent,
    Unit::Number,
];

/// The kind of a tolerance: what a band of width `r` around a value means.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// `r` times the paper's value.
    Relative(f64),
    /// `r` in share units (0.02: two percentage points).
    Points(f64),
    /// `r` in the measure's own unit.
    Absolute(f64),
    /// A factor of `10^r` either way (an order of magnitude: `r = log10 3`).
    Decades(f64),
}

/// The band of "negligible", "all" and "violates" on shares and their differences: two
/// percentage points.
pub const SHARE_BAND: f64 = 0.02;
/// The band on ratios and relative changes: 5%.
pub const RATIO_BAND: f64 = 0.05;
/// The band on an exponent: 0.1 (a power law's exponent fitted over one or two decades is
/// rarely sharper).
pub const EXPONENT_BAND: f64 = 0.1;

impl Unit {
    /// The unit as the definitions write it.
    pub fn name(self) -> &'static str {
        match self {
            Unit::Fraction => "fraction",
            Unit::PercentOfA0 => "percent_of_a0",
            Unit::Points => "points",
            Unit::Ratio => "ratio",
            Unit::Relative => "relative",
            Unit::Exponent => "exponent",
            Unit::Number => "number",
        }
    }

    /// What the unit is, in words.
    pub fn meaning(self) -> &'static str {
        match self {
            Unit::Fraction => "a share of a set of points, printed in %",
            Unit::PercentOfA0 => "a share of the nominal area, printed in % of A0",
            Unit::Points => "a difference of two shares, in percentage points",
            Unit::Ratio => "a ratio of two like quantities",
            Unit::Relative => "a relative deviation or change, x / y - 1, printed in %",
            Unit::Exponent => "the exponent of a power law",
            Unit::Number => "a number in the measure's own unit",
        }
    }

    /// The band that "negligible", "all" and "violates" allow around a value, in this
    /// unit: [`SHARE_BAND`] on shares, [`RATIO_BAND`] on ratios and relative changes,
    /// [`EXPONENT_BAND`] on exponents, and the validation's `resolution` on a number of
    /// the measure's own unit.
    pub fn band(self, resolution: f64) -> Tolerance {
        match self {
            Unit::Fraction | Unit::PercentOfA0 | Unit::Points => Tolerance::Points(SHARE_BAND),
            Unit::Ratio | Unit::Relative => Tolerance::Absolute(RATIO_BAND),
            Unit::Exponent => Tolerance::Absolute(EXPONENT_BAND),
            Unit::Number => Tolerance::Absolute(resolution),
        }
    }

    /// The band's width as a number of the measure's unit.
    pub fn band_width(self, resolution: f64) -> f64 {
        match self.band(resolution) {
            Tolerance::Points(r) | Tolerance::Absolute(r) | Tolerance::Relative(r) => r,
            Tolerance::Decades(r) => r,
        }
    }

    /// The factor and the suffix the page prints a value of this unit with: shares and
    /// relative changes in %, differences of shares in points, the rest as they are.
    pub fn display(self) -> (f64, &'static str) {
        match self {
            Unit::Fraction | Unit::Relative => (100.0, "%"),
            Unit::PercentOfA0 => (100.0, "% of A0"),
            Unit::Points => (100.0, " points"),
            Unit::Ratio | Unit::Exponent | Unit::Number => (1.0, ""),
        }
    }
}

impl Tolerance {
    /// The tolerance in words.
    pub fn text(self) -> String {
        match self {
            Tolerance::Relative(r) => format!("{}% of the paper's value", 100.0 * r),
            Tolerance::Points(r) => format!("{} percentage points", 100.0 * r),
            Tolerance::Absolute(r) => format!("{r} in the measure's unit"),
            Tolerance::Decades(r) => format!("{r} decades either way"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_unit_has_a_name_a_meaning_and_a_band() {
        for u in UNITS {
            let back: Unit = serde_json::from_str(&format!("\"{}\"", u.name())).unwrap();
            assert_eq!(back, u);
            assert!(!u.meaning().is_empty());
            assert!(u.band_width(0.01) > 0.0);
        }
        // A share's band is in points whatever the validation's resolution; a number's is
        // the resolution.
        assert_eq!(Unit::Fraction.band(0.3), Tolerance::Points(SHARE_BAND));
        assert_eq!(Unit::Number.band(0.3), Tolerance::Absolute(0.3));
        assert_eq!(Unit::Points.display(), (100.0, " points"));
    }
}
