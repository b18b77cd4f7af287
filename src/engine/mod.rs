//! The engine: one hard-wall contact problem on a periodic grid, and the sweeps that solve
//! it again while roughness is added.
//!
//! What it may use: [`crate::error`], [`crate::io`] and [`crate::stats`], nothing above.
//! Nothing here knows about Persson's theory, experiments or validations.
//!
//! * [`grid`], [`fft`], [`field`]: the periodic grid, its real transforms, and reductions
//!   that give the same bits on any number of threads;
//! * [`spectrum`], [`surface`]: self-affine spectra and realizations, magnification;
//! * [`elastic`]: the half-space's Green's function and elastic energy;
//! * [`boussinesq`]: the free-boundary half-space (a pixel's Boussinesq response) on a
//!   doubled, zero-padded grid, for surfaces that are not periodic;
//! * [`contact`]: the problem, its solution and the solver-independent residual;
//! * [`distance`]: the Euclidean distance transform of the periodic grid (how far each
//!   point lies from the nearest point of a set);
//! * [`solver`]: the [`solver::Solver`] trait, GFMD and constrained conjugate gradients on
//!   one scaffold (an executor that runs either, their work space, warm starts and the
//!   packaging of a solution), and [`solver::Watched`], which shows every iteration to a
//!   progress display or a cancel check;
//! * [`load`]: the load that gives a target contact area;
//! * [`sweep`]: one realization solved at a sequence of magnifications, warm-started;
//! * [`climb`]: a sweep's fixed-load steps through a list of magnifications, each step
//!   recorded; [`history`]: every point's contact history over a climb (left, came back,
//!   the flux into and out of contact over an interval); [`contact_change`]: which points
//!   entered or left contact between two solutions, and the maps' packing and colours;
//! * [`load_curve`]: one surface solved at increasing loads, each solve warm-started from
//!   the last that converged, with a time budget per load;
//! * [`scene`]: scene files (a surface and a solve);
//! * [`tolerance`]: the slacks of comparisons between magnifications and shells;
//! * [`mod@reference`]: closed-form solutions the solvers are tested against;
//! * [`wide`]: the element-wise loops compiled for the processor's widest vectors (AVX2)
//!   where it has them, with the same numbers.

pub mod boussinesq;
pub mod climb;
pub mod contact;
pub mod contact_change;
pub mod distance;
pub mod elastic;
pub mod fft;
pub mod field;
pub mod grid;
pub mod history;
pub mod load;
pub mod load_curve;
pub mod reference;
pub mod scene;
pub mod solver;
pub mod spectrum;
pub mod surface;
pub mod sweep;
#[cfg(test)]
pub(crate) mod testing;
pub mod tolerance;
pub mod wide;
