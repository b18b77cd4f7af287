//! The cost of a re-entry history (`c_reentry`, paper section 3.3): the climb through every
//! shell at fixed load, each solve warm-started from the last, with each warm-start
//! prediction of [`Prediction`] side by side. The scene is the paper's at any grid:
//! H = 0.8, `lambda_l = N/2`, `lambda_s = 8`, seed 1, the load that gives `a_r = 0.14` at
//! `zeta_max` (found once, outside the timing, by GFMD at the climb's tolerance),
//! `tol = 1e-4` (the tolerance `c_reentry`'s tolerance study accepts).
//!
//! * `history/<prediction>/<solver>/256`: the first [`SHELLS`] shells of the 256^2
//!   history, from the flat interface, one climb per timed iteration; the first climb of
//!   each logs its iterations and FFTs a shell to stderr;
//! * `history/shell/cg@3e-4/256`: the same climb by CG at [`FAST_TOL`], the tolerance at
//!   which the whole 1024^2 history keeps today's share (docs/measured.md).
//!
//! A whole paper-scale history is too long for criterion's samples. With `HISTORY_AB` set,
//! the bench runs instead an interleaved A/B of whole or truncated histories, the
//! predictions taking turns (their order reversed every round), and prints for each run
//! the solver iterations, 2D transforms and CPU seconds (user + system, the whole
//! process) a shell, the re-entry share, and against the default prediction's run of the
//! same round the ratios and the points whose contact at the last step differs:
//!
//! ```text
//! HISTORY_AB="n=1024 shells=400 rounds=2 a_r=0.14 solvers=gfmd,cg predictions=shell,response" \
//!     RAYON_NUM_THREADS=1 cargo bench --bench history
//! ```
//!
//! (`shells=0`: the whole history; `seed=` as well; predictions are `shell`, `response`
//! and `extrapolate:W`; `tols=1e-4,1e-3` runs each prediction at each tolerance, the load
//! found at the first, and compares every run with the default prediction at the first.
//! `runs=gfmd@1e-4,cg@3e-4` instead names solver and tolerance pairs, the load found at
//! the first pair's tolerance, and compares every run with the first pair's default
//! prediction: today's method against another solver at another tolerance.)

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use persson_check::engine::contact::ContactSolution;
use persson_check::engine::contact::Model;
use persson_check::engine::solver::{SolveOptions, SolverKind};
use persson_check::engine::surface::{Surface, SurfaceModel};
use persson_check::engine::sweep::{shell_steps, Prediction, Sweep};
use persson_check::experiments::climb::{climb_steps, Recorder, Stepped};
use persson_check::experiments::history::History;

/// Hurst exponent of the scene.
const HURST: f64 = 0.8;
/// Short-wavelength cutoff, grid spacings (`lambda_l = N/2`).
const LAMBDA_S: f64 = 8.0;
/// Contact area at `zeta_max` that sets the load.
const A_R: f64 = 0.14;
/// The residual tolerance of the histories.
const TOL: f64 = 1e-4;
/// The looser tolerance of the CG climb set beside today's GFMD one.
const FAST_TOL: f64 = 3e-4;
/// Shells of the criterion benchmark's climb.
const SHELLS: usize = 60;

/// One realization, its model, the load and the climb's magnifications.
struct Scene {
    surface: Surface,
    model: Model,
    p0: f64,
    steps: Vec<f64>,
}

impl Scene {
    /// The scene on an `n x n` grid, realization `seed`, at the load of `a_r`.
    fn new(n: usize, seed: u64, a_r: f64, tol: f64) -> Self {
        let params = SurfaceModel::new(n, HURST, n as f64 / 2.0, LAMBDA_S, seed);
        let surface = Surface::generate(&params).expect("valid scene");
        let model = Model::new(surface.grid().clone(), 1.0).expect("valid model");
        let opts = SolveOptions::with_tol(tol);
        let zeta_max = surface.zeta_max();
        let p0 = Sweep::new(&surface, &model, SolverKind::Gfmd, opts)
            .find_load(zeta_max, a_r)
            .expect("load search converges");
        let steps = shell_steps(&surface, 0.0, zeta_max);
        Self {
            surface,
            model,
            p0,
            steps,
        }
    }
}

/// What one climb cost and measured.
struct Run {
    shells: usize,
    iterations: u64,
    transforms: u64,
    cpu_s: f64,
    wall_s: f64,
    share: f64,
    in_contact: Vec<u8>,
    /// Iterations of each shell's solve.
    per_shell: Vec<usize>,
}

/// A history that also keeps each step's iterations.
struct Counted {
    history: History,
    iterations: Vec<usize>,
}

impl Recorder for Counted {
    fn record(
        &mut self,
        step: usize,
        zeta: f64,
        solution: &ContactSolution,
    ) -> persson_check::Result<()> {
        self.iterations.push(solution.stats.iterations);
        self.history.record(step, zeta, solution)
    }
}

/// The quartiles and the largest of `values`.
fn spread(values: &[usize]) -> String {
    let mut v = values.to_vec();
    v.sort_unstable();
    let at = |q: f64| {
        v.get(((v.len() - 1) as f64 * q) as usize)
            .copied()
            .unwrap_or(0)
    };
    format!(
        "{}/{}/{}/{}/{}",
        at(0.1),
        at(0.25),
        at(0.5),
        at(0.9),
        at(1.0)
    )
}

/// CPU seconds of this process so far (user + system, every thread), from `/proc`.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let fields: Vec<&str> = after.split_whitespace().collect();
    // After the command's ')': state is field 3, utime 14 and stime 15 (1-based).
    let ticks = |k: usize| fields.get(k - 3).and_then(|v| v.parse::<f64>().ok());
    match (ticks(14), ticks(15)) {
        (Some(u), Some(s)) => (u + s) / 100.0,
        _ => f64::NAN,
    }
}

/// Climbs the first `shells` shells of `scene` (all: 0) with `kind` and `prediction`.
fn climb(
    scene: &Scene,
    kind: SolverKind,
    (prediction, tol): (Prediction, f64),
    shells: usize,
) -> Run {
    let steps = match shells {
        0 => &scene.steps[..],
        k => &scene.steps[..k.min(scene.steps.len())],
    };
    let opts = SolveOptions::with_tol(tol);
    let mut sweep =
        Sweep::new(&scene.surface, &scene.model, kind, opts).with_prediction(prediction);
    let mut history = Counted {
        history: History::new(scene.model.grid.points(), (f64::INFINITY, f64::INFINITY)),
        iterations: Vec::with_capacity(steps.len()),
    };
    let transforms = scene.model.fft.transforms();
    let (cpu, wall) = (cpu_seconds(), Instant::now());
    let done = climb_steps(
        &mut sweep,
        scene.p0,
        steps,
        Stepped::default(),
        &mut history,
        |_, _, _| Ok(()),
    )
    .expect("the climb converges");
    let (cpu_s, wall_s) = (cpu_seconds() - cpu, wall.elapsed().as_secs_f64());
    let Counted {
        history,
        iterations: per_shell,
    } = history;
    let (contact, reentered, _) = history.counts();
    Run {
        shells: steps.len(),
        iterations: done.iterations,
        transforms: scene.model.fft.transforms() - transforms,
        cpu_s,
        wall_s,
        share: reentered as f64 / contact.max(1) as f64,
        in_contact: history.in_contact,
        per_shell,
    }
}

/// A prediction's name in `HISTORY_AB`: `shell`, `response` or `extrapolate:W`.
fn parse_prediction(s: &str) -> Prediction {
    match s.split_once(':') {
        Some(("extrapolate", w)) => Prediction::Extrapolate(w.parse().expect("a weight")),
        _ if s == "shell" => Prediction::Shell,
        _ if s == "response" => Prediction::Response,
        _ => panic!("unknown prediction {s:?}: shell, response or extrapolate:W"),
    }
}

/// A pair of `runs=`: `solver@tol`.
fn parse_run(s: &str) -> (SolverKind, f64) {
    let (solver, tol) = s.split_once('@').expect("a run is solver@tol");
    (
        SolverKind::from_name(solver).expect("a solver name"),
        tol.parse().expect("a tolerance"),
    )
}

fn name(p: Prediction) -> String {
    match p {
        Prediction::Shell => "shell".into(),
        Prediction::Response => "response".into(),
        Prediction::Extrapolate(w) => format!("extrapolate:{w}"),
    }
}

/// The interleaved A/B of `HISTORY_AB` (see the crate docs).
fn interleaved(spec: &str) {
    let mut n = 1024;
    let (mut shells, mut rounds, mut seed) = (400, 2, 1);
    let (mut a_r, mut tols) = (A_R, vec![TOL]);
    let mut solvers = vec![SolverKind::Gfmd];
    let mut runs: Vec<(SolverKind, f64)> = Vec::new();
    let mut predictions = vec![Prediction::Shell, Prediction::Response];
    for item in spec.split_whitespace() {
        let (key, value) = item.split_once('=').expect("key=value");
        match key {
            "n" => n = value.parse().expect("n"),
            "shells" => shells = value.parse().expect("shells"),
            "rounds" => rounds = value.parse().expect("rounds"),
            "seed" => seed = value.parse().expect("seed"),
            "a_r" => a_r = value.parse().expect("a_r"),
            "tols" => tols = value.split(',').map(|t| t.parse().expect("tol")).collect(),
            "solvers" => {
                solvers = value
                    .split(',')
                    .map(|s| SolverKind::from_name(s).expect("a solver name"))
                    .collect();
            }
            "predictions" => predictions = value.split(',').map(parse_prediction).collect(),
            "runs" => runs = value.split(',').map(parse_run).collect(),
            _ => panic!("unknown key {key:?}"),
        }
    }
    // Each group's runs are compared with its first pair's default prediction: one group
    // per solver over the tolerances, or the named pairs as one group.
    let groups: Vec<Vec<(SolverKind, f64)>> = if runs.is_empty() {
        solvers
            .iter()
            .map(|&k| tols.iter().map(|&t| (k, t)).collect())
            .collect()
    } else {
        tols = runs.iter().map(|r| r.1).collect();
        vec![runs]
    };
    let tol = tols[0];
    let scene = Scene::new(n, seed, a_r, tol);
    eprintln!(
        "history {n}^2, seed {seed}, a_r {a_r} (p0 = {:.6e}), tol {tol}, {} of {} shells",
        scene.p0,
        if shells == 0 {
            scene.steps.len()
        } else {
            shells.min(scene.steps.len())
        },
        scene.steps.len()
    );
    println!("round\tsolver\tprediction\ttol\tit/shell\tfft/shell\tcpu s/shell\twall s/shell\tshare\tit ratio\tfft ratio\tcpu ratio\tshare diff\tdiffering points\titerations d1/q1/median/d9/max");
    for round in 0..rounds {
        for group in &groups {
            let first = group[0];
            let mut order: Vec<(SolverKind, Prediction, f64)> = group
                .iter()
                .flat_map(|&(k, t)| predictions.iter().map(move |&p| (k, p, t)))
                .collect();
            if round % 2 == 1 {
                order.reverse();
            }
            let runs: Vec<((SolverKind, Prediction, f64), Run)> = order
                .into_iter()
                .map(|(k, p, t)| ((k, p, t), climb(&scene, k, (p, t), shells)))
                .collect();
            let base = runs
                .iter()
                .find(|((k, p, t), _)| p.is_shell() && (*k, *t) == first)
                .map(|(_, r)| r);
            for ((kind, p, t), r) in &runs {
                let per = |x: f64| x / r.shells as f64;
                let vs = base.map_or(String::from("\t\t\t\t"), |b| {
                    let differ = r
                        .in_contact
                        .iter()
                        .zip(&b.in_contact)
                        .filter(|(x, y)| x != y)
                        .count();
                    format!(
                        "{:.4}\t{:.4}\t{:.4}\t{:.3e}\t{:.3e}",
                        r.iterations as f64 / b.iterations as f64,
                        r.transforms as f64 / b.transforms as f64,
                        r.cpu_s / b.cpu_s,
                        r.share - b.share,
                        differ as f64 / r.in_contact.len() as f64
                    )
                });
                println!(
                    "{round}\t{}\t{}\t{t:e}\t{:.2}\t{:.2}\t{:.4}\t{:.4}\t{:.6}\t{vs}\t{}",
                    kind.name(),
                    name(*p),
                    per(r.iterations as f64),
                    per(r.transforms as f64),
                    per(r.cpu_s),
                    per(r.wall_s),
                    r.share,
                    spread(&r.per_shell),
                );
            }
        }
    }
}

fn history(c: &mut Criterion) {
    if let Ok(spec) = std::env::var("HISTORY_AB") {
        interleaved(&spec);
        return;
    }
    let mut group = c.benchmark_group("history");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(20));
    let n = 256;
    let scene = std::cell::OnceCell::new();
    let mut runs: Vec<(Prediction, SolverKind, f64)> = [Prediction::Shell, Prediction::Response]
        .into_iter()
        .flat_map(|p| [SolverKind::Gfmd, SolverKind::Cg].map(|k| (p, k, TOL)))
        .collect();
    runs.push((Prediction::Shell, SolverKind::Cg, FAST_TOL));
    for (prediction, kind, tol) in runs {
        let solver = if tol == TOL {
            kind.name().to_string()
        } else {
            format!("{}@{tol:e}", kind.name())
        };
        let id = BenchmarkId::new(format!("{}/{solver}", name(prediction)), n);
        let logged = std::cell::Cell::new(false);
        group.bench_function(id, |b| {
            let scene = scene.get_or_init(|| Scene::new(n, 1, A_R, TOL));
            if !logged.replace(true) {
                let r = climb(scene, kind, (prediction, tol), SHELLS);
                eprintln!(
                    "history/{}/{solver}/{n}: {} shells, {:.2} iterations and {:.2} FFTs a shell",
                    name(prediction),
                    r.shells,
                    r.iterations as f64 / r.shells as f64,
                    r.transforms as f64 / r.shells as f64
                );
            }
            b.iter(|| black_box(climb(scene, kind, (prediction, tol), SHELLS)));
        });
    }
    group.finish();
}

criterion_group!(benches, history);
criterion_main!(benches);
