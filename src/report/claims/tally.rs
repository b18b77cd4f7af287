//! The claims counted by result ([`Counts`], with the class of each contradiction) and the
//! headline verdicts counted against the paper's.

use crate::validation::claims::ClaimKind;
use crate::validation::{ClaimOutcome, ClaimResult, Outcome, Verdict};

/// Why an evidence claim is contradicted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// Every reading the claim states is contradicted too (or it states none).
    DisagreesWithData,
    /// A rival reading of the paper's words gives another result.
    DecidedByAReading,
}

impl Class {
    /// The class in words.
    pub fn text(self) -> &'static str {
        match self {
            Class::DisagreesWithData => "disagrees with the data",
            Class::DecidedByAReading => "decided by a reading",
        }
    }

    /// The class of a contradicted claim: decided by a reading when a rival reading is
    /// measured and not contradicted.
    pub fn of(c: &ClaimOutcome) -> Self {
        let rival_differs = c.readings.iter().any(|r| {
            matches!(
                r.result,
                ClaimResult::Reproduced | ClaimResult::NotEstablished
            )
        });
        if rival_differs {
            Class::DecidedByAReading
        } else {
            Class::DisagreesWithData
        }
    }
}

/// The claims of a set of outcomes counted by result.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    /// Every claim.
    pub all: usize,
    /// Evidence claims reproduced.
    pub reproduced: usize,
    /// Evidence claims contradicted.
    pub contradicted: usize,
    /// Of those, decided by a reading.
    pub by_reading: usize,
    /// Evidence claims not established.
    pub not_established: usize,
    /// Evidence claims not measured.
    pub not_measured: usize,
    /// Evidence claims not judged at this scale.
    pub not_judged: usize,
    /// Consistency checks.
    pub consistency: usize,
    /// Statements the paper makes two ways.
    pub two_ways: usize,
}

impl Counts {
    /// The counts of `claims`.
    pub fn of<'a>(claims: impl IntoIterator<Item = &'a ClaimOutcome>) -> Self {
        let mut n = Counts::default();
        for c in claims {
            n.all += 1;
            match c.kind {
                ClaimKind::Consistency => n.consistency += 1,
                ClaimKind::Inconsistent => n.two_ways += 1,
                ClaimKind::Evidence => match c.result {
                    ClaimResult::Reproduced => n.reproduced += 1,
                    ClaimResult::Contradicted => {
                        n.contradicted += 1;
                        if Class::of(c) == Class::DecidedByAReading {
                            n.by_reading += 1;
                        }
                    }
                    ClaimResult::NotEstablished => n.not_established += 1,
                    ClaimResult::NotMeasured => n.not_measured += 1,
                    ClaimResult::NotJudgedAtThisScale => n.not_judged += 1,
                },
            }
        }
        n
    }

    /// Evidence claims.
    pub fn evidence(&self) -> usize {
        self.all - self.consistency - self.two_ways
    }

    /// The counts in words.
    pub fn text(&self) -> String {
        let judged = if self.not_judged > 0 {
            format!(", {} not judged at this scale", self.not_judged)
        } else {
            String::new()
        };
        format!(
            "{} claims; {} evidence: {} reproduced, {} contradicted ({} disagree with the \
             data, {} decided by a reading), {} not established, {} not measured{judged}; \
             counted apart: {} consistency checks, {} statements the paper makes two ways",
            self.all,
            self.evidence(),
            self.reproduced,
            self.contradicted,
            self.contradicted - self.by_reading,
            self.by_reading,
            self.not_established,
            self.not_measured,
            self.consistency,
            self.two_ways,
        )
    }
}

/// The claims of every outcome, in order.
pub(super) fn every_claim<'a>(outcomes: &[&'a Outcome]) -> Vec<&'a ClaimOutcome> {
    outcomes.iter().flat_map(|o| &o.claims).collect()
}

/// The claim counts of `outcomes` in words (the scorecard's and the main job's summary).
pub fn counts(outcomes: &[&Outcome]) -> String {
    Counts::of(every_claim(outcomes)).text()
}

/// The headline verdicts of `outcomes` against the paper's, in words: "10 of 10 headline
/// verdicts as the paper's (0 hold, 10 violated, 0 inconclusive)".
pub fn headlines(outcomes: &[&Outcome]) -> String {
    let count = |v: Verdict| outcomes.iter().filter(|o| o.verdict == v).count();
    let same = outcomes
        .iter()
        .filter(|o| o.reproduced == Some(true))
        .count();
    let differ: Vec<String> = outcomes
        .iter()
        .filter(|o| o.reproduced == Some(false))
        .map(|o| format!("`{}`", o.name))
        .collect();
    format!(
        "{same} of {} headline verdicts as the paper's ({} hold, {} violated, {} \
         inconclusive){}",
        outcomes.len(),
        count(Verdict::Holds),
        count(Verdict::Violated),
        count(Verdict::Inconclusive),
        if differ.is_empty() {
            String::new()
        } else {
            format!("; not as the paper: {}", differ.join(", "))
        }
    )
}
