//! The same scene and seed give the same numbers whatever the number of threads.
//!
//! Tolerance: none. The golden snapshots (`golden/`, compared by `src/report/golden.rs`)
//! keep values rounded to 3 significant digits ([`persson_check::stats::round_sig`]) and
//! compare them with a relative tolerance of `REL_TOL` = 1e-9, which absorbs float parsing
//! only: they rely on runs being reproducible to the last rounded digit. The
//! FFT and every reduction are written to be independent of the thread count
//! (`src/field.rs`, `src/fft.rs`), so these tests demand more than the snapshots do:
//! bit-identical fields and statistics.

use std::process::{Command, Stdio};

use persson_check::engine::contact::{ContactSolution, Model};
use persson_check::engine::solver::SolveOptions;
use persson_check::engine::solver::SolverKind;
use persson_check::engine::surface::{Surface, SurfaceModel};
use persson_check::engine::sweep::Sweep;

use crate::common::{definitions_with_reentry, outcome_numbers, table_without_wall};

/// A reduced re-entry scene on a grid of two reduction chunks (128^2 = 2 x 8192 points).
const REENTRY_SCENE: &str = "[reduced]
n = 128
hurst = 0.8
lambda_l = 64
lambda_s = 8
seeds = [1, 2]
contact_areas = [0.14]
flux_zeta = 6
flux_dzeta = 1
checkpoint_seconds = 30
tol = 1e-8

";

/// A folder with the built-in `a_diffusion` and `b_drift` (whose reduced scenes share their
/// jobs: 256^2, eight realizations) and a small `c_reentry` ([`REENTRY_SCENE`]).
fn definitions() -> tempfile::TempDir {
    definitions_with_reentry(REENTRY_SCENE, &["a_diffusion", "b_drift"])
}

const NAMES: [&str; 3] = ["a_diffusion", "b_drift", "c_reentry"];

#[test]
fn validations_give_the_same_statistics_on_one_and_two_threads() {
    let defs = definitions();
    let outs: Vec<tempfile::TempDir> = (0..2).map(|_| tempfile::tempdir().unwrap()).collect();
    // Both runs at once: the machine has two cores to share between them.
    let children: Vec<_> = [1, 2]
        .iter()
        .zip(&outs)
        .map(|(threads, out)| {
            Command::new(env!("CARGO_BIN_EXE_persson-check"))
                .arg("--threads")
                .arg(threads.to_string())
                .arg("validate")
                .args(NAMES)
                // The solvers' own bit-identity over thread counts is checked below for
                // both; one solver keeps this test short.
                .args(["--solver", "cg"])
                .arg("--dir")
                .arg(defs.path())
                .arg("--out")
                .arg(out.path())
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for (threads, child) in [1, 2].iter().zip(children) {
        let output = child.wait_with_output().unwrap();
        assert!(
            output.status.success(),
            "--threads {threads} failed:\n{}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let (one, two) = (outs[0].path(), outs[1].path());
    for name in NAMES {
        let (a, b) = (outcome_numbers(one, name), outcome_numbers(two, name));
        for key in [
            "value",
            "std_error",
            "golden",
            "details",
            "checks",
            "max_residual",
        ] {
            assert_eq!(
                a[key], b[key],
                "{name}: {key} differs between 1 and 2 threads"
            );
        }
        assert_eq!(a, b, "{name}: the outcome differs between 1 and 2 threads");
        assert_eq!(
            table_without_wall(one, name),
            table_without_wall(two, name),
            "{name}.csv differs between 1 and 2 threads"
        );
    }
}

/// Solves at `zeta = 8` (cold start), then adds roughness up to `zeta = 10` (warm start),
/// in a pool of `threads` threads; returns the contact area at `zeta = 8` and the last
/// solution.
fn sweep_in_pool(kind: SolverKind, threads: usize) -> (f64, ContactSolution) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        // 256^2: eight reduction chunks, and rows split differently on 1, 2 and 3 threads.
        let surface = Surface::generate(&SurfaceModel::new(256, 0.8, 128.0, 8.0, 7)).unwrap();
        let model = Model::new(surface.grid().clone(), 1.0).unwrap();
        let mut sweep = Sweep::new(&surface, &model, kind, SolveOptions::with_tol(1e-9));
        let p0 = 0.05;
        let area = sweep.solve_at(8.0, p0).unwrap().contact_area();
        sweep.solve_at(10.0, p0).unwrap();
        (area, sweep.take_solution().unwrap())
    })
}

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn solves_are_bit_identical_on_one_two_and_three_threads() {
    for kind in [SolverKind::Cg, SolverKind::Gfmd] {
        let (area, one) = sweep_in_pool(kind, 1);
        for threads in [2, 3] {
            let (area_other, other) = sweep_in_pool(kind, threads);
            let name = kind.name();
            assert_eq!(
                area, area_other,
                "{name}: contact area on {threads} threads"
            );
            assert!(
                bits(&one.pressure) == bits(&other.pressure),
                "{name}: pressure differs between 1 and {threads} threads"
            );
            assert!(
                bits(&one.displacement) == bits(&other.displacement),
                "{name}: displacement differs between 1 and {threads} threads"
            );
            assert_eq!(one.stats.iterations, other.stats.iterations, "{name}");
            assert_eq!(
                one.stats.residual.value().to_bits(),
                other.stats.residual.value().to_bits(),
                "{name}: residual"
            );
        }
    }
}
