//! A magnification sweep (Python's `sweep`): one surface solved while roughness is added,
//! one step at a time, each solve starting from the previous solution predicted for the
//! added roughness ([`crate::engine::sweep`]). The load is a constant `p0` (the paper's
//! protocol) or the load that gives a target contact area at the first step, kept for the
//! steps after it.

use std::ops::ControlFlow;

use crate::engine::contact::{ContactProblem, Model};
use crate::engine::scene::check_zeta;
use crate::engine::solver::{SolveOptions, Solver, Watched};
use crate::engine::surface::Surface;
use crate::engine::sweep::{shell_steps, Sweep};
use crate::error::{Error, Result};

use super::parse::Load;
use super::solve::{Progress, Settled, StopReason};
use super::Spelling;

/// Runs a sweep of `surface` as `settled` asks (its load, solver, options and `E*`; the
/// magnifications are the steps [`SweepRun::step`] is called with): `body` gets the run.
/// `watch` sees the load `p0` and the progress of every iteration of every solve, and
/// answers whether the solve goes on (a stop ends the step in [`Error::Stopped`]); `fields`
/// keeps each step's pressure and gap.
pub fn with_run<R>(
    surface: &Surface,
    settled: &Settled,
    fields: bool,
    mut watch: impl FnMut(f64, Progress) -> ControlFlow<StopReason> + Send + 'static,
    body: impl FnOnce(&mut SweepRun) -> R,
) -> Result<R> {
    let model = Model::new(surface.grid().clone(), settled.e_star)?;
    let solver = Box::new(Watched {
        inner: settled.solver.build(),
        watch: move |problem: &ContactProblem, p: Progress| watch(problem.p0, p),
    });
    let mut run = SweepRun::new(surface, &model, solver, settled.opts, settled.load, fields);
    Ok(body(&mut run))
}

/// The magnifications of a sweep of `surface`: `zetas` as given (each in
/// `[1, zeta_max]`), or else every shell with `zeta_from < zeta <= zeta_to` (default:
/// `zeta_max`), one step per shell.
///
/// # Errors
///
/// If `zetas` is given empty, or a magnification is outside `[1, zeta_max]`.
pub fn steps(
    surface: &Surface,
    zetas: Option<Vec<f64>>,
    zeta_from: f64,
    zeta_to: Option<f64>,
    s: &dyn Spelling,
) -> Result<Vec<f64>> {
    let zeta_max = surface.zeta_max().max(1.0);
    let within =
        |zeta: f64, key: &str| check_zeta(zeta, zeta_max).map_err(|e| e.with_field(&s.name(key)));
    if let Some(list) = zetas {
        if list.is_empty() {
            return Err(Error::invalid(
                &s.name("zetas"),
                "[]",
                "at least one magnification",
            ));
        }
        for &z in &list {
            within(z, "zetas")?;
        }
        return Ok(list);
    }
    within(zeta_from, "zeta_from")?;
    let to = zeta_to.unwrap_or(zeta_max);
    within(to, "zeta_to")?;
    let steps = shell_steps(surface, zeta_from, to);
    if steps.is_empty() {
        return Err(Error::invalid(
            &s.name("zeta_to"),
            to,
            format!(
                "above the first shell with roughness after {} = {zeta_from}",
                s.name("zeta_from")
            ),
        ));
    }
    Ok(steps)
}

/// One step of a sweep.
#[derive(Debug, Clone)]
pub struct SweepStep {
    /// The magnification of this step.
    pub zeta: f64,
    /// Mean pressure.
    pub p0: f64,
    /// Relative contact area.
    pub contact_area: f64,
    /// Elastic energy per unit area.
    pub elastic_energy: f64,
    /// Mean gap.
    pub mean_gap: f64,
    /// Rms gradient of the surface at `zeta`.
    pub rms_gradient: f64,
    /// Iterations of this step's solve.
    pub iterations: usize,
    /// The solver-independent residual reached.
    pub residual: f64,
    /// Wall time of this step's solve, seconds.
    pub wall_s: f64,
    /// Pressure and gap fields, when the sweep keeps them.
    pub fields: Option<(Vec<f64>, Vec<f64>)>,
}

/// A sweep under way: call [`SweepRun::step`] with each magnification in turn.
pub struct SweepRun<'a> {
    sweep: Sweep<'a>,
    surface: &'a Surface,
    load: Load,
    /// The load of the steps: `p0`, or the one found at the first step for a contact area.
    p0: Option<f64>,
    fields: bool,
}

impl<'a> SweepRun<'a> {
    /// A sweep of `surface` on `model` with `solver` at `load`; `fields` keeps each step's
    /// pressure and gap.
    pub fn new(
        surface: &'a Surface,
        model: &'a Model,
        solver: Box<dyn Solver + Send>,
        opts: SolveOptions,
        load: Load,
        fields: bool,
    ) -> Self {
        let p0 = match load {
            Load::Pressure(p0) => Some(p0),
            Load::Area(_) => None,
        };
        Self {
            sweep: Sweep::with_solver(surface, model, solver, opts),
            surface,
            load,
            p0,
            fields,
        }
    }

    /// Solves at magnification `zeta`, starting from the previous step.
    ///
    /// # Errors
    ///
    /// If the solve or, for a contact area, the load search fails (see
    /// [`crate::engine::sweep::Sweep::solve_at`] and [`crate::engine::sweep::Sweep::find_load`]).
    pub fn step(&mut self, zeta: f64) -> Result<SweepStep> {
        match (self.p0, self.load) {
            (Some(p0), _) => {
                self.sweep.solve_at(zeta, p0)?;
            }
            (None, Load::Area(a)) => self.p0 = Some(self.sweep.find_load(zeta, a)?),
            (None, Load::Pressure(_)) => unreachable!("p0 is set for a pressure"),
        }
        let solution = self.sweep.solution().expect("a solve keeps its solution");
        let heights = self.sweep.heights();
        let fields = self
            .fields
            .then(|| (solution.pressure.clone(), solution.gap(heights)));
        Ok(SweepStep {
            zeta,
            p0: solution.p0,
            contact_area: solution.contact_area(),
            elastic_energy: solution.elastic_energy(),
            mean_gap: solution.mean_gap(heights),
            rms_gradient: self.surface.rms_gradient(zeta),
            iterations: solution.stats.iterations,
            residual: solution.stats.residual.value(),
            wall_s: solution.stats.wall_s,
            fields,
        })
    }
}
