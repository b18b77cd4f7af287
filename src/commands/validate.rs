//! `validate`: run named validations (all by default) and write their outcomes.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::engine::solver::SolverKind;
use persson_check::error::{Error, Result};
use persson_check::validation::source::{builtin_sources, select, sources_in, Source};
use persson_check::validation::{Outcome, Registry, RunOptions, Scale};

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
    /// Output folder: <name>.json, <name>.csv and figures.
    #[arg(long)]
    out: PathBuf,
    /// Run one solver only (default: GFMD for the headline and CG for the cross-check).
    #[arg(long, value_enum)]
    solver: Option<SolverKind>,
}

pub fn run(args: Args) -> Result<()> {
    super::check_out_dir(&args.out)?;
    let sources = match &args.dir {
        Some(dir) => definitions_in(dir)?,
        None => builtin_sources(),
    };
    let sources = select(sources, &args.names)?;
    let registry = Registry::builtin();
    // Every definition is checked before any runs: bad input writes nothing.
    for source in &sources {
        registry.check(source)?;
    }
    let opts = RunOptions {
        scale: if args.full {
            Scale::Full
        } else {
            Scale::Reduced
        },
        out: args.out.clone(),
        resume: args.resume,
        progress: true,
        solvers: match args.solver {
            Some(kind) => vec![kind],
            None => RunOptions::BOTH.to_vec(),
        },
    };
    let mut failed = Vec::new();
    for (path, result) in registry.run_all(&sources, &opts) {
        match result {
            Ok(o) => println!("{}", summary_line(&o)),
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
/// there is none), the verdict, the paper's finding, the cross-check and the wall time.
fn summary_line(o: &Outcome) -> String {
    let measured = if o.std_error.is_finite() {
        format!("{:.4} +- {:.4}", o.value, o.std_error)
    } else {
        format!("{:.4} (one realization: no error bar, no verdict)", o.value)
    };
    let cross = match &o.cross_check {
        Some(c) if c.std_error.is_finite() => format!(
            "; {} {:.4} +- {:.4}, {}",
            c.solver,
            c.value,
            c.std_error,
            if c.agrees { "agrees" } else { "DISAGREES" }
        ),
        Some(c) => format!(
            "; {} {:.4}, {}",
            c.solver,
            c.value,
            if c.agrees { "agrees" } else { "DISAGREES" }
        ),
        None => String::new(),
    };
    format!(
        "{:<16} {} = {measured} ({}; Persson {:.4}): {}, paper {}{cross} [{:.1} s]",
        o.name,
        o.statistic,
        o.solver,
        o.persson,
        o.verdict,
        match o.reproduced {
            Some(true) => "reproduced",
            Some(false) => "NOT reproduced",
            None => "undecided",
        },
        o.wall_s
    )
}

/// The definitions in `--dir` (at least one).
fn definitions_in(dir: &std::path::Path) -> Result<Vec<Source>> {
    let sources = sources_in(dir).map_err(|e| match e {
        Error::Io { path, source } if path == dir => Error::invalid(
            "--dir",
            format!("{} ({source})", dir.display()),
            "a readable folder of validation definitions (*.toml)",
        ),
        e => e,
    })?;
    if sources.is_empty() {
        return Err(Error::invalid(
            "--dir",
            format!("{} (no *.toml files)", dir.display()),
            "a folder of validation definitions (*.toml)",
        ));
    }
    Ok(sources)
}
