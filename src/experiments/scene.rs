//! The fields every experiment's scene repeats, declared once.
//!
//! A scene of the validations that follow one self-affine surface model over several
//! realizations starts with the same six keys:
//!
//! ```toml
//! n = 128            # points per side
//! hurst = 0.8        # Hurst exponent H, in (0, 1)
//! lambda_l = 64      # long-wavelength cutoff (grid units), at most n
//! lambda_s = 4       # short-wavelength cutoff, at least 2 grid spacings
//! seeds = [1, 2, 3]  # realizations, distinct
//! tol = 1e-8         # solver residual (see engine::contact::Residual)
//! ```
//!
//! `scene!` declares a scene struct with these fields followed by the experiment's own,
//! and gives it [`Base`]: the surface parameters of a seed, its realization, a sweep, and
//! the range checks, so that no experiment writes them again. The solver is not part of a
//! scene: the runner runs every scene with each solver it is asked for (GFMD for the
//! headline, CG for the cross-check), and a job learns its solver from its
//! [`JobContext`](super::JobContext). (The fields are written into
//! the struct rather than flattened with `#[serde(flatten)]`: flattening loses the
//! position of a bad value in the file and the name of its key in the error message.)

use crate::engine::contact::Model;
use crate::engine::grid::Grid;
use crate::engine::solver::{SolveOptions, SolverKind};
use crate::engine::surface::{Surface, SurfaceParams};
use crate::engine::sweep::Sweep;
use crate::error::Result;

/// The common part of a scene, borrowed from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Base<'a> {
    /// Points per side.
    pub n: usize,
    /// Hurst exponent.
    pub hurst: f64,
    /// Long-wavelength cutoff (grid units).
    pub lambda_l: f64,
    /// Short-wavelength cutoff (grid units).
    pub lambda_s: f64,
    /// Realizations.
    pub seeds: &'a [u64],
    /// Residual tolerance.
    pub tol: f64,
}

/// A generated realization and the elastic model on its grid (`E* = 1`).
pub struct Realization {
    /// The surface.
    pub surface: Surface,
    /// The model on its grid.
    pub model: Model,
}

impl Base<'_> {
    /// The generator parameters of the realization `seed`.
    pub fn params(&self, seed: u64) -> SurfaceParams {
        SurfaceParams::new(self.n, self.hurst, self.lambda_l, self.lambda_s, seed)
    }

    /// `zeta_max = lambda_l / lambda_s`.
    pub fn zeta_max(&self) -> f64 {
        self.lambda_l / self.lambda_s
    }

    /// How many distinct shells (`k2 = mx^2 + my^2`) a magnification climb from `zeta_from`
    /// (excluded) to `zeta_to` (included) resolves one at a time: the steps of a climb
    /// through every shell, counted on the grid without generating a surface.
    pub fn shells(&self, zeta_from: f64, zeta_to: f64) -> usize {
        let Ok(grid) = Grid::new(self.n, 1.0) else {
            return 0;
        };
        let lo = if zeta_from > 0.0 {
            grid.shell_limit(zeta_from, self.lambda_l)
        } else {
            0
        };
        let half = (self.n / 2) as u64;
        let hi = (grid.shell_limit(zeta_to, self.lambda_l) as u64).min(2 * half * half);
        let mut seen = vec![false; hi as usize + 1];
        let r = (hi as f64).sqrt() as u64;
        for i in 0..=r.min(half) {
            for j in i..=r.min(half) {
                let k2 = i * i + j * j;
                if k2 <= hi {
                    seen[k2 as usize] = true;
                }
            }
        }
        seen.iter()
            .enumerate()
            .filter(|&(k2, &s)| s && k2 as u64 > lo as u64)
            .count()
    }

    /// The solver's options.
    pub fn solve_options(&self) -> SolveOptions {
        SolveOptions::with_tol(self.tol)
    }

    /// Checks the grid, the spectrum against the grid, the seeds and the tolerance; errors
    /// name the field.
    pub fn validate(&self) -> Result<()> {
        let grid = Grid::new(self.n, 1.0)?;
        self.params(0).spectrum.validate(&grid)?;
        crate::error::check_seeds(self.seeds)?;
        self.solve_options().validate()
    }

    /// The realization `seed` on its model.
    pub fn realization(&self, seed: u64) -> Result<Realization> {
        let surface = Surface::generate(&self.params(seed))?;
        let model = Model::new(surface.grid().clone(), 1.0)?;
        Ok(Realization { surface, model })
    }

    /// A magnification sweep of `r` with `solver` at this scene's tolerance.
    pub fn sweep<'r>(&self, r: &'r Realization, solver: SolverKind) -> Sweep<'r> {
        Sweep::new(&r.surface, &r.model, solver, self.solve_options())
    }
}

/// Declares an experiment's scene: the fields of [`Base`] (`n`, `hurst`, `lambda_l`,
/// `lambda_s`, `seeds`, `tol`) followed by the experiment's own, with serde
/// derives that refuse unknown keys, and a `base()` accessor.
macro_rules! scene {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $( $(#[$fmeta:meta])* pub $field:ident : $ty:ty, )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            /// Points per side.
            pub n: usize,
            /// Hurst exponent, in (0, 1).
            pub hurst: f64,
            /// Long-wavelength cutoff (grid units).
            pub lambda_l: f64,
            /// Short-wavelength cutoff (grid units).
            pub lambda_s: f64,
            /// Realizations.
            pub seeds: Vec<u64>,
            /// Residual tolerance.
            pub tol: f64,
            $( $(#[$fmeta])* pub $field: $ty, )*
        }

        impl $name {
            /// The fields every scene shares.
            pub fn base(&self) -> $crate::experiments::scene::Base<'_> {
                $crate::experiments::scene::Base {
                    n: self.n,
                    hurst: self.hurst,
                    lambda_l: self.lambda_l,
                    lambda_s: self.lambda_s,
                    seeds: &self.seeds,
                    tol: self.tol,
                }
            }
        }
    };
}
pub(crate) use scene;
