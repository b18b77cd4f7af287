//! `check-surface`: Persson's theory checked on measured height maps, or on line scans
//! (a 1D input, or 2D inputs with `--line`: [`persson_check::measured::line`]).

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::PathBuf;

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use persson_check::error::{Error, Result, StopReason};
use persson_check::measured::check::{CheckOptions, Event, SurfaceCheck};
use persson_check::measured::fill::Fill;
use persson_check::measured::line::check::{LineOptions, DEFAULT_SEEDS, DEFAULT_SIDE};
use persson_check::measured::options::{CHECK_SOLVER, CHECK_TOL, MAX_ITERATIONS};
use persson_check::measured::psd::Boundary;
use persson_check::tasks::check::{check_line, check_surface, load_line, read_input, Input};
use persson_check::tasks::SolverKind;

use super::FLAGS;

/// Arguments of `check-surface`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Height maps (.npy, 2D float, or a plain-text matrix), square or rectangular; several
    /// files are several scans of one surface (the error bars come from them). A 1D input
    /// (a .npy vector, one row or one column of text) is a line scan, a profile.
    #[arg(long, num_args = 1.., required = true)]
    heights: Vec<PathBuf>,
    /// Read 2D inputs as line scans: each row a profile of one surface (its columns are the
    /// profiles across, for the isotropy check). The contact is then simulated on isotropic
    /// surfaces synthesized with the spectrum the profiles imply.
    #[arg(long)]
    line: bool,
    /// Line scans: side of the synthesized surfaces, points (at most the profile's length).
    #[arg(long = "line-side", default_value_t = DEFAULT_SIDE)]
    line_side: usize,
    /// Line scans: synthesized surfaces, one per seed (the error bars come from them).
    #[arg(long = "line-seeds", default_value_t = DEFAULT_SEEDS)]
    line_seeds: u64,
    /// Pixel size, in the heights' length unit: one value, or two (between rows, between
    /// columns) that differ by at most 0.1%.
    #[arg(
        long = "pixel-size",
        allow_negative_numbers = true,
        value_delimiter = ',',
        num_args = 1..=2,
        required = true
    )]
    pixel_size: Vec<f64>,
    /// The heights' length unit (m, mm, µm, nm, ...), printed with every length.
    #[arg(long)]
    unit: Option<String>,
    /// The contact modulus E* in pascals: loads and pressures also in Pa.
    #[arg(long, allow_negative_numbers = true)]
    modulus: Option<f64>,
    /// Points the instrument did not measure (NaN): refused (none), or filled by harmonic
    /// interpolation from their neighbours, up to 10% of a scan.
    #[arg(long, value_enum, default_value_t = Fill::None)]
    fill: Fill,
    /// The scans are periodic (default: measured windows, solved with a free boundary).
    #[arg(long)]
    periodic: bool,
    /// Loads as nominal pressure over the contact modulus, p0/E* (default: eight loads
    /// giving contact areas of about 1% to 30%).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    loads: Option<Vec<f64>>,
    /// The headline solver.
    #[arg(long, value_enum, default_value_t = CHECK_SOLVER)]
    solver: SolverKind,
    /// Skip the cross-check with a second solver (the first of the list other than the
    /// headline one: CG for GFMD, GFMD for any other).
    #[arg(long = "no-cross-check")]
    no_cross_check: bool,
    /// Cross-check every load (default: the lowest, the middle and the highest).
    #[arg(long = "cross-check-all")]
    cross_check_all: bool,
    /// Skip the re-entry share over magnification.
    #[arg(long = "no-reentry")]
    no_reentry: bool,
    /// Residual tolerance of every solve.
    #[arg(long, default_value_t = CHECK_TOL, allow_negative_numbers = true)]
    tol: f64,
    /// Iteration budget of every solve: a load whose solve has not reached the tolerance
    /// after this many iterations is reported as failed, with the solver's state
    /// (iterations, residual against the tolerance, points in contact), and the check
    /// goes on with the other loads.
    #[arg(long = "max-iterations", default_value_t = MAX_ITERATIONS)]
    max_iterations: usize,
    /// Replace spikes before the check (off by default): a point whose height differs
    /// from the median of its eight neighbours by more than K robust deviations (1.4826
    /// times the median absolute deviation of those differences over the scan) is
    /// removed and filled by harmonic interpolation, as missing points are; K >= 3. The
    /// page says how many points were replaced.
    #[arg(long, value_name = "K", allow_negative_numbers = true)]
    despike: Option<f64>,
    /// Output folder: surface.json, surface.md, solves.jsonl, figures/.
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> Result<()> {
    let input = read_input(&args.heights, args.line, &FLAGS)?;
    let pixel_size = match args.pixel_size[..] {
        [p] => [p, p],
        [a, b] => [a, b],
        _ => {
            return Err(Error::invalid(
                "--pixel-size",
                format!("{:?}", args.pixel_size),
                "one value, or two separated by a comma",
            ))
        }
    };
    let opts = CheckOptions {
        pixel_size,
        unit: args.unit,
        boundary: if args.periodic {
            Boundary::Periodic
        } else {
            Boundary::Free
        },
        loads: args.loads,
        solver: args.solver,
        cross_check: !args.no_cross_check,
        cross_check_all: args.cross_check_all,
        tol: args.tol,
        fill: args.fill,
        modulus: args.modulus,
        reentry: !args.no_reentry,
        max_iterations: args.max_iterations,
        despike: args.despike,
    };
    let line = LineOptions {
        side: args.line_side,
        seeds: args.line_seeds,
    };
    let count = match &input {
        Input::Surface(scans) => scans.len(),
        Input::Line(_) => usize::try_from(line.seeds).unwrap_or(usize::MAX),
    };
    let out = args.out.as_path();
    let run = |events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>| -> Result<SurfaceCheck> {
        match &input {
            Input::Surface(scans) => check_surface(scans, &opts, Some(out), &FLAGS, events),
            Input::Line(profiles) => {
                check_line(profiles, &opts, &line, Some(out), &FLAGS, events).map(|c| c.surface)
            }
        }
    };
    let result = if std::io::stderr().is_terminal() {
        let solves = count * if opts.cross_check { 2 } else { 1 };
        let bar = ProgressBar::new(solves as u64);
        bar.set_style(
            ProgressStyle::with_template(
                "{prefix:>16} [{elapsed_precise}] {bar:30} {pos}/{len} curves {msg}",
            )
            .expect("static template"),
        );
        bar.set_prefix("check-surface");
        let mut events = |e: Event| {
            match e {
                Event::Iteration {
                    scan, solver, load, ..
                } => bar.set_message(format!(
                    "scan {}, {}, load {}",
                    scan + 1,
                    solver.name(),
                    load + 1
                )),
                Event::Outliers { .. } => {
                    if let Some(line) = load_line(count, &e) {
                        bar.println(line);
                    }
                }
                Event::Load { load, loads, .. } => {
                    if let Some(line) = load_line(count, &e) {
                        bar.println(line);
                    }
                    // Both curves end at the last load.
                    if load + 1 == loads {
                        bar.inc(1);
                    }
                }
            }
            ControlFlow::Continue(())
        };
        let result = run(&mut events);
        bar.finish_and_clear();
        result?
    } else {
        // A log, a notebook, a batch job: one line per load as it ends.
        let mut events = |e: Event| {
            if let Some(line) = load_line(count, &e) {
                eprintln!("check-surface: {line}");
            }
            ControlFlow::Continue(())
        };
        run(&mut events)?
    };
    if let Input::Line(p) = &input {
        outln!(
            "line scans: {} profile(s) of {} points; contact simulated on {} synthesized \
             surfaces",
            p.count(),
            p.points,
            line.seeds
        );
    }
    for c in &result.comparisons {
        outln!("{:24} {} : {}", c.name, c.statistic, c.verdict);
    }
    for w in &result.warnings {
        outln!("warning: {}: {}", w.name, w.message);
    }
    for f in &result.failures {
        outln!("failed: {}", f.message);
    }
    outln!("wrote {}", args.out.join("surface.md").display());
    Ok(())
}
