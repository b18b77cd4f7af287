//! The audit's page: `audit.md` (the summary, one row per job, every number that differs,
//! what is not covered) and `audit.json` beside it.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

use super::{hash, minutes, Audit, Finding, JobAudit, LISTED, SHOWN};
use crate::error::Result;
use crate::plot::significant;
use crate::validation::audit::{Difference, Reason};

/// Measured times, stored against recomputed: `result.wall_s 2800 s -> 4700 s`.
pub(super) fn times(differences: &[Difference]) -> String {
    let seconds = |v: &Option<Value>| {
        v.as_ref()
            .and_then(Value::as_f64)
            .map_or("n/a".into(), minutes)
    };
    differences
        .iter()
        .map(|d| {
            format!(
                "{} {} stored, {} now",
                d.path,
                seconds(&d.stored),
                seconds(&d.recomputed)
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

impl Audit {
    fn count(&self, f: impl Fn(&Finding) -> bool) -> usize {
        self.jobs.iter().filter(|j| f(&j.finding)).count()
    }

    /// The pairs (validation, solver) the jobs run cover.
    fn covered(&self) -> Vec<(String, String)> {
        let mut out: Vec<(String, String)> = Vec::new();
        for j in self.jobs.iter().filter(|j| j.measured_s.is_some()) {
            for v in &j.job.validations {
                let pair = (v.clone(), j.job.solver.name().to_string());
                if !out.contains(&pair) {
                    out.push(pair);
                }
            }
        }
        out.sort();
        out
    }

    /// The summary: how many jobs were recomputed, covering what, and what they found.
    pub(super) fn summary_text(&self) -> String {
        let identical = self.count(|f| matches!(f, Finding::Identical));
        let timed = self.count(|f| matches!(f, Finding::IdenticalButTimes { .. }));
        let differ = self.count(|f| matches!(f, Finding::Differs { .. }));
        let failed = self.count(|f| matches!(f, Finding::Failed { .. }));
        let not_run = self.count(|f| matches!(f, Finding::NotRun { .. }));
        let covered = self.covered();
        let validations: std::collections::BTreeSet<&String> =
            covered.iter().map(|(v, _)| v).collect();
        let mut s = format!(
            "{} of {} stored job results recomputed, covering {} validation-solver pair{} of \
             {} validation{}: {identical} identical{}, {differ} differ{}, {failed} failed; \
             measured {} against the cost model's {}.",
            self.jobs.len() - not_run,
            self.candidates,
            covered.len(),
            if covered.len() == 1 { "" } else { "s" },
            validations.len(),
            if validations.len() == 1 { "" } else { "s" },
            if timed > 0 {
                format!(
                    ", {timed} identical but for the wall time the result records (a \
                     re-entry history's)"
                )
            } else {
                String::new()
            },
            if differ == 1 { "s" } else { "" },
            minutes(self.measured_s),
            minutes(self.estimate_s),
        );
        if not_run > 0 {
            let _ = write!(
                s,
                " {not_run} sampled job{} not run (budget spent).",
                if not_run == 1 { "" } else { "s" }
            );
        }
        if !self.uncovered.is_empty() {
            let list: Vec<String> = self
                .uncovered
                .iter()
                .map(|u| {
                    format!(
                        "{} {} (cheapest job {})",
                        u.validation,
                        u.solver,
                        minutes(u.estimate_s)
                    )
                })
                .collect();
            let _ = write!(s, " Not covered within the budget: {}.", list.join(", "));
        }
        if !self.unstored.is_empty() {
            let list: Vec<String> = self
                .unstored
                .iter()
                .map(|u| format!("{} {} ({} jobs planned)", u.validation, u.solver, u.planned))
                .collect();
            let _ = write!(s, " No stored result at all: {}.", list.join(", "));
        }
        if !self.idle_solvers.is_empty() {
            let _ = write!(
                s,
                " No results of {} (not in a default run) to audit.",
                self.idle_solvers.join(", ")
            );
        }
        if !self.orphans.is_empty() {
            let _ = write!(
                s,
                " {} stored result{} no job of today's definitions names.",
                self.orphans.len(),
                if self.orphans.len() == 1 { "" } else { "s" }
            );
        }
        s
    }

    /// `audit.md`: the summary, one row per job, the differences, what is not covered.
    pub fn markdown(&self) -> String {
        let mut s = self.header();
        s.push_str(&self.job_table());
        for j in &self.jobs {
            s.push_str(&section(j));
        }
        s.push_str(&self.lists());
        s
    }

    /// The title, the summary, whether it passed, and what recomputed it.
    fn header(&self) -> String {
        let mut s = format!(
            "# Audit of `{}`\n\n**Summary.** {}\n\n{}\n\n",
            self.from.display(),
            self.summary,
            if self.passed {
                "Every job that ran gave its stored result, byte for byte (any measured wall \
                 time a result records aside)."
            } else {
                "**Failed:** a recomputed job differs from its stored result, or failed."
            }
        );
        let _ = writeln!(
            s,
            "Recomputed by commit `{}` on `{}` with {} thread{}, from {}; seed {}, budget {}.\n",
            self.commit,
            self.host,
            self.threads,
            if self.threads == 1 { "" } else { "s" },
            self.started,
            self.seed,
            self.budget_s
                .map_or("none (every job selected)".into(), |b| format!(
                    "{} (jobs sampled while their estimates times {} fit)",
                    minutes(b),
                    self.margin
                )),
        );
        s
    }

    /// One row per job: why it was sampled, what it found, its times and provenance.
    fn job_table(&self) -> String {
        let mut s = String::from(
            "| job | validations | solver | job description | why | finding | measured | \
             estimated | stored run | stored by |\n|---|---|---|---|---|---|---|---|---|---|\n",
        );
        for j in &self.jobs {
            let finding = match &j.finding {
                Finding::Identical => "identical".to_string(),
                Finding::IdenticalButTimes { differences } => {
                    format!(
                        "identical but for its measured time ({})",
                        times(differences)
                    )
                }
                Finding::Differs { count, .. } => format!("**differs** ({count} values)"),
                Finding::Failed { .. } => "**failed**".into(),
                Finding::NotRun { .. } => "not run (budget)".into(),
            };
            let why = match &j.reason {
                Reason::Named => "named".to_string(),
                Reason::Cheapest { validation, solver } => {
                    format!("cheapest of {validation} {solver}")
                }
                Reason::Random => "random".into(),
            };
            let stored_by = match (&j.job.stored, j.commit_differs) {
                (Some(r), Some(true)) => format!(
                    "`{}` (another commit)",
                    &hash(&r.commit)[..hash(&r.commit).len().min(10)]
                ),
                (Some(_), _) => "this commit".into(),
                (None, _) => "no provenance".into(),
            };
            let _ = writeln!(
                s,
                "| `{}` | {} | {} | `{}` | {why} | {finding} | {} | {} | {} | {stored_by} |",
                j.job.key,
                j.job.validations.join(", "),
                j.job.solver.name(),
                j.job.job,
                j.measured_s.map_or("".into(), minutes),
                minutes(j.job.estimate_s),
                j.job
                    .stored
                    .as_ref()
                    .map_or("".into(), |r| minutes(r.wall_s)),
            );
        }
        s.push('\n');
        s
    }

    /// The validations and solvers without any stored result, and the stored results no
    /// job names.
    fn lists(&self) -> String {
        let mut s = String::new();
        if !self.unstored.is_empty() {
            s.push_str("## Validations and solvers without a stored result\n\n");
            for u in &self.unstored {
                let _ = writeln!(
                    s,
                    "- {} {}: none of its {} jobs has a stored result",
                    u.validation, u.solver, u.planned
                );
            }
            s.push('\n');
        }
        if !self.orphans.is_empty() {
            s.push_str("## Stored results no job of today's definitions names\n\n");
            for p in &self.orphans {
                let _ = writeln!(s, "- `{}`", p.display());
            }
        }
        s
    }

    /// Writes `audit.md` and `audit.json` into `out`.
    ///
    /// # Errors
    ///
    /// If a file cannot be written ([`crate::Error::Io`]).
    pub fn write(&self, out: &Path) -> Result<()> {
        crate::io::write_atomic(&out.join("audit.md"), self.markdown().as_bytes())?;
        let json = serde_json::to_vec_pretty(self).expect("audits serialise");
        crate::io::write_atomic(&out.join("audit.json"), &json)
    }
}

/// The section of a job that differs (its provenance and up to [`SHOWN`] of the numbers
/// that differ) or failed (its error); nothing for any other job.
fn section(j: &JobAudit) -> String {
    let mut s = String::new();
    match &j.finding {
        Finding::Differs {
            count, differences, ..
        } => {
            let _ = writeln!(
                s,
                "## `{}`: {count} value{} differ{}\n",
                j.job.key,
                if *count == 1 { "" } else { "s" },
                if *count == 1 { "s" } else { "" }
            );
            let _ = writeln!(
                s,
                "Stored by {} ({}); the definition that computed it is {}.\n",
                j.job
                    .stored
                    .as_ref()
                    .map_or("an unknown commit".into(), |r| format!(
                        "commit `{}` on {}",
                        r.commit, r.host
                    )),
                match j.commit_differs {
                    Some(true) => "another commit than this build's",
                    Some(false) => "this build's commit",
                    None => "no provenance",
                },
                match j.definition_differs {
                    Some(true) => "not today's copy",
                    Some(false) => "today's copy",
                    None => "unknown",
                }
            );
            s.push_str(
                "| where | stored | recomputed | difference | relative |\n|---|---|---|---|---|\n",
            );
            for d in differences.iter().take(SHOWN) {
                let v = |x: &Option<Value>| x.as_ref().map_or("(absent)".into(), |v| v.to_string());
                let _ = writeln!(
                    s,
                    "| `{}` | {} | {} | {} | {} |",
                    d.path,
                    v(&d.stored),
                    v(&d.recomputed),
                    d.abs.map_or("".into(), |a| significant(a, 3)),
                    d.rel.map_or("".into(), |r| significant(r, 3)),
                );
            }
            if *count > SHOWN {
                let _ = writeln!(
                    s,
                    "\n... and {} more (audit.json lists up to {LISTED}).",
                    count - SHOWN
                );
            }
            s.push('\n');
        }
        Finding::Failed { error } => {
            let _ = writeln!(s, "## `{}`: failed\n\n{error}\n", j.job.key);
        }
        _ => {}
    }
    s
}
