//! The one rule that decides a claim about an estimate: every check of a validation, its
//! verdict, the agreement of two solvers and the paper's range go through [`decide`].
//!
//! A claim is a statement about the confidence interval `value +- z std_error` of an
//! estimate, `z` the significance in standard errors, against a threshold or a target
//! ([`Claim`]). A claim is decided only when the estimate has an error bar: with one
//! realization the spread over realizations is unknown, and so is whether the value
//! reflects the ensemble or the one surface drawn. Such a claim is
//! [`Decision::Undecided`], whatever its value, and so is a claim on a value that is not
//! a number. With `z = 0` a claim compares the value alone, but still only when it has an
//! error bar: an ordering of two ensemble means is as much a statement about the ensemble
//! as a significance test.
//!
//! Decisions combine in three-valued (Kleene) logic: a conjunction fails when one part
//! fails, is undecided when none fails and one is undecided, and passes otherwise
//! ([`Decision::all`]).

use super::Estimate;

/// What a check asks of an estimate's interval `value +- z std_error`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Claim {
    /// The interval lies above `threshold`: `value - z std_error > threshold`.
    Above(f64),
    /// The interval lies below `threshold`: `value + z std_error < threshold`.
    Below(f64),
    /// The interval comes within `tolerance` of `target` (the value is consistent with
    /// it up to a deviation that does not matter): `|value - target| <= z std_error +
    /// tolerance`.
    Near {
        /// The value claimed.
        target: f64,
        /// The deviation that does not matter.
        tolerance: f64,
    },
    /// The whole interval lies within `resolution` of `target` (an equivalence test):
    /// `|value - target| + z std_error <= resolution`.
    Within {
        /// The value claimed.
        target: f64,
        /// The largest deviation allowed.
        resolution: f64,
    },
    /// The interval overlaps `[lo, hi]`: `value + z std_error >= lo` and
    /// `value - z std_error <= hi`.
    Overlaps(f64, f64),
}

/// The outcome of a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Decision {
    /// The data support the claim.
    Passed,
    /// The data contradict it.
    Failed,
    /// The data cannot tell: no error bar (one realization), or no value.
    Undecided,
}

impl Decision {
    /// `Passed` when `holds`, else `Failed`.
    pub fn from_bool(holds: bool) -> Self {
        if holds {
            Decision::Passed
        } else {
            Decision::Failed
        }
    }

    /// Whether the claim passed (false when failed or undecided).
    pub fn passed(self) -> bool {
        self == Decision::Passed
    }

    /// Whether the data decide the claim.
    pub fn is_decided(self) -> bool {
        self != Decision::Undecided
    }

    /// The conjunction: failed if any failed, else undecided if any is undecided, else
    /// passed (also for none).
    pub fn all(decisions: impl IntoIterator<Item = Decision>) -> Self {
        let mut out = Decision::Passed;
        for d in decisions {
            match d {
                Decision::Failed => return Decision::Failed,
                Decision::Undecided => out = Decision::Undecided,
                Decision::Passed => {}
            }
        }
        out
    }
}

impl std::ops::Not for Decision {
    type Output = Decision;

    /// The opposite claim: passed and failed swap, undecided stays.
    fn not(self) -> Self {
        match self {
            Decision::Passed => Decision::Failed,
            Decision::Failed => Decision::Passed,
            Decision::Undecided => Decision::Undecided,
        }
    }
}

/// Decides `claim` about `estimate` at `significance` standard errors: undecided when the
/// estimate has no error bar or no finite value, else whether the interval
/// `value +- significance std_error` satisfies the claim.
pub fn decide(estimate: Estimate, claim: Claim, significance: f64) -> Decision {
    if !(estimate.value.is_finite() && estimate.has_error()) {
        return Decision::Undecided;
    }
    let v = estimate.value;
    let half = significance * estimate.std_error;
    Decision::from_bool(match claim {
        Claim::Above(threshold) => v - half > threshold,
        Claim::Below(threshold) => v + half < threshold,
        Claim::Near { target, tolerance } => (v - target).abs() <= half + tolerance,
        Claim::Within { target, resolution } => (v - target).abs() + half <= resolution,
        Claim::Overlaps(lo, hi) => v + half >= lo && v - half <= hi,
    })
}

/// The values a statement asserts: an interval, each end open or closed, possibly
/// infinite, or every value but one ([`Region::Except`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Region {
    /// `lo < x < hi`, with the ends included where closed.
    Interval {
        /// Lower end (may be `-inf`).
        lo: f64,
        /// Whether `lo` belongs to the region.
        lo_closed: bool,
        /// Upper end (may be `inf`).
        hi: f64,
        /// Whether `hi` belongs to the region.
        hi_closed: bool,
    },
    /// Every value outside the band `[lo, hi]` (a law stated as violated, without a
    /// direction: the band is where the law holds to the resolution).
    Outside(f64, f64),
    /// Every value but this one (no band: never contradicted; outcomes of earlier versions
    /// hold it).
    Except(f64),
}

impl Region {
    /// `[lo, hi]`.
    pub fn closed(lo: f64, hi: f64) -> Self {
        Region::Interval {
            lo,
            lo_closed: true,
            hi,
            hi_closed: true,
        }
    }

    /// `(t, inf)`.
    pub fn above(t: f64) -> Self {
        Region::Interval {
            lo: t,
            lo_closed: false,
            hi: f64::INFINITY,
            hi_closed: false,
        }
    }

    /// `(-inf, t)`.
    pub fn below(t: f64) -> Self {
        Region::Interval {
            lo: f64::NEG_INFINITY,
            lo_closed: false,
            hi: t,
            hi_closed: false,
        }
    }

    /// `[t, inf)`.
    pub fn at_least(t: f64) -> Self {
        Region::Interval {
            lo: t,
            lo_closed: true,
            hi: f64::INFINITY,
            hi_closed: false,
        }
    }

    /// `(-inf, t]`.
    pub fn at_most(t: f64) -> Self {
        Region::Interval {
            lo: f64::NEG_INFINITY,
            lo_closed: false,
            hi: t,
            hi_closed: true,
        }
    }

    /// Whether the value `x` lies in the region.
    pub fn contains(&self, x: f64) -> bool {
        match *self {
            Region::Interval {
                lo,
                lo_closed,
                hi,
                hi_closed,
            } => {
                let above_lo = if lo_closed { x >= lo } else { x > lo };
                let below_hi = if hi_closed { x <= hi } else { x < hi };
                above_lo && below_hi
            }
            Region::Outside(lo, hi) => x < lo || x > hi,
            Region::Except(t) => x != t,
        }
    }

    /// The distance from `x` to the region's edge: how far the value may move before it
    /// leaves the region (inside) or enters it (outside); infinite where no edge is near.
    pub fn margin(&self, x: f64) -> f64 {
        match *self {
            Region::Interval { lo, hi, .. } => {
                if self.contains(x) {
                    (x - lo).min(hi - x)
                } else if x < lo {
                    lo - x
                } else {
                    x - hi
                }
            }
            Region::Outside(lo, hi) => {
                if x < lo {
                    lo - x
                } else if x > hi {
                    x - hi
                } else {
                    (x - lo).min(hi - x)
                }
            }
            Region::Except(t) => (x - t).abs(),
        }
    }
}

/// Whether the data establish that an estimate lies in `region`, in three values: passed
/// (established) when the whole interval `value +- z std_error` lies in the region, failed
/// (contradicted) when none of it does, undecided (not established) otherwise, and when
/// the estimate has no error bar or no finite value. A region outside a band is
/// contradicted when the whole interval lies inside the band. A region of every value but
/// one is never contradicted: no interval of finite width excludes all other values.
pub fn establish(estimate: Estimate, region: Region, significance: f64) -> Decision {
    if !(estimate.value.is_finite() && estimate.has_error()) {
        return Decision::Undecided;
    }
    let half = significance * estimate.std_error;
    let (a, b) = (estimate.value - half, estimate.value + half);
    match region {
        Region::Interval {
            lo,
            lo_closed,
            hi,
            hi_closed,
        } => {
            if region.contains(a) && region.contains(b) {
                Decision::Passed
            } else {
                let left_of = if lo_closed { b < lo } else { b <= lo };
                let right_of = if hi_closed { a > hi } else { a >= hi };
                if left_of || right_of {
                    Decision::Failed
                } else {
                    Decision::Undecided
                }
            }
        }
        Region::Outside(lo, hi) => {
            if b < lo || a > hi {
                Decision::Passed
            } else if a >= lo && b <= hi {
                Decision::Failed
            } else {
                Decision::Undecided
            }
        }
        Region::Except(t) => {
            if t < a || t > b {
                Decision::Passed
            } else {
                Decision::Undecided
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const Z: f64 = 3.0;

    #[test]
    fn a_region_is_established_contradicted_or_neither() {
        let e = |v, s| Estimate::new(v, s);
        let r = Region::closed(0.9, 1.1);
        assert_eq!(establish(e(1.0, 0.01), r, 3.0), Decision::Passed);
        assert_eq!(establish(e(1.0, 0.05), r, 3.0), Decision::Undecided);
        assert_eq!(establish(e(1.5, 0.05), r, 3.0), Decision::Failed);
        // A sign: established above 2.1 standard errors, never contradicted by one below.
        assert_eq!(
            establish(e(-0.186, 0.089), Region::below(0.0), 3.0),
            Decision::Undecided
        );
        assert_eq!(
            establish(e(-0.186, 0.05), Region::below(0.0), 3.0),
            Decision::Passed
        );
        assert_eq!(
            establish(e(0.186, 0.05), Region::below(0.0), 3.0),
            Decision::Failed
        );
        // An open end: an interval ending on it does not reach into the region.
        assert_eq!(
            establish(e(-1.0, 1.0 / 3.0), Region::above(0.0), 3.0),
            Decision::Failed
        );
        assert_eq!(establish(e(1.0, f64::NAN), r, 3.0), Decision::Undecided);
        assert_eq!(
            establish(e(1.0, 0.1), Region::Except(0.5), 3.0),
            Decision::Passed
        );
        assert_eq!(
            establish(e(1.0, 0.1), Region::Except(1.1), 3.0),
            Decision::Undecided
        );
        // A law violated: outside its band is established, inside it contradicted.
        let violated = Region::Outside(0.9, 1.1);
        assert_eq!(establish(e(0.41, 0.015), violated, 3.0), Decision::Passed);
        assert_eq!(establish(e(1.0, 0.02), violated, 3.0), Decision::Failed);
        assert_eq!(establish(e(1.05, 0.02), violated, 3.0), Decision::Undecided);
        assert!(violated.contains(0.5) && !violated.contains(1.0));
        assert!((violated.margin(1.0) - 0.1).abs() < 1e-12);
        assert!((violated.margin(0.5) - 0.4).abs() < 1e-12);
        assert!(Region::closed(0.9, 1.1).contains(1.0));
        assert!((Region::closed(0.9, 1.1).margin(1.0) - 0.1).abs() < 1e-12);
        assert!((Region::above(0.0).margin(-0.5) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn claims_read_the_interval_at_the_significance() {
        let e = Estimate::new(1.0, 0.1);
        // Interval [0.7, 1.3] at z = 3.
        assert_eq!(decide(e, Claim::Above(0.6), Z), Decision::Passed);
        assert_eq!(decide(e, Claim::Above(0.8), Z), Decision::Failed);
        assert_eq!(decide(e, Claim::Below(1.4), Z), Decision::Passed);
        assert_eq!(decide(e, Claim::Below(1.2), Z), Decision::Failed);
        let near = |target, tolerance| Claim::Near { target, tolerance };
        assert_eq!(decide(e, near(1.25, 0.0), Z), Decision::Passed);
        assert_eq!(decide(e, near(1.5, 0.0), Z), Decision::Failed);
        assert_eq!(decide(e, near(1.5, 0.25), Z), Decision::Passed);
        let within = |target, resolution| Claim::Within { target, resolution };
        assert_eq!(decide(e, within(1.0, 0.35), Z), Decision::Passed);
        assert_eq!(decide(e, within(1.0, 0.25), Z), Decision::Failed);
        assert_eq!(decide(e, Claim::Overlaps(1.2, 2.0), Z), Decision::Passed);
        assert_eq!(decide(e, Claim::Overlaps(1.4, 2.0), Z), Decision::Failed);
        assert_eq!(decide(e, Claim::Overlaps(0.0, 0.6), Z), Decision::Failed);
    }

    #[test]
    fn without_an_error_bar_nothing_is_decided() {
        let one = Estimate::mean_of(&[0.5]);
        for claim in [
            Claim::Above(0.0),
            Claim::Below(1.0),
            Claim::Near {
                target: 0.5,
                tolerance: 1.0,
            },
            Claim::Within {
                target: 0.5,
                resolution: 1.0,
            },
            Claim::Overlaps(0.0, 1.0),
        ] {
            assert_eq!(decide(one, claim, Z), Decision::Undecided, "{claim:?}");
            // Not even a comparison of the value alone.
            assert_eq!(decide(one, claim, 0.0), Decision::Undecided, "{claim:?}");
        }
        let no_value = Estimate::new(f64::NAN, 0.1);
        assert_eq!(decide(no_value, Claim::Above(0.0), Z), Decision::Undecided);
    }

    #[test]
    fn a_zero_significance_compares_the_value_alone() {
        let e = Estimate::new(0.2, 5.0);
        assert_eq!(decide(e, Claim::Above(0.0), 0.0), Decision::Passed);
        assert_eq!(decide(e, Claim::Below(0.2), 0.0), Decision::Failed);
        // An exact value (zero error) is decided at any significance.
        let exact = Estimate::new(0.2, 0.0);
        assert_eq!(decide(exact, Claim::Above(0.1), Z), Decision::Passed);
    }

    #[test]
    fn decisions_combine_in_three_valued_logic() {
        use Decision::*;
        assert_eq!(Decision::all([Passed, Passed]), Passed);
        assert_eq!(Decision::all([Passed, Undecided]), Undecided);
        assert_eq!(Decision::all([Undecided, Failed, Passed]), Failed);
        assert_eq!(Decision::all([]), Passed);
        assert_eq!(!Passed, Failed);
        assert_eq!(!Undecided, Undecided);
        assert!(Passed.passed() && !Undecided.passed() && !Undecided.is_decided());
    }
}
