//! A probe for refactorings of the CG solver that must not change its numerics: prints
//! the iteration count, the residual and a digest of the bit patterns of the pressure and
//! displacement for a set of solves (cold and warm, both preconditioning modes, and two
//! failing solves). Run before and after a change and compare the output:
//!
//! `cargo test --test suite cg_bits -- --ignored --nocapture`

use persson_check::engine::contact::{ContactProblem, ContactSolution, Model};
use persson_check::engine::solver::{ConstrainedCg, SolveOptions, Solver, Start};
use persson_check::engine::surface::{Surface, SurfaceModel};
use sha2::{Digest, Sha256};

/// The first twelve bytes of the SHA-256 of the bit patterns of `v`, in hex.
pub(crate) fn digest(v: &[f64]) -> String {
    let mut hasher = Sha256::new();
    for x in v {
        hasher.update(x.to_bits().to_le_bytes());
    }
    hasher
        .finalize()
        .iter()
        .take(12)
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// One line of a probe: iterations, residual bits and digests of a solution, or the error.
pub(crate) fn line(label: &str, result: &persson_check::error::Result<ContactSolution>) -> String {
    match result {
        Ok(s) => format!(
            "{label}: ok it={} res={:016x} p={} u={}",
            s.stats.iterations,
            s.stats.residual.value().to_bits(),
            digest(&s.pressure),
            digest(&s.displacement)
        ),
        Err(e) => format!("{label}: err {e:?}"),
    }
}

/// The two failing solves of a probe, with `solver` at `p0 = 0.01`: a small iteration
/// budget, and a tolerance below the rounding floor.
pub(crate) fn failures(
    solver: &mut dyn Solver,
    model: &Model,
    h: &[f64],
    label: &str,
    out: &mut Vec<String>,
) {
    let problem = ContactProblem::new(model, h, 0.01).unwrap();
    let short = SolveOptions {
        tol: 1e-10,
        max_iter: 7,
    };
    out.push(line(
        &format!("{label} budget"),
        &solver.solve(&problem, Start::Cold, &short),
    ));
    let floor = SolveOptions {
        tol: 1e-14,
        max_iter: 3000,
    };
    out.push(line(
        &format!("{label} floor"),
        &solver.solve(&problem, Start::Cold, &floor),
    ));
}

/// A probe's surface: its size, Hurst exponent, model and full-resolution heights.
pub(crate) struct Scene {
    pub n: usize,
    pub hurst: f64,
    pub surface: Surface,
    pub model: Model,
    pub h: Vec<f64>,
}

/// The probes' surfaces: `n` of 128 and 256, `H` of 0.8 and 0.3, `lambda_l = n / 2`,
/// `lambda_s = 4`, seed 11.
pub(crate) fn scenes() -> impl Iterator<Item = Scene> {
    [128usize, 256].into_iter().flat_map(|n| {
        [0.8, 0.3].into_iter().map(move |hurst| {
            let params = SurfaceModel::new(n, hurst, n as f64 / 2.0, 4.0, 11);
            let surface = Surface::generate(&params).unwrap();
            let model = Model::new(surface.grid().clone(), 1.0).unwrap();
            let h = surface.heights_at(f64::INFINITY, &model.fft);
            Scene {
                n,
                hurst,
                surface,
                model,
                h,
            }
        })
    })
}

/// Prints a probe's lines, and writes them to the file the environment variable `var`
/// names, if set.
pub(crate) fn emit(out: &[String], var: &str) {
    let text = out.join("\n");
    println!("{text}");
    if let Ok(path) = std::env::var(var) {
        std::fs::write(path, text + "\n").unwrap();
    }
}

#[test]
#[ignore = "a probe: prints digests to compare before and after a change"]
fn cg_bits() {
    let mut out = Vec::new();
    for Scene {
        n,
        hurst,
        surface: _,
        model,
        h,
    } in scenes()
    {
        for preconditioned in [true, false] {
            for p0 in [0.01, 0.1, 1.0] {
                let label = format!("n={n} H={hurst} pc={preconditioned} p0={p0}");
                let mut cg = ConstrainedCg::default();
                cg.preconditioned = preconditioned;
                let opts = SolveOptions::with_tol(1e-9);
                let problem = ContactProblem::new(&model, &h, p0).unwrap();
                let cold = cg.solve(&problem, Start::Cold, &opts);
                out.push(line(&format!("{label} cold"), &cold));
                if let Ok(prev) = &cold {
                    let warm_problem = ContactProblem::new(&model, &h, p0 * 1.1).unwrap();
                    let warm = cg.solve(&warm_problem, Start::Warm(prev), &opts);
                    out.push(line(&format!("{label} warm"), &warm));
                }
            }
        }
        if n == 128 {
            failures(
                &mut ConstrainedCg::default(),
                &model,
                &h,
                &format!("n={n} H={hurst}"),
                &mut out,
            );
        }
    }
    emit(&out, "CG_BITS_OUT");
}
