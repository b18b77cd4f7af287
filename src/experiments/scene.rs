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
//! `scene!` declares a scene struct with these fields followed by the experiment's own, and
//! gives it [`Base`]: the surface model (the one [`SurfaceModel`] of scene files, the
//! command line and Python), the realization of a seed, its realization, a sweep, and the
//! range checks, so that no experiment writes them again. `step_scene!` adds the fields of
//! one step of magnification at fixed load (`contact_area`, `zeta`, `dzeta`), with the
//! check of the step and the step itself ([`Base::validate_step`], [`Base::step`]). The
//! solver is not part of a scene: the runner runs every scene with each solver it is asked
//! for (GFMD for the headline, CG for the cross-check), and a job learns its solver from
//! its [`JobContext`](super::JobContext). (The fields are written into
//! the struct rather than flattened with `#[serde(flatten)]`: flattening loses the
//! position of a bad value in the file and the name of its key in the error message.)

use crate::engine::contact::{ContactSolution, Model};
use crate::engine::grid::Grid;
use crate::engine::scene::check_zeta;
use crate::engine::solver::{SolveOptions, SolverKind};
use crate::engine::surface::{Surface, SurfaceModel};
use crate::engine::sweep::Sweep;
use crate::error::{check_open, check_positive, Error, Result};
use crate::stats::realizations;

/// The common part of a scene, borrowed from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Base<'a> {
    /// The surface model (Gaussian, `g_bar = 1`, no roll-off; its seed is each of
    /// `seeds` in turn).
    pub surface: SurfaceModel,
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

impl<'a> Base<'a> {
    /// The common part of a scene: the surface model of `n`, `hurst`, `lambda_l` and
    /// `lambda_s`, over `seeds`, solved to `tol`.
    pub fn new(
        n: usize,
        hurst: f64,
        lambda_l: f64,
        lambda_s: f64,
        seeds: &'a [u64],
        tol: f64,
    ) -> Self {
        Self {
            surface: SurfaceModel {
                seed: None,
                ..SurfaceModel::new(n, hurst, lambda_l, lambda_s, 0)
            },
            seeds,
            tol,
        }
    }

    /// The realization `seed` of the surface model.
    pub fn params(&self, seed: u64) -> SurfaceModel {
        self.surface.seeded(seed)
    }

    /// `zeta_max = lambda_l / lambda_s`.
    pub fn zeta_max(&self) -> f64 {
        self.surface.zeta_max()
    }

    /// How many distinct shells (`k2 = mx^2 + my^2`) a magnification climb from `zeta_from`
    /// (excluded) to `zeta_to` (included) resolves one at a time: the steps of a climb
    /// through every shell, counted on the grid without generating a surface.
    pub fn shells(&self, zeta_from: f64, zeta_to: f64) -> usize {
        let Ok(grid) = Grid::new(self.surface.n, 1.0) else {
            return 0;
        };
        let lambda_l = self.surface.lambda_l;
        let lo = if zeta_from > 0.0 {
            grid.shell_limit(zeta_from, lambda_l)
        } else {
            0
        };
        let half = (self.surface.n / 2) as u64;
        let hi = (grid.shell_limit(zeta_to, lambda_l) as u64).min(2 * half * half);
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
        self.surface.validate()?;
        crate::error::check_seeds(self.seeds)?;
        self.solve_options().validate()
    }

    /// Checks the scene's fields ([`Base::validate`]) and one step of magnification at
    /// fixed load: the contact area that sets the load in (0, 1), `zeta` in
    /// `[1, zeta_max]`, `dzeta > 0` with `zeta + dzeta <= zeta_max`; errors name the field.
    pub fn validate_step(&self, contact_area: f64, zeta: f64, dzeta: f64) -> Result<()> {
        self.validate()?;
        check_open("contact_area", contact_area, 0.0, 1.0)?;
        let zeta_max = self.zeta_max();
        check_zeta(zeta, zeta_max)?;
        check_positive("dzeta", dzeta)?;
        check_zeta(zeta + dzeta, zeta_max).map_err(|_| {
            Error::invalid(
                "dzeta",
                dzeta,
                format!("with zeta + dzeta <= zeta_max = {zeta_max}"),
            )
        })
    }

    /// The runs in words, as the accounts open: `"Over 8 realizations (H = 0.8, 256x256
    /// grid, lambda_l = 128, lambda_s = 4)"`.
    pub fn over(&self) -> String {
        format!(
            "Over {} (H = {}, {}x{} grid, lambda_l = {}, lambda_s = {})",
            realizations(self.seeds.len()),
            self.surface.hurst,
            self.surface.n,
            self.surface.n,
            self.surface.lambda_l,
            self.surface.lambda_s
        )
    }

    /// The runs in words, grid first: `"8 realizations (256x256, H = 0.8, lambda_l = 128,
    /// lambda_s = 4)"`.
    pub fn runs(&self) -> String {
        format!(
            "{} ({}x{}, H = {}, lambda_l = {}, lambda_s = {})",
            realizations(self.seeds.len()),
            self.surface.n,
            self.surface.n,
            self.surface.hurst,
            self.surface.lambda_l,
            self.surface.lambda_s
        )
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

    /// One step of magnification at fixed load: `r` solved at `zeta` at the load that
    /// gives `contact_area` there, then at `zeta + dzeta` at the same load, warm-started.
    pub fn step(
        &self,
        r: &Realization,
        solver: SolverKind,
        zeta: f64,
        dzeta: f64,
        contact_area: f64,
    ) -> Result<Step> {
        let mut sweep = self.sweep(r, solver);
        let (p0, before) = load_at(&mut sweep, zeta, contact_area)?;
        let after = sweep.solve_at(zeta + dzeta, p0)?.clone();
        Ok(Step { p0, before, after })
    }

    /// `r` solved at `zeta` at the load that gives `contact_area` there: the load and
    /// the solution (the first half of [`Base::step`]).
    pub fn solve_at_load(
        &self,
        r: &Realization,
        solver: SolverKind,
        zeta: f64,
        contact_area: f64,
    ) -> Result<(f64, ContactSolution)> {
        load_at(&mut self.sweep(r, solver), zeta, contact_area)
    }
}

/// The load that gives `contact_area` at `zeta` on `sweep`, and the solution there.
fn load_at(sweep: &mut Sweep, zeta: f64, contact_area: f64) -> Result<(f64, ContactSolution)> {
    let p0 = sweep.find_load(zeta, contact_area)?;
    let solution = sweep
        .solution()
        .expect("find_load keeps its solution")
        .clone();
    Ok((p0, solution))
}

/// The two solutions of one step of magnification at fixed load ([`Base::step`]).
pub struct Step {
    /// The load.
    pub p0: f64,
    /// The solution before the step.
    pub before: ContactSolution,
    /// The solution after it.
    pub after: ContactSolution,
}

/// Whether `list` is non-empty and strictly increasing.
pub fn increasing<T: PartialOrd>(list: &[T]) -> bool {
    !list.is_empty() && list.windows(2).all(|w| w[1] > w[0])
}

/// The error of a list field `field` that is not what `allowed` says.
pub fn list_error<T: std::fmt::Debug>(field: &str, list: &[T], allowed: &str) -> Error {
    Error::invalid(field, format!("{list:?}"), allowed)
}

/// Checks that the list field `field` is non-empty and strictly increasing.
pub fn check_increasing<T: PartialOrd + std::fmt::Debug>(field: &str, list: &[T]) -> Result<()> {
    if increasing(list) {
        Ok(())
    } else {
        Err(list_error(field, list, "a non-empty increasing list"))
    }
}

/// Declares a struct whose first fields are the bracketed ones (each with its docs),
/// followed by the struct's own, with serde derives that refuse unknown keys and the items
/// after `impl` in its `impl` block: the one shape of [`scene!`] and of
/// [`other_grid!`](super::other_grid::other_grid), which name their fields.
macro_rules! fields_first {
    (
        [$( $(#[$lmeta:meta])* $lead:ident : $lty:ty, )*]
        impl { $($items:tt)* }
        $(#[$meta:meta])*
        pub struct $name:ident {
            $( $(#[$fmeta:meta])* pub $field:ident : $ty:ty, )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $( $(#[$lmeta])* pub $lead: $lty, )*
            $( $(#[$fmeta])* pub $field: $ty, )*
        }

        impl $name {
            $($items)*
        }
    };
}
pub(crate) use fields_first;

/// The part of a scene that its planned realizations (`more_seeds`) make up
/// ([`crate::experiments::Jobs::part`]).
pub const PLANNED: &str = "planned";

/// Whether `parts` (of a merge that leaves them out) names the planned realizations.
pub fn leaves_out_planned(parts: &std::collections::BTreeSet<String>) -> bool {
    parts.contains(PLANNED)
}

/// A scene's JSON as the jobs' keys see it: without the planned realizations
/// (`more_seeds`, at any depth: a variant's or the waterfall's too), which only add jobs
/// of their own.
pub fn without_planned(mut scene: serde_json::Value) -> serde_json::Value {
    fn strip(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(map) => {
                map.remove("more_seeds");
                map.values_mut().for_each(strip);
            }
            serde_json::Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    strip(&mut scene);
    scene
}

/// A scene's JSON as its statistics see it: wherever a table lists `seeds` and
/// `more_seeds`, the planned realizations follow the others in `seeds` (a plan with a
/// single `seed`, the waterfall's, keeps its `more_seeds`).
pub fn planned_folded(mut scene: serde_json::Value) -> serde_json::Value {
    fn fold(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(map) => {
                if map.get("seeds").is_some_and(|s| s.is_array()) {
                    if let Some(serde_json::Value::Array(more)) = map.remove("more_seeds") {
                        if let Some(serde_json::Value::Array(seeds)) = map.get_mut("seeds") {
                            seeds.extend(more);
                        }
                    }
                }
                map.values_mut().for_each(fold);
            }
            serde_json::Value::Array(items) => items.iter_mut().for_each(fold),
            _ => {}
        }
    }
    fold(&mut scene);
    scene
}

/// `scene` with its planned realizations folded into its `seeds` ([`planned_folded`]), as
/// the statistics of a run see it.
pub fn with_planned_folded<S: serde::Serialize + serde::de::DeserializeOwned>(scene: &S) -> S {
    let json = serde_json::to_value(scene).expect("scenes serialise");
    serde_json::from_value(planned_folded(json)).expect("a scene with its seeds folded reads back")
}

/// Declares an experiment's scene: the fields of [`Base`] (`n`, `hurst`, `lambda_l`,
/// `lambda_s`, `seeds`, `more_seeds`, `tol`) followed by the experiment's own, with serde
/// derives that refuse unknown keys, and `base()` and `all_seeds()` accessors.
macro_rules! scene {
    ($($item:tt)*) => {
        $crate::experiments::scene::fields_first! {
            [
                /// Points per side.
                n: usize,
                /// Hurst exponent, in (0, 1).
                hurst: f64,
                /// Long-wavelength cutoff (grid units).
                lambda_l: f64,
                /// Short-wavelength cutoff (grid units).
                lambda_s: f64,
                /// Realizations.
                seeds: Vec<u64>,
                /// Realizations that a plan of sample sizes added after the scene's
                /// results were stored (`docs/power-plan.md`): run and concluded as `seeds`
                /// are, left out of the jobs' keys (the stored results keep theirs), and
                /// a part of the scene of their own ([`PLANNED`](crate::experiments::scene::PLANNED))
                /// that a merge with `--partial` leaves out until all their jobs have
                /// results.
                #[serde(default, skip_serializing_if = "Vec::is_empty")]
                more_seeds: Vec<u64>,
                /// Residual tolerance.
                tol: f64,
            ]
            impl {
                /// Every realization: `seeds`, then `more_seeds`.
                pub fn all_seeds(&self) -> Vec<u64> {
                    self.seeds.iter().chain(&self.more_seeds).copied().collect()
                }

                /// The fields every scene shares.
                pub fn base(&self) -> $crate::experiments::scene::Base<'_> {
                    $crate::experiments::scene::Base::new(
                        self.n,
                        self.hurst,
                        self.lambda_l,
                        self.lambda_s,
                        &self.seeds,
                        self.tol,
                    )
                }
            }
            $($item)*
        }
    };
}
pub(crate) use scene;

/// Declares the scene of one step of magnification at fixed load: the fields of [`scene!`],
/// then `contact_area`, `zeta` and `dzeta`, then the experiment's own; with
/// `validate_one_step()` ([`Base::validate_step`] of these three) and `one_step(r,
/// solver)` (the step of realization `r`, [`Base::step`]).
macro_rules! step_scene {
    (
        $(#[$meta:meta])*
        pub struct $name:ident { $($own:tt)* }
    ) => {
        $crate::experiments::scene::scene! {
            $(#[$meta])*
            pub struct $name {
                /// Relative contact area at `zeta` (sets the load).
                pub contact_area: f64,
                /// Magnification before the step.
                pub zeta: f64,
                /// The step of magnification.
                pub dzeta: f64,
                $($own)*
            }
        }

        impl $name {
            /// Checks the scene's fields and its step; errors name the field
            /// ([`Base::validate_step`](crate::experiments::scene::Base::validate_step)).
            pub fn validate_one_step(&self) -> $crate::error::Result<()> {
                self.base()
                    .validate_step(self.contact_area, self.zeta, self.dzeta)
            }

            /// The step of realization `r` from `zeta` to `zeta + dzeta` with `solver`, at
            /// the load that gives `contact_area` at `zeta`.
            pub fn one_step(
                &self,
                r: &$crate::experiments::scene::Realization,
                solver: $crate::engine::solver::SolverKind,
            ) -> $crate::error::Result<$crate::experiments::scene::Step> {
                self.base()
                    .step(r, solver, self.zeta, self.dzeta, self.contact_area)
            }
        }
    };
}
pub(crate) use step_scene;

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn planned_scene() -> serde_json::Value {
        json!({
            "seeds": [1, 2],
            "more_seeds": [3, 4],
            "variants": [{"name": "v", "seeds": [1], "more_seeds": [2]}],
            "waterfall": {"seed": 1, "more_seeds": [2, 3]},
        })
    }

    #[test]
    fn the_keys_never_see_planned_realizations_at_any_depth() {
        let keyed = without_planned(planned_scene());
        assert_eq!(
            keyed,
            json!({
                "seeds": [1, 2],
                "variants": [{"name": "v", "seeds": [1]}],
                "waterfall": {"seed": 1},
            })
        );
    }

    #[test]
    fn the_statistics_see_planned_realizations_after_the_others() {
        let folded = planned_folded(planned_scene());
        assert_eq!(
            folded,
            json!({
                "seeds": [1, 2, 3, 4],
                "variants": [{"name": "v", "seeds": [1, 2]}],
                // A single seed's plan keeps its further seeds.
                "waterfall": {"seed": 1, "more_seeds": [2, 3]},
            })
        );
        // A scene without any is unchanged.
        let plain = json!({"seeds": [1, 2], "tol": 1e-6});
        assert_eq!(planned_folded(plain.clone()), plain);
    }
}
