//! # persson-check
//!
//! A theory-versus-simulation harness for Persson's contact mechanics of randomly rough
//! elastic surfaces, after Dapp, Prodanov & Müser, J. Phys.: Condens. Matter 26, 355002
//! (2014) ("the paper"). A rigid self-affine surface is pressed against an elastic
//! half-space; hard-wall contact is solved with GFMD, with constrained conjugate gradients
//! and with FIRE while roughness is added one magnification at a time, and each assumption
//! of Persson's theory is measured against the simulation.
//!
//! Units, the Fourier convention, magnification, the residual, the validations and the
//! command-line contract are fixed in [`conventions`]; in short: lengths in grid spacings,
//! pressures in units of `E*`, surfaces of unit rms gradient, and
//! `f~(q) = N^-2 sum_r f(r) exp(-i q.r)`.
//!
//! ## Layers
//!
//! Each folder is a layer and uses only the layers below it (a test in `tests/` checks
//! this, and that no two modules depend on each other):
//!
//! | layer | what it is |
//! |---|---|
//! | [`tasks`] | the tasks both front ends offer (surface, solve, sweep, theory, validations, surface checks, parsers) |
//! | [`report`], [`measured`] | the Markdown scorecard, from outcome files; Persson checked on measured height maps (`check-surface`) |
//! | [`validation`] | definitions, verdicts, the registry of experiments, the runner |
//! | [`experiments`], [`speed`] | the measurements behind the validations; the speed study |
//! | [`persson`] | Persson's theory on a realization's own spectrum |
//! | [`engine`] | grid, FFT, surfaces, half-space, contact problem, solvers, sweeps |
//! | [`plot`] | figure descriptions and their rendering |
//! | [`io`], [`stats`], [`provenance`] | atomic files, `.npy`, checkpoints; estimates with errors; provenance |
//! | [`error`] | the error type |
//!
//! The binary's subcommands (`src/commands/`) and the Python package (`python/`) sit on
//! top, and call [`tasks`] for everything they both offer.
//!
//! ## The paper's equations
//!
//! The code cites the paper's equations by their LaTeX labels; their printed numbers:
//!
//! | label | printed | what |
//! |---|---|---|
//! | `1Gaussian` | (2) | Gaussian transition probability |
//! | `broadening` | (3) | shell broadening `Dp^2` |
//! | `transitionFinal` | (4) | mirror-Gaussian transition probability |
//! | `pressureDistOri` | (5) | pressure distribution of the original theory |
//! | `gamma` | (8) | correction factor `S(a_r) = gamma + (1 - gamma) a_r^2` |
//! | `elasticEnergy_h_q` | (9) | Persson's energy of a mode, `E_P(p0, q)` |
//! | `elasticEnergy_h_tot` | (11a) | total `E_P(p0)` |
//! | `elasticEnergy_h_tot_wS` | (11b) | total corrected `E_c(p0)` |
//! | `elasticEnergy_u` | (12) | the exact energies, (12a) and (12b) |
//! | `elasticEnergy_u_q` | (12a) | exact energy of a mode, `E_exa(p0, q, zeta)` |
//! | `elasticEnergy_u_tot` | (12b) | exact total `E_exa(p0, zeta)` |
//! | `contactArea` | (15) | empirical contact-area law |
//! | `switching` | (16) | its switching function |
//! | `elastic_energy_norm` | (19) | normalised energy of a band, `E_norm` |
//! | `elastic_energy_norm_predicted` | (20) | its prediction, `S Theta(zeta - zeta_t)` |
//! | `S_q_numerical` | (21) | incremental correction factor `S~` |
//! | `2ndMoment` | (A.3) | second moment of the mirror Gaussian |
//! | `approxDeltaPress` | (A.4) | closed-form start of its inversion |

#[doc = include_str!("../docs/conventions.md")]
pub mod conventions {}

pub mod engine;
pub mod error;
pub mod experiments;
pub mod io;
pub mod measured;
pub mod persson;
pub mod plot;
pub mod provenance;
pub mod report;
pub mod speed;
pub mod stats;
pub mod tasks;
pub mod validation;

pub use error::{Error, Result};
