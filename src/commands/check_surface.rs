//! `check-surface`: Persson's theory checked on measured height maps.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use persson_check::engine::solver::SolverKind;
use persson_check::error::Result;
use persson_check::measured::check::CheckOptions;
use persson_check::measured::psd::Boundary;
use persson_check::tasks::check::{check_surface, read_scans};

use super::FLAGS;

/// Arguments of `check-surface`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Height maps (.npy, 2D float, or a plain-text matrix), square; several files are
    /// several scans of one surface (the error bars come from them).
    #[arg(long, num_args = 1.., required = true)]
    heights: Vec<PathBuf>,
    /// Pixel size, in the heights' length unit.
    #[arg(long = "pixel-size", allow_negative_numbers = true)]
    pixel_size: f64,
    /// The scans are periodic (default: measured windows, solved with a free boundary).
    #[arg(long)]
    periodic: bool,
    /// Loads as nominal pressure over the contact modulus, p0/E* (default: eight loads
    /// giving contact areas of about 1% to 30%).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    loads: Option<Vec<f64>>,
    /// The headline solver.
    #[arg(long, value_enum, default_value_t = SolverKind::Gfmd)]
    solver: SolverKind,
    /// Skip the cross-check with a second solver (CG for GFMD, GFMD for any other).
    #[arg(long = "no-cross-check")]
    no_cross_check: bool,
    /// Residual tolerance of every solve.
    #[arg(long, default_value_t = 1e-6, allow_negative_numbers = true)]
    tol: f64,
    /// Output folder: surface.json, surface.md, figures/.
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    let scans = read_scans(&args.heights, &FLAGS)?;
    let opts = CheckOptions {
        pixel_size: args.pixel_size,
        boundary: if args.periodic {
            Boundary::Periodic
        } else {
            Boundary::Free
        },
        loads: args.loads,
        solver: args.solver,
        cross_check: !args.no_cross_check,
        tol: args.tol,
    };
    let solves = scans.len() * if opts.cross_check { 2 } else { 1 };
    let bar = ProgressBar::new(solves as u64);
    bar.set_style(
        ProgressStyle::with_template(
            "{prefix:>16} [{elapsed_precise}] {bar:30} {pos}/{len} curves {msg}",
        )
        .expect("static template"),
    );
    bar.set_prefix("check-surface");
    let mut last = None;
    let mut progress = |scan: usize, solver: SolverKind, load: usize, _| {
        let key = (scan, solver);
        if last.is_some_and(|k| k != key) {
            bar.inc(1);
        }
        last = Some(key);
        bar.set_message(format!(
            "scan {}, {}, load {}",
            scan + 1,
            solver.name(),
            load + 1
        ));
    };
    let result = check_surface(&scans, &opts, Some(&args.out), &FLAGS, &mut progress)?;
    bar.finish_and_clear();
    for c in &result.comparisons {
        println!("{:24} {} : {}", c.name, c.statistic, c.verdict);
    }
    println!("wrote {}", args.out.join("surface.md").display());
    Ok(())
}
