//! # persson-check
//!
//! A theory-versus-simulation harness for Persson's contact mechanics of randomly rough
//! elastic surfaces, after Dapp, Prodanov & Müser, J. Phys.: Condens. Matter 26, 355002
//! (2014) ("the paper"). A rigid self-affine surface is pressed against an elastic
//! half-space; hard-wall contact is solved with GFMD and with constrained conjugate
//! gradients while roughness is added one magnification at a time, and each assumption of
//! Persson's theory is measured against the simulation.
//!
//! ## Units
//!
//! Lengths are in grid spacings (`a = 1`), pressures in units of `E*` (`E* = 1`), and
//! generated surfaces have unit rms gradient at full resolution, so that `p0` is also the
//! reduced pressure `p0 / (E* g_bar)` at full resolution.
//!
//! ## Fourier convention
//!
//! `f~(q) = N^-2 sum_r f(r) exp(-i q.r)`, `f(r) = sum_q f~(q) exp(i q.r)`, so that
//! `mean(f^2) = sum_q |f~(q)|^2`, with `q = 2 pi (m, n) / L`. Real fields are stored as
//! half spectra ([`grid`]).
//!
//! ## Map
//!
//! * [`grid`], [`fft`], [`field`]: the periodic grid, its transforms and reductions;
//! * [`spectrum`], [`surface`]: self-affine spectra and realizations;
//! * [`elastic`]: the half-space Green's function and elastic energy;
//! * [`contact`], [`solver`], [`load`]: the hard-wall problem, its two solvers, and the
//!   load that gives a target contact area;
//! * [`persson`]: Persson's theory, original and corrected, on a realization's own spectrum;
//! * [`sweep`]: magnification sweeps with warm starts;
//! * [`validation`], [`area`]: named validations with verdicts, and the experiments
//!   behind them;
//! * [`modes`]: the single-mode elastic energy, Persson's assumptions (d) and (e);
//! * [`energy`]: the total elastic energy and the incremental correction factor;
//! * [`stats`], [`plot`]: estimates with error bars, and figures;
//! * [`crate::engine::reference`]: closed-form solutions the solvers are tested against;
//! * [`npy`], [`scene`], [`io`]: `.npy` fields, scene files, atomic writes.

pub mod engine;
pub mod error;
pub mod experiments;
pub mod io;
pub mod persson;
pub mod plot;
pub mod provenance;
pub mod report;
pub mod speed;
pub mod stats;
pub mod validation;

pub use error::{Error, Result};
