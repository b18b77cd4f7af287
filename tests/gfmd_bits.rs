//! A probe for refactorings of the GFMD solver that must not change its numerics: prints
//! the iteration count, the residual and a digest of the bit patterns of the pressure and
//! displacement for a set of solves (cold, warm after a load change with the solver kept,
//! a load search and a sweep of a few magnification shells with the solver kept, and two
//! failing solves). Run before and after a change and compare the output:
//!
//! `cargo test --test suite gfmd_bits -- --ignored --nocapture`
//!
//! The other dynamics methods' probes ([`crate::fire_bits`]) run the same solves
//! ([`probe`]).

use persson_check::engine::contact::ContactProblem;
use persson_check::engine::solver::{Gfmd, SolveOptions, Solver, Start};
use persson_check::engine::sweep::{shell_steps, Sweep};

use crate::cg_bits::{emit, failures, line, scenes, Scene};

/// Shells of the sweep, from the first above this magnification.
const SWEEP_FROM: f64 = 3.0;
/// Shells solved in the sweep.
const SWEEP_SHELLS: usize = 4;

#[test]
#[ignore = "a probe: prints digests to compare before and after a change"]
fn gfmd_bits() {
    probe(&|| Box::new(Gfmd::default()), "GFMD_BITS_OUT");
}

/// The probe's solves with fresh solvers from `build`, emitted as `var` says ([`emit`]).
pub(crate) fn probe(build: &dyn Fn() -> Box<dyn Solver + Send>, var: &str) {
    let mut out = Vec::new();
    for Scene {
        n,
        hurst,
        surface,
        model,
        h,
    } in scenes()
    {
        let opts = SolveOptions::with_tol(1e-9);
        for p0 in [0.01, 0.1, 1.0] {
            let label = format!("n={n} H={hurst} p0={p0}");
            // One solver for both solves: the warm solve begins from the step the
            // cold one ended with.
            let mut solver = build();
            let problem = ContactProblem::new(&model, &h, p0).unwrap();
            let cold = solver.solve(&problem, Start::Cold, &opts);
            out.push(line(&format!("{label} cold"), &cold));
            if let Ok(prev) = &cold {
                let warm_problem = ContactProblem::new(&model, &h, p0 * 1.1).unwrap();
                let warm = solver.solve(&warm_problem, Start::Warm(prev), &opts);
                out.push(line(&format!("{label} warm"), &warm));
            }
        }
        // A load search, then shells added one by one, warm-started from predicted
        // states, with one solver throughout.
        let steps = shell_steps(&surface, SWEEP_FROM, f64::INFINITY);
        let mut sweep = Sweep::with_solver(&surface, &model, build(), opts);
        let label = format!("n={n} H={hurst} sweep");
        match sweep.find_load(steps[0], 0.1) {
            Ok(p0) => {
                out.push(line(
                    &format!("{label} load p0={:016x}", p0.to_bits()),
                    &Ok(sweep.solution().unwrap().clone()),
                ));
                for &zeta in &steps[1..=SWEEP_SHELLS] {
                    let step = sweep.solve_at(zeta, p0).cloned();
                    out.push(line(&format!("{label} zeta={zeta:.6}"), &step));
                }
            }
            Err(e) => out.push(format!("{label} load: err {e:?}")),
        }
        if n == 128 {
            failures(
                build().as_mut(),
                &model,
                &h,
                &format!("n={n} H={hurst}"),
                &mut out,
            );
        }
    }
    emit(&out, var);
}
