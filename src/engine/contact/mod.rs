//! The hard-wall contact problem, its solution, and the solver-independent residual.
//!
//! Problem ([`crate::conventions`], section 2): find the displacement `u` of the elastic surface and the
//! contact pressure `p` over a rigid substrate of heights `h` such that
//!
//! ```text
//!     g = u - h >= 0,   p >= 0,   p g = 0,   mean(p) = p0,   p~(q) = (q E*/2) u~(q), q != 0.
//! ```
//!
//! One file for each part, after ContactMechanics' split of physics, system and algorithm:
//!
//! - [`model`]: the elastic body as the solvers see it, [`Model`] (see "The elastic
//!   operator" there); no solver computes `q E*/2` itself;
//! - [`problem`]: one problem, [`ContactProblem`] (a model, heights, the mean pressure), and
//!   the gap [`gap`];
//! - [`residual`]: the solver-independent [`Residual`] every solution is judged by, each
//!   component written once;
//! - [`solution`]: a converged [`ContactSolution`] and how it was reached, [`SolveStats`].
//!
//! Every item is re-exported here: `engine::contact::Model` is `engine::contact::model::Model`.

pub mod model;
pub mod problem;
pub mod residual;
pub mod solution;

pub use model::Model;
pub use problem::{gap, ContactProblem};
pub use residual::Residual;
pub use solution::{ContactSolution, SolveStats};
