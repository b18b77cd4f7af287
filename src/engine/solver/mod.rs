//! Hard-wall contact solvers (SPEC section 3).
//!
//! * [`Gfmd`]: Green's function molecular dynamics as in the paper: damped dynamics of the
//!   displacement modes in reciprocal space with the hard wall applied in real space,
//!   mass-weighted so that every mode shares one frequency, relaxed with FIRE.
//! * [`ConstrainedCg`]: constrained conjugate gradients on the pressure
//!   (Polonsky & Keer 1999), the algorithm of tamaas and ContactMechanics.
//!
//! Both implement [`crate::engine::contact::Solver`], start cold or from a previous solution, stop
//! at the solver-independent [`crate::engine::contact::Residual`], and fail with
//! [`crate::Error::NotConverged`] (carrying the residual) or [`crate::Error::NonFinite`]
//! rather than return an unconverged field.

mod cg;
mod gfmd;

pub use cg::ConstrainedCg;
pub use gfmd::{FireParams, Gfmd};

use serde::{Deserialize, Serialize};

use crate::engine::contact::Solver;

/// The solvers by name, for scenes and the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum SolverKind {
    /// Green's function molecular dynamics with FIRE.
    Gfmd,
    /// Constrained conjugate gradients (Polonsky-Keer).
    #[default]
    Cg,
}

impl SolverKind {
    /// A fresh solver of this kind.
    pub fn build(self) -> Box<dyn Solver + Send> {
        match self {
            SolverKind::Gfmd => Box::new(Gfmd::default()),
            SolverKind::Cg => Box::new(ConstrainedCg::default()),
        }
    }

    /// The solver's short name.
    pub fn name(self) -> &'static str {
        match self {
            SolverKind::Gfmd => "gfmd",
            SolverKind::Cg => "cg",
        }
    }
}

/// Resizes `v` to `len` (contents unspecified).
pub(crate) fn ensure_len<T: Clone + Default>(v: &mut Vec<T>, len: usize) {
    if v.len() != len {
        v.clear();
        v.resize(len, T::default());
    }
}
