//! Hard-wall contact solvers (SPEC section 3).
//!
//! * [`Gfmd`]: Green's function molecular dynamics as in the paper: damped dynamics of the
//!   displacement modes in reciprocal space with the hard wall applied in real space,
//!   mass-weighted so that every mode shares one frequency, relaxed with FIRE.
//! * [`ConstrainedCg`]: constrained conjugate gradients on the pressure
//!   (Polonsky & Keer 1999), the algorithm of tamaas and ContactMechanics.
//!
//! Both implement [`crate::contact::Solver`], start cold or from a previous solution, stop
//! at the solver-independent [`crate::contact::Residual`], and fail with
//! [`crate::Error::NotConverged`] (carrying the residual) or [`crate::Error::NonFinite`]
//! rather than return an unconverged field.

mod cg;
mod gfmd;

pub use cg::ConstrainedCg;
pub use gfmd::{FireParams, Gfmd};

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::contact::{Model, Solver};

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

/// `out = K^-1 x`: the zero-mean displacement produced by the pressure field `x`.
/// `spec` is work space.
pub(crate) fn apply_compliance(model: &Model, x: &[f64], out: &mut [f64], spec: &mut [Complex64]) {
    model.fft.forward(x, spec);
    for (s, c) in spec.iter_mut().zip(model.halfspace.compliance()) {
        *s *= *c;
    }
    model.fft.inverse_in_place(spec, out);
}

/// Resizes `v` to `len` (contents unspecified).
pub(crate) fn ensure_len<T: Clone + Default>(v: &mut Vec<T>, len: usize) {
    if v.len() != len {
        v.clear();
        v.resize(len, T::default());
    }
}
