//! `solve`: one hard-wall contact problem, at a given load or a given contact area.

use std::ops::ControlFlow;
use std::path::PathBuf;

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};

use persson_check::error::{Error, Result};
use persson_check::tasks::solve::{Origin, Progress, SolveArgs, Solved};
use persson_check::tasks::{check_out_dir, surface, Flags, SolveOptions, SolverKind};

use super::{SurfaceArgs, FLAGS};

/// Arguments of `solve`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// Heights from a .npy file (float64, N x N) instead of a generated surface.
    #[arg(long, conflicts_with_all = ["scene", "n", "hurst", "lambda_l", "lambda_s", "seed"])]
    heights: Option<PathBuf>,
    /// With --heights: the wavelength that defines zeta = |q| / q_l (default: the box size).
    #[arg(
        long = "file-lambda-l",
        requires = "heights",
        allow_negative_numbers = true
    )]
    file_lambda_l: Option<f64>,
    #[command(flatten)]
    surface: SurfaceArgs,
    /// Mean pressure p0 (units of E*).
    #[arg(long, conflicts_with = "contact_area", allow_negative_numbers = true)]
    p0: Option<f64>,
    /// Target relative contact area, in (0, 1): p0 is found by root finding.
    #[arg(long = "contact-area", allow_negative_numbers = true)]
    contact_area: Option<f64>,
    /// Magnification (default: full resolution).
    #[arg(long, allow_negative_numbers = true)]
    zeta: Option<f64>,
    /// Solver.
    #[arg(long, value_enum)]
    solver: Option<SolverKind>,
    /// Residual tolerance, in [1e-14, 1).
    #[arg(long, allow_negative_numbers = true)]
    tol: Option<f64>,
    /// Iteration budget per solve.
    #[arg(
        long = "max-iter",
        default_value_t = SolveOptions::DEFAULT_MAX_ITER,
        allow_negative_numbers = true
    )]
    max_iter: usize,
    /// Output directory: summary.json, summary.csv, pressure.npy, displacement.npy, gap.npy.
    #[arg(long)]
    out: PathBuf,
}

/// The flags of `solve --heights`: the heights' `lambda_l` is `--file-lambda-l`.
const HEIGHTS_FLAGS: Flags<'static> = Flags {
    renamed: &[("lambda_l", "--file-lambda-l")],
};

pub fn run(args: Args) -> Result<()> {
    // Every flag is checked before any work.
    let checked = SolveArgs {
        p0: args.p0,
        contact_area: args.contact_area,
        zeta: args.zeta,
        lambda_l: args.file_lambda_l,
        solver: args.solver,
        tol: args.tol,
        max_iter: Some(args.max_iter),
    }
    .check(&FLAGS, &HEIGHTS_FLAGS)?;
    check_out_dir(&args.out, &FLAGS)?;
    let (surface, scene) = match &args.heights {
        Some(path) => {
            let surface = surface::read_heights(path, args.file_lambda_l, &HEIGHTS_FLAGS)?;
            (surface, None)
        }
        None => {
            let scene = args.surface.resolve()?;
            (surface::realization(&scene)?, Some(scene))
        }
    };
    let seed = scene.and_then(|s| s.surface.seed).unwrap_or(0);
    let origin = match (&args.heights, args.surface.scene.as_deref()) {
        (Some(path), _) => Origin::File(path),
        (None, Some(path)) => Origin::Scene { path, seed },
        (None, None) => Origin::Generated { seed },
    };
    // A load given on the command line replaces the scene's.
    let table = scene.map(|s| s.solve).unwrap_or_default();
    let settled = checked.settle(Some(&table), &FLAGS)?;
    let bar = spinner(settled.solver());
    // Every 16th iteration ticks the spinner.
    let solved = settled.run(&surface, origin, &FLAGS, |p0, p: Progress| {
        if p.iteration % 16 == 0 {
            bar.set_message(format!(
                "p0 {p0:.4e}  iteration {}  residual {:.2e}",
                p.iteration, p.residual
            ));
            bar.tick();
        }
        ControlFlow::Continue(())
    })?;
    bar.finish_and_clear();
    write_outputs(&args.out, &solved)
}

fn spinner(kind: SolverKind) -> ProgressBar {
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} {prefix} [{elapsed}] {msg}")
            .expect("static template"),
    );
    bar.set_prefix(kind.name());
    bar
}

fn write_outputs(dir: &std::path::Path, solved: &Solved) -> Result<()> {
    let Solved {
        heights,
        solution,
        summary,
    } = solved;
    let n = summary.n;
    let gap = solution.gap(heights);
    persson_check::io::npy::write_field(&dir.join("pressure.npy"), n, &solution.pressure)?;
    persson_check::io::npy::write_field(&dir.join("displacement.npy"), n, &solution.displacement)?;
    persson_check::io::npy::write_field(&dir.join("gap.npy"), n, &gap)?;
    let json = serde_json::to_string_pretty(summary).expect("summary serialises");
    persson_check::io::write_atomic(&dir.join("summary.json"), json.as_bytes())?;
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record([
        "n",
        "p0",
        "contact_area",
        "elastic_energy",
        "mean_gap",
        "residual",
        "iterations",
        "wall_s",
        "solver",
        "zeta",
    ])
    .and_then(|_| {
        csv.write_record([
            summary.n.to_string(),
            summary.p0.to_string(),
            summary.contact_area.to_string(),
            summary.elastic_energy.to_string(),
            summary.mean_gap.to_string(),
            summary.residual.to_string(),
            summary.iterations.to_string(),
            summary.wall_s.to_string(),
            summary.solver.to_string(),
            summary.zeta.to_string(),
        ])
    })
    .map_err(|e| Error::io(dir.join("summary.csv"), std::io::Error::other(e)))?;
    let bytes = csv.into_inner().map_err(|e| {
        Error::io(
            dir.join("summary.csv"),
            std::io::Error::other(e.to_string()),
        )
    })?;
    persson_check::io::write_atomic(&dir.join("summary.csv"), &bytes)
}
