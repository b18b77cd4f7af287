//! `validate`: run named validations (all by default) and write their outcomes.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use persson_check::error::{Error, Result};
use persson_check::validation::source::{builtin_sources, select, sources_in, Source};
use persson_check::validation::{Registry, RunOptions, Scale};

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
    };
    let mut failed = Vec::new();
    for (path, result) in registry.run_all(&sources, &opts) {
        match result {
            Ok(o) => println!(
                "{:<16} {} = {:.4} +- {:.4} (Persson {:.4}): {}, paper {} [{:.1} s]",
                o.name,
                o.statistic,
                o.value,
                o.std_error,
                o.persson,
                o.verdict,
                match o.reproduced {
                    Some(true) => "reproduced",
                    Some(false) => "NOT reproduced",
                    None => "undecided",
                },
                o.wall_s
            ),
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
