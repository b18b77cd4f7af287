//! An experiment is added by writing its module and registering it once: here a tiny one,
//! defined in this test, runs through the same runner, verdict and outputs as the built-in
//! ones.

use serde::{Deserialize, Serialize};

use persson_check::engine::solver::SolverKind;
use persson_check::error::Result;
use persson_check::experiments::declared::DetailTable;
use persson_check::experiments::{Criteria, Experiment, Guard, JobContext, Jobs, Run, Work};
use persson_check::stats::{decide, Claim, Estimate};
use persson_check::validation::{Registry, RunOptions, Scale, Source, Verdict};

/// The scene: realizations, and the value each one "measures" around.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CoinScene {
    seeds: Vec<u64>,
    centre: f64,
}

/// Measures `centre + (seed mod 3 - 1) / 100` for each seed.
struct Coin;

impl Jobs for CoinScene {
    const FAMILY: &'static str = "coin";
    type Job = u64;
    type JobResult = f64;

    fn validate(&self) -> Result<()> {
        persson_check::error::check_seeds(&self.seeds)
    }

    fn jobs(&self) -> Vec<u64> {
        self.seeds.clone()
    }

    fn work(&self, _seed: &u64) -> Work {
        // No solves: a coin costs nothing.
        Work::default()
    }

    fn run_job(&self, seed: &u64, _ctx: &JobContext) -> Result<f64> {
        Ok(self.centre + ((seed % 3) as f64 - 1.0) / 100.0)
    }

    fn residual(_result: &f64) -> f64 {
        // No solves.
        0.0
    }
}

/// What a coin's run gives: the mean and the number of realizations.
struct CoinStats {
    mean: Estimate,
    count: usize,
}

impl Experiment for Coin {
    type Scene = CoinScene;
    type Stats = CoinStats;

    fn stats(run: &Run<Self>) -> Result<CoinStats> {
        let values: Vec<f64> = run.results.iter().map(|r| r.1).collect();
        Ok(CoinStats {
            mean: Estimate::mean_of(&values),
            count: values.len(),
        })
    }

    fn headline(s: &CoinStats) -> (Estimate, f64) {
        (s.mean, 0.5)
    }

    fn detail_table<'s>(_scene: &'s CoinScene, _c: &'s Criteria) -> DetailTable<'s, CoinStats> {
        let mut t = DetailTable::default();
        t.always("count", "realizations", |s: &CoinStats| {
            Estimate::new(s.count as f64, 0.0)
        });
        t
    }

    fn guards(run: &Run<Self>, s: &CoinStats) -> Vec<Guard> {
        vec![Guard::new(
            "above_half",
            "the mean is above one half",
            decide(s.mean, Claim::Above(0.5), 0.0),
            format!("{} ({})", s.mean.value, run.criteria.name),
        )]
    }

    fn account(_run: &Run<Self>, _s: &CoinStats) -> String {
        "A coin.".into()
    }
}

const DEFINITION: &str = r#"
name = "coin"
experiment = "coin"
title = "Coin"
assumption = "the coin is fair"
statistic = "mean"
persson = "one half"

[verdict]
significance = 3.0
resolution = 0.01

[paper]
finding = "the coin is biased"
verdict = "violated"

[reduced]
seeds = [1, 2, 3, 4, 5, 6]
centre = 0.7

[full]
seeds = [1, 2, 3]
centre = 0.7
"#;

#[test]
fn a_registered_experiment_runs_like_a_built_in_one() {
    let source = Source {
        path: "builtin:coin".into(),
        text: DEFINITION.to_string(),
    };
    let out = tempfile::tempdir().unwrap();
    let opts = RunOptions::new(Scale::Reduced, out.path());
    // Unknown to the built-in table, with the known names listed.
    let e = Registry::builtin()
        .run(&source, &opts)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("\"coin\" is unknown") && e.contains("reentry"),
        "{e}"
    );

    let registry = Registry::builtin().with::<Coin>("coin");
    registry.check(&source).unwrap();
    let o = registry
        .run(&source, &opts)
        .unwrap()
        .expect("a whole run has an outcome");
    assert!((o.value - 0.7).abs() < 1e-12, "{}", o.value);
    assert_eq!(o.verdict, Verdict::Violated);
    assert_eq!(o.reproduced, Some(true));
    assert_eq!(o.details[0].key, "count");
    // Both solvers ran (the toy ignores them): the cross-check agrees exactly.
    assert_eq!(o.solver, "gfmd");
    assert_eq!(o.cross_checks.len(), 1, "{:?}", o.cross_checks);
    let cross = &o.cross_checks[0];
    assert!(cross.agrees && cross.value == o.value, "{cross:?}");
    assert!(out.path().join("coin.json").exists());
    assert_eq!(
        std::fs::read_dir(out.path().join("jobs/coin/reduced"))
            .unwrap()
            .count(),
        12,
        "one stored result per job and solver"
    );
}

#[test]
fn every_solver_after_the_headline_gives_a_cross_check() {
    let source = Source {
        path: "builtin:coin".into(),
        text: DEFINITION.to_string(),
    };
    let registry = Registry::builtin().with::<Coin>("coin");
    let out = tempfile::tempdir().unwrap();
    let mut opts = RunOptions::new(Scale::Reduced, out.path());
    opts.solvers = SolverKind::ALL.iter().rev().copied().collect();
    let o = registry.run(&source, &opts).unwrap().unwrap();
    assert_eq!(o.solver, opts.solvers[0].name());
    let crossed: Vec<&str> = o.cross_checks.iter().map(|c| c.solver.as_str()).collect();
    let rest: Vec<&str> = opts.solvers[1..].iter().map(|s| s.name()).collect();
    assert_eq!(
        crossed, rest,
        "one cross-check per solver, in the run's order"
    );
    assert!(o.cross_checks.iter().all(|c| c.agrees));
    // The outcome file lists them all.
    let written: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.path().join("coin.json")).unwrap()).unwrap();
    assert_eq!(
        written["cross_checks"].as_array().unwrap().len(),
        rest.len()
    );
    // A solver named twice is refused, naming it.
    opts.solvers = vec![SolverKind::Cg, SolverKind::Gfmd, SolverKind::Cg];
    let e = registry.run(&source, &opts).unwrap_err().to_string();
    assert!(e.contains("solvers") && e.contains("cg twice"), "{e}");
}
