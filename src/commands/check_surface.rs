//! `check-surface`: Persson's theory checked on measured height maps, or on line scans
//! (a 1D input, 2D inputs with `--line`, or an x-y profile at non-uniform positions with
//! `--line-scan`, resampled onto even spacing: [`persson_check::measured::line`]). The
//! flags make the one request Python's keywords make too
//! ([`persson_check::tasks::check::CheckRequest`]); this command reads the inputs, shows
//! progress and prints what the check found. `--scales FILE.toml` checks one surface
//! measured at several scales ([`persson_check::tasks::scales`]).

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use persson_check::error::Result;
use persson_check::measured::check::{CheckOptions, Event};
use persson_check::measured::fill::Fill;
use persson_check::measured::line::check::{LineOptions, DEFAULT_SEEDS, DEFAULT_SIDE};
use persson_check::measured::options::{CHECK_SOLVER, CHECK_TOL, MAX_ITERATIONS};
use persson_check::measured::psd::Boundary;
use persson_check::measured::units::{eng, length};
use persson_check::tasks::check::{
    load_line, read_input, read_line_scan, CheckRequest, Checked, Input, SurfaceTask,
};
use persson_check::tasks::scales::{check_scales, read_list};
use persson_check::tasks::SolverKind;

use super::FLAGS;

/// Arguments of `check-surface`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Height maps (.npy, 2D float, or a plain-text matrix), square or rectangular; several
    /// files are several scans of one surface (the error bars come from them). A 1D input
    /// (a .npy vector, one row or one column of text) is a line scan, a profile.
    #[arg(long, num_args = 1.., required_unless_present_any = ["line_scan", "scales"])]
    heights: Vec<PathBuf>,
    /// One surface measured at several scales: a scan list (TOML), a [[scan]] table per
    /// scan with its file, pixel_size, unit (optional; scans in other units are converted)
    /// and line (optional). Their spectra are stitched into the surface's, Persson's
    /// theory is evaluated on it and on each scan's band, and each height map is simulated
    /// and set against both. Each scan brings its own pixel size: --pixel-size is refused.
    #[arg(long, value_name = "FILE.toml", conflicts_with_all = ["heights", "line_scan", "line", "pixel_size"])]
    scales: Option<PathBuf>,
    /// A line scan at non-uniform positions: a two-column text file (position, height a
    /// line, in one length unit), resampled onto as many evenly spaced points by linear
    /// interpolation, with a warning; the positions must increase strictly. Its spacing
    /// is the pixel size (--pixel-size may be left out).
    #[arg(long = "line-scan", value_name = "FILE", conflicts_with_all = ["heights", "line"])]
    line_scan: Option<PathBuf>,
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
        required_unless_present_any = ["line_scan", "scales"]
    )]
    pixel_size: Option<Vec<f64>>,
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
    /// Skip the pixel's own error (default: every load also solved on the scan coarsened
    /// by 2, and by 4 where each side keeps 32 points, and the contact area extrapolated
    /// to a vanishing pixel, against which the theory is set).
    #[arg(long = "no-extrapolate")]
    no_extrapolate: bool,
    /// Keep every wavelength down to the pixel (default: each scan cut at its shortest
    /// reliable wavelength, the onset of a noise floor in its spectrum or the tip's
    /// limit with --tip-radius, in the spectrum and in the heights solved).
    #[arg(long = "no-cutoff")]
    no_cutoff: bool,
    /// The radius of the instrument's tip, in the heights' unit: wavelengths whose rms
    /// curvature the tip cannot follow are cut.
    #[arg(long = "tip-radius", allow_negative_numbers = true)]
    tip_radius: Option<f64>,
    /// Output folder: surface.json, surface.md, solves.jsonl, figures/.
    #[arg(long)]
    out: PathBuf,
}

impl Args {
    /// The request the flags make (the one Python's keywords make too).
    fn request(&self) -> CheckRequest {
        CheckRequest {
            pixel_size: self.pixel_size.clone(),
            periodic: self.periodic,
            options: CheckOptions {
                unit: self.unit.clone(),
                loads: self.loads.clone(),
                solver: self.solver,
                cross_check: !self.no_cross_check,
                cross_check_all: self.cross_check_all,
                tol: self.tol,
                fill: self.fill,
                modulus: self.modulus,
                reentry: !self.no_reentry,
                max_iterations: self.max_iterations,
                despike: self.despike,
                extrapolate: !self.no_extrapolate,
                cutoff: !self.no_cutoff,
                tip_radius: self.tip_radius,
                ..CheckOptions::default()
            },
            line: LineOptions {
                side: self.line_side,
                seeds: self.line_seeds,
            },
        }
    }
}

pub fn run(args: Args) -> Result<()> {
    if let Some(list) = &args.scales {
        return scales(&args, list);
    }
    let (input, own_pixel) = match &args.line_scan {
        Some(path) => {
            let (input, pixel, warning) = read_line_scan(path)?;
            eprintln!("warning: {}: {warning}", path.display());
            (input, Some(pixel))
        }
        None => (read_input(&args.heights, args.line, &FLAGS)?, None),
    };
    let task = args.request().task(input, own_pixel, &FLAGS)?;
    let result = if std::io::stderr().is_terminal() {
        with_progress_bar(&task, &args.out)?
    } else {
        // A log, a notebook, a batch job: one line per load as it ends.
        let count = task.curves();
        let mut events = |e: Event| {
            if let Some(line) = load_line(count, &e) {
                eprintln!("check-surface: {line}");
            }
            ControlFlow::Continue(())
        };
        task.run(Some(&args.out), &FLAGS, &mut events)?
    };
    summarize(&task, &result, &args.out);
    Ok(())
}

/// The check of one surface at several scales (`--scales`): a line per load as it ends,
/// then a line per areal scan's comparison and where the page is.
fn scales(args: &Args, list: &Path) -> Result<()> {
    let scans = read_list(list, &FLAGS)?;
    let request = args.request();
    let opts = CheckOptions {
        boundary: if args.periodic {
            Boundary::Periodic
        } else {
            Boundary::Free
        },
        ..request.options
    };
    let count = scans.len();
    let mut events = |e: Event| {
        if let Some(line) = load_line(count, &e) {
            eprintln!("check-surface: {line}");
        }
        ControlFlow::Continue(())
    };
    let result = check_scales(scans, &opts, Some(&args.out), &FLAGS, &mut events)?;
    let u = result.unit.as_deref();
    for g in &result.stitched.gaps {
        let two_pi = 2.0 * std::f64::consts::PI;
        outln!(
            "gap: no scan resolves the wavelengths from {} down to {}: the stitched spectrum \
             is interpolated across it",
            length(two_pi / g.from, u),
            length(two_pi / g.to, u)
        );
    }
    outln!(
        "stitched spectrum: {} bins from q = {} to {} 1/{}; whole surface: rms slope {}",
        result.stitched.bins.len(),
        eng(result.stitched.band.lo),
        eng(result.stitched.band.hi),
        u.unwrap_or("length unit"),
        eng(result.slope_rms)
    );
    for f in &result.scans {
        let Some(rows) = &f.comparison else { continue };
        for r in [rows.first(), rows.last()].into_iter().flatten() {
            outln!(
                "{}: p0 = {} E*: a_r = {} simulated, Persson {} on its band, {} on the whole \
                 surface",
                f.label,
                eng(r.p0),
                eng(r.a_r),
                eng(r.a_r_persson_band),
                eng(r.a_r_persson_whole)
            );
        }
    }
    for f in &result.scans {
        let Some(check) = &f.check else { continue };
        for w in &check.warnings {
            outln!("{}: warning: {}: {}", f.label, w.name, w.message);
        }
        for failure in &check.failures {
            outln!("{}: failed: {}", f.label, failure.message);
        }
    }
    outln!("wrote {}", args.out.join("scales.md").display());
    Ok(())
}

/// The check run with a progress bar on the terminal: one step per curve, a line per
/// load.
fn with_progress_bar(task: &SurfaceTask, out: &Path) -> Result<Checked> {
    let count = task.curves();
    let solves = count * if task.opts.cross_check { 2 } else { 1 };
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
    let result = task.run(Some(out), &FLAGS, &mut events);
    bar.finish_and_clear();
    result
}

/// What the check found, a line each: the line scans, the comparisons, the warnings and
/// the failed solves, and where the page is.
fn summarize(task: &SurfaceTask, checked: &Checked, out: &Path) {
    if let Input::Line(p) = &task.input {
        outln!(
            "line scans: {} profile(s) of {} points; contact simulated on {} synthesized \
             surfaces",
            p.count(),
            p.points,
            task.line.seeds
        );
    }
    let result = checked.surface();
    for c in &result.comparisons {
        outln!("{:24} {} : {}", c.name, c.statistic, c.verdict);
    }
    for w in &result.warnings {
        outln!("warning: {}: {}", w.name, w.message);
    }
    for f in &result.failures {
        outln!("failed: {}", f.message);
    }
    outln!("wrote {}", out.join("surface.md").display());
}
