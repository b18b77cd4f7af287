//! `persson-check`: the command line (conventions, section 7, in the library's docs).
//!
//! ```text
//! persson-check surface  (--scene FILE.toml | --n N --hurst H --lambda-l L --lambda-s S --seed K)
//!                        [--zeta Z] --out FILE.npy
//! persson-check solve    (--heights FILE.npy | --scene FILE.toml) (--p0 P | --contact-area A)
//!                        [--zeta Z] [--solver gfmd|cg|fire] [--tol T] --out DIR
//! persson-check validate [NAME ...] [--full] [--solvers S1,S2,...] --out DIR
//! persson-check report   [--from DIR] --out FILE.md [--golden DIR] [--history FILE]
//! persson-check speed    [--n N] [--floor-n N ...] [--repeats K] --out DIR
//! persson-check check-surface --heights FILE... --pixel-size DX [--periodic]
//!                        [--loads P1,P2,...] [--solver gfmd|cg|fire] [--no-cross-check] --out DIR
//! persson-check audit    [--from DIR] [--budget 20m] [--seed K] [--job KEY ...]
//!                        [--validation NAME ...] [--out DIR]
//! persson-check compare  BASE NEW [--out FILE.md] [--z Z]
//! persson-check claims   [--full DIR] [--reduced DIR] [--write [FILE.md]]
//! ```
//!
//! Exit code 0 on success; otherwise a message on stderr and a non-zero code, and no
//! partial output files. `audit` and `compare` answer a question: 0 when nothing differs
//! (or moved), 1 when something does, 2 when they could not answer (bad input).

mod commands;

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use persson_check::tasks::parse::MAX_THREADS;

/// Tests Persson's contact mechanics theory against hard-wall contact simulations.
#[derive(Parser, Debug)]
#[command(name = "persson-check", version, about, long_about = None)]
struct Cli {
    /// Worker threads (default: all cores).
    #[arg(
        long,
        global = true,
        allow_negative_numbers = true,
        value_parser = clap::value_parser!(u16).range(1..=MAX_THREADS as i64)
    )]
    threads: Option<u16>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Generate a self-affine surface and write its heights as .npy.
    Surface(commands::surface::Args),
    /// Solve one hard-wall contact problem and write its fields and summary.
    Solve(commands::solve::Args),
    /// Run named validations (all by default) and write their outcomes.
    Validate(commands::validate::Args),
    /// Write the scorecard of the outcomes in a folder (and of the speed study there, if
    /// any); reads the folder only.
    Report(commands::report::Args),
    /// Run the speed-against-error study and write speed.json and its figures into a folder
    /// (which `report` then shows).
    Speed(commands::speed::Args),
    /// Check Persson's theory on measured height maps (contact area, pressures, energy).
    CheckSurface(commands::check_surface::Args),
    /// Recompute a sample of committed job results and compare them byte for byte.
    Audit(commands::audit::Args),
    /// Compare two folders of outcomes statistic by statistic (z-scores, flips).
    Compare(commands::compare::Args),
    /// The paper's claims, full and reduced scenes side by side (the table of docs/claims.md).
    Claims(commands::claims::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Some(t) = cli.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(t as usize)
            .build_global()
        {
            eprintln!("error: --threads: {e}");
            return ExitCode::from(2);
        }
    }
    let result = match cli.command {
        Command::Surface(args) => commands::surface::run(args),
        Command::Solve(args) => commands::solve::run(args),
        Command::Validate(args) => commands::validate::run(args),
        Command::Report(args) => commands::report::run(args),
        Command::Speed(args) => commands::speed::run(args),
        Command::CheckSurface(args) => commands::check_surface::run(args),
        Command::Audit(args) => return answer(commands::audit::run(args)),
        Command::Compare(args) => return answer(commands::compare::run(args)),
        Command::Claims(args) => commands::claims::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The exit code of a command that answers whether something differs: 0 no, 1 yes, 2 when
/// it could not answer (the error on stderr).
fn answer(result: persson_check::error::Result<bool>) -> ExitCode {
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
