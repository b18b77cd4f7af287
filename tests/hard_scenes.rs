//! Numerically hard scenes: the hard cases every solver of the list must survive.
//!
//! Every solve here must either converge, with fields that satisfy the hard-wall
//! conditions to the requested tolerance ([`check_solution`]), or fail with
//! [`Error::NotConverged`] carrying a finite residual ([`run`]): never a NaN, never a
//! silently wrong answer. Where several solvers converge they must agree to what the
//! tolerance implies ([`assert_agree`]), and warm starts across loads and magnifications
//! must reach the cold solution ([`assert_warm_reaches_cold`]).
//!
//! Grids are as small as each scene's physics allows (each test says why), so that the
//! file runs in well under a minute in the dev profile. Run with `--nocapture` to see one
//! line per scene and solver: residual, iterations, contact area.

use persson_check::engine::contact::{ContactProblem, ContactSolution, Model};
use persson_check::engine::field;
use persson_check::engine::grid::Grid;
use persson_check::engine::load::{persson_load_guess, solve_for_area, AreaSearch, AreaTarget};
use persson_check::engine::reference::Westergaard;
use persson_check::engine::solver::SolverKind;
use persson_check::engine::solver::{SolveOptions, Solver, Start};
use persson_check::engine::surface::{Surface, SurfaceModel};
use persson_check::error::Termination;
use persson_check::Error;

use crate::common::contact::{assert_agree, check_solution, contact_differences, sinusoid};

/// Every solver, in the order of the list.
const ALL: [SolverKind; SolverKind::ALL.len()] = SolverKind::ALL;

/// The tolerance of the scenes: two orders tighter than the default, so that agreement
/// between the solvers is tested well below the size of any physical effect.
const TOL: f64 = 1e-10;

/// A self-affine surface at full resolution, with its model (`E* = 1`).
fn self_affine(params: &SurfaceModel) -> (Surface, Model, Vec<f64>) {
    let surface = Surface::generate(params).unwrap();
    let model = Model::new(surface.grid().clone(), 1.0).unwrap();
    let h = surface.heights_at(f64::INFINITY, &model.fft);
    (surface, model, h)
}

/// The options of the scenes: tolerance `tol` and the default budget.
fn opts(tol: f64) -> SolveOptions {
    SolveOptions::with_tol(tol)
}

/// One solve, checked: `Ok` is a converged solution that passed [`check_solution`], `Err`
/// the residual of a [`Error::NotConverged`], which must be finite and above the
/// tolerance. Any other outcome (a non-finite state, a vague error) fails the test.
fn run(
    scene: &str,
    kind: SolverKind,
    solver: &mut dyn Solver,
    problem: &ContactProblem,
    start: Start,
    opts: &SolveOptions,
) -> Result<ContactSolution, f64> {
    match solver.solve(problem, start, opts) {
        Ok(s) => {
            check_solution(scene, kind, problem, &s, opts.tol);
            Ok(s)
        }
        Err(e @ Error::NotConverged { residual, tol, .. }) => {
            assert!(
                residual.is_finite() && residual > tol,
                "{scene}, {}: {e}",
                kind.name()
            );
            let text = e.to_string();
            assert!(
                text.contains("did not converge") && text.contains("residual"),
                "{text}"
            );
            eprintln!("{scene:<34} {:<4} not converged: {text}", kind.name());
            Err(residual)
        }
        Err(e) => panic!("{scene}, {}: {e}", kind.name()),
    }
}

/// A solve to [`TOL`] that must converge (every scene here does, for every solver).
fn converge(
    scene: &str,
    kind: SolverKind,
    solver: &mut dyn Solver,
    problem: &ContactProblem,
    start: Start,
) -> ContactSolution {
    let s = run(scene, kind, solver, problem, start, &opts(TOL))
        .unwrap_or_else(|r| panic!("{scene}, {}: not converged, residual {r:e}", kind.name()));
    eprintln!(
        "{scene:<34} {:<4} residual {:.2e}  iterations {:>5}{}  a_r {:.6}",
        kind.name(),
        s.stats.residual.value(),
        s.stats.iterations,
        if s.stats.warm { " (warm)" } else { "" },
        s.contact_area()
    );
    s
}

/// A cold solve of `h` at `p0` with a fresh solver of `kind`.
fn cold(scene: &str, kind: SolverKind, model: &Model, h: &[f64], p0: f64) -> ContactSolution {
    let problem = ContactProblem::new(model, h, p0).unwrap();
    converge(scene, kind, kind.build().as_mut(), &problem, Start::Cold)
}

/// The load CG's search ended at (`found`: each solver's search, in the order of
/// [`SolverKind::ALL`]), where every other solver's solution agrees with CG's: its own if
/// its search ended there too (the searches see the same areas at the same loads), or a
/// cold solve at that load.
fn agree_with_cg(scene: &str, found: &[ContactSolution], model: &Model, h: &[f64]) -> f64 {
    let cg = &found[SolverKind::Cg.index()];
    for (&kind, s) in ALL.iter().zip(found) {
        if kind == SolverKind::Cg {
            continue;
        }
        let same = if s.p0 == cg.p0 {
            s.clone()
        } else {
            let label = format!("{scene}, {} at cg's load", kind.name());
            cold(&label, kind, model, h, cg.p0)
        };
        assert_agree(scene, cg, &same, TOL);
    }
    cg.p0
}

/// Solves `h` at `p0` warm from `from` and cold with one solver of `kind`; both must
/// converge to the same solution. Returns the warm and cold iteration counts.
fn assert_warm_reaches_cold(
    scene: &str,
    kind: SolverKind,
    model: &Model,
    h: &[f64],
    p0: f64,
    from: &ContactSolution,
) -> (usize, usize) {
    let problem = ContactProblem::new(model, h, p0).unwrap();
    let mut solver = kind.build();
    let warm = converge(scene, kind, solver.as_mut(), &problem, Start::Warm(from));
    let cold = converge(scene, kind, solver.as_mut(), &problem, Start::Cold);
    assert!(warm.stats.warm && !cold.stats.warm);
    assert_agree(scene, &cold, &warm, TOL);
    (warm.stats.iterations, cold.stats.iterations)
}

/// Indices of the points in contact.
fn contact_points(s: &ContactSolution) -> Vec<usize> {
    (0..s.pressure.len())
        .filter(|&i| s.pressure[i] > 0.0)
        .collect()
}

/// Largest periodic Chebyshev distance between two of `points` on an `n x n` grid.
fn spread(points: &[usize], n: usize) -> usize {
    let d = |a: usize, b: usize| {
        let x = a.abs_diff(b);
        x.min(n - x)
    };
    let mut far = 0;
    for &a in points {
        for &b in points {
            far = far.max(d(a / n, b / n).max(d(a % n, b % n)));
        }
    }
    far
}

/// The random surface of the low- and high-load scenes: 128^2, H = 0.8, lambda_l = 64,
/// lambda_s = 4 (4 points per shortest wavelength, zeta_max = 16). 128^2 holds 16 384
/// points, so a_r = 1e-4 is one to three points (one asperity tip) and a_r > 0.999 leaves
/// at most 16 points out of contact: both extremes are reached at the grid's resolution,
/// and a finer grid would only make them cost more.
fn extreme_load_surface() -> (Surface, Model, Vec<f64>) {
    self_affine(&SurfaceModel::new(128, 0.8, 64.0, 4.0, 5))
}

#[test]
fn very_low_load_single_asperity() {
    let (surface, model, h) = extreme_load_surface();
    let n = model.grid.n();
    let target = AreaTarget {
        contact_area: 1e-4,
        p0_guess: persson_load_guess(1e-4, 1.0, 1.0),
    };
    let mut found = Vec::new();
    for kind in ALL {
        let mut solver = kind.build();
        let s = solve_for_area(
            solver.as_mut(),
            &model,
            &h,
            target,
            Start::Cold,
            &opts(TOL),
            &AreaSearch::default(),
        )
        .unwrap_or_else(|e| panic!("{}: {e}", kind.name()))
        .solution;
        let problem = ContactProblem::new(&model, &h, s.p0).unwrap();
        check_solution("a_r = 1e-4 (load search)", kind, &problem, &s, TOL);
        let points = contact_points(&s);
        eprintln!(
            "a_r = 1e-4 (load search)           {:<4} p0 {:.4e}  residual {:.2e}  iterations {}  a_r {:.3e} ({} points)",
            kind.name(),
            s.p0,
            s.stats.residual.value(),
            s.stats.iterations,
            s.contact_area(),
            points.len()
        );
        // The search accepts |a_r - 1e-4| <= 1.5 / N^2: one to three points, and they are
        // one asperity (neighbours).
        assert!((1..=3).contains(&points.len()), "{points:?}");
        assert!(spread(&points, n) <= 2, "contact points {points:?}");
        found.push(s);
    }
    // The searches see the same areas at the same loads, so they end at the same load.
    let p0 = agree_with_cg("a_r = 1e-4", &found, &model, &h);

    // Warm starts across loads, by a decade up and down. At p0 / 10 only the highest point
    // touches; from there the contact set must grow, and a lone contact point's gap is zero
    // by construction, so the conjugate-gradient step is 0/0 (this start once failed with
    // a non-finite step length).
    for (kind, s) in ALL.iter().zip(&found) {
        let mut steps = Vec::new();
        let lone = cold("a_r = 1e-4: p0 / 10", *kind, &model, &h, 0.1 * p0);
        assert_eq!(contact_points(&lone).len(), 1, "{}", kind.name());
        steps.push(assert_warm_reaches_cold(
            "a_r = 1e-4: lone point -> p0",
            *kind,
            &model,
            &h,
            p0,
            &lone,
        ));
        for factor in [10.0, 0.1] {
            steps.push(assert_warm_reaches_cold(
                &format!("a_r = 1e-4: p0 -> {factor} p0"),
                *kind,
                &model,
                &h,
                factor * p0,
                s,
            ));
        }
        // Across magnifications: zeta = 8 -> 16 (full) at the same load.
        let h8 = surface.heights_at(8.0, &model.fft);
        let at8 = cold("a_r = 1e-4: zeta = 8", *kind, &model, &h8, p0);
        steps.push(assert_warm_reaches_cold(
            "a_r = 1e-4: zeta 8 -> 16",
            *kind,
            &model,
            &h,
            p0,
            &at8,
        ));
        check_warm_iterations(*kind, &steps);
    }
}

/// Warm starts from a nearby load or magnification pay for CG (a few iterations instead of
/// tens). GFMD's count is set by its slowest relaxation, which a nearby start hardly
/// shortens: only reported.
fn check_warm_iterations(kind: SolverKind, steps: &[(usize, usize)]) {
    eprintln!("  {} warm vs cold iterations: {steps:?}", kind.name());
    if kind == SolverKind::Cg {
        for &(warm, cold) in steps {
            assert!(
                warm <= cold,
                "cg: warm start took {warm} > {cold} iterations"
            );
        }
    }
}

#[test]
fn near_full_contact() {
    let (surface, model, h) = extreme_load_surface();
    let n2 = model.grid.points() as f64;
    let target = AreaTarget {
        contact_area: 0.9995,
        p0_guess: persson_load_guess(0.9995, 1.0, 1.0),
    };
    let mut found = Vec::new();
    for kind in ALL {
        let mut solver = kind.build();
        let s = solve_for_area(
            solver.as_mut(),
            &model,
            &h,
            target,
            Start::Cold,
            &opts(TOL),
            &AreaSearch::default(),
        )
        .unwrap_or_else(|e| panic!("{}: {e}", kind.name()))
        .solution;
        let problem = ContactProblem::new(&model, &h, s.p0).unwrap();
        check_solution("a_r = 0.9995 (load search)", kind, &problem, &s, TOL);
        let a = s.contact_area();
        eprintln!(
            "a_r = 0.9995 (load search)         {:<4} p0 {:.4e}  residual {:.2e}  iterations {}  a_r {a:.6} ({} points out)",
            kind.name(),
            s.p0,
            s.stats.residual.value(),
            s.stats.iterations,
            ((1.0 - a) * n2).round()
        );
        assert!(a > 0.999 && a < 1.0, "{}: a_r = {a}", kind.name());
        found.push(s);
    }
    let p0 = agree_with_cg("a_r = 0.9995", &found, &model, &h);

    // Warm starts: a little less load (a_r stays > 0.99), from almost no contact (p0 / 1e5,
    // a few points) to almost full contact in one step and back, and zeta 8 -> 16.
    for (kind, s) in ALL.iter().zip(&found) {
        let mut steps = Vec::new();
        steps.push(assert_warm_reaches_cold(
            "a_r = 0.9995: p0 -> 0.8 p0",
            *kind,
            &model,
            &h,
            0.8 * p0,
            s,
        ));
        // A start this far off need not save iterations: only convergence is asked.
        let sparse = cold("a_r = 0.9995: p0 / 1e5", *kind, &model, &h, 1e-5 * p0);
        assert_warm_reaches_cold(
            "a_r = 0.9995: p0 / 1e5 -> p0",
            *kind,
            &model,
            &h,
            p0,
            &sparse,
        );
        assert_warm_reaches_cold(
            "a_r = 0.9995: p0 -> p0 / 1e5",
            *kind,
            &model,
            &h,
            1e-5 * p0,
            s,
        );
        let h8 = surface.heights_at(8.0, &model.fft);
        let at8 = cold("a_r = 0.9995: zeta = 8", *kind, &model, &h8, p0);
        steps.push(assert_warm_reaches_cold(
            "a_r = 0.9995: zeta 8 -> 16",
            *kind,
            &model,
            &h,
            p0,
            &at8,
        ));
        check_warm_iterations(*kind, &steps);
    }
}

/// H = 0.3 up to zeta_max = lambda_l / lambda_s = 128. lambda_s = 2 is the shortest
/// wavelength a grid holds and lambda_l cannot exceed L, so 256^2 is the smallest grid
/// that allows it. A low H puts the gradient, and with it the pressure, at the shortest
/// scales: many small patches on a field that changes from point to point.
#[test]
fn hurst_03_at_zeta_128() {
    let params = SurfaceModel::new(256, 0.3, 256.0, 2.0, 7);
    let (surface, model, h) = self_affine(&params);
    assert_eq!(params.zeta_max(), 128.0);
    assert!(surface.zeta_max() > 127.0, "{}", surface.zeta_max());
    for p0 in [0.01, 0.1] {
        let scene = format!("H = 0.3, zeta 128, p0 = {p0}");
        let cg = cold(&scene, SolverKind::Cg, &model, &h, p0);
        let gfmd = cold(&scene, SolverKind::Gfmd, &model, &h, p0);
        assert_agree(&scene, &cg, &gfmd, TOL);
    }
    // The last magnification step of a sweep, warm: zeta 64 -> 128.
    let h64 = surface.heights_at(64.0, &model.fft);
    for kind in ALL {
        let at64 = cold("H = 0.3, zeta 64, p0 = 0.1", kind, &model, &h64, 0.1);
        let step =
            assert_warm_reaches_cold("H = 0.3: zeta 64 -> 128", kind, &model, &h, 0.1, &at64);
        check_warm_iterations(kind, &[step]);
    }
}

/// One grid point 100 rms heights above a gently rough surface (g_bar = 0.01). At low
/// load it is a point load, with a known answer; at higher load a pressure peak hundreds
/// of times p0 sits in a ring out of contact inside a half-contact. 64^2 suffices: the
/// spike is one point on any grid, and the rough part needs only a few wavelengths.
#[test]
fn single_tall_spike() {
    let n = 64;
    let mut params = SurfaceModel::new(n, 0.8, 32.0, 4.0, 11);
    params.rms_gradient = 0.01;
    let (_, model, mut h) = self_affine(&params);
    let spike = n * n / 2 + n / 2;
    h[spike] = field::max(&h) + 100.0 * field::std_dev(&h);
    let n2 = (n * n) as f64;

    // The spike alone carries the load: p = p0 N^2 on it, 0 elsewhere.
    let p0 = 1e-4;
    let mut alone = Vec::new();
    for kind in ALL {
        let s = cold("spike alone, p0 = 1e-4", kind, &model, &h, p0);
        assert_eq!(contact_points(&s), vec![spike], "{}", kind.name());
        let exact = p0 * n2;
        let err = (s.pressure[spike] - exact).abs() / exact;
        // The same bound as the load (see check_solution): all of it is on this point.
        let bound = if kind == SolverKind::Cg { 1e-12 } else { TOL };
        assert!(
            err <= bound,
            "{}: spike pressure off by {err:e}",
            kind.name()
        );
        alone.push(s);
    }
    assert_agree("spike alone, p0 = 1e-4", &alone[0], &alone[1], TOL);

    // Pressed into the rough surface.
    let p0 = 3e-3;
    let mut pressed = Vec::new();
    for kind in ALL {
        let s = cold("spike in rough contact, p0 = 3e-3", kind, &model, &h, p0);
        let a = s.contact_area();
        assert!(a > 0.3 && a < 0.6, "{}: a_r = {a}", kind.name());
        assert!(s.pressure[spike] > 100.0 * p0, "{}", kind.name());
        for (di, dj) in [(0, 1), (1, 0), (1, 1), (1, n - 1)] {
            for k in [spike + di * n + dj, spike + (n - di) * n + (n - dj) % n] {
                let k = k % (n * n);
                assert_eq!(
                    s.pressure[k],
                    0.0,
                    "{}: neighbour {k} of the spike",
                    kind.name()
                );
            }
        }
        pressed.push(s);
    }
    assert_agree(
        "spike in rough contact, p0 = 3e-3",
        &pressed[0],
        &pressed[1],
        TOL,
    );
}

/// Half the domain raised by 1: on the periodic grid, two straight steps, with a pressure
/// singularity at each contact edge and height content up to the Nyquist wavenumber. The
/// problem is one-dimensional, so the pressure must not vary along y. At p0 = 0.01 only
/// the plateau touches: a periodic row of flat punches of half-width c = L/4, whose
/// pressure (mean p0, integrable edge singularities) is
/// `p(x) = p0 cos(pi x / L) / sqrt(sin^2(pi c / L) - sin^2(pi x / L))`, x from the
/// plateau's centre, `sqrt(2) p0` there. The grid places each edge to within half a
/// spacing, so the centre pressure is off by O(1/N): 64^2 resolves it to 1%, enough to
/// tell a right answer from a wrong one. At p0 = 0.1 the lower level touches too.
#[test]
fn step() {
    let n = 64;
    let model = Model::new(Grid::new(n, 1.0).unwrap(), 1.0).unwrap();
    let h: Vec<f64> = (0..n * n)
        .map(|k| if k % n < n / 2 { 1.0 } else { 0.0 })
        .collect();
    for p0 in [0.01, 0.1] {
        let scene = format!("step, p0 = {p0}");
        let mut both = Vec::new();
        for kind in ALL {
            let s = cold(&scene, kind, &model, &h, p0);
            let p = &s.pressure;
            let largest = field::max(p);
            let along_y = (0..n * n)
                .map(|k| (p[k] - p[k % n]).abs())
                .fold(0.0, f64::max);
            assert!(
                along_y <= 1e-12 * largest,
                "{}: pressure varies along y by {along_y:e}",
                kind.name()
            );
            if p0 == 0.01 {
                // Contact is exactly the plateau.
                for (k, &pk) in p.iter().enumerate() {
                    assert_eq!(pk > 0.0, k % n < n / 2, "{}: point {k}", kind.name());
                }
                // The plateau's centre lies between columns n/4 - 1 and n/4.
                let centre = 0.5 * (p[n / 4 - 1] + p[n / 4]);
                let exact = std::f64::consts::SQRT_2 * p0;
                let err = (centre - exact).abs() / exact;
                eprintln!(
                    "  {}: centre pressure {centre:.5e}, flat punch {exact:.5e}",
                    kind.name()
                );
                assert!(
                    err <= 1.0 / n as f64,
                    "{}: centre pressure off by {err:e}",
                    kind.name()
                );
            }
            both.push(s);
        }
        assert_agree(&scene, &both[0], &both[1], TOL);
    }
}

/// Heights and load scaled together, `h -> s h`, `p0 -> s p0` at fixed E*: the exact
/// solution scales, `p -> s p`, `u -> s u`, with the same contact set.
///
/// * `s = 2^20, 2^-20`: every operation of both solvers is homogeneous of degree one in
///   `(h, p, u)` or compares dimensionless ratios, and multiplying by a power of two is
///   exact in binary floating point (far from overflow and underflow), so the scaled solve
///   does the same operations on exactly scaled numbers: bit for bit `s` times the
///   unscaled fields, in the same number of iterations.
/// * `s = 1e6, 1e-6`: every product rounds differently (half an ulp, 1e-16), but the
///   solvers take the same decisions (contact sets, step control), so the fields differ
///   by rounding accumulated over the iterations; 1e-11 of the field's largest value is
///   100 times what is observed and 10 times below the tolerance. Iteration counts may
///   differ by one where a stopping test sits on the tolerance.
///
/// The surface and loads are the extreme ones of the tests above (3 points in contact,
/// a_r = 0.05 and a_r > 0.999).
#[test]
fn scaled_heights_and_load() {
    let (_, model, h) = extreme_load_surface();
    let max_rel = |a: &[f64], b: &[f64], s: f64| {
        let largest = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - s * y).abs())
            .fold(0.0, f64::max)
            / (s * largest)
    };
    for p0 in [1.4e-5, 0.05, 1.6] {
        for kind in ALL {
            let base = cold(&format!("scale 1, p0 = {p0}"), kind, &model, &h, p0);
            for s in [1e6, 1e-6, 1048576.0, 1.0 / 1048576.0] {
                let hs: Vec<f64> = h.iter().map(|x| s * x).collect();
                let scene = format!("scale {s:e}, p0 = {p0}");
                let x = cold(&scene, kind, &model, &hs, s * p0);
                assert_eq!(
                    contact_differences(&x, &base),
                    0,
                    "{scene}, {}",
                    kind.name()
                );
                let dp = max_rel(&x.pressure, &base.pressure, s);
                let du = max_rel(&x.displacement, &base.displacement, s);
                let (ix, ib) = (x.stats.iterations, base.stats.iterations);
                eprintln!(
                    "  {}: pressure {dp:.1e}, displacement {du:.1e}, iterations {ix} vs {ib}",
                    kind.name()
                );
                if s.log2().fract() == 0.0 {
                    assert_eq!(ix, ib, "{scene}, {}", kind.name());
                    for (a, b) in x.pressure.iter().zip(&base.pressure) {
                        assert_eq!(a.to_bits(), (s * b).to_bits(), "{scene}, {}", kind.name());
                    }
                    for (a, b) in x.displacement.iter().zip(&base.displacement) {
                        assert_eq!(a.to_bits(), (s * b).to_bits(), "{scene}, {}", kind.name());
                    }
                } else {
                    assert!(
                        ix.abs_diff(ib) <= 1,
                        "{scene}, {}: {ix} vs {ib}",
                        kind.name()
                    );
                    assert!(
                        dp <= 1e-11 && du <= 1e-11,
                        "{scene}, {}: pressure {dp:e}, displacement {du:e}",
                        kind.name()
                    );
                }
            }
        }
    }
}

/// Grids that are not powers of two: 96 = 2^5 3 and 100 = 2^2 5^2 (mixed radix), 127
/// (prime) and 135 = 3^3 5 (odd: no Nyquist row or column). A random surface on each must
/// converge with both solvers, which must agree; Westergaard's sinusoid on 100^2 and
/// 127^2 must match the exact solution as well as power-of-two grids of similar size do.
#[test]
fn non_power_of_two_grids() {
    for n in [96usize, 100, 127, 135] {
        let (_, model, h) = self_affine(&SurfaceModel::new(n, 0.8, n as f64 / 2.0, 4.0, 3));
        let scene = format!("N = {n}, p0 = 0.05");
        let cg = cold(&scene, SolverKind::Cg, &model, &h, 0.05);
        let gfmd = cold(&scene, SolverKind::Gfmd, &model, &h, 0.05);
        assert_agree(&scene, &cg, &gfmd, TOL);
    }
}

/// Westergaard on grids that are not powers of two, side by side with power-of-two grids
/// of similar size under the same bounds: the contact area within two grid spacings of
/// the exact one and the peak pressure within 1e-3 (both as in `tests/solvers.rs`; the
/// errors observed are below 1.5 spacings and 3e-4 on every grid, and do not depend on
/// how N factors), and full contact exact.
#[test]
fn westergaard_on_non_power_of_two_grids() {
    let h0 = 1.0;
    for kind in ALL {
        for ratio in [0.3, 0.8] {
            for n in [64usize, 100, 127, 128] {
                let (model, h) = sinusoid(n, h0);
                let exact = Westergaard {
                    h0,
                    lambda: n as f64,
                    e_star: 1.0,
                };
                let p0 = ratio * exact.full_contact_pressure();
                let scene = format!("Westergaard N = {n}, p0/p* = {ratio}");
                let s = cold(&scene, kind, &model, &h, p0);
                let area = (s.contact_area() - exact.contact_fraction(p0)).abs() * n as f64;
                let peak = (field::max(&s.pressure) - exact.peak_pressure(p0)).abs()
                    / exact.peak_pressure(p0);
                eprintln!(
                    "  {}: area off by {area:.2} spacings, peak by {peak:.1e}",
                    kind.name()
                );
                assert!(
                    area <= 2.0,
                    "{scene}, {}: area off by {area} spacings",
                    kind.name()
                );
                assert!(
                    peak <= 1e-3,
                    "{scene}, {}: peak off by {peak:e}",
                    kind.name()
                );
            }
        }
        for n in [100usize, 127, 135] {
            let (model, h) = sinusoid(n, h0);
            let exact = Westergaard {
                h0,
                lambda: n as f64,
                e_star: 1.0,
            };
            let p0 = 1.5 * exact.full_contact_pressure();
            let s = cold(
                &format!("Westergaard N = {n}, full contact"),
                kind,
                &model,
                &h,
                p0,
            );
            assert_eq!(s.contact_area(), 1.0);
            for (k, &p) in s.pressure.iter().enumerate() {
                let e = exact.pressure(p0, (k % n) as f64);
                assert!(
                    (p - e).abs() <= 1e-9 * p0,
                    "{}: N = {n}, point {k}: {p} vs {e}",
                    kind.name()
                );
            }
        }
    }
}

/// A tolerance below the residual's rounding floor: at a_r ~ 2e-4 the equilibrium part is
/// computed from displacements of the order of the heights against pressures of order
/// 1e-3, and cannot fall much below 1e-12. Both solvers must fail with the residual they
/// reached (GFMD once reported the residual of a stale stress, 1e14; CG drifted off the
/// solution at rounding level and reported 1e-3), and CG, whose estimate has stopped
/// improving, well before its budget.
#[test]
fn unreachable_tolerance_fails_with_the_residual_reached() {
    let (_, model, h) = extreme_load_surface();
    let problem = ContactProblem::new(&model, &h, 3e-5).unwrap();
    for (kind, budget, reached) in [
        (SolverKind::Cg, 20_000, 1e-11),
        (SolverKind::Gfmd, 1500, 1e-10),
    ] {
        let opts = SolveOptions {
            tol: 1e-14,
            max_iter: budget,
        };
        let scene = "a_r = 2e-4, tol = 1e-14";
        let residual = run(
            scene,
            kind,
            kind.build().as_mut(),
            &problem,
            Start::Cold,
            &opts,
        )
        .map(|s| s.stats.residual.value())
        .expect_err("converged below the rounding floor");
        assert!(
            residual <= reached,
            "{}: residual {residual:e}",
            kind.name()
        );
        if kind == SolverKind::Cg {
            match kind.build().solve(&problem, Start::Cold, &opts) {
                Err(e @ Error::NotConverged { iterations, .. }) => {
                    assert!(iterations < 2000, "cg: {iterations} iterations");
                    // CG gives up at its rounding floor, long before its budget.
                    assert_eq!(e.termination(), Some(Termination::Stalled), "{e}");
                    assert!(e.to_string().contains("stalled"), "{e}");
                }
                other => panic!("cg: {:?}", other.err()),
            }
        }
    }
}

/// Small budgets on the hard scenes end either in a converged solution or in
/// [`Error::NotConverged`] with a finite residual above the tolerance, whatever state the
/// solver was in. (CG once reported "did not converge: residual 5.4e-13 > tolerance 1e-10"
/// when its last allowed step had converged.)
#[test]
fn exhausted_budgets_on_hard_scenes_are_clean_errors() {
    let (_, model, h) = extreme_load_surface();
    let n = 64;
    let flat_step = Model::new(Grid::new(n, 1.0).unwrap(), 1.0).unwrap();
    let step: Vec<f64> = (0..n * n)
        .map(|k| if k % n < n / 2 { 1.0 } else { 0.0 })
        .collect();
    let scenes: [(&str, &Model, &[f64], f64); 3] = [
        ("budget: a_r = 2e-4", &model, &h, 3e-5),
        ("budget: a_r = 0.9995", &model, &h, 1.6),
        ("budget: step", &flat_step, &step, 0.01),
    ];
    for (scene, model, h, p0) in scenes {
        let problem = ContactProblem::new(model, h, p0).unwrap();
        for kind in ALL {
            for max_iter in [1, 7, 20] {
                let opts = SolveOptions { tol: TOL, max_iter };
                let out = run(
                    scene,
                    kind,
                    kind.build().as_mut(),
                    &problem,
                    Start::Cold,
                    &opts,
                );
                assert!(max_iter > 1 || out.is_err(), "{scene}, {}", kind.name());
            }
        }
    }
}

/// A levelled AFM scan of a flat sample: a terrace step of 0.1 grid spacings across a
/// surface whose roughness is 0.03 spacings rms, with twelve particles 0.5 to 2.6 spacings
/// tall and one to two wide (pixel-sharp: local slopes beyond 1), on `n x n` points,
/// deterministic. The flat terrace comes into contact in thousands of points at once when
/// the load rises, while the particle tips need pressures hundreds of times `p0`.
fn terrace_with_particles(n: usize) -> Vec<f64> {
    use rand::Rng;
    use rand_chacha::rand_core::SeedableRng;
    let params = SurfaceModel::new(n, 0.8, n as f64 / 4.0, 4.0, 2);
    let (_, _, rough) = self_affine(&params);
    let scale = 0.03 / field::std_dev(&rough);
    let mut h: Vec<f64> = rough.iter().map(|v| v * scale).collect();
    for (k, v) in h.iter_mut().enumerate() {
        let (y, x) = ((k / n) as f64, (k % n) as f64);
        if y > 0.4 * n as f64 + 0.1 * x {
            *v -= 0.1;
        }
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
    let mut uniform =
        |lo: f64, hi: f64| lo + (hi - lo) * (rng.next_u64() >> 11) as f64 / 2f64.powi(53);
    for _ in 0..12 {
        let (cx, cy) = (uniform(0.0, n as f64), uniform(0.0, n as f64));
        let (top, width) = (uniform(0.5, 2.6), uniform(0.7, 2.0));
        for (k, v) in h.iter_mut().enumerate() {
            let (y, x) = ((k / n) as f64, (k % n) as f64);
            let r2 = (x - cx).powi(2) + (y - cy).powi(2);
            *v += top * (-r2 / (2.0 * width * width)).exp();
        }
    }
    h
}

/// The terrace with particles loaded step by step, each load warm-started from the last,
/// on a free boundary (the measured window, as `check-surface` solves it) and periodic.
/// With the full Polonsky-Keer step, CG fell into a cycle here (the contact set
/// alternating between two sets thousands of points apart, the particle tips two spacings
/// inside the wall) and ran out of any budget, where GFMD converges; the damped step
/// ([`persson_check::engine::solver::ConstrainedCg`], "Stopping") must bring every load to
/// the tolerance, and both solvers must agree. 128^2 shows the cycle at the sixth load.
#[test]
fn terrace_with_particles_warm_along_the_loads() {
    let n = 128;
    let h = terrace_with_particles(n);
    let loads = [0.0002, 0.0004, 0.000654, 0.001, 0.0016, 0.0025, 0.004];
    let free = Model::free_boundary(n, 1.0).unwrap();
    let periodic = Model::new(Grid::new(n, 1.0).unwrap(), 1.0).unwrap();
    for (boundary, model) in [("free", &free), ("periodic", &periodic)] {
        let heights = model.pad_heights(&h).unwrap();
        // The load over the window, as a mean over the model's grid.
        let share = (n * n) as f64 / model.grid.points() as f64;
        let mut last: Vec<Option<ContactSolution>> = SolverKind::ALL.iter().map(|_| None).collect();
        for &p0 in &loads {
            let scene = format!("terrace, {boundary}, p0 = {p0}");
            let problem = ContactProblem::new(model, &heights, p0 * share).unwrap();
            let mut solved = Vec::new();
            for (kind, prev) in SolverKind::ALL.iter().zip(&mut last) {
                let start = prev.as_ref().map_or(Start::Cold, Start::Warm);
                let s = run(
                    &scene,
                    *kind,
                    kind.build().as_mut(),
                    &problem,
                    start,
                    &opts(1e-8),
                )
                .unwrap_or_else(|r| panic!("{scene}, {}: residual {r:e}", kind.name()));
                eprintln!(
                    "{scene:<34} {:<4} iterations {:>5}  a_r {:.6}",
                    kind.name(),
                    s.stats.iterations,
                    s.contact_area() / share
                );
                *prev = Some(s.clone());
                solved.push(s);
            }
            assert_agree(&scene, &solved[0], &solved[1], 1e-8);
        }
    }
}

/// The terrace with particles on the free boundary, loaded as `check-surface` loads a
/// scan, by the CG that a measured scan gets
/// ([`persson_check::measured::body::scan_solver`]: its safeguards act after
/// [`persson_check::engine::solver::SCAN_STAGNATION`] iterations without progress, not
/// 200): every load reaches the tolerance with the answer of the default CG, and the
/// loads whose full step cycles cost fewer iterations in all.
#[test]
fn terrace_with_particles_by_the_scans_cg() {
    let n = 128;
    let h = terrace_with_particles(n);
    let loads = [0.0002, 0.0004, 0.000654, 0.001, 0.0016, 0.0025, 0.004];
    let model = Model::free_boundary(n, 1.0).unwrap();
    let heights = model.pad_heights(&h).unwrap();
    let share = (n * n) as f64 / model.grid.points() as f64;
    let mut scan = persson_check::measured::body::scan_solver(SolverKind::Cg);
    let mut plain = SolverKind::Cg.build();
    let (mut last_scan, mut last_plain): (Option<ContactSolution>, Option<ContactSolution>) =
        (None, None);
    let (mut its_scan, mut its_plain) = (0, 0);
    for &p0 in &loads {
        let scene = format!("terrace, free, p0 = {p0}, the scans' CG");
        let problem = ContactProblem::new(&model, &heights, p0 * share).unwrap();
        let start = last_scan.as_ref().map_or(Start::Cold, Start::Warm);
        let s = run(
            &scene,
            SolverKind::Cg,
            scan.as_mut(),
            &problem,
            start,
            &opts(1e-8),
        )
        .unwrap_or_else(|r| panic!("{scene}: residual {r:e}"));
        let start = last_plain.as_ref().map_or(Start::Cold, Start::Warm);
        let d = run(
            &scene,
            SolverKind::Cg,
            plain.as_mut(),
            &problem,
            start,
            &opts(1e-8),
        )
        .unwrap_or_else(|r| panic!("{scene}, default CG: residual {r:e}"));
        eprintln!(
            "{scene:<44} iterations {:>5} (default window {:>5})",
            s.stats.iterations, d.stats.iterations
        );
        assert_agree(&scene, &s, &d, 1e-8);
        its_scan += s.stats.iterations;
        its_plain += d.stats.iterations;
        last_scan = Some(s);
        last_plain = Some(d);
    }
    assert!(
        its_scan + 100 < its_plain,
        "the scans' window took {its_scan} iterations over the loads, the default {its_plain}"
    );
}

/// A lone spike pixel beside a smooth contact patch, the shape of an interferometer scan
/// with an instrument spike (`tests/fixtures/spike_beside_patch.npy`, 128^2, pixel 1: a
/// paraboloid of depth 0.03 over the half-width, band-limited self-affine roughness of
/// rms 0.009 and one pixel 0.5 above it), at a load where the spike is pressed in to the
/// patch's level and carries a large share of the load. Polonsky-Keer's rescaling of the
/// load takes from the spike at every step what the step gave it, and the patch can swing
/// by a thousand points around it: an unpreconditioned Polonsky-Keer written apart from
/// this crate cycles on this scene with the spike 0.22 inside the wall. This crate's
/// preconditioned CG solves it without its safeguards (31 iterations), so the scene
/// guards the converged answer; the cycle that needs the projected load (see
/// `engine::solver::cg`, "Stopping") shows at full scale, on a 640 x 480 scan.
#[test]
fn spike_beside_a_smooth_patch() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/spike_beside_patch.npy");
    let h = persson_check::measured::scan::Scan::read(&path)
        .unwrap()
        .heights;
    let n = 128;
    let model = Model::new(Grid::new(n, 1.0).unwrap(), 1.0).unwrap();
    let spike = (0..n * n).max_by(|&a, &b| h[a].total_cmp(&h[b])).unwrap();
    let p0 = 3e-4;
    let s = cold(
        "spike beside a smooth patch",
        SolverKind::Cg,
        &model,
        &h,
        p0,
    );
    let a = s.contact_area();
    assert!(a > 0.01 && a < 0.5, "a_r = {a}");
    assert!(
        s.pressure[spike] > 100.0 * p0 / a,
        "the spike carries far more than the patch's mean pressure: {} against {}",
        s.pressure[spike],
        p0 / a
    );
}
