//! Contact scenes with exact solutions and the checks every converged solution must pass,
//! shared by the solver tests ([`crate::solvers`], [`crate::hard_scenes`],
//! [`crate::conformance`]).

use persson_check::engine::contact::{ContactProblem, ContactSolution, Model, Residual};
use persson_check::engine::field;
use persson_check::engine::grid::Grid;
use persson_check::engine::reference::Hertz;
use persson_check::engine::solver::SolverKind;

/// `h(x, y) = h0 cos(2 pi x / L)`: one wavelength across the box, constant along y.
pub fn sinusoid(n: usize, h0: f64) -> (Model, Vec<f64>) {
    let model = Model::new(Grid::new(n, 1.0).unwrap(), 1.0).unwrap();
    let h = (0..n * n)
        .map(|k| h0 * (2.0 * std::f64::consts::PI * (k % n) as f64 / n as f64).cos())
        .collect();
    (model, h)
}

/// A sphere of radius `radius` (a paraboloid) centred at `(row, column)` = `centre` of a
/// `rows x cols` free-boundary window, pressed with `force`: the model, the padded heights
/// and the padded grid's `p0`.
pub fn sphere_on_free_window(
    (rows, cols): (usize, usize),
    centre: (f64, f64),
    radius: f64,
    force: f64,
) -> (Model, Vec<f64>, f64) {
    let model = Model::free_window(rows, cols, 1.0).unwrap();
    let (cy, cx) = centre;
    let window: Vec<f64> = (0..rows * cols)
        .map(|k| {
            let (x, y) = ((k % cols) as f64 + 0.5 - cx, (k / cols) as f64 + 0.5 - cy);
            -(x * x + y * y) / (2.0 * radius)
        })
        .collect();
    let heights = model.pad_heights(&window).unwrap();
    let p0 = force / model.grid.points() as f64;
    (model, heights, p0)
}

/// A sphere centred on a `n x n` free-boundary window (see [`sphere_on_free_window`]).
pub fn sphere_on_free_boundary(n: usize, radius: f64, force: f64) -> (Model, Vec<f64>, f64) {
    let c = 0.5 * n as f64;
    sphere_on_free_window((n, n), (c, c), radius, force)
}

/// A solution `s` by `kind` of a sphere pressed with `force` on a free-boundary `model`
/// against `hertz` with contact radius `a`: pressure only under the wall, carrying the
/// whole force (to 1e-8, relative), and the contact area (points with `p > 0`) and the
/// peak pressure within 3% of Hertz's (the contact edge is placed to a grid spacing).
pub fn assert_hertz(
    kind: SolverKind,
    model: &Model,
    s: &ContactSolution,
    hertz: &Hertz,
    (a, force): (f64, f64),
) {
    let outside: f64 = (0..s.pressure.len())
        .filter(|&k| !model.under_wall(k))
        .map(|k| s.pressure[k].abs())
        .sum();
    assert_eq!(outside, 0.0, "{}: pressure off the window", kind.name());
    let total: f64 = s.pressure.iter().sum();
    assert!(
        (total / force - 1.0).abs() < 1e-8,
        "{}: force {total} vs {force}",
        kind.name()
    );
    let area = s.pressure.iter().filter(|&&p| p > 0.0).count() as f64;
    let exact = std::f64::consts::PI * a * a;
    assert!(
        (area / exact - 1.0).abs() < 0.03,
        "{}: contact area {area} vs Hertz {exact:.1}",
        kind.name()
    );
    let peak = s.pressure.iter().copied().fold(0.0, f64::max);
    assert!(
        (peak / hertz.peak_pressure(force) - 1.0).abs() < 0.03,
        "{}: peak {peak} vs {}",
        kind.name(),
        hertz.peak_pressure(force)
    );
}

/// The hard-wall conditions on a converged solution, checked from its fields alone.
pub fn check_solution(
    scene: &str,
    kind: SolverKind,
    problem: &ContactProblem,
    s: &ContactSolution,
    tol: f64,
) {
    let name = kind.name();
    let (p, u, h) = (&s.pressure, &s.displacement, problem.heights);
    assert!(
        field::all_finite(p) && field::all_finite(u),
        "{scene}, {name}: non-finite field"
    );
    // The residual reported is that of the returned fields, and meets the tolerance.
    let model = problem.model;
    let mut spec = model.fft.new_spectrum();
    let mut scratch = vec![0.0; model.grid.points()];
    let again = Residual::evaluate(problem, p, u, &mut spec, &mut scratch);
    let reported = s.stats.residual.value();
    assert!(
        reported <= tol && again.value() <= tol,
        "{scene}, {name}: residual {reported:e} (re-evaluated {:e}) > {tol:e}",
        again.value()
    );
    assert!(
        (again.value() - reported).abs() <= 1e-6 * reported + 1e-15,
        "{scene}, {name}: reported residual {reported:e}, fields' residual {:e}",
        again.value()
    );
    assert!(
        field::min(p) >= 0.0,
        "{scene}, {name}: tensile pressure {}",
        field::min(p)
    );
    // The load: CG rescales the pressure to it at every iteration, so it holds to
    // rounding. A dynamics method's pressure (GFMD's, FIRE's) is the wall's reaction,
    // whose mean differs from p0 by the stress the dynamics has not yet relaxed: that is
    // the `load` part of its residual, bounded by the tolerance.
    let load = (field::mean(p) - problem.p0).abs() / problem.p0;
    let bound = if kind == SolverKind::Cg { 1e-12 } else { tol };
    assert!(
        load <= bound,
        "{scene}, {name}: mean(p) off p0 by {load:e} (relative)"
    );
    let min_gap = u
        .iter()
        .zip(h)
        .map(|(u, h)| u - h)
        .fold(f64::INFINITY, f64::min);
    assert!(
        min_gap >= -tol * problem.length_scale,
        "{scene}, {name}: penetration {min_gap:e} (length scale {:e})",
        problem.length_scale
    );
}

/// `rms(p) / p0`: the residual measures unbalanced stress relative to `rms(p)`, so a
/// solution at residual `tol` fixes the stresses, and with them the energy relative to
/// `p0 x (displacement)`, to about `tol rms(p) / p0`. Concentrated contact (one asperity,
/// one spike) makes this factor large: `sqrt(1 / a_r)` for equal pressures.
fn concentration(s: &ContactSolution) -> f64 {
    (field::sum_map(&s.pressure, |_, p| p * p) / s.pressure.len() as f64).sqrt() / s.p0
}

/// Points in contact in one solution and not in the other.
pub fn contact_differences(a: &ContactSolution, b: &ContactSolution) -> usize {
    a.pressure
        .iter()
        .zip(&b.pressure)
        .filter(|(x, y)| (**x > 0.0) != (**y > 0.0))
        .count()
}

/// Two converged solutions of one problem agree to what the tolerance implies: contact
/// sets up to two points at the contact edge (where the pressure is of the order of the
/// tolerance), elastic energies to `10 tol k` and pressure fields to `100 tol k` in
/// relative L2, with `k` the [`concentration`] (1 to 2 for spread-out contact).
pub fn assert_agree(scene: &str, a: &ContactSolution, b: &ContactSolution, tol: f64) {
    let k = concentration(a).max(1.0);
    let differ = contact_differences(a, b);
    let (ea, eb) = (a.elastic_energy(), b.elastic_energy());
    let energy = (ea - eb).abs() / ea;
    let diff = field::sum_zip(&a.pressure, &b.pressure, |x, y| (x - y) * (x - y)).sqrt();
    let l2 = diff / field::sum_map(&a.pressure, |_, x| x * x).sqrt();
    eprintln!(
        "{scene:<34} {} vs {}: {differ} contact points differ, energy {energy:.1e}, pressure L2 {l2:.1e} (k = {k:.1})",
        a.stats.solver, b.stats.solver
    );
    assert!(differ <= 2, "{scene}: {differ} contact points differ");
    assert!(
        energy <= 10.0 * tol * k,
        "{scene}: energies {ea:e} vs {eb:e} (relative {energy:e}, k = {k})"
    );
    assert!(
        l2 <= 100.0 * tol * k,
        "{scene}: pressure fields differ by {l2:e} (relative L2, k = {k})"
    );
}
