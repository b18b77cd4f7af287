//! `solve`: one hard-wall contact problem, at a given load or a given contact area.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;

use persson_check::engine::contact::{ContactProblem, ContactSolution, Model, Residual};
use persson_check::engine::grid::{Grid, MAX_N, MIN_N};
use persson_check::engine::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use persson_check::engine::scene::{check_zeta, SolveScene};
use persson_check::engine::solver::SolverKind;
use persson_check::engine::solver::{Progress, SolveOptions, Solver, Start};
use persson_check::engine::surface::Surface;
use persson_check::error::{check_open, check_positive, Error, Result, Termination};

use super::{as_flag, check_out_dir, SurfaceArgs};

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
        default_value_t = 100_000,
        allow_negative_numbers = true
    )]
    max_iter: usize,
    /// Output directory: summary.json, summary.csv, pressure.npy, displacement.npy, gap.npy.
    #[arg(long)]
    out: PathBuf,
}

/// `summary.json` (conventions, section 7, plus additions).
#[derive(Debug, Serialize)]
struct Summary {
    n: usize,
    p0: f64,
    contact_area: f64,
    elastic_energy: f64,
    mean_gap: f64,
    residual: f64,
    iterations: usize,
    wall_s: f64,
    solver: &'static str,
    /// Why the solve stopped: always `converged` here (a solve that stops otherwise is an
    /// error that names its reason, and writes nothing).
    termination: Termination,
    zeta: f64,
    rms_gradient: f64,
    reduced_pressure: f64,
    e_star: f64,
    tol: f64,
    load_solves: usize,
    source: String,
    residual_components: Residual,
    tamaas_error: f64,
}

pub fn run(args: Args) -> Result<()> {
    check_flags(&args)?;
    check_out_dir(&args.out)?;
    let (surface, settings, source) = match &args.heights {
        Some(path) => {
            let surface = read_heights(path, args.file_lambda_l)?;
            (surface, SolveScene::default(), path.display().to_string())
        }
        None => {
            let (scene, surface) = args.surface.generate()?;
            let source = match &args.surface.scene {
                Some(p) => format!("{} (seed {})", p.display(), scene.surface.seed.unwrap_or(0)),
                None => format!("generated (seed {})", scene.surface.seed.unwrap_or(0)),
            };
            (surface, scene.solve, source)
        }
    };
    let zeta_max = surface.zeta_max().max(1.0);
    let zeta = args.zeta.or(settings.zeta).unwrap_or(zeta_max);
    check_zeta(zeta, zeta_max).map_err(|e| {
        e.with_field(if args.zeta.is_some() {
            "--zeta"
        } else {
            "solve.zeta"
        })
    })?;
    let kind = args.solver.or(settings.solver).unwrap_or_default();
    let opts = SolveOptions {
        tol: args.tol.or(settings.tol).unwrap_or(1e-8),
        max_iter: args.max_iter,
    };
    opts.validate()?;
    let e_star = settings.e_star.unwrap_or(1.0);
    // A load given on the command line replaces the scene's (both were checked).
    let load = if args.p0.is_some() || args.contact_area.is_some() {
        (args.p0, args.contact_area)
    } else {
        (settings.p0, settings.contact_area)
    };
    let load = match load {
        (Some(p0), None) => Load::Pressure(p0),
        (None, Some(a)) => Load::Area(a),
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                "load",
                "both p0 and contact_area",
                "one of --p0 or --contact-area",
            ))
        }
        (None, None) => {
            return Err(Error::invalid(
                "load",
                "missing",
                "--p0 P or --contact-area A (or in the scene's [solve] table)",
            ))
        }
    };

    let model = Model::new(surface.grid().clone(), e_star)?;
    let heights = surface.heights_at(zeta, &model.fft);
    let g_bar = surface.rms_gradient(zeta);
    let bar = spinner(kind);
    let mut solver = Monitored {
        inner: kind.build(),
        bar: &bar,
    };
    let (solution, solves) = match load {
        Load::Pressure(p0) => {
            let problem = ContactProblem::new(&model, &heights, p0)?;
            (solver.solve(&problem, Start::Cold, &opts)?, 1)
        }
        Load::Area(a) => {
            if g_bar <= 0.0 {
                return Err(Error::invalid(
                    "contact_area",
                    a,
                    "reachable: the surface is flat (zero rms gradient), so contact is \
                     complete at any load; give --p0 instead",
                ));
            }
            let target = AreaTarget {
                contact_area: a,
                p0_guess: persson_load_guess(a, g_bar.max(1e-300), e_star),
            };
            let found = solve_for_area(
                &mut solver,
                &model,
                &heights,
                target,
                Start::Cold,
                &opts,
                &AreaSearch::default(),
            )?;
            (found.solution, found.solves)
        }
    };
    bar.finish_and_clear();
    // The solver's work buffers (24 bytes per point with CG) are not needed to write.
    drop(solver);
    write_outputs(&args.out, &model, &heights, &solution, |s| Summary {
        n: model.grid.n(),
        p0: s.p0,
        contact_area: s.contact_area(),
        elastic_energy: s.elastic_energy(),
        mean_gap: s.mean_gap(&heights),
        residual: s.stats.residual.value(),
        iterations: s.stats.iterations,
        wall_s: s.stats.wall_s,
        solver: s.stats.solver,
        termination: Termination::Converged,
        zeta,
        rms_gradient: g_bar,
        reduced_pressure: s.p0 / (e_star * g_bar),
        e_star,
        tol: opts.tol,
        load_solves: solves,
        source: source.clone(),
        residual_components: s.stats.residual,
        tamaas_error: s.stats.residual.tamaas,
    })
}

/// Checks the ranges of the flags given, before any work; errors name the flag (`--zeta`
/// gets its upper bound once the surface is known).
fn check_flags(args: &Args) -> Result<()> {
    if let Some(p0) = args.p0 {
        check_positive("--p0", p0)?;
    }
    if let Some(a) = args.contact_area {
        check_open("--contact-area", a, 0.0, 1.0)?;
    }
    if let Some(zeta) = args.zeta {
        if !(zeta.is_finite() && zeta >= 1.0) {
            return Err(Error::invalid(
                "--zeta",
                zeta,
                "in [1, zeta_max = lambda_l / lambda_s]",
            ));
        }
    }
    if let Some(lambda) = args.file_lambda_l {
        check_positive("--file-lambda-l", lambda)?;
    }
    SolveOptions {
        tol: args.tol.unwrap_or(1e-8),
        max_iter: args.max_iter,
    }
    .validate()
    .map_err(as_flag)
}

/// The surface of a heights file; a `--file-lambda-l` beyond the box is named as the flag,
/// anything else as the file.
fn read_heights(path: &std::path::Path, file_lambda_l: Option<f64>) -> Result<Surface> {
    let field = persson_check::io::npy::read_field(path, MIN_N..=MAX_N)?;
    let grid = Grid::new(field.n, 1.0).map_err(|e| Error::bad_file(path, e.to_string()))?;
    Surface::from_heights(grid, &field.values, file_lambda_l).map_err(|e| match &e {
        Error::InvalidInput { field, .. } if field == "lambda_l" => e.with_field("--file-lambda-l"),
        _ => Error::bad_file(path, e.to_string()),
    })
}

enum Load {
    Pressure(f64),
    Area(f64),
}

/// A solver whose iterations tick a progress bar.
struct Monitored<'a> {
    inner: Box<dyn Solver + Send>,
    bar: &'a ProgressBar,
}

impl Solver for Monitored<'_> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn solve_monitored(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress),
    ) -> Result<ContactSolution> {
        let bar = self.bar;
        let p0 = problem.p0;
        self.inner.solve_monitored(problem, start, opts, &mut |p| {
            if p.iteration % 16 == 0 {
                bar.set_message(format!(
                    "p0 {p0:.4e}  iteration {}  residual {:.2e}",
                    p.iteration, p.residual
                ));
                bar.tick();
            }
            monitor(p);
        })
    }
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

fn write_outputs<F: Fn(&ContactSolution) -> Summary>(
    dir: &std::path::Path,
    model: &Model,
    heights: &[f64],
    solution: &ContactSolution,
    summary: F,
) -> Result<()> {
    let n = model.grid.n();
    let summary = summary(solution);
    let gap = solution.gap(heights);
    persson_check::io::npy::write_field(&dir.join("pressure.npy"), n, &solution.pressure)?;
    persson_check::io::npy::write_field(&dir.join("displacement.npy"), n, &solution.displacement)?;
    persson_check::io::npy::write_field(&dir.join("gap.npy"), n, &gap)?;
    let json = serde_json::to_string_pretty(&summary).expect("summary serialises");
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
