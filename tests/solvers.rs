//! Every hard-wall solver ([`SolverKind::ALL`]) against exact solutions, conservation laws
//! and the others.

use persson_check::engine::contact::{ContactProblem, ContactSolution, Model};
use persson_check::engine::field;
use persson_check::engine::grid::Grid;
use persson_check::engine::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use persson_check::engine::reference::{Hertz, Westergaard};
use persson_check::engine::solver::SolverKind;
use persson_check::engine::solver::{SolveOptions, Start};
use persson_check::engine::surface::{Surface, SurfaceModel};
use persson_check::error::Termination;
use persson_check::Error;

use crate::common::contact::{assert_hertz, sinusoid, sphere_on_free_window};

fn solve(kind: SolverKind, model: &Model, h: &[f64], p0: f64, tol: f64) -> ContactSolution {
    let problem = ContactProblem::new(model, h, p0).unwrap();
    let mut solver = kind.build();
    solver
        .solve(&problem, Start::Cold, &SolveOptions::with_tol(tol))
        .unwrap_or_else(|e| panic!("{}: {e}", kind.name()))
}

#[test]
fn westergaard_contact_area_and_peak_pressure_converge_with_resolution() {
    let h0 = 1.0;
    for kind in SolverKind::ALL {
        for ratio in [0.05, 0.3, 0.8] {
            let mut area_err = Vec::new();
            let mut peak_err = Vec::new();
            for n in [32usize, 64, 128] {
                let (model, h) = sinusoid(n, h0);
                let exact = Westergaard {
                    h0,
                    lambda: n as f64,
                    e_star: 1.0,
                };
                let p0 = ratio * exact.full_contact_pressure();
                let s = solve(kind, &model, &h, p0, 1e-10);
                let area = s.contact_area();
                let peak = field::max(&s.pressure);
                let ea = (area - exact.contact_fraction(p0)).abs();
                let ep = (peak - exact.peak_pressure(p0)).abs() / exact.peak_pressure(p0);
                // The contact edge is located to within one grid spacing on each side.
                assert!(
                    ea <= 2.0 / n as f64,
                    "{}: p0/p* = {ratio}, N = {n}: area {area} vs {}",
                    kind.name(),
                    exact.contact_fraction(p0)
                );
                area_err.push(ea);
                peak_err.push(ep);
            }
            let fmt = |v: &[f64]| {
                v.iter()
                    .map(|x| format!("{x:.2e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            eprintln!(
                "{} p0/p* = {ratio}: area errors [{}], peak errors [{}]",
                kind.name(),
                fmt(&area_err),
                fmt(&peak_err)
            );
            // Refinement by 4 reduces both errors.
            assert!(
                area_err[2] < area_err[0] || area_err[2] < 1e-12,
                "{}: area errors {area_err:?}",
                kind.name()
            );
            assert!(
                peak_err[2] < peak_err[0],
                "{}: peak errors {peak_err:?}",
                kind.name()
            );
            assert!(
                peak_err[2] < 0.02,
                "{}: peak errors {peak_err:?}",
                kind.name()
            );
        }
    }
}

#[test]
fn full_contact_on_a_random_surface_matches_persson_exactly() {
    let surface = Surface::generate(&SurfaceModel::new(64, 0.8, 32.0, 4.0, 3)).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    // g_bar = 1: pressure fluctuations have rms E* g_bar / 2 = 0.5, so p0 = 5 stays in full
    // contact (the most tensile point would need a 10-sigma excursion).
    let p0 = 5.0;
    for kind in SolverKind::ALL {
        let s = solve(kind, &model, &h, p0, 1e-11);
        assert_eq!(s.contact_area(), 1.0, "{}", kind.name());
        let var = field::std_dev(&s.pressure).powi(2);
        assert!(
            (var - 0.25).abs() < 1e-9,
            "{}: var(p) = {var}, expected (E* g_bar / 2)^2 = 0.25",
            kind.name()
        );
        let u = s.displacement_spectrum(&model);
        let exact = model.halfspace.mode_energies(&model.grid, &u);
        let predicted = model.halfspace.mode_energies(&model.grid, surface.modes());
        for (q, (e, p)) in exact.iter().zip(&predicted).enumerate().skip(1) {
            assert!(
                (e - p).abs() <= 1e-9 * p.max(1e-6 * 1e-6),
                "{}: mode {q}: E_exa {e} vs (E*/4) q |h~|^2 = {p}",
                kind.name()
            );
        }
    }
}

#[test]
fn flat_surface_carries_the_load_uniformly() {
    let model = Model::new(Grid::new(32, 1.0).unwrap(), 1.0).unwrap();
    let h = vec![0.25; 32 * 32];
    for kind in SolverKind::ALL {
        let s = solve(kind, &model, &h, 0.37, 1e-10);
        assert!(
            (field::mean(&s.pressure) - 0.37).abs() <= 1e-12 * 0.37,
            "{}",
            kind.name()
        );
        assert!(s.pressure.iter().all(|&p| (p - 0.37).abs() <= 1e-12));
        assert_eq!(s.contact_area(), 1.0);
    }
}

#[test]
fn load_balance_and_energy_identity_hold_on_random_contact() {
    let surface = Surface::generate(&SurfaceModel::new(128, 0.8, 64.0, 4.0, 8)).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    for kind in SolverKind::ALL {
        let s = solve(kind, &model, &h, 0.05, 1e-10);
        let load = (field::mean(&s.pressure) - 0.05).abs() / 0.05;
        let bound = if kind == SolverKind::Cg { 1e-12 } else { 1e-10 };
        assert!(load <= bound, "{}: load error {load}", kind.name());
        // Energy from real space equals energy from Fourier space.
        let u = s.displacement_spectrum(&model);
        let ef = model.halfspace.energy_fourier(&model.grid, &u);
        let er = s.elastic_energy();
        assert!(
            (ef - er).abs() <= 1e-8 * ef,
            "{}: energy {ef} (Fourier) vs {er} (real)",
            kind.name()
        );
    }
}

/// Every solver agrees with CG to what their tolerance implies: at residual `tol` the energies agree
/// to a few `tol` and the pressure fields (relative L2) to within two orders of `tol`, the
/// contact edge being where the fields are least determined.
#[test]
fn solvers_agree_on_a_random_surface() {
    const TOL: f64 = 1e-10;
    let surface = Surface::generate(&SurfaceModel::new(256, 0.8, 128.0, 4.0, 1)).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    for target in [0.1, 0.01] {
        let p0 = persson_load_guess(target, 1.0, 1.0) * 0.8;
        let a = solve(SolverKind::Cg, &model, &h, p0, TOL);
        let ar_a = a.contact_area();
        assert!(
            (ar_a / target - 1.0).abs() < 0.5,
            "load guess off: a_r = {ar_a} for target {target}"
        );
        for kind in SolverKind::ALL {
            if kind == SolverKind::Cg {
                continue;
            }
            let b = solve(kind, &model, &h, p0, TOL);
            let ar_b = b.contact_area();
            let points = (ar_a - ar_b).abs() * (256.0 * 256.0);
            let diff = field::sum_zip(&a.pressure, &b.pressure, |x, y| (x - y) * (x - y)).sqrt();
            let norm = field::sum_map(&a.pressure, |_, x| x * x).sqrt();
            let name = kind.name();
            eprintln!(
                "target {target}: a_r {ar_a} vs {ar_b} ({name}), energy rel diff {:.2e}, pressure L2 {:.2e}, iterations cg {} {name} {}",
                (a.elastic_energy() - b.elastic_energy()).abs() / a.elastic_energy(),
                diff / norm,
                a.stats.iterations,
                b.stats.iterations
            );
            assert!(
                points <= 2.0,
                "{name}: a_r {ar_a} vs {ar_b}: {points} points differ"
            );
            let (ea, eb) = (a.elastic_energy(), b.elastic_energy());
            assert!(
                (ea - eb).abs() <= 10.0 * TOL * ea,
                "{name}: energy {ea} vs {eb}"
            );
            assert!(
                diff / norm <= 100.0 * TOL,
                "{name}: pressure fields differ by {:e} (relative L2)",
                diff / norm
            );
        }
    }
}

#[test]
fn very_low_and_near_full_contact_converge() {
    let surface = Surface::generate(&SurfaceModel::new(128, 0.8, 64.0, 4.0, 5)).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    for kind in SolverKind::ALL {
        let low = solve(kind, &model, &h, 2e-4, 1e-9);
        let a = low.contact_area();
        assert!(a > 0.0 && a < 1e-3, "{}: a_r = {a}", kind.name());
        let mut solver = kind.build();
        let target = AreaTarget {
            contact_area: 0.995,
            p0_guess: persson_load_guess(0.995, 1.0, 1.0),
        };
        let high = solve_for_area(
            solver.as_mut(),
            &model,
            &h,
            target,
            Start::Cold,
            &SolveOptions::with_tol(1e-9),
            &AreaSearch::default(),
        )
        .unwrap();
        let a = high.solution.contact_area();
        assert!(a > 0.99 && a < 1.0, "{}: a_r = {a}", kind.name());
    }
}

#[test]
fn warm_start_reaches_the_cold_solution() {
    let surface = Surface::generate(&SurfaceModel::new(128, 0.8, 64.0, 4.0, 2)).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h_lo = surface.heights_at(8.0, &model.fft);
    let h_hi = surface.heights_at(9.0, &model.fft);
    for kind in SolverKind::ALL {
        let mut solver = kind.build();
        let opts = SolveOptions::with_tol(1e-10);
        let lo = solver
            .solve(
                &ContactProblem::new(&model, &h_lo, 0.1).unwrap(),
                Start::Cold,
                &opts,
            )
            .unwrap();
        let problem = ContactProblem::new(&model, &h_hi, 0.1).unwrap();
        let warm = solver.solve(&problem, Start::Warm(&lo), &opts).unwrap();
        let cold = solver.solve(&problem, Start::Cold, &opts).unwrap();
        assert!(warm.stats.warm && !cold.stats.warm);
        let (ew, ec) = (warm.elastic_energy(), cold.elastic_energy());
        assert!(
            (ew - ec).abs() <= 1e-8 * ec,
            "{}: {ew} vs {ec}",
            kind.name()
        );
        assert!(
            (warm.contact_area() - cold.contact_area()).abs() <= 2.0 / (128.0 * 128.0),
            "{}",
            kind.name()
        );
    }
}

/// A load doubled on a warm start puts thousands of points into contact at once; the
/// preconditioned iteration must give them pressures in its own units (this case once
/// oscillated without converging).
#[test]
fn warm_start_across_a_doubled_load_converges() {
    let surface = Surface::generate(&SurfaceModel::new(256, 0.3, 128.0, 8.0, 1)).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    for kind in SolverKind::ALL {
        let mut solver = kind.build();
        let opts = SolveOptions {
            tol: 1e-8,
            max_iter: 1000,
        };
        let lo = solver
            .solve(
                &ContactProblem::new(&model, &h, 0.12).unwrap(),
                Start::Cold,
                &opts,
            )
            .unwrap();
        let hi = solver
            .solve(
                &ContactProblem::new(&model, &h, 0.25).unwrap(),
                Start::Warm(&lo),
                &opts,
            )
            .unwrap_or_else(|e| panic!("{}: {e}", kind.name()));
        assert!(
            hi.stats.iterations < 300,
            "{}: {}",
            kind.name(),
            hi.stats.iterations
        );
        assert!(hi.contact_area() > lo.contact_area());
    }
}

#[test]
fn budget_exhaustion_is_an_error_with_the_residual() {
    let (model, h) = full_resolution(SurfaceModel::new(64, 0.8, 32.0, 4.0, 2));
    let problem = ContactProblem::new(&model, &h, 0.1).unwrap();
    for kind in SolverKind::ALL {
        let opts = SolveOptions {
            tol: 1e-12,
            max_iter: 3,
        };
        let (reason, iterations, residual) = not_converged(kind, &problem, &opts);
        assert_eq!(reason, Termination::BudgetExhausted, "{}", kind.name());
        assert_eq!(iterations, 3);
        assert!(residual > 1e-12 && residual.is_finite());
    }
}

/// The model and the full-resolution heights of the surface of `params`.
fn full_resolution(params: SurfaceModel) -> (Model, Vec<f64>) {
    let surface = Surface::generate(&params).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    (model, h)
}

/// The reason, iterations and residual of a solve by `kind` that must fail as not
/// converged.
fn not_converged(
    kind: SolverKind,
    problem: &ContactProblem,
    opts: &SolveOptions,
) -> (Termination, usize, f64) {
    match kind.build().solve(problem, Start::Cold, opts) {
        Err(Error::NotConverged {
            reason,
            iterations,
            residual,
            ..
        }) => (reason, iterations, residual),
        other => panic!(
            "{}: expected a solve that does not converge, got {:?}",
            kind.name(),
            other.map(|s| s.stats)
        ),
    }
}

/// A tolerance below the residual's rounding floor (the probes' scene at `p0 = 0.01`,
/// tol 1e-14) ends as a stalled solve with the residual reached, not at the end of the
/// budget.
#[test]
fn a_tolerance_below_the_rounding_floor_stalls_with_the_residual_reached() {
    let (model, h) = full_resolution(SurfaceModel::new(128, 0.8, 64.0, 4.0, 11));
    let problem = ContactProblem::new(&model, &h, 0.01).unwrap();
    let opts = SolveOptions {
        tol: 1e-14,
        max_iter: 3000,
    };
    for kind in SolverKind::ALL {
        let (reason, iterations, residual) = not_converged(kind, &problem, &opts);
        assert_eq!(reason, Termination::Stalled, "{}", kind.name());
        assert!(iterations < 3000, "{}: {iterations}", kind.name());
        assert!(
            residual > 1e-14 && residual < 1e-12,
            "{}: {residual:e}",
            kind.name()
        );
    }
}

#[test]
fn non_finite_heights_are_rejected_before_solving() {
    let model = Model::new(Grid::new(16, 1.0).unwrap(), 1.0).unwrap();
    let mut h = vec![0.0; 256];
    h[17] = f64::NAN;
    let e = ContactProblem::new(&model, &h, 0.1)
        .unwrap_err()
        .to_string();
    assert!(e.contains("heights"), "{e}");
    let e = ContactProblem::new(&model, &vec![0.0; 256], -1.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("p0"), "{e}");
}

#[test]
fn heights_whose_spread_overflows_are_rejected() {
    let model = Model::new(Grid::new(16, 1.0).unwrap(), 1.0).unwrap();
    // Every value is finite, but their squares are not (the mean is 0).
    let h: Vec<f64> = (0..256)
        .map(|i| if i % 2 == 0 { 1e200 } else { -1e200 })
        .collect();
    let e = ContactProblem::new(&model, &h, 0.1)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("heights") && e.contains("overflows") && e.contains("squares are finite"),
        "{e}"
    );
    // The sum overflows too: the mean is infinite although every value is finite.
    let e = ContactProblem::new(&model, &vec![f64::MAX; 256], 0.1)
        .unwrap_err()
        .to_string();
    assert!(e.contains("heights") && e.contains("overflows"), "{e}");
    // Large but harmless heights are accepted.
    let h: Vec<f64> = h.iter().map(|v| v * 1e-50).collect();
    assert!(ContactProblem::new(&model, &h, 0.1).is_ok());
}

/// A rectangular window, the sphere off its centre along the long side: the padded grid
/// is the rectangle of twice each side and the contact (radius 40) far from the edges.
/// Every solver, with the tolerances of the square window's (`conformance`): force, area
/// and peak pressure ([`assert_hertz`]).
#[test]
fn a_sphere_on_a_rectangular_free_boundary_gives_hertz_contact_area() {
    let radius = 1000.0;
    let hertz = Hertz {
        radius,
        e_star: 1.0,
    };
    let a = 40.0;
    let force = hertz.force_for_radius(a);
    let (model, h, p0) = sphere_on_free_window((120, 200), (60.0, 90.0), radius, force);
    assert_eq!((model.grid.rows(), model.grid.cols()), (240, 400));
    for kind in SolverKind::ALL {
        let s = solve(kind, &model, &h, p0, 1e-8);
        assert_hertz(kind, &model, &s, &hertz, (a, force));
    }
}

/// The same sphere on the window turned a quarter turn (200 x 120, centre transposed):
/// the pressure is the transpose of the first one, point for point, with CG (to rounding:
/// the transforms run along the other axes).
#[test]
fn a_rectangular_free_boundary_turned_a_quarter_turn_gives_the_transposed_contact() {
    let (radius, force) = (1000.0, 2000.0);
    let (wide, hw, pw) = sphere_on_free_window((120, 200), (60.0, 90.0), radius, force);
    let (tall, ht, pt) = sphere_on_free_window((200, 120), (90.0, 60.0), radius, force);
    let sw = solve(SolverKind::Cg, &wide, &hw, pw, 1e-10);
    let st = solve(SolverKind::Cg, &tall, &ht, pt, 1e-10);
    let (rows, cols) = (wide.grid.rows(), wide.grid.cols());
    let mut worst: f64 = 0.0;
    for i in 0..rows {
        for j in 0..cols {
            let (a, b) = (sw.pressure[i * cols + j], st.pressure[j * rows + i]);
            worst = worst.max((a - b).abs());
        }
    }
    let peak = sw.pressure.iter().copied().fold(0.0, f64::max);
    assert!(
        worst < 1e-6 * peak,
        "pressures differ by {worst:e} (peak {peak:e})"
    );
}

/// The conventions and the command line's synopsis list every solver where they list the
/// solvers' names (`--solver a|b|...`), in the order of [`SolverKind::ALL`].
#[test]
fn the_documents_name_every_solver() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let all = SolverKind::NAMES.join("|");
    let mut lists = 0;
    for file in ["docs/conventions.md", "src/main.rs"] {
        let text = std::fs::read_to_string(root.join(file)).unwrap();
        for (at, _) in text.match_indices("--solver ") {
            let names: String = text[at + "--solver ".len()..]
                .chars()
                .take_while(|c| c.is_ascii_lowercase() || *c == '|')
                .collect();
            if names.contains('|') {
                assert_eq!(names, all, "{file}: --solver {names}");
                lists += 1;
            }
        }
    }
    assert!(lists >= 4, "{lists} lists of solvers found");
}
