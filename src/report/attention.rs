//! The summary's "needs attention" list: inconclusive verdicts, headline verdicts that are
//! not the paper's, implementation guards that fail, solvers that disagree, golden values
//! that differ. The paper's claims are counted in their own section, never here: a side
//! claim does not make a validation "contradicted".

use super::format::{no_nan, pm, sig};
use super::golden::GoldenMatch;
use super::outcomes::Loaded;
use crate::validation::Verdict;

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
            lines.push(format!(
                "{}: the headline verdict is NOT THE PAPER'S: this run finds the assumption {} \
                 where the paper finds it {} ({} = {}).",
                o.name,
                o.verdict,
                o.paper_verdict,
                o.statistic,
                pm(o.value, o.std_error)
            ));
        }
        for g in o.guards.iter().filter(|g| g.decided && !g.passed) {
            lines.push(format!(
                "{}: an implementation guard FAILED: {} ({}).",
                o.name,
                no_nan(&g.name),
                no_nan(&g.detail)
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
