//! The plan of a run over many machines: every job of the named validations with its
//! estimated cost and its share ([`crate::conventions`], sections 7 and 8), and the checks
//! that let `--merge` conclude from the shares' stored results.
//!
//! A job's cost is estimated from its [`Work`] (grid points, load searches, warm-started
//! solves) as
//!
//! `t = c_solver * P log2(P) * (w_search (N / 256)^k * searches + solves + w_shell * shells)`
//!
//! seconds on one core, with `P = N^2` the grid points: an FFT-based iteration costs
//! `P log2 P`, and a solve a number of iterations that depends on the solver and on how
//! close its start is (a load search from cold, a step of a fraction of an octave, or a
//! single added shell). Warm starts take about as many iterations on every grid; a search
//! from cold takes more on larger grids, as `N^k` ([`SEARCH_GROWTH`]). The constants
//! ([`CG_SECONDS`] times the solver's [`SolverKind::relative_cost`], [`SEARCH_SOLVES`],
//! [`SHELL_SOLVES`]) are fitted to
//! the measured job times of the reduced scenes, and [`SEARCH_GROWTH`] to a 4096^2 search
//! (the full `c_flux` scene): each stored result records its wall time, and `--plan --out DIR` sets
//! the estimate beside the measurement of every finished job (`measured_s`, and the range
//! of measured over estimated in `measured_over_estimated`). `docs/measured.md`
//! states the fit.
//!
//! Jobs that several validations share (the same scene of the same family, so the same
//! result file) appear once, under the first validation that names them.

use std::collections::{BTreeSet, HashSet};
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::shard::{assign, share_costs, Shard};
use super::store::{load_run, StoredRun};
use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};
use crate::experiments::Work;

/// Seconds per `P log2 P` per warm-started solve of constrained conjugate gradients; the
/// other solvers' are these times their [`SolverKind::relative_cost`].
pub const CG_SECONDS: f64 = 4.38e-8;
/// A load search, in warm-started solves.
pub const SEARCH_SOLVES: f64 = 3.5;
/// A single-shell step, in warm-started solves.
pub const SHELL_SOLVES: f64 = 0.55;
/// Growth of a load search's cost with the grid side, beyond `P log2 P`: `(N / 256)^k`.
pub const SEARCH_GROWTH: f64 = 0.6;

/// The estimated wall time of `work` with `solver` on one core, seconds.
pub fn estimate_seconds(work: Work, solver: SolverKind) -> f64 {
    let p = work.points.max(2) as f64;
    let per_solve = solver.relative_cost() * CG_SECONDS;
    let search = SEARCH_SOLVES * (p.sqrt() / 256.0).powf(SEARCH_GROWTH);
    per_solve * p * p.log2() * (search * work.searches + work.solves + SHELL_SOLVES * work.shells)
}

/// One job of a run, as planned.
#[derive(Debug, Clone)]
pub struct PlannedUnit {
    /// The validation that names it first.
    pub validation: String,
    /// The solver.
    pub solver: SolverKind,
    /// The job (the experiment's own description: seed, load, ...).
    pub job: serde_json::Value,
    /// Its result file.
    pub path: PathBuf,
    /// What it costs.
    pub work: Work,
    /// Estimated wall time on one core, seconds.
    pub cost: f64,
    /// The optional part of its scene it belongs to ([`crate::experiments::Jobs::part`]).
    pub part: Option<String>,
}

/// One job in the printed plan.
#[derive(Debug, Clone, Serialize)]
pub struct PlanRow {
    /// The validation.
    pub validation: String,
    /// The job.
    pub job: serde_json::Value,
    /// The solver.
    pub solver: String,
    /// The key of its result file (`jobs/<family>/<scale>/<key>.json`).
    pub key: String,
    /// Grid points of its solves (what its memory scales with).
    pub points: usize,
    /// Its load searches.
    pub searches: f64,
    /// Its warm-started solves.
    pub solves: f64,
    /// Its single-shell steps.
    pub shells: f64,
    /// Estimated wall time on one core, seconds.
    pub cost: f64,
    /// Its share (1-based), when the plan has shares.
    pub shard: Option<usize>,
    /// The optional part of its scene it belongs to (a re-entry variant), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub part: Option<String>,
    /// Its measured wall time, when its result is already in the output folder.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_s: Option<f64>,
}

/// The plan of a run.
#[derive(Debug, Clone, Serialize)]
pub struct Plan {
    /// Every distinct job, in the order the validations name them.
    pub jobs: Vec<PlanRow>,
    /// How many shares (`None`: no split asked for).
    pub shards: Option<usize>,
    /// Estimated cost of each share, seconds on one core.
    pub share_costs: Vec<f64>,
    /// Estimated cost of all jobs, core-hours.
    pub core_hours: f64,
    /// Jobs with a measurement: the measured over the estimated time, least and most.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_over_estimated: Option<(f64, f64)>,
    #[serde(skip)]
    paths: Vec<PathBuf>,
}

impl Plan {
    /// The plan of `units` (jobs named twice kept once) split into `shards` shares.
    pub fn new(units: Vec<PlannedUnit>, shards: Option<usize>) -> Self {
        let mut seen = HashSet::new();
        let units: Vec<PlannedUnit> = units
            .into_iter()
            .filter(|u| seen.insert(u.path.clone()))
            .collect();
        let costs: Vec<f64> = units.iter().map(|u| u.cost).collect();
        let assigned = shards.map(|n| assign(&costs, n));
        let share_costs = match (&assigned, shards) {
            (Some(a), Some(n)) => share_costs(&costs, a, n),
            _ => Vec::new(),
        };
        let mut ratios = Vec::new();
        let jobs = units
            .iter()
            .enumerate()
            .map(|(i, u)| {
                let measured_s = load_run(&u.path).and_then(|s| s.run).map(|r| r.wall_s);
                if let Some(m) = measured_s {
                    ratios.push(m / u.cost);
                }
                PlanRow {
                    validation: u.validation.clone(),
                    job: u.job.clone(),
                    solver: u.solver.name().to_string(),
                    key: key_of(&u.path),
                    points: u.work.points,
                    searches: u.work.searches,
                    solves: u.work.solves,
                    shells: u.work.shells,
                    cost: u.cost,
                    shard: assigned.as_ref().map(|a| a[i]),
                    part: u.part.clone(),
                    measured_s,
                }
            })
            .collect();
        let measured_over_estimated = (!ratios.is_empty()).then(|| {
            (
                ratios.iter().copied().fold(f64::INFINITY, f64::min),
                ratios.iter().copied().fold(0.0, f64::max),
            )
        });
        Self {
            jobs,
            shards,
            share_costs,
            core_hours: costs.iter().sum::<f64>() / 3600.0,
            measured_over_estimated,
            paths: units.into_iter().map(|u| u.path).collect(),
        }
    }

    /// The result files of share `shard`'s jobs.
    pub fn share(&self, shard: Shard) -> HashSet<PathBuf> {
        self.jobs
            .iter()
            .zip(&self.paths)
            .filter(|(row, _)| row.shard == Some(shard.k))
            .map(|(_, p)| p.clone())
            .collect()
    }

    /// Checks that every job has a stored result `--merge` may use: present and readable,
    /// and computed by the same commit unless `accept_other_commit`. The result's file name
    /// is its job key, a hash of everything the job computes (the scale, the scene and the
    /// job: [`crate::validation::store::job_key`]), so a result found under the key is a
    /// result of this job: an edit of the definition outside what the job computes (a
    /// comment, the other scale's scene, the paper's finding) keeps it valid, and an edit of
    /// a parameter of its scene changes the key, so that the job runs again. The hash of the
    /// definition file that computed a result stays in its provenance. The error names every
    /// missing job with the share that owns it, or the refused result and why. With
    /// `partial`, a job of an optional part of its scene ([`PlanRow::part`]) may be missing:
    /// the merge concludes without that part.
    pub fn check_merge(&self, accept_other_commit: bool, partial: bool) -> Result<()> {
        let commit = crate::provenance::commit_label();
        let stored: Vec<Option<StoredRun>> = self.paths.iter().map(|p| load_run(p)).collect();
        // The share count of the run, from the shares' own records.
        let counts: BTreeSet<usize> = stored
            .iter()
            .flatten()
            .filter_map(|s| s.run.as_ref()?.shard.as_ref())
            .filter_map(|k_n| k_n.split_once('/')?.1.parse().ok())
            .collect();
        let owners = match counts.iter().next_back() {
            Some(&n) if counts.len() == 1 => {
                let costs: Vec<f64> = self.jobs.iter().map(|j| j.cost).collect();
                Some((assign(&costs, n), n))
            }
            _ => None,
        };
        let mut missing = Vec::new();
        for (i, (row, s)) in self.jobs.iter().zip(&stored).enumerate() {
            let Some(s) = s else {
                if partial && row.part.is_some() {
                    continue;
                }
                let owner = match &owners {
                    Some((a, n)) => format!("shard {}/{n}", a[i]),
                    None if counts.len() > 1 => {
                        format!("results of several share counts {counts:?}: owner unknown")
                    }
                    None => "no share has stored results".into(),
                };
                missing.push(format!(
                    "{} {} job {} ({}) [{owner}]",
                    row.validation, row.solver, row.job, row.key
                ));
                continue;
            };
            let Some(run) = &s.run else { continue };
            if run.commit != commit && !accept_other_commit {
                return Err(Error::bad_file(
                    &self.paths[i],
                    format!(
                        "job result computed by commit {}, this is {commit}: run it again, or \
                         pass --accept-other-commit to merge it anyway (recorded in the \
                         outcome)",
                        run.commit
                    ),
                ));
            }
        }
        if missing.is_empty() {
            Ok(())
        } else {
            Err(Error::invalid(
                "--merge",
                format!(
                    "{} of {} jobs have no result:\n  {}",
                    missing.len(),
                    self.jobs.len(),
                    missing.join("\n  ")
                ),
                "every job's result under <out>/jobs/ (run the shares that own them)",
            ))
        }
    }
}

/// The key of a result file: its name without `.json`.
fn key_of(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cost_grows_like_p_log_p_times_solves() {
        let warm = |n: usize| Work {
            searches: 0.0,
            ..Work::search_then(n, 10, 0)
        };
        let cg = |w: Work| estimate_seconds(w, SolverKind::Cg);
        let ratio = cg(warm(256)) / cg(warm(128));
        assert!((ratio - 4.0 * 16.0 / 14.0).abs() < 1e-12, "{ratio}");
        // A search from cold grows faster than P log P.
        let search = |n: usize| cg(Work::search_then(n, 0, 0));
        assert!(search(256) / search(128) > ratio);
        assert!(cg(Work::search_then(128, 10, 10)) > cg(Work::search_then(128, 10, 0)));
        assert!(estimate_seconds(warm(128), SolverKind::Gfmd) > cg(warm(128)));
    }

    #[test]
    fn shared_jobs_are_planned_once() {
        let unit = |v: &str, p: &str, cost: f64| PlannedUnit {
            validation: v.into(),
            solver: SolverKind::Cg,
            job: serde_json::json!(1),
            path: PathBuf::from(p),
            work: Work::default(),
            cost,
            part: None,
        };
        let plan = Plan::new(
            vec![
                unit("a", "x.json", 2.0),
                unit("a", "y.json", 1.0),
                unit("b", "x.json", 2.0),
            ],
            Some(2),
        );
        assert_eq!(plan.jobs.len(), 2);
        assert_eq!(plan.jobs[0].validation, "a");
        assert_eq!(plan.share_costs, vec![2.0, 1.0]);
        let one = plan.share(Shard { k: 1, n: 2 });
        assert!(one.contains(Path::new("x.json")) && one.len() == 1);
    }
}
