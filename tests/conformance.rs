//! One conformance check run over every solver of [`SolverKind::ALL`], after RustFFT's
//! `check_fft_algorithm`: a solver added to the list passes [`check_solver`] or fails here.
//! For each solver:
//!
//! 1. every solution it returns meets the hard-wall conditions, with the residual of its
//!    fields below the tolerance asked for ([`check_solution`]);
//! 2. a warm start from its own converged solution converges at once, before any step (0
//!    iterations: every method judges its start first), to the same solution
//!    ([`assert_agree`]);
//! 3. Westergaard's sinusoid, periodic, has an exact solution: in partial contact the
//!    area within two grid spacings and the peak pressure within 1e-3 (the bounds of
//!    `hard_scenes`), in full contact the pressure exact to 1e-9 `p0` point by point;
//! 4. a sphere on the free boundary gives Hertz's contact ([`assert_hertz`]);
//! 5. a solve stopped by its monitor at iteration `k` (cancelled, or over its time) ends
//!    in [`Error::Stopped`] at `k`, and leaves the solver sound: its next warm solve
//!    converges to the cold answer, bit for bit as a solver that was never stopped
//!    ([`stopped_then_warm`]);
//! 6. the units do not matter ([`units_do_not_matter`], after ContactMechanics'
//!    unit-neutrality test): the scene of 2 with the modulus `E*` scaled by `a` and every
//!    length (grid spacing and heights) by `b`, at the load `a p0`, is the same problem, whose
//!    pressure is `a p` and displacement `b u`. With powers of two for `a`, `b` and `a / b`
//!    (even powers, so that no square root of a ratio of them is rounded) every operation
//!    of a solve scales exactly: the scaled solve takes the same iterations to the same
//!    bits. With other factors the two agree to what the tolerance implies.
//!
//! The scenes are the smallest that resolve each property, so that the check costs a few
//! seconds in release; the solver tests (`solvers`, `hard_scenes`) go further.

use std::ops::ControlFlow;

use persson_check::engine::contact::{ContactProblem, ContactSolution, Model};
use persson_check::engine::field;
use persson_check::engine::grid::Grid;
use persson_check::engine::reference::{Hertz, Westergaard};
use persson_check::engine::solver::{
    Progress, SolveOptions, Solver, SolverKind, Start, StopReason,
};
use persson_check::engine::surface::{Surface, SurfaceModel};
use persson_check::error::Error;

use crate::common::contact::{
    assert_agree, assert_hertz, check_solution, sinusoid, sphere_on_free_boundary,
};

/// The tolerance of the periodic scenes: two orders tighter than the default, as in
/// `hard_scenes`, so that agreement is tested well below any physical effect.
const TOL: f64 = 1e-10;

/// A solve of `problem` by `solver` (of `kind`) from `start` to `tol` that must converge
/// and pass [`check_solution`].
fn converged(
    scene: &str,
    kind: SolverKind,
    solver: &mut dyn Solver,
    problem: &ContactProblem,
    start: Start,
    tol: f64,
) -> ContactSolution {
    let s = solver
        .solve(problem, start, &SolveOptions::with_tol(tol))
        .unwrap_or_else(|e| panic!("{scene}, {}: {e}", kind.name()));
    check_solution(scene, kind, problem, &s, tol);
    eprintln!(
        "{scene:<30} {:<4} residual {:.2e}  iterations {:>5}{}  a_r {:.4}",
        kind.name(),
        s.stats.residual.value(),
        s.stats.iterations,
        if s.stats.warm { " (warm)" } else { "" },
        s.contact_area()
    );
    s
}

/// The random surface of the scenes below (64^2, H = 0.8, lambda_l = 32, lambda_s = 4,
/// seed 3) at full resolution, on a periodic model with `E* = 1`: the model and heights.
fn random_scene() -> (Model, Vec<f64>) {
    let surface = Surface::generate(&SurfaceModel::new(64, 0.8, 32.0, 4.0, 3)).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    (model, h)
}

/// Cold, then warm from the cold solution, on a random surface in partial contact
/// (64^2, H = 0.8, lambda_l = 32, lambda_s = 4, p0 = 0.1 E* g_bar).
fn warm_from_the_solution(kind: SolverKind) {
    let (model, h) = random_scene();
    let problem = ContactProblem::new(&model, &h, 0.1).unwrap();
    let mut solver = kind.build();
    let scene = "random surface";
    let cold = converged(scene, kind, solver.as_mut(), &problem, Start::Cold, TOL);
    let warm = converged(
        scene,
        kind,
        solver.as_mut(),
        &problem,
        Start::Warm(&cold),
        TOL,
    );
    assert!(!cold.stats.warm && warm.stats.warm, "{}", kind.name());
    assert!(
        warm.stats.iterations == 0,
        "{}: {} iterations from the converged solution (cold: {})",
        kind.name(),
        warm.stats.iterations,
        cold.stats.iterations
    );
    assert_agree(scene, &cold, &warm, TOL);
}

/// The iteration at which [`stopped_then_warm`] stops a solve: past the first few, where
/// every method is mid-way.
const STOP_AT: usize = 4;

/// On the random surface of [`warm_from_the_solution`]: solved at `p0 = 0.1`, then a solve
/// at `p0 = 0.12` warm from it (and another cold) stopped at iteration [`STOP_AT`] by its
/// monitor; then the same warm solve again, not stopped, by the same solver.
fn stopped_then_warm(kind: SolverKind) {
    let (model, h) = random_scene();
    let (first, second) = (
        ContactProblem::new(&model, &h, 0.1).unwrap(),
        ContactProblem::new(&model, &h, 0.12).unwrap(),
    );
    let opts = SolveOptions::with_tol(TOL);
    let scene = "random surface, stopped";
    let name = kind.name();

    let mut solver = kind.build();
    let from = converged(scene, kind, solver.as_mut(), &first, Start::Cold, TOL);
    for (start, reason) in [
        (Start::Warm(&from), StopReason::Cancelled),
        (Start::Cold, StopReason::OutOfTime),
    ] {
        let mut seen = Vec::new();
        let stopped = solver.solve_monitored(&second, start, &opts, &mut |p: Progress| {
            seen.push(p.iteration);
            if p.iteration == STOP_AT {
                ControlFlow::Break(reason)
            } else {
                ControlFlow::Continue(())
            }
        });
        match stopped {
            Err(Error::Stopped {
                solver: by,
                reason: why,
                iteration,
                residual,
            }) => {
                assert_eq!((by, why, iteration), (name, reason, STOP_AT), "{name}");
                assert!(residual.is_finite(), "{name}: estimate {residual}");
            }
            other => panic!("{name}: a solve stopped at {STOP_AT} gave {other:?}"),
        }
        assert_eq!(
            seen.last(),
            Some(&STOP_AT),
            "{name}: the monitor is not asked again after it answers stop"
        );
    }

    let warm = converged(
        scene,
        kind,
        solver.as_mut(),
        &second,
        Start::Warm(&from),
        TOL,
    );
    let cold = converged(
        scene,
        kind,
        kind.build().as_mut(),
        &second,
        Start::Cold,
        TOL,
    );
    assert_agree(scene, &cold, &warm, TOL);

    // A solver that was never stopped, through the same converged solves.
    let mut fresh = kind.build();
    let from_fresh = converged(scene, kind, fresh.as_mut(), &first, Start::Cold, TOL);
    let unstopped = converged(
        scene,
        kind,
        fresh.as_mut(),
        &second,
        Start::Warm(&from_fresh),
        TOL,
    );
    assert_eq!(
        solve_bits(&warm),
        solve_bits(&unstopped),
        "{name}: the stops changed the next solve (iterations, pressure and displacement bits)"
    );
}

/// A solve's iterations and the bits of its pressure and displacement, for comparisons
/// that must be exact.
fn solve_bits(s: &ContactSolution) -> (usize, Vec<u64>, Vec<u64>) {
    (
        s.stats.iterations,
        field_bits(&s.pressure),
        field_bits(&s.displacement),
    )
}

/// A field's bits.
fn field_bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|v| v.to_bits()).collect()
}

/// Westergaard's sinusoid on 64^2, `h0 = 1`: partial contact at `0.3 p*` and full contact
/// at `1.5 p*`.
fn westergaard(kind: SolverKind) {
    let (n, h0) = (64usize, 1.0);
    let (model, h) = sinusoid(n, h0);
    let exact = Westergaard {
        h0,
        lambda: n as f64,
        e_star: 1.0,
    };
    let mut solver = kind.build();
    let p0 = 0.3 * exact.full_contact_pressure();
    let problem = ContactProblem::new(&model, &h, p0).unwrap();
    let s = converged(
        "Westergaard, partial",
        kind,
        solver.as_mut(),
        &problem,
        Start::Cold,
        TOL,
    );
    let area = (s.contact_area() - exact.contact_fraction(p0)).abs() * n as f64;
    let peak = (field::max(&s.pressure) - exact.peak_pressure(p0)).abs() / exact.peak_pressure(p0);
    assert!(area <= 2.0, "{}: area off by {area} spacings", kind.name());
    assert!(peak <= 1e-3, "{}: peak off by {peak:e}", kind.name());

    let p0 = 1.5 * exact.full_contact_pressure();
    let problem = ContactProblem::new(&model, &h, p0).unwrap();
    let s = converged(
        "Westergaard, full",
        kind,
        solver.as_mut(),
        &problem,
        Start::Cold,
        1e-11,
    );
    assert_eq!(s.contact_area(), 1.0, "{}", kind.name());
    for (k, &p) in s.pressure.iter().enumerate() {
        let e = exact.pressure(p0, (k % n) as f64);
        assert!(
            (p - e).abs() <= 1e-9 * p0,
            "{}: point {k}: {p} vs {e}",
            kind.name()
        );
    }
}

/// A sphere of radius 1000 on a 192^2 free-boundary window, pressed to a contact radius
/// of 40 grid spacings (far from the window's edges).
fn hertz_on_the_free_boundary(kind: SolverKind) {
    let (n, radius, a) = (192usize, 1000.0, 40.0);
    let hertz = Hertz {
        radius,
        e_star: 1.0,
    };
    let force = hertz.force_for_radius(a);
    let (model, h, p0) = sphere_on_free_boundary(n, radius, force);
    let problem = ContactProblem::new(&model, &h, p0).unwrap();
    let s = converged(
        "Hertz, free boundary",
        kind,
        kind.build().as_mut(),
        &problem,
        Start::Cold,
        1e-8,
    );
    assert_hertz(kind, &model, &s, &hertz, (a, force));
}

/// The scene of [`warm_from_the_solution`] solved cold in grid units and again with the
/// modulus scaled by `a` and the lengths by `b` (see the module docs, 6).
fn units_do_not_matter(kind: SolverKind) {
    let (model, h) = random_scene();
    let grid = &model.grid;
    let solve = |a: f64, b: f64| {
        let model = Model::new(Grid::new(grid.n(), b).unwrap(), a).unwrap();
        let h: Vec<f64> = h.iter().map(|h| b * h).collect();
        let problem = ContactProblem::new(&model, &h, a * 0.1).unwrap();
        let scene = format!("random surface, E* x {a}, lengths x {b}");
        let mut s = converged(
            &scene,
            kind,
            kind.build().as_mut(),
            &problem,
            Start::Cold,
            TOL,
        );
        s.pressure.iter_mut().for_each(|p| *p /= a);
        s.displacement.iter_mut().for_each(|u| *u /= b);
        s.p0 /= a;
        s
    };
    let name = kind.name();
    let unit = solve(1.0, 1.0);
    let exact = solve(16.0, 0.25);
    assert_eq!(
        solve_bits(&exact),
        solve_bits(&unit),
        "{name}: E* x 16 and lengths x 1/4 change the solve (iterations, pressure and displacement bits)"
    );
    let scaled = solve(3.7, 0.013);
    assert_agree("random surface, other units", &unit, &scaled, TOL);
}

/// Every property of the module docs, for one solver.
fn check_solver(kind: SolverKind) {
    warm_from_the_solution(kind);
    stopped_then_warm(kind);
    westergaard(kind);
    hertz_on_the_free_boundary(kind);
    units_do_not_matter(kind);
}

#[test]
fn every_solver_conforms() {
    for kind in SolverKind::ALL {
        check_solver(kind);
    }
}
