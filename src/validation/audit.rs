//! Auditing stored job results: which of a run folder's job results today's definitions
//! plan, a sample of them within a time budget, each recomputed alone with this build, and
//! the stored and recomputed results compared byte for byte.
//!
//! A job result (`jobs/<family>/<scale>/<key>.json`, see [`super::store`]) is found by its
//! key, a hash of everything the job computes, so a stored result that today's plan names
//! is a result of the very job today's code would run ([`candidates`]). Every solver the
//! crate has ([`SolverKind::ALL`]) is looked for. Results that no job of today's
//! definitions names (an edited scene) cannot be recomputed and are listed, and so are the
//! validations and solvers whose jobs have no stored result at all (a solver that a default
//! run leaves out and of which the folder holds nothing is named once).
//!
//! The sample ([`pick`]): for every validation and solver, in increasing order of the
//! cheapest job that covers the pair (by the cost model, [`super::plan::estimate_seconds`]),
//! that job, while the estimated total times [`COST_MARGIN`] stays within the budget; then
//! the other jobs in a random order drawn from the seed, each taken while it still fits.
//! Without a budget every job is taken.
//!
//! A job is recomputed ([`recompute`]) as the only job of a one-share run into a scratch
//! folder, exactly as a share of a sharded run computes it, and the `result` part of the
//! two files ([`top_level_value`]) is compared byte for byte; where the bytes differ,
//! [`differences`] names every number that differs and by how much. A result may hold the
//! time its job took (a re-entry history's `wall_s`, which its account reports): such a
//! number ([`MEASURED_TIMES`]) differs between any two runs, and [`only_measured_times`]
//! tells a result that differs in nothing else.

use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use rand::seq::SliceRandom;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use serde_json::Value;

use super::definition::Scale;
use super::registry::Registry;
use super::runner::{Mode, RunOptions};
use super::shard::Shard;
use super::source::Source;
use super::store::{load_run, JobRun};
use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};

/// The factor on the cost model's estimate when a sample is fitted into a budget: at paper
/// scale measured job times run 1.2 to 2 times the estimate on a busy 2-core machine (the
/// cost section of `docs/cluster.md`: "plan on about 1.5 times the table").
pub const COST_MARGIN: f64 = 1.5;

/// The keys under which a job's result holds a measured time rather than a computed
/// number (the wall time of a re-entry history's sweep).
pub const MEASURED_TIMES: &[&str] = &["wall_s"];

/// Whether every one of `differences` is a measured time ([`MEASURED_TIMES`]) with a number
/// on both sides (and there is at least one).
pub fn only_measured_times(differences: &[Difference]) -> bool {
    !differences.is_empty()
        && differences.iter().all(|d| {
            let key = d.path.rsplit('.').next().unwrap_or("");
            MEASURED_TIMES.contains(&key) && d.abs.is_some()
        })
}

/// A stored job result that today's definitions plan.
#[derive(Debug, Clone, Serialize)]
pub struct Candidate {
    /// The job's key (its file name without `.json`).
    pub key: String,
    /// Its file, relative to the run folder (`jobs/<family>/<scale>/<key>.json`).
    pub relative: PathBuf,
    /// The scale of its scene.
    pub scale: Scale,
    /// Every validation whose run needs it, in the order of the definitions.
    pub validations: Vec<String>,
    /// The solver.
    pub solver: SolverKind,
    /// The job (the experiment's own description).
    pub job: Value,
    /// The cost model's estimate, seconds on one core.
    pub estimate_s: f64,
    /// The stored result's provenance, when it has one.
    pub stored: Option<JobRun>,
}

/// The stored job results of a run folder.
#[derive(Debug, Clone, Default)]
pub struct Found {
    /// Those today's definitions plan, in plan order.
    pub candidates: Vec<Candidate>,
    /// Those no job of today's definitions names (relative paths).
    pub orphans: Vec<PathBuf>,
    /// Validations and solvers with planned jobs of which none has a stored result (the
    /// solvers of a default run, and any other the folder holds results of).
    pub unstored: Vec<Unstored>,
    /// Solvers outside a default run ([`RunOptions::DEFAULT_SOLVERS`]) of which the folder
    /// holds no result at all.
    pub idle_solvers: Vec<String>,
}

/// A validation and solver whose planned jobs have no stored result in the run folder.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unstored {
    /// The validation.
    pub validation: String,
    /// The solver.
    pub solver: String,
    /// How many jobs its definition plans.
    pub planned: usize,
}

/// The scales with a jobs folder under `from/jobs/<family>/`.
fn scales_in(from: &Path) -> Vec<Scale> {
    [Scale::Reduced, Scale::Full]
        .into_iter()
        .filter(|s| {
            std::fs::read_dir(from.join("jobs"))
                .map(|families| {
                    families
                        .filter_map(|f| f.ok())
                        .any(|f| f.path().join(s.to_string()).is_dir())
                })
                .unwrap_or(false)
        })
        .collect()
}

/// Every stored result file under `from/jobs/<family>/<scale>/`, relative to `from`.
fn stored_files(from: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(families) = std::fs::read_dir(from.join("jobs")) else {
        return out;
    };
    for family in families.filter_map(|e| e.ok()) {
        let Ok(scales) = std::fs::read_dir(family.path()) else {
            continue;
        };
        for scale in scales.filter_map(|e| e.ok()) {
            let Ok(files) = std::fs::read_dir(scale.path()) else {
                continue;
            };
            for f in files.filter_map(|e| e.ok()) {
                let path = f.path();
                let name = path.file_name().unwrap_or_default().to_string_lossy();
                // Result files only: not checkpoint folders, not temporary files.
                if path.is_file() && name.ends_with(".json") && !name.contains(".tmp.") {
                    out.push(path.strip_prefix(from).unwrap_or(&path).to_path_buf());
                }
            }
        }
    }
    out.sort();
    out
}

/// The stored results in `from` that the definitions `sources` plan, at every scale with
/// a jobs folder there, with every solver of the crate; those they do not plan; and the
/// validations and solvers with planned jobs but no stored result.
pub fn candidates(registry: &Registry, sources: &[Source], from: &Path) -> Result<Found> {
    let mut by_path: BTreeMap<PathBuf, usize> = BTreeMap::new();
    let mut found = Found::default();
    // (validation, solver) -> (jobs planned, jobs stored)
    let mut pairs: BTreeMap<(String, &'static str), (usize, usize)> = BTreeMap::new();
    for scale in scales_in(from) {
        let opts = RunOptions {
            solvers: SolverKind::ALL.to_vec(),
            ..RunOptions::new(scale, from)
        };
        for source in sources {
            for unit in registry.jobs(source, &opts)? {
                let pair = pairs
                    .entry((unit.validation.clone(), unit.solver.name()))
                    .or_default();
                pair.0 += 1;
                pair.1 += usize::from(unit.path.is_file());
                if let Some(&i) = by_path.get(&unit.path) {
                    let c: &mut Candidate = &mut found.candidates[i];
                    if !c.validations.contains(&unit.validation) {
                        c.validations.push(unit.validation);
                    }
                    continue;
                }
                if !unit.path.is_file() {
                    continue;
                }
                by_path.insert(unit.path.clone(), found.candidates.len());
                found.candidates.push(Candidate {
                    key: unit
                        .path
                        .file_stem()
                        .unwrap_or_default()
                        .to_string_lossy()
                        .to_string(),
                    relative: unit.path.strip_prefix(from).unwrap_or(&unit.path).into(),
                    scale,
                    validations: vec![unit.validation],
                    solver: unit.solver,
                    job: unit.job,
                    estimate_s: unit.cost,
                    stored: load_run(&unit.path).and_then(|s| s.run),
                });
            }
        }
    }
    let planned: HashSet<&PathBuf> = found.candidates.iter().map(|c| &c.relative).collect();
    found.orphans = stored_files(from)
        .into_iter()
        .filter(|p| !planned.contains(p))
        .collect();
    // A solver the folder holds no result of at all (one a run leaves out by default) is
    // named once, not with every validation.
    let holds = |solver: &str| pairs.iter().any(|((_, s), (_, n))| *s == solver && *n > 0);
    found.idle_solvers = SolverKind::ALL
        .into_iter()
        .filter(|s| !RunOptions::DEFAULT_SOLVERS.contains(s) && !holds(s.name()))
        .map(|s| s.name().to_string())
        .collect();
    found.unstored = pairs
        .into_iter()
        .filter(|((_, solver), (_, stored))| {
            *stored == 0 && !found.idle_solvers.iter().any(|s| s == solver)
        })
        .map(|((validation, solver), (planned, _))| Unstored {
            validation,
            solver: solver.into(),
            planned,
        })
        .collect();
    Ok(found)
}

/// Why a job is in the sample.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reason {
    /// Asked for by key (or by its validation, without a budget).
    Named,
    /// The cheapest job of a validation and solver not yet covered.
    Cheapest {
        /// The validation.
        validation: String,
        /// The solver.
        solver: String,
    },
    /// Drawn at random once every pair was covered.
    Random,
}

/// A validation and solver no job of the sample covers: its cheapest job did not fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Uncovered {
    /// The validation.
    pub validation: String,
    /// The solver.
    pub solver: String,
    /// The cheapest job's key.
    pub key: String,
    /// Its estimate, seconds.
    pub estimate_s: f64,
}

/// The sample: which candidates, why, in the order they run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Selection {
    /// Indices into the candidates with the reason, in run order.
    pub picks: Vec<(usize, Reason)>,
    /// Pairs left uncovered.
    pub uncovered: Vec<Uncovered>,
    /// The estimated total of the picks, seconds (before the margin).
    pub estimate_s: f64,
}

/// The sample of `candidates` within `budget_s` seconds (every candidate without one):
/// the cheapest job of each validation and solver, then the others at random from `seed`,
/// each while the estimated total times [`COST_MARGIN`] fits (see the module's docs).
pub fn pick(candidates: &[Candidate], budget_s: Option<f64>, seed: u64) -> Selection {
    let fits = |total: f64, c: &Candidate| match budget_s {
        None => true,
        Some(b) => (total + c.estimate_s) * COST_MARGIN <= b,
    };
    // The cheapest job of every (validation, solver), ties to the first in plan order.
    let mut pairs: Vec<((String, SolverKind), usize)> = Vec::new();
    for (i, c) in candidates.iter().enumerate() {
        for v in &c.validations {
            let pair = (v.clone(), c.solver);
            match pairs.iter_mut().find(|(p, _)| *p == pair) {
                Some((_, best)) if candidates[*best].estimate_s > c.estimate_s => *best = i,
                Some(_) => {}
                None => pairs.push((pair, i)),
            }
        }
    }
    pairs.sort_by(|a, b| {
        candidates[a.1]
            .estimate_s
            .total_cmp(&candidates[b.1].estimate_s)
    });
    let mut picked = vec![false; candidates.len()];
    let mut sel = Selection {
        picks: Vec::new(),
        uncovered: Vec::new(),
        estimate_s: 0.0,
    };
    for ((validation, solver), i) in pairs {
        if picked[i] {
            continue;
        }
        let c = &candidates[i];
        if fits(sel.estimate_s, c) {
            picked[i] = true;
            sel.estimate_s += c.estimate_s;
            sel.picks.push((
                i,
                Reason::Cheapest {
                    validation,
                    solver: solver.name().into(),
                },
            ));
        } else {
            sel.uncovered.push(Uncovered {
                validation,
                solver: solver.name().into(),
                key: c.key.clone(),
                estimate_s: c.estimate_s,
            });
        }
    }
    let mut rest: Vec<usize> = (0..candidates.len()).filter(|&i| !picked[i]).collect();
    rest.shuffle(&mut ChaCha8Rng::seed_from_u64(seed));
    for i in rest {
        if fits(sel.estimate_s, &candidates[i]) {
            sel.estimate_s += candidates[i].estimate_s;
            sel.picks.push((i, Reason::Random));
        }
    }
    sel
}

/// A recomputed job result: the file's bytes and the wall time.
#[derive(Debug, Clone)]
pub struct Recomputed {
    /// The whole stored file as this build writes it.
    pub bytes: Vec<u8>,
    /// Wall time of the run, seconds.
    pub wall_s: f64,
}

/// Recomputes `candidate` alone with this build, by the definition `source` (one that
/// needs it), as the one job of a one-share run into `scratch`; the result file is read
/// and removed.
pub fn recompute(
    registry: &Registry,
    source: &Source,
    candidate: &Candidate,
    scratch: &Path,
) -> Result<Recomputed> {
    let path = scratch.join(&candidate.relative);
    let opts = RunOptions {
        solvers: vec![candidate.solver],
        mode: Mode::Share {
            shard: Shard::new(1, 1)?,
            jobs: Arc::new(HashSet::from([path.clone()])),
        },
        ..RunOptions::new(candidate.scale, scratch)
    };
    let timer = Instant::now();
    registry.run(source, &opts)?;
    let wall_s = timer.elapsed().as_secs_f64();
    let bytes = std::fs::read(&path).map_err(|e| {
        Error::bad_file(
            &path,
            format!("the recomputed job wrote no result ({e}): its key is not planned by the definition"),
        )
    })?;
    std::fs::remove_file(&path).ok();
    Ok(Recomputed { bytes, wall_s })
}

/// The bytes of the value of the key `key` of the JSON object `bytes` (top level only, as
/// written, without the white space around it), or `None` when it has no such key or is
/// not a JSON object.
pub fn top_level_value<'a>(bytes: &'a [u8], key: &str) -> Option<&'a [u8]> {
    let object: std::collections::BTreeMap<String, &'a serde_json::value::RawValue> =
        serde_json::from_slice(bytes).ok()?;
    object.get(key).map(|raw| raw.get().as_bytes())
}

/// A number (or any value) that differs between a stored and a recomputed result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Difference {
    /// Where, from the result's root: `result.steps[3].contact_area`.
    pub path: String,
    /// The stored value (`None`: absent).
    pub stored: Option<Value>,
    /// The recomputed value (`None`: absent).
    pub recomputed: Option<Value>,
    /// `|recomputed - stored|`, for two numbers.
    pub abs: Option<f64>,
    /// The same over the larger magnitude, for two numbers.
    pub rel: Option<f64>,
}

/// The differences between `stored` and `recomputed` (values under `root`): the count,
/// and the first `limit` of them in document order. Two numbers differ when their JSON
/// text does (so `-0.0` differs from `0.0`, and `1` from `1.0`).
pub fn differences(
    root: &str,
    stored: &Value,
    recomputed: &Value,
    limit: usize,
) -> (usize, Vec<Difference>) {
    let mut out = (0, Vec::new());
    walk(
        &mut root.to_string(),
        Some(stored),
        Some(recomputed),
        limit,
        &mut out,
    );
    out
}

fn walk(
    path: &mut String,
    a: Option<&Value>,
    b: Option<&Value>,
    limit: usize,
    out: &mut (usize, Vec<Difference>),
) {
    let mut note = |path: &str, a: Option<&Value>, b: Option<&Value>| {
        out.0 += 1;
        if out.1.len() < limit {
            let (x, y) = (a.and_then(Value::as_f64), b.and_then(Value::as_f64));
            let abs = x.zip(y).map(|(x, y)| (y - x).abs());
            let rel = x
                .zip(y)
                .zip(abs)
                .map(|((x, y), d)| d / x.abs().max(y.abs()));
            out.1.push(Difference {
                path: path.to_string(),
                stored: a.cloned(),
                recomputed: b.cloned(),
                abs,
                rel,
            });
        }
    };
    match (a, b) {
        (Some(Value::Object(x)), Some(Value::Object(y))) => {
            let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
            for k in keys {
                let len = path.len();
                path.push('.');
                path.push_str(k);
                walk(path, x.get(k), y.get(k), limit, out);
                path.truncate(len);
            }
        }
        (Some(Value::Array(x)), Some(Value::Array(y))) => {
            for k in 0..x.len().max(y.len()) {
                let len = path.len();
                path.push_str(&format!("[{k}]"));
                walk(path, x.get(k), y.get(k), limit, out);
                path.truncate(len);
            }
        }
        (Some(x), Some(y)) if same_text(x, y) => {}
        (a, b) => note(path, a, b),
    }
}

/// Whether two values are written alike (numbers by their text: `-0.0` is not `0.0`).
fn same_text(x: &Value, y: &Value) -> bool {
    let (a, b) = (x.to_string(), y.to_string());
    a == b
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn finds_the_top_level_value_of_a_key() {
        let text = br#"{"solver":"cg","job":{"result":1,"s":"a\"}"},"result":{"x":[1,{"y":"}"}],"run":2},"run":null}"#;
        let v = top_level_value(text, "result").unwrap();
        assert_eq!(v, br#"{"x":[1,{"y":"}"}],"run":2}"#);
        assert_eq!(top_level_value(text, "run").unwrap(), b"null");
        assert_eq!(top_level_value(text, "solver").unwrap(), br#""cg""#);
        assert_eq!(top_level_value(text, "other"), None);
        assert_eq!(top_level_value(b" { \"a\" : 1.5 } ", "a").unwrap(), b"1.5");
        assert_eq!(top_level_value(b"[1]", "a"), None);
    }

    #[test]
    fn differences_name_every_number_that_differs() {
        let a = json!({"x": [1.0, 2.0, 3.0], "y": {"z": 0.0, "w": "s"}, "gone": 1});
        let b = json!({"x": [1.0, 2.5, 3.0, 4.0], "y": {"z": -0.0, "w": "s"}});
        let (n, d) = differences("result", &a, &b, 10);
        let paths: Vec<&str> = d.iter().map(|d| d.path.as_str()).collect();
        assert_eq!(n, 4);
        assert_eq!(
            paths,
            ["result.gone", "result.x[1]", "result.x[3]", "result.y.z"]
        );
        assert_eq!(d[1].abs, Some(0.5));
        assert_eq!(d[1].rel, Some(0.2));
        assert_eq!(d[0].recomputed, None);
        let (n, d) = differences("result", &a, &b, 1);
        assert_eq!((n, d.len()), (4, 1));
        assert_eq!(differences("r", &a, &a, 10).0, 0);
        assert!(!only_measured_times(&d));
        let timed = |x: f64| json!({"shells": 3, "wall_s": x});
        let (_, d) = differences("result", &timed(2800.1), &timed(4700.5), 10);
        assert!(only_measured_times(&d));
        let (_, d) = differences(
            "result",
            &timed(1.0),
            &json!({"shells": 4, "wall_s": 2.0}),
            10,
        );
        assert!(!only_measured_times(&d));
        assert!(!only_measured_times(&[]));
    }

    fn candidate(key: &str, validations: &[&str], solver: SolverKind, cost: f64) -> Candidate {
        Candidate {
            key: key.into(),
            relative: PathBuf::from(format!("jobs/f/full/{key}.json")),
            scale: Scale::Full,
            validations: validations.iter().map(|v| v.to_string()).collect(),
            solver,
            job: json!(null),
            estimate_s: cost,
            stored: None,
        }
    }

    #[test]
    fn covers_each_validation_and_solver_cheapest_first_then_at_random() {
        use SolverKind::{Cg, Gfmd};
        let c = vec![
            candidate("a1", &["a", "b"], Gfmd, 10.0),
            candidate("a2", &["a", "b"], Gfmd, 5.0),
            candidate("a3", &["a", "b"], Cg, 4.0),
            candidate("c1", &["c"], Gfmd, 100.0),
            candidate("c2", &["c"], Cg, 1000.0),
            candidate("d1", &["d"], Cg, 1.0),
            candidate("d2", &["d"], Cg, 1.0),
            candidate("d3", &["d"], Cg, 1.0),
        ];
        // Budget for the four cheapest pairs and two more seconds, with the margin.
        let sel = pick(&c, Some((1.0 + 4.0 + 5.0 + 100.0 + 2.0) * COST_MARGIN), 7);
        let keys: Vec<&str> = sel.picks.iter().map(|(i, _)| c[*i].key.as_str()).collect();
        // d, a/b cg, a/b gfmd (one job covers both validations), c gfmd; c cg does not fit.
        assert_eq!(&keys[..4], ["d1", "a3", "a2", "c1"]);
        assert_eq!(
            sel.picks[2].1,
            Reason::Cheapest {
                validation: "a".into(),
                solver: "gfmd".into()
            }
        );
        assert_eq!(sel.uncovered.len(), 1);
        assert_eq!(sel.uncovered[0].key, "c2");
        // Two of the three 1-second jobs left fit; a1 (10 s) does not.
        assert_eq!(keys.len(), 6);
        assert!(keys[4..].iter().all(|k| k.starts_with('d')));
        assert!(sel.estimate_s * COST_MARGIN <= (112.0) * COST_MARGIN);
        // The same seed, the same sample; every job without a budget.
        assert_eq!(pick(&c, Some(168.0), 7), sel);
        assert_eq!(pick(&c, None, 3).picks.len(), c.len());
    }
}
