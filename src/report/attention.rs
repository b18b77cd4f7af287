//! The summary's "needs attention" list: inconclusive verdicts, findings contradicted,
//! solvers that disagree, golden values that differ.

use super::format::{no_nan, num, pm, sig};
use super::golden::GoldenMatch;
use super::outcomes::Loaded;
use crate::stats::{decide, Claim, Estimate};
use crate::validation::claims::ClaimKind;
use crate::validation::{ClaimResult, Verdict};

/// Plain statements of what needs a reviewer's eye.
pub(super) fn attention(loaded: &[Loaded], golden: &[GoldenMatch]) -> Vec<String> {
    let mut lines = Vec::new();
    for (l, g) in loaded.iter().zip(golden) {
        let o = &l.outcome;
        if o.verdict == Verdict::Inconclusive {
            lines.push(format!(
                "{}: the verdict is INCONCLUSIVE: {} = {} does not separate \"holds\" from \
                 \"violated\" at z = {} with resolution {}; the paper's finding is therefore \
                 neither reproduced nor refuted.",
                o.name,
                o.statistic,
                pm(o.value, o.std_error),
                sig(o.rule.significance, 3),
                sig(o.rule.resolution, 3)
            ));
        }
        if o.reproduced == Some(false) {
            let failed: Vec<String> = o
                .checks
                .iter()
                .filter(|c| c.decided && !c.passed)
                .map(|c| format!("{} ({})", no_nan(&c.name), no_nan(&c.detail)))
                .collect();
            let claims: Vec<String> = o
                .claims
                .iter()
                .filter(|c| c.kind == ClaimKind::Evidence && c.result == ClaimResult::Contradicted)
                .map(|c| format!("`{}` ({})", c.key, no_nan(&c.paper)))
                .collect();
            let in_range = o.paper_range.is_none_or(|(lo, hi)| {
                decide(
                    Estimate::new(o.value, o.std_error),
                    Claim::Overlaps(lo, hi),
                    o.rule.significance,
                )
                .passed()
            });
            let mut reasons = Vec::new();
            if o.verdict != o.paper_verdict {
                reasons.push(format!(
                    "this run finds the assumption {} where the paper finds it {}",
                    o.verdict, o.paper_verdict
                ));
            }
            if !in_range {
                reasons.push(format!(
                    "the measurement lies outside the range that reproduces the paper (paper: {})",
                    o.paper_value.map_or_else(|| "no value stated".into(), num)
                ));
            }
            if !failed.is_empty() {
                reasons.push(format!("failed checks: {}", failed.join("; ")));
            }
            if !claims.is_empty() {
                reasons.push(format!("claims contradicted: {}", claims.join(", ")));
            }
            if reasons.is_empty() {
                reasons.push("the outcome names no reason (written by an older version?)".into());
            }
            let why = reasons.join("; ");
            lines.push(format!(
                "{}: the paper's finding is CONTRADICTED: {why}.",
                o.name
            ));
        }
        for c in o.cross_checks.iter().filter(|c| !c.agrees) {
            lines.push(format!(
                "{}: the two solvers DISAGREE: {} {} against {} {}, more than {} combined \
                 standard errors apart (or, without error bars, more than the resolution {}); \
                 the headline is not confirmed.",
                o.name,
                o.solver,
                pm(o.value, o.std_error),
                c.solver,
                pm(c.value, c.std_error),
                sig(o.rule.significance, 3),
                sig(o.rule.resolution, 3)
            ));
        }
        if let GoldenMatch::Differ(d, path) = g {
            lines.push(format!(
                "{}: {} golden value(s) differ from {}: {}.",
                o.name,
                d.len(),
                path.display(),
                d.join("; ")
            ));
        }
    }
    lines
}
