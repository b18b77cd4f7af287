//! A scan as a contact problem, and its load curve: the rigid scan pressed onto an elastic
//! half-space (`E* = 1`, lengths in pixels), periodic or with a free boundary
//! ([`crate::engine::boussinesq`]), solved at increasing loads, each solve warm-started
//! from the last.
//!
//! What a solve gives the check, all over the scan's own window: the relative contact
//! area (points with `p > 0`), the elastic energy per unit area of the roughness and the
//! window's pressures. A solve that fails (no convergence, or over its time budget) is
//! recorded as such, with the solver and the load, and the curve goes on from the last
//! load that converged: one load never costs the others.
//!
//! The loads are stepped on the engine's [`LoadCurve`]. A time budget stops a solve from
//! its per-iteration monitor: past the deadline the monitor answers stop
//! ([`StopReason::OutOfTime`]) and the solve is recorded as over time; the solver is left
//! ready, and the next load starts warm from the last that converged. A solve cancelled
//! from outside (Ctrl-C in Python, through `monitor`) ends the check with its error.
//!
//! The energy of the roughness is that of the pressure beyond a flat punch's: with
//! `p_f` the pressure under a flat rigid punch of the window's shape at unit nominal load,
//! `E_el = (1/2) mean_window(dp (G * dp))` with `dp = p - p0 p_f` (zero outside the
//! window) and `G` the half-space's response. The flat punch displaces its window
//! uniformly, so `p_f` is orthogonal to `G * dp` for any `dp` of zero total load, and the
//! whole work of `p` splits exactly into the punch's and this:
//! `W(p) = p0^2 W(p_f) + W(dp)`. For a periodic scan `p_f = 1`, and `E_el` is the energy
//! of the fluctuation `p - p0`, `(1/2) mean[(p - p0) u]` ([`crate::engine::elastic`]), as in
//! Persson's theory, whose energy has no `q = 0` part. For a free boundary the punch's
//! share, the indentation of a finite window into the half-space (of order
//! `p0^2 L / E*`, with the pressure rising towards the window's edges), is left out: an
//! infinite rough surface under a uniform load has none.

use std::ops::ControlFlow;
use std::time::{Duration, Instant};

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use super::psd::{Boundary, ScanSpectrum, Shape};
use super::theory::E_STAR;
use crate::engine::contact::{ContactProblem, ContactSolution, Model};
use crate::engine::grid::Grid;
use crate::engine::load_curve::{ends_the_solve, LoadCurve, SolveEnd};
use crate::engine::solver::{ConstrainedCg, SCAN_STAGNATION};
use crate::engine::solver::{Progress, SolveOptions, Solver, SolverKind, Start};
use crate::error::{Error, Result, StopReason};

/// One scan as a contact problem.
pub struct Body {
    /// The elastic model (the doubled grid for a free boundary).
    pub model: Model,
    /// The heights on the model's grid (pixels), padded for a free boundary.
    pub heights: Vec<f64>,
    /// The scan's shape (pixels).
    pub shape: Shape,
    /// For a free boundary: the half spectrum of `M^2 G`, the Boussinesq response on the
    /// doubled grid, for the elastic displacement with its mean.
    response: Option<Vec<Complex64>>,
    /// For a free boundary: the flat punch's pressure at unit nominal load, `p_f`.
    punch: Vec<f64>,
}

/// Residual tolerance of the flat punch's solve.
const PUNCH_TOL: f64 = 1e-10;

impl Body {
    /// The contact problem of `spectrum`'s heights (detrended for a free boundary).
    pub fn new(spectrum: &ScanSpectrum) -> Result<Self> {
        let shape = spectrum.shape;
        match spectrum.boundary {
            Boundary::Periodic => Ok(Self {
                model: Model::new(Grid::new(shape.rows, 1.0)?, E_STAR)?,
                heights: spectrum.heights.clone(),
                shape,
                response: None,
                punch: Vec::new(),
            }),
            Boundary::Free => {
                let model = Model::free_window(shape.rows, shape.cols, E_STAR)?;
                let heights = model.pad_heights(&spectrum.heights)?;
                let (rows, cols) = (model.grid.rows(), model.grid.cols());
                let g = crate::engine::boussinesq::padded_response(rows, cols, 1.0, E_STAR);
                let mut spec = model.fft.new_spectrum();
                model.fft.forward(&g, &mut spec);
                let scale = (rows * cols) as f64;
                spec.iter_mut().for_each(|v| *v *= scale);
                let punch = flat_punch(&model, shape)?;
                Ok(Self {
                    model,
                    heights,
                    shape,
                    response: Some(spec),
                    punch,
                })
            }
        }
    }

    /// Puts the heights of `spectrum`, another scan of the same shape and boundary, on
    /// this body: its half-space, response and flat punch depend on the shape alone.
    pub fn set_heights(&mut self, spectrum: &ScanSpectrum) -> Result<()> {
        self.heights = match spectrum.boundary {
            Boundary::Periodic => spectrum.heights.clone(),
            Boundary::Free => self.model.pad_heights(&spectrum.heights)?,
        };
        Ok(())
    }

    /// The window's share of the model's grid (1 for a periodic scan).
    pub fn window_share(&self) -> f64 {
        self.shape.points() as f64 / self.model.grid.points() as f64
    }

    /// The window's values of a field on the model's grid, row-major.
    pub fn window(&self, field: &[f64]) -> Vec<f64> {
        window_of(&self.model, self.shape, field)
    }

    /// The elastic energy per unit area of the window under `solution` (see the module
    /// docs).
    pub fn elastic_energy(&self, solution: &ContactSolution) -> f64 {
        let Some(response) = &self.response else {
            return solution.elastic_energy();
        };
        let fft = &self.model.fft;
        let p0 = solution.p0 / self.window_share();
        let dp: Vec<f64> = (0..solution.pressure.len())
            .map(|k| {
                if self.model.under_wall(k) {
                    solution.pressure[k] - p0 * self.punch[k]
                } else {
                    0.0
                }
            })
            .collect();
        let mut spec = fft.new_spectrum();
        fft.forward(&dp, &mut spec);
        spec.iter_mut().zip(response).for_each(|(p, g)| *p *= g.re);
        let mut u = vec![0.0; self.model.grid.points()];
        fft.inverse(&spec, &mut u, &mut Vec::new());
        let work: f64 = dp.iter().zip(&u).map(|(p, u)| p * u).sum();
        0.5 * work / self.shape.points() as f64
    }
}

/// The values of a field on `model`'s grid over the `shape` window at its origin,
/// row-major (the whole field for a periodic model of that shape).
pub fn window_of(model: &Model, shape: Shape, field: &[f64]) -> Vec<f64> {
    field
        .chunks(model.grid.cols())
        .take(shape.rows)
        .flat_map(|row| &row[..shape.cols])
        .copied()
        .collect()
}

/// The pressure under a flat rigid punch of the window's shape at unit nominal load (mean
/// 1 over the window, zero outside), on `model`'s free boundary: the whole window in
/// contact with a flat wall, solved by CG to [`PUNCH_TOL`].
fn flat_punch(model: &Model, shape: Shape) -> Result<Vec<f64>> {
    let flat = model.pad_heights(&vec![0.0; shape.points()])?;
    let share = shape.points() as f64 / model.grid.points() as f64;
    let problem = ContactProblem::new(model, &flat, share)?;
    let solution =
        SolverKind::Cg
            .build()
            .solve(&problem, Start::Cold, &SolveOptions::with_tol(PUNCH_TOL))?;
    Ok(solution.pressure)
}

/// One load of a curve as one solver found it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Solved {
    /// The load, `p0 / E*` over the window.
    pub p0: f64,
    /// Relative contact area of the window.
    pub contact_area: f64,
    /// Elastic energy per unit area (`E*` times pixels).
    pub energy: f64,
    /// Iterations of the solve.
    pub iterations: usize,
    /// Its residual.
    pub residual: f64,
    /// Its wall time, seconds.
    pub wall_s: f64,
}

/// A solve that ended without a solution: the solver, the load and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Failed {
    /// The solver.
    pub solver: SolverKind,
    /// The load, `p0 / E*` over the window.
    pub p0: f64,
    /// What happened, naming the solver and the load.
    pub message: String,
    /// Wall time spent on it, seconds.
    pub wall_s: f64,
    /// The solver's state where it stopped, when it said: its iterations, the residual
    /// reached (against [`SolveOptions::tol`]) and the points in contact.
    #[serde(default)]
    pub state: Option<SolveState>,
}

/// Where a solve that did not converge stopped.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SolveState {
    /// Iterations done.
    pub iterations: usize,
    /// The residual reached (the smallest evaluated, or the estimate when stopped over
    /// time).
    pub residual: f64,
    /// The tolerance asked for.
    pub tol: f64,
    /// Points in contact (`p > 0`) in the state stopped, when known.
    pub contact_points: Option<usize>,
}

/// A load of a curve: solved, or failed.
pub type Outcome = std::result::Result<Solved, Failed>;

/// A load curve: every load's outcome, and the window's pressures at every load solved.
#[derive(Debug, Clone)]
pub struct Curve {
    /// The solver.
    pub solver: SolverKind,
    /// Which of the check's loads each entry is (`0..n` for a curve over every load).
    pub index: Vec<usize>,
    /// One entry per load solved, in the order of the loads.
    pub points: Vec<Outcome>,
    /// The window's pressures over the load (`p / p0`) at every load solved.
    pub pressures: Vec<Option<Vec<f32>>>,
    /// Wall time of the whole curve, seconds.
    pub wall_s: f64,
}

impl Curve {
    /// The check's load `i`, if this curve solved it.
    pub fn solved(&self, i: usize) -> Option<&Solved> {
        let k = self.index.iter().position(|&j| j == i)?;
        self.points[k].as_ref().ok()
    }
}

/// The solver `kind` as a measured scan needs it: CG with the scans' stagnation window
/// ([`SCAN_STAGNATION`]), so that its safeguards against a cycling step act after 25
/// iterations without progress rather than 200; the others as built.
pub fn scan_solver(kind: SolverKind) -> Box<dyn Solver + Send> {
    match kind {
        SolverKind::Cg => {
            let mut cg = ConstrainedCg::default();
            cg.stagnation = SCAN_STAGNATION;
            Box::new(cg)
        }
        other => other.build(),
    }
}

/// Solves `body` at `loads` (increasing) with `solver` to `opts.tol` within
/// `opts.max_iter` iterations a load, on the engine's [`LoadCurve`]: each load
/// warm-started from the last that converged; `budget[i]` bounds the time of load `i`
/// (`None`: no bound). `on_load` sees every load's outcome as it ends, `monitor` every
/// iteration.
pub fn solve_curve(
    body: &Body,
    loads: &[f64],
    solver: SolverKind,
    opts: SolveOptions,
    budget: &[Option<Duration>],
    on_load: &mut dyn FnMut(usize, &Outcome),
    monitor: &mut dyn FnMut(usize, Progress) -> ControlFlow<StopReason>,
) -> Result<Curve> {
    let timer = Instant::now();
    let mut curve = LoadCurve::new(&body.model, &body.heights, scan_solver(solver), opts);
    let mut points = Vec::with_capacity(loads.len());
    let mut pressures = Vec::with_capacity(loads.len());
    for (i, &p0) in loads.iter().enumerate() {
        let began = Instant::now();
        let allowed = budget.get(i).copied().flatten();
        let run = curve.solve(
            p0 * body.window_share(),
            allowed.map(|d| began + d),
            &mut |p| monitor(i, p),
        );
        let load = Load {
            solver,
            p0,
            at: format!(
                "{} at p0 = {p0:.3e} E* (load {} of {})",
                solver.name(),
                i + 1,
                loads.len()
            ),
            began,
            allowed,
            tol: opts.tol,
            max_iter: opts.max_iter,
        };
        let outcome = match run {
            Ok(solution) => match load.solved(body, &solution) {
                Ok((solved, window)) => {
                    pressures.push(Some(window));
                    curve.keep(solution);
                    Ok(solved)
                }
                Err(failed) => Err(failed),
            },
            Err(SolveEnd::Error(e)) if !ends_the_solve(&e) => return Err(e),
            Err(end) => Err(load.failed(end)),
        };
        if outcome.is_err() {
            pressures.push(None);
            curve.reject();
        }
        on_load(i, &outcome);
        points.push(outcome);
    }
    Ok(Curve {
        solver,
        index: (0..loads.len()).collect(),
        points,
        pressures,
        wall_s: timer.elapsed().as_secs_f64(),
    })
}

/// One load of a curve being solved: what its outcome names.
struct Load {
    solver: SolverKind,
    /// The load over the window, `p0 / E*`.
    p0: f64,
    /// The solver and the load, for messages.
    at: String,
    began: Instant,
    /// The load's time budget.
    allowed: Option<Duration>,
    /// The tolerance and the iteration budget.
    tol: f64,
    max_iter: usize,
}

impl Load {
    /// The load failed with `message` (and the solver's state where it said).
    fn fail(&self, message: String, state: Option<SolveState>) -> Failed {
        Failed {
            solver: self.solver,
            p0: self.p0,
            message,
            wall_s: self.began.elapsed().as_secs_f64(),
            state,
        }
    }

    /// A converged `solution` as the curve's point, with the window's pressures over the
    /// load (`p / p0`); failed where the surface touched the floor outside the scan.
    fn solved(
        &self,
        body: &Body,
        solution: &ContactSolution,
    ) -> std::result::Result<(Solved, Vec<f32>), Failed> {
        let touched = (0..solution.pressure.len())
            .filter(|&k| !body.model.under_wall(k))
            .any(|k| solution.pressure[k] > 0.0);
        if touched {
            return Err(self.fail(
                format!(
                    "{}: the surface touched the floor outside the scan",
                    self.at
                ),
                None,
            ));
        }
        let window = body.window(&solution.pressure);
        let contact = window.iter().filter(|&&p| p > 0.0).count();
        let solved = Solved {
            p0: self.p0,
            contact_area: contact as f64 / window.len() as f64,
            energy: body.elastic_energy(solution),
            iterations: solution.stats.iterations,
            residual: solution.stats.residual.value(),
            wall_s: solution.stats.wall_s,
        };
        let p0 = self.p0;
        Ok((solved, window.iter().map(|p| (p / p0) as f32).collect()))
    }

    /// The failure of a solve that ended without a solution (`end` ends the solve only).
    fn failed(&self, end: SolveEnd) -> Failed {
        let at = &self.at;
        match end {
            SolveEnd::Error(Error::NotConverged {
                solver: name,
                reason,
                iterations,
                residual,
                tol,
                contact_points,
            }) => {
                let contact = contact_points
                    .map(|c| format!(", {c} points in contact"))
                    .unwrap_or_default();
                self.fail(
                    format!(
                        "{at}: {name} did not converge ({reason}): residual {residual:.3e} > \
                         tolerance {tol:.1e} after {iterations} iterations (budget {}){contact}",
                        self.max_iter
                    ),
                    Some(SolveState {
                        iterations,
                        residual,
                        tol,
                        contact_points,
                    }),
                )
            }
            SolveEnd::Error(e) => self.fail(format!("{at}: {e}"), None),
            SolveEnd::OutOfTime(p) => self.fail(
                format!(
                    "{at}: stopped over its time budget of {:.1} s, after {} iterations, \
                     residual estimate {:.3e} > tolerance {:.1e}",
                    self.allowed.map_or(0.0, |d| d.as_secs_f64()),
                    p.iteration,
                    p.residual,
                    self.tol
                ),
                Some(SolveState {
                    iterations: p.iteration,
                    residual: p.residual,
                    tol: self.tol,
                    contact_points: None,
                }),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::surface::{Surface, SurfaceModel};

    fn scan(n: usize, boundary: Boundary) -> ScanSpectrum {
        let s = Surface::generate(&SurfaceModel::new(n, 0.8, n as f64, 4.0, 3)).unwrap();
        let fft = crate::engine::fft::Fft2::new(s.grid());
        let shape = Shape { rows: n, cols: n };
        ScanSpectrum::new(&s.heights_at(f64::INFINITY, &fft), shape, 1.0, boundary).unwrap()
    }

    /// `(1/2) sum_ab x_a G_ab y_b / n^2` over the window's points, by the direct sum of
    /// the pixel Boussinesq response.
    fn direct_work(x: &[f64], y: &[f64], n: usize, m: usize) -> f64 {
        let mut work = 0.0;
        for a in 0..n * n {
            for b in 0..n * n {
                let (ia, ja, ib, jb) = (a / n, a % n, b / n, b % n);
                let g = crate::engine::boussinesq::pixel_displacement(
                    ja as f64 - jb as f64,
                    ia as f64 - ib as f64,
                    1.0,
                    1.0,
                );
                work += x[ia * m + ja] * g * y[ib * m + jb];
            }
        }
        0.5 * work / (n * n) as f64
    }

    #[test]
    fn the_free_boundary_energy_is_the_work_beyond_the_flat_punch() {
        let n = 8;
        let body = Body::new(&scan(n, Boundary::Free)).unwrap();
        let m = body.model.grid.n();
        // The flat punch presses its whole window, with mean 1, and displaces it uniformly.
        let pf = &body.punch;
        let window: Vec<usize> = (0..m * m).filter(|&k| body.model.under_wall(k)).collect();
        assert!(window.iter().all(|&k| pf[k] > 0.0));
        let mean = window.iter().map(|&k| pf[k]).sum::<f64>() / window.len() as f64;
        assert!((mean - 1.0).abs() < 1e-12, "{mean}");
        let u: Vec<f64> = window
            .iter()
            .map(|&k| {
                let mut e = vec![0.0; m * m];
                e[k] = 1.0;
                2.0 * (n * n) as f64 * direct_work(&e, pf, n, m)
            })
            .collect();
        let (lo, hi) = u
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
        assert!(
            (hi - lo) < 1e-8 * hi,
            "punch displacement from {lo} to {hi}"
        );

        let mut p = vec![0.0; m * m];
        for i in 0..n {
            for j in 0..n {
                p[i * m + j] = ((i * 3 + j * 5) % 7) as f64 * 0.01;
            }
        }
        let solution = ContactSolution {
            pressure: p.clone(),
            displacement: vec![0.0; m * m],
            p0: crate::engine::field::mean(&p),
            stats: crate::engine::contact::SolveStats {
                solver: "none",
                iterations: 0,
                residual: Default::default(),
                wall_s: 0.0,
                warm: false,
            },
        };
        let p0 = crate::engine::field::mean(&p) * (m * m) as f64 / (n * n) as f64;
        let dp: Vec<f64> = (0..m * m)
            .map(|k| {
                if body.model.under_wall(k) {
                    p[k] - p0 * pf[k]
                } else {
                    0.0
                }
            })
            .collect();
        let e = body.elastic_energy(&solution);
        let direct = direct_work(&dp, &dp, n, m);
        assert!((e / direct - 1.0).abs() < 1e-9, "{e} vs {direct}");
        // The whole work splits into the punch's and the roughness's.
        let whole = direct_work(&p, &p, n, m);
        let punch = p0 * p0 * direct_work(pf, pf, n, m);
        assert!(
            (whole - punch - e).abs() < 1e-9 * whole,
            "{whole} vs {punch} + {e}"
        );
    }

    #[test]
    fn a_curve_rises_with_the_load_on_both_boundaries() {
        for boundary in [Boundary::Periodic, Boundary::Free] {
            let body = Body::new(&scan(32, boundary)).unwrap();
            let mut seen = Vec::new();
            let curve = solve_curve(
                &body,
                &[0.02, 0.05, 0.1],
                SolverKind::Cg,
                SolveOptions::with_tol(1e-8),
                &[],
                &mut |i, o| seen.push((i, o.is_ok())),
                &mut |_, _| ControlFlow::Continue(()),
            )
            .unwrap();
            assert_eq!(seen, vec![(0, true), (1, true), (2, true)]);
            let areas: Vec<f64> = (0..3)
                .map(|i| curve.solved(i).unwrap().contact_area)
                .collect();
            assert!(
                areas.windows(2).all(|w| w[0] < w[1]),
                "{boundary:?}: {areas:?}"
            );
            let kept = curve.pressures[1].as_ref().unwrap();
            assert_eq!(kept.len(), 32 * 32);
            let mean = kept.iter().map(|&p| f64::from(p)).sum::<f64>() / kept.len() as f64;
            assert!(
                (mean - 1.0).abs() < 1e-6,
                "{boundary:?}: mean p/p0 = {mean}"
            );
        }
    }

    #[test]
    fn a_load_over_its_time_budget_is_recorded_and_the_next_load_is_solved() {
        let body = Body::new(&scan(32, Boundary::Free)).unwrap();
        let budget = [Some(Duration::ZERO), None];
        let curve = solve_curve(
            &body,
            &[0.02, 0.05],
            SolverKind::Gfmd,
            SolveOptions::with_tol(1e-8),
            &budget,
            &mut |_, _| {},
            &mut |_, _| ControlFlow::Continue(()),
        )
        .unwrap();
        let failed = curve.points[0].as_ref().unwrap_err();
        assert_eq!((failed.solver, failed.p0), (SolverKind::Gfmd, 0.02));
        assert!(
            failed
                .message
                .starts_with("gfmd at p0 = 2.000e-2 E* (load 1 of 2)")
                && failed.message.contains("time budget"),
            "{}",
            failed.message
        );
        assert!(curve.pressures[0].is_none());
        // The second load starts cold and converges.
        let solved = curve.solved(1).unwrap();
        assert!(solved.contact_area > 0.0 && solved.residual <= 1e-8);
    }

    #[test]
    fn a_cancelled_solve_ends_the_curve_with_its_stop() {
        let body = Body::new(&scan(32, Boundary::Periodic)).unwrap();
        let mut loads_ended = 0;
        let e = solve_curve(
            &body,
            &[0.02, 0.05],
            SolverKind::Cg,
            SolveOptions::with_tol(1e-8),
            &[None, None],
            &mut |_, _| loads_ended += 1,
            &mut |_, p| {
                if p.iteration == 1 {
                    ControlFlow::Break(StopReason::Cancelled)
                } else {
                    ControlFlow::Continue(())
                }
            },
        )
        .unwrap_err();
        assert_eq!(e.stopped(), Some(StopReason::Cancelled), "{e}");
        assert_eq!(loads_ended, 0, "a cancel is not a failed load");
    }

    #[test]
    fn a_load_over_its_iteration_budget_reports_the_solver_state() {
        let body = Body::new(&scan(32, Boundary::Free)).unwrap();
        let opts = SolveOptions {
            tol: 1e-8,
            max_iter: 2,
        };
        let curve = solve_curve(
            &body,
            &[0.02],
            SolverKind::Cg,
            opts,
            &[],
            &mut |_, _| {},
            &mut |_, _| ControlFlow::Continue(()),
        )
        .unwrap();
        let failed = curve.points[0].as_ref().unwrap_err();
        let state = failed.state.expect("the solver's state");
        assert_eq!((state.iterations, state.tol), (2, 1e-8));
        assert!(state.residual > 1e-8, "{state:?}");
        let contact = state.contact_points.expect("the points in contact");
        assert!(contact > 0 && contact <= 64 * 64, "{state:?}");
        assert!(
            failed.message.contains("after 2 iterations (budget 2)")
                && failed
                    .message
                    .contains(&format!("{contact} points in contact")),
            "{}",
            failed.message
        );
    }
}
