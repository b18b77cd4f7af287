//! What every solve needs besides its own steps: the work buffers kept between solves, the
//! check that a warm start fits the problem, the packaging of fields into a
//! [`ContactSolution`] with its residual and statistics, and the errors a solve ends with.

use std::time::Instant;

use rustfft::num_complex::Complex64;

use crate::engine::contact::{ContactProblem, ContactSolution, Residual, SolveStats};
use crate::engine::grid::Grid;
use crate::engine::solver::Start;
use crate::error::{Error, Result, Termination};

/// A solver's work space, kept from solve to solve (a sweep solves thousands of times on
/// one grid): a half spectrum and `K` real fields.
#[derive(Debug, Clone)]
pub struct Workspace<const K: usize> {
    spec: Vec<Complex64>,
    fields: [Vec<f64>; K],
}

impl<const K: usize> Default for Workspace<K> {
    fn default() -> Self {
        Self {
            spec: Vec::new(),
            fields: std::array::from_fn(|_| Vec::new()),
        }
    }
}

impl<const K: usize> Workspace<K> {
    /// The spectrum and the fields, sized for `grid` (their contents are what the last
    /// solve left, or zeros).
    pub fn on(&mut self, grid: &Grid) -> (&mut Vec<Complex64>, [&mut Vec<f64>; K]) {
        ensure_len(&mut self.spec, grid.modes());
        for field in &mut self.fields {
            ensure_len(field, grid.points());
        }
        (&mut self.spec, self.fields.each_mut())
    }
}

/// Resizes `v` to `len` (contents unspecified).
fn ensure_len<T: Clone + Default>(v: &mut Vec<T>, len: usize) {
    if v.len() != len {
        v.clear();
        v.resize(len, T::default());
    }
}

/// The previous solution of a warm start (`None` for a cold one), checked to lie on
/// `grid`.
///
/// # Errors
///
/// If the previous solution's fields are not one value per point of `grid`.
pub fn warm_start<'s>(start: Start<'s>, grid: &Grid) -> Result<Option<&'s ContactSolution>> {
    let Start::Warm(prev) = start else {
        return Ok(None);
    };
    let n2 = grid.points();
    for len in [prev.pressure.len(), prev.displacement.len()] {
        if len != n2 {
            return Err(Error::invalid(
                "warm start",
                format!("{len} points"),
                format!("a solution on the same grid ({n2} points)"),
            ));
        }
    }
    Ok(Some(prev))
}

/// What one solve records about itself, the solver, whether it started warm and when it
/// began, and what it makes from that: the [`ContactSolution`] with its [`SolveStats`]
/// ([`SolveRecord::solution`], [`SolveRecord::accept`]) and the errors that name the
/// solver ([`SolveRecord::not_converged`], [`SolveRecord::non_finite`],
/// [`SolveRecord::lost_contact`]).
#[derive(Debug, Clone, Copy)]
pub struct SolveRecord {
    solver: &'static str,
    warm: bool,
    began: Instant,
}

impl SolveRecord {
    /// The record of a solve by `solver` beginning now.
    pub fn begin(solver: &'static str, warm: bool) -> Self {
        Self {
            solver,
            warm,
            began: Instant::now(),
        }
    }

    /// The fields `(pressure, displacement)` as a solution of `problem` after `iterations`
    /// iterations, with their [`Residual`]; `spec` (a half spectrum) and `scratch` (a real
    /// field) are work space for it.
    pub fn solution(
        &self,
        problem: &ContactProblem,
        (pressure, displacement): (Vec<f64>, Vec<f64>),
        iterations: usize,
        spec: &mut [Complex64],
        scratch: &mut [f64],
    ) -> ContactSolution {
        let residual = Residual::evaluate(problem, &pressure, &displacement, spec, scratch);
        ContactSolution {
            pressure,
            displacement,
            p0: problem.p0,
            stats: SolveStats {
                solver: self.solver,
                iterations,
                residual,
                wall_s: self.began.elapsed().as_secs_f64(),
                warm: self.warm,
            },
        }
    }

    /// The end of a solve stopped for `reason` after `iterations` iterations: `solution`
    /// if its residual meets `tol`, and otherwise the error, which reports the smaller of
    /// its residual and `earlier`, the smallest residual an earlier check reached (for a
    /// method that keeps one).
    ///
    /// # Errors
    ///
    /// If the residual of `solution` is above `tol` ([`Error::NotConverged`], with the
    /// points in contact).
    pub fn accept(
        &self,
        solution: ContactSolution,
        tol: f64,
        (iterations, reason): (usize, Termination),
        earlier: Option<f64>,
    ) -> Result<ContactSolution> {
        let residual = solution.stats.residual.value();
        if residual <= tol {
            return Ok(solution);
        }
        let mut error = self.not_converged(
            (iterations, reason),
            earlier.map_or(residual, |r| residual.min(r)),
            tol,
        );
        if let Error::NotConverged { contact_points, .. } = &mut error {
            *contact_points = Some(solution.pressure.iter().filter(|&&p| p > 0.0).count());
        }
        Err(error)
    }

    /// The error of a solve stopped for `reason` after `iterations` iterations with
    /// `residual` above `tol`.
    pub fn not_converged(
        &self,
        (iterations, reason): (usize, Termination),
        residual: f64,
        tol: f64,
    ) -> Error {
        Error::NotConverged {
            solver: self.solver,
            reason,
            iterations,
            residual,
            tol,
            contact_points: None,
        }
    }

    /// The error of a solve that met a non-finite `what` at iteration `iteration`.
    pub fn non_finite(&self, what: &'static str, iteration: usize) -> Error {
        Error::NonFinite {
            solver: self.solver,
            what,
            iteration,
        }
    }

    /// The error of a solve of `problem` whose contact set emptied at iteration
    /// `iteration`.
    pub fn lost_contact(&self, problem: &ContactProblem, iteration: usize) -> Error {
        Error::LostContact {
            solver: self.solver,
            iteration,
            p0: problem.p0,
        }
    }
}
