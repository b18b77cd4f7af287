//! Hard-wall contact solvers ([`crate::conventions`], section 4).
//!
//! * [`Gfmd`]: Green's function molecular dynamics as in the paper: damped dynamics of the
//!   displacement modes in reciprocal space with the hard wall applied in real space,
//!   mass-weighted so that every mode shares one frequency, relaxed with a momentum
//!   schedule that restarts when the force opposes the motion.
//! * [`ConstrainedCg`]: constrained conjugate gradients on the pressure
//!   (Polonsky & Keer 1999), the algorithm of tamaas and ContactMechanics;
//! * [`Fire`]: the fast inertial relaxation engine (Bitzek et al. 2006) on GFMD's masses:
//!   the same mass-weighted dynamics (`dynamics.rs`), relaxed by FIRE's velocity mixing
//!   and adaptive time step.
//!
//! [`SolverKind::ALL`] lists them, one entry each: adding a solver is its folder and one
//! entry. All are [`Solver`]s, start cold or from a previous solution, stop at the
//! solver-independent [`crate::engine::contact::Residual`], and fail with
//! [`crate::Error::NotConverged`] (carrying the residual), [`crate::Error::NonFinite`] or
//! [`crate::Error::LostContact`] rather than return an unconverged field. A monitor may
//! stop a running solve (a time budget, a cancel): the solve then ends in
//! [`crate::Error::Stopped`], and the solver is ready for its next solve.
//!
//! # One scaffold under all
//!
//! A solver keeps only its own steps. What every solve does is written once:
//!
//! * [`executor`]: the loop that runs any [`executor::Method`] (after argmin's executor):
//!   the method starts a solve from a problem and a start (`init`), and each iteration
//!   measures the residual estimate the monitor sees (`measure`), judges whether the solve
//!   has converged or must stop (`judge`), and takes the rest of its step (`step`); at the
//!   end, `terminate` returns the final state or the error, with an explicit
//!   [`Termination`](crate::error::Termination); the monitor's answer
//!   ([`ControlFlow`]) stops a solve from outside;
//! * [`workspace`]: the work buffers kept between solves, the check that a warm start is
//!   on the problem's grid, and the packaging of fields into a
//!   [`ContactSolution`] with its residual and [`SolveStats`](crate::engine::contact::SolveStats);
//! * in [`crate::engine::contact`]: the residual's components and the gap; in
//!   [`crate::engine::field`]: the chunked reductions that give the same bits on any
//!   number of threads; the elastic operator (kernels, point compliance, inverse masses)
//!   comes from the [`Model`](crate::engine::contact::Model).

mod cg;
mod dynamics;
pub mod executor;
mod fire;
mod gfmd;
pub mod workspace;

pub use cg::{ConstrainedCg, SCAN_STAGNATION};
pub use fire::{Fire, FireParams};
pub use gfmd::{Gfmd, GfmdParams};

use std::ops::ControlFlow;

use serde::{Deserialize, Serialize};

use crate::engine::contact::{ContactProblem, ContactSolution};
use crate::error::{Error, Result};

pub use crate::error::StopReason;

/// Writes [`SolverKind`] from the list of methods: one entry per solver, its kind and its
/// [`executor::Method`] (whose [`executor::Method::NAME`] is the solver's name), from which
/// [`SolverKind::ALL`], the names, the parser, the constructor and the cost follow.
macro_rules! solvers {
    ($($(#[$attr:meta])* $kind:ident => $method:ty,)+) => {
        /// The solvers, by name: for scenes, the command line, Python and the studies
        /// ([`SolverKind::ALL`] lists them).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
        pub enum SolverKind {
            $($(#[$attr])* $kind,)+
        }

        /// How many solvers there are.
        const SOLVER_COUNT: usize = [$(stringify!($kind)),+].len();

        impl SolverKind {
            /// Every solver, in the order of the list: the paper's method first.
            pub const ALL: [SolverKind; SOLVER_COUNT] = [$(SolverKind::$kind),+];
            /// Their names, in the same order.
            pub const NAMES: [&'static str; SOLVER_COUNT] =
                [$(<$method as executor::Method>::NAME),+];

            /// A fresh solver of this kind.
            pub fn build(self) -> Box<dyn Solver + Send> {
                match self {
                    $(SolverKind::$kind => Box::new(<$method>::default()),)+
                }
            }

            /// The time of a warm-started solve relative to CG's
            /// ([`executor::Method::RELATIVE_COST`]).
            pub fn relative_cost(self) -> f64 {
                match self {
                    $(SolverKind::$kind => <$method as executor::Method>::RELATIVE_COST,)+
                }
            }
        }
    };
}

solvers! {
    /// Green's function molecular dynamics (mass-weighted, accelerated damped dynamics).
    Gfmd => Gfmd,
    /// Constrained conjugate gradients (Polonsky-Keer).
    #[default]
    Cg => ConstrainedCg,
    /// FIRE on GFMD's masses (Bitzek et al. 2006).
    Fire => Fire,
}

impl SolverKind {
    /// The solver's short name.
    pub fn name(self) -> &'static str {
        Self::NAMES[self.index()]
    }

    /// Its place in [`SolverKind::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The solver named `name`, or `None`: the one parser of solver names (clap's, from
    /// [`SolverKind::ALL`] and the names).
    pub fn from_name(name: &str) -> Option<Self> {
        <Self as clap::ValueEnum>::from_str(name, false).ok()
    }

    /// The names as a message lists them: `"gfmd", "cg" or "fire"`.
    pub fn listed() -> String {
        let quoted: Vec<String> = Self::NAMES.iter().map(|n| format!("{n:?}")).collect();
        match quoted.split_last() {
            Some((last, [])) => last.clone(),
            Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
            None => String::new(),
        }
    }
}

impl clap::ValueEnum for SolverKind {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        Some(clap::builder::PossibleValue::new(self.name()))
    }
}

impl Serialize for SolverKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for SolverKind {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let name = std::borrow::Cow::<str>::deserialize(d)?;
        Self::from_name(&name).ok_or_else(|| serde::de::Error::unknown_variant(&name, &Self::NAMES))
    }
}

/// Solver settings shared by every solver.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SolveOptions {
    /// Requested residual (see [`Residual`](crate::engine::contact::Residual)).
    pub tol: f64,
    /// Iteration budget; exceeding it is an error carrying the residual reached.
    pub max_iter: usize,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            tol: Self::DEFAULT_TOL,
            max_iter: Self::DEFAULT_MAX_ITER,
        }
    }
}

impl SolveOptions {
    /// The residual asked for when none is given: the command line's `--tol`, Python's
    /// `tol`, a scene's `[solve] tol` (the one place this default is written).
    pub const DEFAULT_TOL: f64 = 1e-8;

    /// The iteration budget of a solve when none is given (`--max-iter`, `max_iter`).
    pub const DEFAULT_MAX_ITER: usize = 100_000;

    /// Options with tolerance `tol`.
    pub fn with_tol(tol: f64) -> Self {
        Self {
            tol,
            ..Self::default()
        }
    }

    /// Checks the ranges.
    ///
    /// # Errors
    ///
    /// If `tol` is outside `[1e-14, 1)` or `max_iter` is 0.
    pub fn validate(&self) -> Result<()> {
        if !(self.tol.is_finite() && self.tol >= 1e-14 && self.tol < 1.0) {
            return Err(Error::invalid("tol", self.tol, "in [1e-14, 1)"));
        }
        if self.max_iter == 0 {
            return Err(Error::invalid("max_iter", 0, ">= 1"));
        }
        Ok(())
    }
}

/// Where a solve starts.
#[derive(Debug, Clone, Copy)]
pub enum Start<'a> {
    /// From scratch (uniform pressure, flat displacement).
    Cold,
    /// From a previous solution: another load, or a lower magnification.
    Warm(&'a ContactSolution),
}

/// Progress of a solve, for monitors (progress bars, logs, time budgets).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Iteration number.
    pub iteration: usize,
    /// The solver's running estimate of the residual.
    pub residual: f64,
}

/// A hard-wall contact solver. Every [`executor::Method`] is one, run by
/// [`executor::run`].
pub trait Solver {
    /// Short name ([`SolverKind::NAMES`]).
    fn name(&self) -> &'static str;

    /// Solves `problem` from `start` to `opts.tol`, or fails with the residual reached;
    /// `monitor` sees every iteration and answers whether the solve goes on
    /// ([`ControlFlow::Break`] stops it).
    ///
    /// # Errors
    ///
    /// If the start does not fit the problem ([`Error::InvalidInput`]), the monitor stops
    /// the solve ([`Error::Stopped`], with the last progress; the solver stays ready for
    /// its next solve), or the solve ends short of the tolerance ([`Error::NotConverged`],
    /// with the residual reached), meets a non-finite value ([`Error::NonFinite`]) or
    /// loses every contact point ([`Error::LostContact`]).
    fn solve_monitored(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress) -> ControlFlow<StopReason>,
    ) -> Result<ContactSolution>;

    /// Solves `problem` from `start` to `opts.tol`, or fails with the residual reached.
    ///
    /// # Errors
    ///
    /// As [`Solver::solve_monitored`].
    fn solve(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
    ) -> Result<ContactSolution> {
        self.solve_monitored(problem, start, opts, &mut |_| ControlFlow::Continue(()))
    }

    /// What the solver carries from one solve to the next besides the solution (GFMD: the
    /// step its last solve ended with), so that a sweep resumed from a checkpoint solves
    /// as the uninterrupted one did; `None` when it carries nothing.
    fn carried(&self) -> Option<f64> {
        None
    }

    /// Sets what [`Solver::carried`] returns, as a resumed sweep's checkpoint holds it.
    fn carry(&mut self, _carried: Option<f64>) {}
}

impl<M: executor::Method> Solver for M {
    fn name(&self) -> &'static str {
        M::NAME
    }

    fn solve_monitored(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress) -> ControlFlow<StopReason>,
    ) -> Result<ContactSolution> {
        opts.validate()?;
        let solve = self.init(problem, start, opts)?;
        executor::run(solve, M::NAME, opts.max_iter, monitor)
    }

    fn carried(&self) -> Option<f64> {
        executor::Method::carried(self)
    }

    fn carry(&mut self, carried: Option<f64>) {
        executor::Method::carry(self, carried);
    }
}

/// A solver whose every iteration is also shown to `watch`, with the problem being
/// solved: a progress display, or a check that stops the solve (its answer, as a
/// monitor's). The caller's own monitor still sees every iteration; either one stops the
/// solve.
pub struct Watched<F> {
    /// The solver that does the work.
    pub inner: Box<dyn Solver + Send>,
    /// Sees each iteration of every solve.
    pub watch: F,
}

impl<F: FnMut(&ContactProblem, Progress) -> ControlFlow<StopReason>> Solver for Watched<F> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn solve_monitored(
        &mut self,
        problem: &ContactProblem,
        start: Start,
        opts: &SolveOptions,
        monitor: &mut dyn FnMut(Progress) -> ControlFlow<StopReason>,
    ) -> Result<ContactSolution> {
        let watch = &mut self.watch;
        self.inner.solve_monitored(problem, start, opts, &mut |p| {
            let watched = watch(problem, p);
            monitor(p)?;
            watched
        })
    }

    fn carried(&self) -> Option<f64> {
        self.inner.carried()
    }

    fn carry(&mut self, carried: Option<f64>) {
        self.inner.carry(carried);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::testing::rough_contact;

    #[test]
    fn every_solver_has_one_name_that_parses_serialises_and_builds_it() {
        for (k, kind) in SolverKind::ALL.into_iter().enumerate() {
            let name = kind.name();
            assert_eq!(kind.index(), k);
            assert_eq!(SolverKind::NAMES.iter().filter(|&&n| n == name).count(), 1);
            assert_eq!(SolverKind::from_name(name), Some(kind));
            assert_eq!(kind.build().name(), name);
            let json = serde_json::to_string(&kind).unwrap();
            assert_eq!(json, format!("{name:?}"));
            assert_eq!(serde_json::from_str::<SolverKind>(&json).unwrap(), kind);
            assert!(kind.relative_cost() > 0.0);
            assert!(SolverKind::listed().contains(&format!("{name:?}")));
        }
        assert_eq!(SolverKind::from_name("fem"), None);
        let e = serde_json::from_str::<SolverKind>("\"fem\"").unwrap_err();
        assert!(e.to_string().contains("unknown variant `fem`"), "{e}");
        assert_eq!(
            SolverKind::Cg.relative_cost(),
            1.0,
            "CG is the unit of cost"
        );
    }

    #[test]
    fn watched_sees_every_iteration_and_leaves_the_solution_alone() {
        let (surface, model) = rough_contact(32, 0.8, 3);
        let heights = surface.heights_at(surface.zeta_max(), &model.fft);
        let problem = ContactProblem::new(&model, &heights, 0.05).unwrap();
        let opts = SolveOptions::with_tol(1e-8);
        let plain = SolverKind::Gfmd
            .build()
            .solve(&problem, Start::Cold, &opts)
            .unwrap();

        let mut watched_p0 = Vec::new();
        let mut watched = Vec::new();
        let mut seen = Vec::new();
        let solution = Watched {
            inner: SolverKind::Gfmd.build(),
            watch: |problem: &ContactProblem, p: Progress| {
                watched_p0.push(problem.p0);
                watched.push(p.iteration);
                ControlFlow::Continue(())
            },
        }
        .solve_monitored(&problem, Start::Cold, &opts, &mut |p| {
            seen.push(p.iteration);
            ControlFlow::Continue(())
        })
        .unwrap();

        assert_eq!(solution.pressure, plain.pressure);
        assert_eq!(
            watched, seen,
            "the watcher and the caller's monitor see the same"
        );
        assert_eq!(watched.first(), Some(&0));
        assert!(watched.len() >= solution.stats.iterations);
        assert!(watched_p0.iter().all(|&p0| p0 == 0.05));
    }
}
