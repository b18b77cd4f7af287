//! The outcome of a validation run: `<name>.json`.
//!
//! A number that is not known is NaN in memory and `null` in the file (serde_json writes
//! NaN as `null`): the standard error of one realization, a detail without an error bar.
//! Every float field that can be NaN reads `null` back as NaN, and reads as NaN when the
//! file leaves it out ([`crate::stats::null_as_nan`], [`crate::stats::nan`]), so an outcome
//! written from one realization (or by an earlier version) reads back as it was written.
//! Fields added since the first outcomes read as empty when absent (`claims`, `studies`,
//! `merge`); the one cross-check of early outcomes (`cross_check`) reads as a list of one.

use std::collections::BTreeMap;

use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};

use super::claims::ClaimOutcome;
use super::definition::{Scale, Verdict, VerdictRule};
use super::measure::Measure;
pub use super::measures::PendingPart;
use super::store::JobRun;
use crate::experiments::study::Study;
use crate::experiments::{Detail, Guard};
use crate::stats::{nan, null_as_nan, null_as_nan_values};

/// The record of one validation run: `<name>.json` ([`crate::conventions`], section 7).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Name.
    pub name: String,
    /// Title.
    pub title: String,
    /// Assumption under test.
    pub assumption: String,
    /// The headline statistic in words.
    pub statistic: String,
    /// The measured headline statistic.
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub value: f64,
    /// Its standard error.
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub std_error: f64,
    /// Persson's prediction of the statistic.
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub persson: f64,
    /// Persson's prediction in words.
    pub persson_text: String,
    /// The paper's finding in words.
    pub paper: String,
    /// The paper's value, if stated.
    pub paper_value: Option<f64>,
    /// The range of the headline that reproduces the paper, if the definition states one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paper_range: Option<(f64, f64)>,
    /// The paper's verdict.
    pub paper_verdict: Verdict,
    /// The verdict of this run.
    pub verdict: Verdict,
    /// Whether the headline verdict is the paper's (`None` when inconclusive). The paper's
    /// statements are the `claims`, each judged on its own and counted apart.
    pub reproduced: Option<bool>,
    /// The verdict rule used.
    pub rule: VerdictRule,
    /// Scale of the scene.
    pub scale: Scale,
    /// The scene, as run.
    pub scene: serde_json::Value,
    /// Hash of the definition file (SHA-256, hex).
    pub definition_sha256: String,
    /// Wall time of the whole validation, seconds (of a merge: the time during which at
    /// least one of its jobs ran).
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub wall_s: f64,
    /// Largest solver residual over all solves.
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub max_residual: f64,
    /// Secondary statistics.
    pub details: Vec<Detail>,
    /// Implementation guards (a counting identity, a conservation law): never part of a
    /// verdict. Outcomes written before the claims judged every statement held the
    /// paper's findings here as `checks`; they read as guards.
    #[serde(default, alias = "checks")]
    pub guards: Vec<Guard>,
    /// Account generated from the numbers.
    pub account: String,
    /// Golden values.
    #[serde(deserialize_with = "null_as_nan_values")]
    pub golden: BTreeMap<String, f64>,
    /// The paper's claims this validation tests, each with its measurement and result.
    #[serde(default)]
    pub claims: Vec<ClaimOutcome>,
    /// Studies: tables of rows beside the headline, with their notes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub studies: Vec<Study>,
    /// Files written (tables, figures), relative to the output directory.
    pub files: Vec<String>,
    /// Worker threads used.
    pub threads: usize,
    /// The solver of the headline statistic.
    #[serde(default)]
    pub solver: String,
    /// The same statistic from each other solver run on the same scene, in the order of
    /// the run's solvers (none when one solver ran). An outcome written before there could
    /// be several holds one, or `null`, as `cross_check`: it reads as a list of that one.
    #[serde(default, alias = "cross_check", deserialize_with = "one_or_many")]
    pub cross_checks: Vec<CrossCheck>,
    /// For an outcome merged from a sharded run: the shares that computed its jobs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merge: Option<MergeRecord>,
}

impl Outcome {
    /// The paper's value beside the detail `d`: that of the claim measuring it, where a
    /// claim gives one (the last, in the definition's order), else the experiment's own.
    /// A read of the outcome: the run never writes a claim's value into its details.
    pub fn paper_value_of(&self, d: &Detail) -> Option<f64> {
        let measures_d = |c: &&ClaimOutcome| match c.measure.parse::<Measure>() {
            Ok(Measure::Detail { key, grid }) => key == d.key && (grid.is_none() || grid == d.grid),
            _ => false,
        };
        self.claims
            .iter()
            .rev()
            .filter(|c| c.paper_value.is_some())
            .find(measures_d)
            .and_then(|c| c.paper_value)
            .or(d.paper)
    }
}

/// The provenance of an outcome merged from the stored results of a sharded run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MergeRecord {
    /// The commit of the merging code.
    pub commit: String,
    /// Whether job results of another commit were accepted (`--accept-other-commit`).
    pub other_commits_accepted: bool,
    /// Every share (or unsharded run) whose results went into the outcome.
    pub shards: Vec<ShardRecord>,
    /// The optional parts of the scene left out because some of their jobs have no result
    /// yet (`--partial`): the outcome concludes the rest, and a claim that reads one of
    /// their measures says it is pending. Empty for a complete merge.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pending: Vec<PendingPart>,
}

/// One share of a sharded run, as its stored results record it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShardRecord {
    /// `K/N`, or "unsharded" for results of a plain run.
    pub shard: String,
    /// Host name.
    pub host: String,
    /// Start of its first job, RFC 3339 UTC.
    pub start: String,
    /// End of its last job, RFC 3339 UTC.
    pub end: String,
    /// Jobs of this outcome it computed.
    pub jobs: usize,
    /// Its commit.
    pub commit: String,
}

impl ShardRecord {
    /// The shares of a set of job provenances, one record per share and host, in order.
    pub fn from_runs(runs: &[JobRun]) -> Vec<Self> {
        let mut groups: BTreeMap<(String, String, String), Vec<&JobRun>> = BTreeMap::new();
        for r in runs {
            let shard = r.shard.clone().unwrap_or_else(|| "unsharded".into());
            groups
                .entry((shard, r.host.clone(), r.commit.clone()))
                .or_default()
                .push(r);
        }
        groups
            .into_iter()
            .map(|((shard, host, commit), rs)| {
                let first = rs
                    .iter()
                    .min_by(|a, b| a.span.0.total_cmp(&b.span.0))
                    .expect("non-empty group");
                let last = rs
                    .iter()
                    .max_by(|a, b| a.span.1.total_cmp(&b.span.1))
                    .expect("non-empty group");
                ShardRecord {
                    shard,
                    host,
                    start: first.start.clone(),
                    end: last.end.clone(),
                    jobs: rs.len(),
                    commit,
                }
            })
            .collect()
    }
}

/// The headline statistic measured again with another solver (same surfaces, loads and
/// tolerance).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CrossCheck {
    /// The solver.
    pub solver: String,
    /// Its value of the statistic.
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub value: f64,
    /// Its standard error.
    #[serde(deserialize_with = "null_as_nan", default = "nan")]
    pub std_error: f64,
    /// Whether the two solvers agree within their combined error (see
    /// [`super::VerdictRule::agree`]).
    pub agrees: bool,
}

/// The cross-checks as written: a list, or (an outcome of an earlier version, under
/// `cross_check`) one cross-check or `null`.
fn one_or_many<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<CrossCheck>, D::Error> {
    struct OneOrMany;

    impl<'de> Visitor<'de> for OneOrMany {
        type Value = Vec<CrossCheck>;

        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a list of cross-checks, one cross-check, or null")
        }

        fn visit_unit<E: serde::de::Error>(self) -> Result<Self::Value, E> {
            Ok(Vec::new())
        }

        fn visit_none<E: serde::de::Error>(self) -> Result<Self::Value, E> {
            Ok(Vec::new())
        }

        fn visit_some<D2: Deserializer<'de>>(self, d: D2) -> Result<Self::Value, D2::Error> {
            d.deserialize_any(self)
        }

        fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Self::Value, A::Error> {
            Vec::deserialize(SeqAccessDeserializer::new(seq))
        }

        fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
            Ok(vec![CrossCheck::deserialize(MapAccessDeserializer::new(
                map,
            ))?])
        }
    }

    d.deserialize_any(OneOrMany)
}
