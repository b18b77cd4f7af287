//! The audit of a run folder's stored job results (`persson-check audit`): a sample of
//! them recomputed alone with this build and compared byte for byte
//! ([`crate::validation::audit`] picks, recomputes and compares), reported as `audit.md`
//! and `audit.json`.
//!
//! The report says, for every job, why it was sampled, whether its result is identical,
//! and where it is not: every number that differs with its absolute and relative
//! difference, and whether the stored result came from another commit or another version
//! of its definition. It gives the cost model's estimate beside the measured time of each
//! job, and the validations and solvers no job of the sample covers.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;
use serde_json::Value;

use crate::error::{Error, Result};
use crate::plot::significant;
use crate::provenance;
use crate::validation::audit::{
    candidates, differences, only_measured_times, pick, recompute, top_level_value, Candidate,
    Difference, Found, Reason, Uncovered, Unstored, COST_MARGIN,
};
use crate::validation::source::{builtin_sources, select, Source};
use crate::validation::Registry;

mod page;

use page::times;

/// The budget when neither jobs nor validations are named: 20 minutes.
pub const DEFAULT_BUDGET_S: f64 = 1200.0;

/// Differences listed per job in `audit.json` (all are counted).
pub(super) const LISTED: usize = 200;
/// Differences shown per job in `audit.md`.
pub(super) const SHOWN: usize = 8;

/// What to audit.
#[derive(Debug, Clone)]
pub struct AuditOptions {
    /// The run folder (holding `jobs/`).
    pub from: PathBuf,
    /// Where `audit.md` and `audit.json` go (and the scratch folder while it runs).
    pub out: PathBuf,
    /// Wall-time budget, seconds (`None`: every job selected).
    pub budget_s: Option<f64>,
    /// Seed of the random part of the sample.
    pub seed: u64,
    /// Only these jobs, by key (every one of them, whatever the budget).
    pub jobs: Vec<String>,
    /// Only the jobs these validations need.
    pub validations: Vec<String>,
}

/// What became of one job.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "finding", rename_all = "snake_case")]
pub enum Finding {
    /// The recomputed result equals the stored one byte for byte.
    Identical,
    /// The results differ in measured times alone (a history's own wall time), every
    /// computed number equal.
    IdenticalButTimes {
        /// The measured times, stored and recomputed.
        differences: Vec<Difference>,
    },
    /// The bytes differ.
    Differs {
        /// How many values differ.
        count: usize,
        /// The largest relative difference of two numbers.
        largest_rel: Option<f64>,
        /// The first of them.
        differences: Vec<Difference>,
    },
    /// The job could not be recomputed (or its stored file read).
    Failed {
        /// Why.
        error: String,
    },
    /// Not run: the budget was spent.
    NotRun {
        /// Why.
        why: String,
    },
}

/// One audited job.
#[derive(Debug, Clone, Serialize)]
pub struct JobAudit {
    /// The job, as the candidate lists it.
    #[serde(flatten)]
    pub job: Candidate,
    /// Why it was sampled.
    pub reason: Reason,
    /// Wall time of the recomputation, seconds.
    pub measured_s: Option<f64>,
    /// Whether the stored result's commit is not this build's (`None`: no provenance).
    pub commit_differs: Option<bool>,
    /// Whether the definition that computed it is not this build's copy.
    pub definition_differs: Option<bool>,
    /// What was found.
    #[serde(flatten)]
    pub finding: Finding,
}

impl JobAudit {
    /// The job in one line: key, validations, solver, finding, times.
    pub fn line(&self) -> String {
        let finding = match &self.finding {
            Finding::Identical => "identical".to_string(),
            Finding::IdenticalButTimes { differences } => format!(
                "identical but for its measured time ({})",
                times(differences)
            ),
            Finding::Differs {
                count, largest_rel, ..
            } => format!(
                "DIFFERS: {count} value{} (largest relative difference {}){}",
                if *count == 1 { "" } else { "s" },
                largest_rel.map_or("n/a".into(), |r| significant(r, 2)),
                if self.commit_differs == Some(true) {
                    ", stored by another commit"
                } else {
                    ""
                }
            ),
            Finding::Failed { error } => format!("FAILED: {error}"),
            Finding::NotRun { why } => format!("not run: {why}"),
        };
        format!(
            "{} {} {:<5} {}: {finding} [{} estimated {}]",
            self.job.key,
            self.job.validations.join("+"),
            self.job.solver.name(),
            self.job.job,
            self.measured_s
                .map_or("".into(), |m| format!("{} measured,", minutes(m))),
            minutes(self.job.estimate_s),
        )
    }
}

/// What the audit is about to do or has done, for a front end's progress display.
pub enum Event<'a> {
    /// The sample is drawn: how many jobs, estimated seconds in all.
    Planned(usize, f64),
    /// Job `k` (from 0) starts.
    Started(usize, &'a Candidate),
    /// A job is done.
    Done(&'a JobAudit),
}

/// The audit.
#[derive(Debug, Clone, Serialize)]
pub struct Audit {
    /// The run folder.
    pub from: PathBuf,
    /// This build's commit.
    pub commit: String,
    /// The machine's name.
    pub host: String,
    /// Worker threads.
    pub threads: usize,
    /// Start, RFC 3339 UTC.
    pub started: String,
    /// The seed.
    pub seed: u64,
    /// The budget, seconds.
    pub budget_s: Option<f64>,
    /// The factor on estimates when fitting the budget.
    pub margin: f64,
    /// Stored results that today's definitions plan (after any filter).
    pub candidates: usize,
    /// Stored results no job of today's definitions names.
    pub orphans: Vec<PathBuf>,
    /// Validations and solvers no sampled job covers.
    pub uncovered: Vec<Uncovered>,
    /// Validations and solvers (every solver of the crate) with no stored result at all.
    pub unstored: Vec<Unstored>,
    /// Solvers outside a default run of which the folder holds no result.
    pub idle_solvers: Vec<String>,
    /// Every sampled job, in run order.
    pub jobs: Vec<JobAudit>,
    /// The estimate of the jobs run, seconds.
    pub estimate_s: f64,
    /// Their measured time, seconds.
    pub measured_s: f64,
    /// The audit in one paragraph.
    pub summary: String,
    /// No job that ran differs or failed (a job the budget left out fails nothing).
    pub passed: bool,
}

/// Parses a duration: a number with `s`, `m` (or `min`) or `h`, e.g. `20m`, `2h`, `90s`.
///
/// # Errors
///
/// If `text` is not a positive number followed by one of the units.
pub fn parse_budget(text: &str) -> Result<f64> {
    let bad = || {
        Error::invalid(
            "--budget",
            text,
            "a duration > 0 with its unit: 90s, 20m, 2h (or 1.5h)",
        )
    };
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .ok_or_else(bad)?;
    let (number, unit) = t.split_at(split);
    let x: f64 = number.parse().map_err(|_| bad())?;
    let scale = match unit.trim() {
        "s" => 1.0,
        "m" | "min" => 60.0,
        "h" => 3600.0,
        _ => return Err(bad()),
    };
    if !(x.is_finite() && x > 0.0) {
        return Err(bad());
    }
    Ok(x * scale)
}

/// Minutes or seconds in words: `42 s`, `3.5 min`, `1.2 h`.
pub fn minutes(s: f64) -> String {
    if s < 60.0 {
        format!("{} s", significant(s, 2))
    } else if s < 3600.0 {
        format!("{} min", significant(s / 60.0, 2))
    } else {
        format!("{} h", significant(s / 3600.0, 2))
    }
}

/// The hash of a commit label (`<hash> (with uncommitted changes)` -> `<hash>`).
pub(super) fn hash(label: &str) -> &str {
    label.split_whitespace().next().unwrap_or("")
}

/// The candidates of `opts.from` after the filters, with every validation and job named
/// checked; the orphans and the validations and solvers without stored results as found.
fn chosen(registry: &Registry, sources: &[Source], opts: &AuditOptions) -> Result<Found> {
    if !opts.from.join("jobs").is_dir() {
        return Err(Error::invalid(
            "--from",
            opts.from.display(),
            "a run folder with stored job results (<from>/jobs/<family>/<scale>/<key>.json)",
        ));
    }
    select(sources.to_vec(), &opts.validations).map_err(|e| e.with_field("--validation"))?;
    let mut found = candidates(registry, sources, &opts.from)?;
    let named = |v: &String| opts.validations.is_empty() || opts.validations.contains(v);
    found.unstored.retain(|u| named(&u.validation));
    let mut cands: Vec<Candidate> = std::mem::take(&mut found.candidates)
        .into_iter()
        .filter(|c| c.validations.iter().any(named))
        .collect();
    if !opts.jobs.is_empty() {
        for key in &opts.jobs {
            if cands.iter().any(|c| &c.key == key) {
                continue;
            }
            let orphan = found
                .orphans
                .iter()
                .any(|p| p.file_stem().is_some_and(|s| s.to_string_lossy() == *key));
            let allowed = if orphan {
                "a job today's definitions plan (this result's key is no job of theirs: its \
                 scene was edited since)"
                    .to_string()
            } else {
                format!(
                    "the key of a stored result under {}/jobs{}",
                    opts.from.display(),
                    if opts.validations.is_empty() {
                        ""
                    } else {
                        " of the validations named"
                    }
                )
            };
            return Err(Error::invalid("--job", key, allowed));
        }
        cands.retain(|c| opts.jobs.contains(&c.key));
    }
    if cands.is_empty() {
        return Err(Error::invalid(
            "--from",
            opts.from.display(),
            "a run folder holding results of jobs today's definitions plan",
        ));
    }
    found.candidates = cands;
    Ok(found)
}

/// Audits `opts.from`: draws the sample, recomputes each job in turn (telling `event`),
/// writes `audit.md` and `audit.json` into `opts.out`.
///
/// # Errors
///
/// If the budget is not positive, `opts.out` is not a folder, `opts.from` holds no
/// stored job results, a validation or job named is unknown, a stored result cannot be
/// read, or the audit's files cannot be written.
pub fn audit(
    registry: &Registry,
    opts: &AuditOptions,
    event: &mut dyn FnMut(Event),
) -> Result<Audit> {
    if let Some(b) = opts.budget_s {
        if !(b.is_finite() && b > 0.0) {
            return Err(Error::invalid("--budget", b, "a duration > 0"));
        }
    }
    super::check_out_dir(&opts.out, &super::Flags::default())?;
    let sources = builtin_sources();
    let Found {
        candidates: cands,
        orphans,
        unstored,
        idle_solvers,
    } = chosen(registry, &sources, opts)?;
    let budget = if opts.jobs.is_empty() {
        opts.budget_s
    } else {
        None
    };
    let mut selection = pick(&cands, budget, opts.seed);
    if !opts.jobs.is_empty() {
        for p in &mut selection.picks {
            p.1 = Reason::Named;
        }
    }
    event(Event::Planned(selection.picks.len(), selection.estimate_s));
    let scratch = opts.out.join("scratch");
    let started = provenance::now_utc();
    let timer = Instant::now();
    let mut jobs = Vec::new();
    for (k, (i, reason)) in selection.picks.iter().enumerate() {
        let c = &cands[*i];
        let elapsed = timer.elapsed().as_secs_f64();
        let finding_before = match budget {
            Some(b) if elapsed + c.estimate_s * COST_MARGIN > b => Some(Finding::NotRun {
                why: format!(
                    "{} of the budget's {} spent, the job estimated at {} (times {COST_MARGIN})",
                    minutes(elapsed),
                    minutes(b),
                    minutes(c.estimate_s)
                ),
            }),
            _ => None,
        };
        if finding_before.is_none() {
            event(Event::Started(k, c));
        }
        let (finding, measured_s) = match finding_before {
            Some(f) => (f, None),
            None => audit_one(registry, &sources, c, &opts.from, &scratch),
        };
        let stored = c.stored.as_ref();
        let job = JobAudit {
            job: c.clone(),
            reason: reason.clone(),
            measured_s,
            commit_differs: stored.map(|r| hash(&r.commit) != provenance::COMMIT),
            definition_differs: stored.and_then(|r| {
                let source = select(sources.clone(), std::slice::from_ref(&r.definition)).ok()?;
                Some(source.first()?.sha256() != r.definition_sha256)
            }),
            finding,
        };
        event(Event::Done(&job));
        jobs.push(job);
    }
    std::fs::remove_dir_all(&scratch).ok();
    let ran = |j: &&JobAudit| j.measured_s.is_some();
    let mut audit = Audit {
        from: opts.from.clone(),
        commit: provenance::commit_label(),
        host: crate::io::host_name(),
        threads: rayon::current_num_threads(),
        started,
        seed: opts.seed,
        budget_s: budget,
        margin: COST_MARGIN,
        candidates: cands.len(),
        orphans,
        uncovered: selection.uncovered,
        unstored,
        idle_solvers,
        estimate_s: jobs.iter().filter(ran).map(|j| j.job.estimate_s).sum(),
        measured_s: jobs.iter().filter_map(|j| j.measured_s).sum(),
        passed: !jobs
            .iter()
            .any(|j| matches!(j.finding, Finding::Differs { .. } | Finding::Failed { .. })),
        jobs,
        summary: String::new(),
    };
    audit.summary = audit.summary_text();
    audit.write(&opts.out)?;
    Ok(audit)
}

/// Recomputes one job and compares it with the stored result: the finding and the
/// measured time.
fn audit_one(
    registry: &Registry,
    sources: &[Source],
    c: &Candidate,
    from: &Path,
    scratch: &Path,
) -> (Finding, Option<f64>) {
    let failed = |e: String| (Finding::Failed { error: e }, None);
    let source = match select(sources.to_vec(), &c.validations[..1]) {
        Ok(s) => s.into_iter().next().expect("one definition selected"),
        Err(e) => return failed(e.to_string()),
    };
    let stored_path = from.join(&c.relative);
    let stored = match std::fs::read(&stored_path) {
        Ok(b) => b,
        Err(e) => return failed(Error::io(&stored_path, e).to_string()),
    };
    let again = match recompute(registry, &source, c, scratch) {
        Ok(r) => r,
        Err(e) => return failed(e.to_string()),
    };
    let measured = Some(again.wall_s);
    let (Some(a), Some(b)) = (
        top_level_value(&stored, "result"),
        top_level_value(&again.bytes, "result"),
    ) else {
        return (
            Finding::Failed {
                error: format!("{}: no `result` in the stored file", stored_path.display()),
            },
            measured,
        );
    };
    if a == b {
        return (Finding::Identical, measured);
    }
    let parse = |bytes: &[u8]| serde_json::from_slice::<Value>(bytes).unwrap_or(Value::Null);
    let (count, listed) = differences("result", &parse(a), &parse(b), usize::MAX);
    if only_measured_times(&listed) {
        return (
            Finding::IdenticalButTimes {
                differences: listed,
            },
            measured,
        );
    }
    let largest_rel = listed
        .iter()
        .filter_map(|d| d.rel)
        .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))));
    let finding = Finding::Differs {
        // Bytes that differ with equal values (white space, key order) still differ.
        count: count.max(1),
        largest_rel,
        differences: listed.into_iter().take(LISTED).collect(),
    };
    (finding, measured)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_read_with_their_units() {
        assert_eq!(parse_budget("20m").unwrap(), 1200.0);
        assert_eq!(parse_budget("2h").unwrap(), 7200.0);
        assert_eq!(parse_budget("1.5h").unwrap(), 5400.0);
        assert_eq!(parse_budget("90s").unwrap(), 90.0);
        assert_eq!(parse_budget("5min").unwrap(), 300.0);
        for bad in ["20", "m", "0m", "-5m", "5 days", ""] {
            let e = parse_budget(bad).unwrap_err().to_string();
            assert!(e.contains("--budget"), "{bad}: {e}");
        }
    }
}
