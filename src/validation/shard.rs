//! Shares of the work for runs over many machines ([`crate::conventions`], section 8).
//!
//! A run of several validations is a list of jobs, each with an estimated cost
//! ([`crate::experiments::Jobs::work`], [`super::plan::estimate_seconds`]).
//! [`assign`] splits the list into `N` disjoint shares by the longest-processing-time
//! rule: jobs in decreasing cost, each to
//! the share with the least estimated cost so far (ties to the lower index, equal costs in
//! job order), which keeps the largest share within 4/3 of the best possible split and is
//! deterministic, so every process of an array computes the same split on its own.
//!
//! A [`Shard`] is the `K`-th of `N` shares (`1 <= K <= N`), given as `K/N` or read from
//! the scheduler that started the process ([`Shard::from_env`]): a Slurm job array or a
//! Kubernetes indexed job.

use std::fmt;

use crate::error::{Error, Result};

/// The `k`-th of `n` shares of the jobs (`1 <= k <= n`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which share, from 1.
    pub k: usize,
    /// How many shares.
    pub n: usize,
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

/// Where `--shard auto` looks for its share.
pub const SCHEDULER_VARIABLES: &str = "SLURM_ARRAY_TASK_ID with SLURM_ARRAY_TASK_MIN and \
     SLURM_ARRAY_TASK_COUNT (a Slurm job array), or JOB_COMPLETION_INDEX with --shards N (a \
     Kubernetes indexed job)";

impl Shard {
    /// The share `k` of `n`, checked.
    pub fn new(k: usize, n: usize) -> Result<Self> {
        if n == 0 {
            return Err(Error::invalid(
                "--shard",
                format!("{k}/{n}"),
                "K/N with N >= 1",
            ));
        }
        if k == 0 || k > n {
            return Err(Error::invalid(
                "--shard",
                format!("{k}/{n}"),
                format!("K/N with 1 <= K <= N (here N = {n})"),
            ));
        }
        Ok(Self { k, n })
    }

    /// Parses `K/N`.
    pub fn parse(text: &str) -> Result<Self> {
        let bad = || {
            Error::invalid(
                "--shard",
                text,
                "K/N with whole numbers 1 <= K <= N (e.g. 2/8), or auto",
            )
        };
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let k = k.trim().parse::<usize>().map_err(|_| bad())?;
        let n = n.trim().parse::<usize>().map_err(|_| bad())?;
        Self::new(k, n)
    }

    /// The share given by the scheduler that started this process, from its environment
    /// (`var` looks a variable up): a Slurm job array (task `ID - MIN + 1` of `COUNT`) or
    /// a Kubernetes indexed job (`JOB_COMPLETION_INDEX + 1` of `shards`).
    pub fn from_env(var: impl Fn(&str) -> Option<String>, shards: Option<usize>) -> Result<Self> {
        let number =
            |name: &str| -> Result<Option<usize>> {
                match var(name) {
                    None => Ok(None),
                    Some(v) => v.trim().parse::<usize>().map(Some).map_err(|_| {
                        Error::invalid(name, v, "a whole number (set by the scheduler)")
                    }),
                }
            };
        if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?;
            let count = number("SLURM_ARRAY_TASK_COUNT")?;
            let (Some(min), Some(count)) = (min, count) else {
                return Err(Error::invalid(
                    "--shard auto",
                    "SLURM_ARRAY_TASK_ID set without SLURM_ARRAY_TASK_MIN and \
                     SLURM_ARRAY_TASK_COUNT",
                    "a Slurm job array (sbatch --array), which sets all three",
                ));
            };
            if id < min || id - min >= count {
                return Err(Error::invalid(
                    "--shard auto",
                    format!("SLURM_ARRAY_TASK_ID = {id}, MIN = {min}, COUNT = {count}"),
                    "a contiguous array (--array=MIN-MAX without a step), ID within it",
                ));
            }
            return Self::new(id - min + 1, count);
        }
        if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            let n = shards.ok_or_else(|| {
                Error::invalid(
                    "--shards",
                    "missing",
                    "the job's completions (JOB_COMPLETION_INDEX gives only the index)",
                )
            })?;
            return Self::new(index + 1, n);
        }
        Err(Error::invalid(
            "--shard auto",
            "no scheduler variables",
            format!("started by a scheduler that sets {SCHEDULER_VARIABLES}"),
        ))
    }
}

/// The share (1-based) of each job of estimated cost `costs[i]` among `n` shares, by the
/// longest-processing-time rule.
pub fn assign(costs: &[f64], n: usize) -> Vec<usize> {
    assert!(n >= 1, "at least one share");
    let mut order: Vec<usize> = (0..costs.len()).collect();
    // Decreasing cost; equal costs keep job order (a stable sort).
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]));
    let mut load = vec![0.0f64; n];
    let mut share = vec![0; costs.len()];
    for i in order {
        let lightest = (0..n)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .expect("n >= 1");
        load[lightest] += costs[i];
        share[i] = lightest + 1;
    }
    share
}

/// The estimated cost of each share (index `k - 1`).
pub fn share_costs(costs: &[f64], shares: &[usize], n: usize) -> Vec<f64> {
    let mut total = vec![0.0; n];
    for (c, &s) in costs.iter().zip(shares) {
        total[s - 1] += c;
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn parses_and_checks_k_of_n() {
        assert_eq!(Shard::parse("2/8").unwrap(), Shard { k: 2, n: 8 });
        assert_eq!(Shard::parse("1/1").unwrap(), Shard { k: 1, n: 1 });
        for bad in ["0/3", "4/3", "3/0", "a/b", "3", "", "-1/3", "1/3/4"] {
            let e = Shard::parse(bad).unwrap_err().to_string();
            assert!(e.contains("--shard"), "{bad}: {e}");
        }
    }

    #[test]
    fn slurm_array_gives_one_based_shares() {
        let s = Shard::from_env(
            env(&[
                ("SLURM_ARRAY_TASK_ID", "12"),
                ("SLURM_ARRAY_TASK_MIN", "10"),
                ("SLURM_ARRAY_TASK_COUNT", "4"),
            ]),
            None,
        )
        .unwrap();
        assert_eq!(s, Shard { k: 3, n: 4 });
        let e = Shard::from_env(env(&[("SLURM_ARRAY_TASK_ID", "1")]), None).unwrap_err();
        assert!(e.to_string().contains("SLURM_ARRAY_TASK_COUNT"), "{e}");
    }

    #[test]
    fn kubernetes_index_needs_the_count() {
        let s = Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "0")]), Some(5)).unwrap();
        assert_eq!(s, Shard { k: 1, n: 5 });
        let e = Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "0")]), None).unwrap_err();
        assert!(e.to_string().contains("--shards"), "{e}");
        let e = Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "5")]), Some(5)).unwrap_err();
        assert!(e.to_string().contains("6/5"), "{e}");
    }

    #[test]
    fn no_scheduler_names_what_it_looked_for() {
        let e = Shard::from_env(env(&[]), Some(3)).unwrap_err().to_string();
        for var in [
            "SLURM_ARRAY_TASK_ID",
            "SLURM_ARRAY_TASK_MIN",
            "SLURM_ARRAY_TASK_COUNT",
            "JOB_COMPLETION_INDEX",
        ] {
            assert!(e.contains(var), "{e}");
        }
    }

    #[test]
    fn longest_first_balances_and_is_deterministic() {
        let costs = [5.0, 1.0, 4.0, 2.0, 3.0, 3.0];
        let shares = assign(&costs, 3);
        assert_eq!(shares, assign(&costs, 3));
        let totals = share_costs(&costs, &shares, 3);
        assert_eq!(totals, vec![6.0, 6.0, 6.0]);
        // Twelve equal jobs on four shares: three each.
        let shares = assign(&[2.0; 12], 4);
        for k in 1..=4 {
            assert_eq!(shares.iter().filter(|&&s| s == k).count(), 3);
        }
        // More shares than jobs leaves shares empty, never a job unassigned.
        let shares = assign(&[1.0, 1.0], 3);
        assert_eq!(shares, vec![1, 2]);
    }
}
