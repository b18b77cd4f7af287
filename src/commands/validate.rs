//! `validate`: run named validations (all by default) and write their outcomes.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::report::claims::Counts;
use persson_check::tasks::parse::MAX_SHARDS;
use persson_check::tasks::SolverKind;
use persson_check::tasks::{check_out_dir, validations};
use persson_check::validation::shard::Shard;
use persson_check::validation::source::Source;
use persson_check::validation::{Mode, Outcome, Registry};

use super::FLAGS;

/// Arguments of `validate`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Validations to run (default: all).
    names: Vec<String>,
    /// Run the full (paper-scale) scenes instead of the reduced ones.
    #[arg(long)]
    full: bool,
    /// Read definitions from this folder (default: the built-in copies of validations/).
    #[arg(long)]
    dir: Option<PathBuf>,
    /// Reuse job results already in the output folder (continue an interrupted run).
    #[arg(long)]
    resume: bool,
    /// Output folder: <name>.json, <name>.csv and figures (optional with --plan, where
    /// it adds the measured time of every finished job).
    #[arg(long, required_unless_present = "plan")]
    out: Option<PathBuf>,
    /// The solvers, comma-separated: the first for the headline, each other for a
    /// cross-check (default: gfmd,cg, GFMD for the headline and CG for the cross-check).
    #[arg(long, alias = "solver", value_enum, value_delimiter = ',')]
    solvers: Vec<SolverKind>,
    /// Run only share K of N of the jobs (K/N, 1 <= K <= N), or the share the scheduler
    /// gives (auto: a Slurm job array, or a Kubernetes indexed job with --shards N); writes
    /// job results under <out>/jobs/ and no outcome. Finished jobs are skipped.
    #[arg(long, conflicts_with_all = ["merge", "plan", "resume"])]
    shard: Option<String>,
    /// Number of shares, for --plan and for --shard auto in a Kubernetes indexed job.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_SHARDS as i64))]
    shards: Option<u32>,
    /// Write the outcomes from the job results the shares stored under <out>/jobs/,
    /// exactly as one process running every job would; runs nothing.
    #[arg(long, conflicts_with_all = ["plan", "resume"])]
    merge: bool,
    /// With --merge: accept job results computed by another commit (recorded in the
    /// outcome).
    #[arg(long, requires = "merge")]
    accept_other_commit: bool,
    /// With --merge: conclude without a scene's optional parts (a re-entry variant) whose
    /// jobs do not all have results yet; the outcome names them as pending, with their
    /// progress and the plan's cost of the rest, and a claim that reads one says so.
    #[arg(long, requires = "merge")]
    partial: bool,
    /// Print the jobs with their estimated cost (and share, with --shards N) as JSON; runs
    /// nothing.
    #[arg(long)]
    plan: bool,
}

pub fn run(args: Args) -> Result<()> {
    if let Some(out) = &args.out {
        check_out_dir(out, &FLAGS)?;
    }
    let sources = definitions(args.dir.as_deref(), &args.names)?;
    let registry = Registry::builtin();
    // Every definition is checked before any runs: bad input writes nothing.
    validations::check(&registry, &sources)?;
    // Without --out (a plan only), results are looked for nowhere.
    let out = args.out.clone().unwrap_or_default();
    let mut opts = validations::run_options(args.full, out, args.resume, true, &args.solvers);
    let shard = match args.shard.as_deref() {
        None => None,
        Some("auto") => Some(Shard::from_env(
            |name| std::env::var(name).ok(),
            args.shards.map(|n| n as usize),
        )?),
        Some(text) => Some(Shard::parse(text)?),
    };
    if args.plan || shard.is_some() || args.merge {
        let shards = shard.map(|s| s.n).or(args.shards.map(|n| n as usize));
        let plan = validations::plan(&registry, &sources, &opts, shards)?;
        if args.plan {
            let json = serde_json::to_string_pretty(&plan).expect("plans serialise");
            outln!("{json}");
            return Ok(());
        }
        if let Some(shard) = shard {
            let jobs = plan.share(shard);
            eprintln!(
                "shard {shard}: {} of {} jobs (estimated {:.2} core-hours of {:.2})",
                jobs.len(),
                plan.jobs.len(),
                plan.share_costs[shard.k - 1] / 3600.0,
                plan.core_hours
            );
            opts.mode = Mode::Share {
                shard,
                jobs: Arc::new(jobs),
            };
        } else {
            // Merge: every job's result must be there (and usable) before anything is
            // written, but for the optional parts' with --partial.
            validations::merge(&plan, args.accept_other_commit, args.partial, &mut opts)?;
        }
    }
    let mut failed = Vec::new();
    for (path, result) in validations::run(&registry, &sources, &opts, &|| true) {
        match result {
            Ok(Some(o)) => outln!("{}", summary_line(&o)),
            Ok(None) => {}
            Err(e) => {
                eprintln!("error: {e}");
                failed.push(path.display().to_string());
            }
        }
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(Error::invalid(
            "validations",
            format!("{} failed", failed.len()),
            format!("all to run ({})", failed.join(", ")),
        ))
    }
}

/// One line per outcome: the headline with its error bar (or the plain statement that
/// there is none), the verdict and whether it is the paper's, the cross-checks, the
/// evidence claims by result, and the wall time.
fn summary_line(o: &Outcome) -> String {
    let measured = if o.std_error.is_finite() {
        format!("{:.4} +- {:.4}", o.value, o.std_error)
    } else {
        format!("{:.4} (one realization: no error bar, no verdict)", o.value)
    };
    let cross: String = o
        .cross_checks
        .iter()
        .map(|c| {
            let value = if c.std_error.is_finite() {
                format!("{:.4} +- {:.4}", c.value, c.std_error)
            } else {
                format!("{:.4}", c.value)
            };
            let agrees = if c.agrees { "agrees" } else { "DISAGREES" };
            format!("; {} {value}, {agrees}", c.solver)
        })
        .collect();
    let claims = Counts::of(&o.claims);
    format!(
        "{:<16} {} = {measured} ({}; Persson {:.4}): {}, {}{cross}; claims: {} reproduced, {} \
         contradicted, {} not established [{:.1} s]",
        o.name,
        o.statistic,
        o.solver,
        o.persson,
        o.verdict,
        match o.reproduced {
            Some(true) => "as the paper",
            Some(false) => "NOT as the paper",
            None => "inconclusive",
        },
        claims.reproduced,
        claims.contradicted,
        claims.not_established,
        o.wall_s
    )
}

/// The definitions named, from `--dir` or the built-in copies; a `--dir` that cannot be
/// read is named as the flag.
fn definitions(dir: Option<&Path>, names: &[String]) -> Result<Vec<Source>> {
    validations::definitions(dir, names, &FLAGS).map_err(|e| match (e, dir) {
        (Error::Io { path, source }, Some(dir)) if path == dir => Error::invalid(
            "--dir",
            format!("{} ({source})", dir.display()),
            "a readable folder of validation definitions (*.toml)",
        ),
        (e, _) => e,
    })
}
