//! What sets the one-step flux: the flux into and out of contact of the paper's
//! contact-change figure (paper, figure "reentry_visualization": 0.675% in, 0.597% out of
//! the area, 4096^2, H = 0.8, a_r = 0.14, zeta 128 -> 129.5) measured again while one
//! setting at a time moves away from a base configuration:
//!
//! * `tol`: the solver's residual tolerance;
//! * `dzeta_over_zeta`: the relative step, in multiples of the headline step's
//!   `dzeta / zeta` (the paper's figure: 1.5 / 128);
//! * `lambda_s`: the discretisation, grid spacings per shortest wavelength, at the same
//!   surface (the grid and `lambda_l` scale with it, so the modes and `zeta` stay);
//! * `lambda_l_over_l`: the roll-off wavelength over the system size, the step kept at the
//!   same place relative to `zeta_max`;
//! * `control`: the step at fixed load (0) or at fixed contact area (1);
//! * `solver`: GFMD (0) or CG (1);
//! * `hurst`: the Hurst exponent, and `contact_area`: the contact area at `zeta` (were the
//!   paper's stated parameters misprinted?); the Hurst exponents of `later_hurst_values`
//!   are rows as those of `hurst_values`, added after the full scene's study had run (the
//!   jobs' keys leave that list out, [`crate::experiments::flux::FluxScene`]'s `key_scene`);
//! * `transition`: the paper's transition scene (section 3.1, figure "reentry_histogram":
//!   H = 0.5, a_r = 0.01, zeta 63 -> 63.3), whose share of the non-contact that enters
//!   contact the paper gives as about 1%.
//!
//! Each row is a mean over realizations with its standard error, as a fraction of the
//! nominal area and of the true contact area at `zeta`, with the net over the mean one-way
//! flux and the share of the non-contact at `zeta` that enters contact (the transition out
//! of the zero-pressure bin). A row also states the step actually taken: the modes it adds
//! and the height variance they carry, relative to the variance at `zeta` (on a coarse
//! grid two nominal steps can add the same shells). Configurations shared by several rows
//! (the base is in every list) run once.
//!
//! Every row also checks the net-flow identity, a counting identity of any two sets of
//! points in contact: those in contact after the step are those before, plus those that
//! entered, less those that left, so the net flow to non-contact, `out - in`, is
//! `-(a_r(zeta + dzeta) - a_r(zeta))` ([`crate::experiments::flux::net_flow_residual`]),
//! whatever the control. At fixed load that is the fall of the contact area over the step;
//! at fixed area the control holds `a_r` (to [`crate::engine::load::HELD_AREA_REL_TOL`],
//! far below what the step changes at fixed load), so the net flow is near zero and the
//! row shows the fluxes of a step that changes the contact's shape but not its size.

mod step;
mod table;

use serde::{Deserialize, Serialize};

use crate::engine::load::HELD_AREA_REL_TOL;
use crate::engine::solver::SolverKind;
use crate::error::{check_once, check_open, check_positive, Error, Result};
use crate::experiments::contact_change::net_over_gross;
use crate::experiments::flux::net_flow_residual;
use crate::experiments::scene::Base;
use crate::stats::Estimate;

pub use self::step::{run, step_taken};
pub use self::table::{study, COLUMNS, KEY};

/// The study, as a scene states it (`[reduced.sensitivity]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensitivityPlan {
    /// Points per side of the base configuration.
    pub n: usize,
    /// Long-wavelength cutoff of the base (grid units).
    pub lambda_l: f64,
    /// Short-wavelength cutoff of the base (grid units).
    pub lambda_s: f64,
    /// Realizations of every configuration.
    pub seeds: Vec<u64>,
    /// Contact area at `zeta` (sets the load).
    pub contact_area: f64,
    /// Magnification before the step, base.
    pub zeta: f64,
    /// Tolerance of the base.
    pub tol: f64,
    /// Solver of the base.
    pub solver: SolverKind,
    /// Tolerances (the base's among them).
    pub tols: Vec<f64>,
    /// Steps `dzeta / zeta` in multiples of the headline step's.
    pub step_factors: Vec<f64>,
    /// Shortest wavelengths in grid spacings, the same surface on a finer or coarser grid.
    pub lambda_s_values: Vec<f64>,
    /// `lambda_l / L` values.
    pub lambda_l_fractions: Vec<f64>,
    /// Also the step at fixed contact area.
    pub fixed_area: bool,
    /// Solvers (the base's among them).
    pub solvers: Vec<SolverKind>,
    /// Hurst exponents (the scene's is the base's).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hurst_values: Vec<f64>,
    /// More Hurst exponents, rows as those of `hurst_values`, added after the full scene's
    /// study had run. The jobs' keys see the plan without this list
    /// ([`crate::experiments::flux::FluxScene`]'s `key_scene`), so the stored results keep
    /// their keys; the new rows' jobs are told apart by their configuration, which names
    /// the exponent.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub later_hurst_values: Vec<f64>,
    /// Contact areas at `zeta` (the base's is `contact_area`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contact_areas: Vec<f64>,
    /// The paper's transition scene as one more row (none: not run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transition: Option<TransitionRow>,
}

/// A row at settings of its own: the paper's transition scene (H = 0.5, a_r = 0.01, zeta
/// 63 -> 63.3), on a grid that resolves it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransitionRow {
    /// Points per side.
    pub n: usize,
    /// Long-wavelength cutoff (grid units).
    pub lambda_l: f64,
    /// Short-wavelength cutoff (grid units).
    pub lambda_s: f64,
    /// Hurst exponent.
    pub hurst: f64,
    /// Contact area at `zeta`.
    pub contact_area: f64,
    /// Magnification before the step.
    pub zeta: f64,
    /// The step.
    pub dzeta: f64,
}

/// One configuration of the study: everything a step depends on besides the Hurst
/// exponent and the seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyConfig {
    /// Points per side.
    pub n: usize,
    /// Long-wavelength cutoff (grid units).
    pub lambda_l: f64,
    /// Short-wavelength cutoff (grid units).
    pub lambda_s: f64,
    /// Contact area at `zeta`.
    pub contact_area: f64,
    /// Magnification before the step.
    pub zeta: f64,
    /// The step.
    pub dzeta: f64,
    /// Tolerance.
    pub tol: f64,
    /// Solver.
    pub solver: SolverKind,
    /// Whether the step keeps the contact area (else the load).
    pub fixed_area: bool,
    /// The relative tolerance the contact area is held to over a step at fixed area
    /// ([`crate::engine::load::HELD_AREA_REL_TOL`]); none at fixed load. Results stored
    /// before the area was held this tightly (a load search's 2e-3, more than the step
    /// changes the area) have none and no longer belong to any job.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area_tol: Option<f64>,
    /// Hurst exponent (none: the scene's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hurst: Option<f64>,
}

/// One realization of one configuration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyJob {
    /// Seed.
    pub seed: u64,
    /// Configuration.
    pub config: StudyConfig,
}

/// What one study job measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyResult {
    /// Contact area at `zeta`.
    pub a_r_old: f64,
    /// Contact area at `zeta + dzeta`.
    pub a_r_new: f64,
    /// Fraction of the nominal area entering contact.
    pub flux_in: f64,
    /// Fraction of the nominal area leaving contact.
    pub flux_out: f64,
    /// Largest solver residual.
    pub max_residual: f64,
    /// Height variance of the modes the step adds, over the height variance at `zeta`
    /// (absent in results stored before it was recorded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub variance_added: Option<f64>,
    /// Modes the step adds (full spectrum, non-zero amplitude).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes_added: Option<u64>,
}

/// A row the plan states, whether or not its jobs have results: its setting, value and
/// label, as the row's own ([`SensitivityRow`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedRow {
    /// The setting varied.
    pub parameter: &'static str,
    /// Its value.
    pub value: f64,
    /// The value in words.
    pub label: String,
}

impl PlannedRow {
    /// Whether `row` is this planned row's result.
    pub fn is(&self, row: &SensitivityRow) -> bool {
        row.parameter == self.parameter && row.value == self.value
    }
}

/// One row of the study: one setting at one value, averaged over realizations.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensitivityRow {
    /// The setting varied (`tol`, `dzeta_over_zeta`, `lambda_s`, `lambda_l_over_l`,
    /// `control`, `solver`, `hurst`, `contact_area`, `transition`).
    pub parameter: String,
    /// Its value (`control`: 0 fixed load, 1 fixed area; `solver`: 0 GFMD, 1 CG).
    pub value: f64,
    /// The value in words.
    pub label: String,
    /// The configuration.
    pub config: StudyConfig,
    /// Realizations.
    pub realizations: usize,
    /// Flux into contact, fraction of the nominal area.
    pub flux_in: Estimate,
    /// Flux out of contact, fraction of the nominal area.
    pub flux_out: Estimate,
    /// Flux into contact, fraction of the true contact area at `zeta`.
    pub flux_in_of_contact: Estimate,
    /// Flux out of contact, fraction of the true contact area at `zeta`.
    pub flux_out_of_contact: Estimate,
    /// Contact area at `zeta`.
    pub contact_area: Estimate,
    /// Net over mean one-way flux, `|out - in| / ((out + in) / 2)`, per realization.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net_over_gross: Option<Estimate>,
    /// Net flow to non-contact, `out - in`, fraction of the nominal area.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net_flow: Option<Estimate>,
    /// The net-flow identity's residual, `(out - in) + (a_r(zeta + dzeta) - a_r(zeta))`,
    /// per realization (none at fixed area, where the identity is not applicable).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net_flow_residual: Option<Estimate>,
    /// Share of the non-contact at `zeta` in contact after the step, `in / (1 - a_r)`.
    // Serialised as "zero_bin": the stored name is kept for the committed results.
    #[serde(rename = "zero_bin", default, skip_serializing_if = "Option::is_none")]
    pub flux_in_of_noncontact: Option<Estimate>,
    /// Height variance the step adds over the variance at `zeta` (absent where the
    /// results did not record it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub variance_added: Option<Estimate>,
    /// Modes the step adds (mean over realizations; equal for all of them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes_added: Option<f64>,
}

impl SensitivityPlan {
    /// Checks the ranges (`step`: the headline's relative step `dzeta / zeta`); errors
    /// name the field.
    pub fn validate(&self, hurst: f64, step: f64) -> Result<()> {
        check_open("sensitivity.contact_area", self.contact_area, 0.0, 1.0)?;
        check_positive("sensitivity.zeta", self.zeta)?;
        crate::error::check_seeds(&self.seeds)?;
        let lists: [(&str, &[f64]); 4] = [
            ("sensitivity.tols", &self.tols),
            ("sensitivity.step_factors", &self.step_factors),
            ("sensitivity.lambda_s_values", &self.lambda_s_values),
            ("sensitivity.lambda_l_fractions", &self.lambda_l_fractions),
        ];
        for (field, values) in lists {
            for &v in values {
                check_positive(field, v)?;
            }
            check_once(field, values)?;
        }
        for &h in &self.hurst_values {
            check_open("sensitivity.hurst_values", h, 0.0, 1.0)?;
        }
        check_once("sensitivity.hurst_values", &self.hurst_values)?;
        for (k, &h) in self.later_hurst_values.iter().enumerate() {
            check_open("sensitivity.later_hurst_values", h, 0.0, 1.0)?;
            if self.hurst_values.contains(&h) || self.later_hurst_values[..k].contains(&h) {
                return Err(Error::invalid(
                    "sensitivity.later_hurst_values",
                    h,
                    "an exponent not already in hurst_values or earlier in this list",
                ));
            }
        }
        for &a in &self.contact_areas {
            check_open("sensitivity.contact_areas", a, 0.0, 1.0)?;
        }
        check_once("sensitivity.contact_areas", &self.contact_areas)?;
        if let Some(t) = &self.transition {
            check_open("sensitivity.transition.hurst", t.hurst, 0.0, 1.0)?;
            check_open(
                "sensitivity.transition.contact_area",
                t.contact_area,
                0.0,
                1.0,
            )?;
            check_positive("sensitivity.transition.zeta", t.zeta)?;
            check_positive("sensitivity.transition.dzeta", t.dzeta)?;
        }
        if self.solvers.is_empty() {
            return Err(Error::invalid("sensitivity.solvers", "[]", "at least one"));
        }
        for (parameter, _, _, config) in self.rows(step) {
            let base = Base::new(
                config.n,
                config.hurst.unwrap_or(hurst),
                config.lambda_l,
                config.lambda_s,
                &self.seeds,
                config.tol,
            );
            base.validate()
                .map_err(|e| e.with_field(&format!("sensitivity.{parameter}")))?;
            crate::engine::scene::check_zeta(config.zeta + config.dzeta, base.zeta_max())
                .map_err(|e| e.with_field(&format!("sensitivity.{parameter}")))?;
        }
        Ok(())
    }

    /// The base configuration, stepping by the relative step `step`.
    pub fn base(&self, step: f64) -> StudyConfig {
        StudyConfig {
            n: self.n,
            lambda_l: self.lambda_l,
            lambda_s: self.lambda_s,
            contact_area: self.contact_area,
            zeta: self.zeta,
            dzeta: step * self.zeta,
            tol: self.tol,
            solver: self.solver,
            fixed_area: false,
            area_tol: None,
            hurst: None,
        }
    }

    /// Every row as `(parameter, value, label, configuration)`, the steps in multiples
    /// of `step`, the headline's relative step.
    pub fn rows(&self, step: f64) -> Vec<(&'static str, f64, String, StudyConfig)> {
        let base = self.base(step);
        let mut rows = Vec::new();
        for &tol in &self.tols {
            let c = StudyConfig {
                tol,
                ..base.clone()
            };
            rows.push(("tol", tol, format!("{tol:e}"), c));
        }
        for &f in &self.step_factors {
            let r = f * step;
            let c = StudyConfig {
                dzeta: r * base.zeta,
                ..base.clone()
            };
            rows.push(("dzeta_over_zeta", r, format!("{f} x the headline step"), c));
        }
        for &ls in &self.lambda_s_values {
            let scale = ls / base.lambda_s;
            let c = StudyConfig {
                n: (base.n as f64 * scale).round() as usize,
                lambda_l: base.lambda_l * scale,
                lambda_s: ls,
                ..base.clone()
            };
            rows.push(("lambda_s", ls, format!("{ls} (n = {})", c.n), c));
        }
        for &fr in &self.lambda_l_fractions {
            let lambda_l = fr * base.n as f64;
            let zeta = base.zeta * lambda_l / base.lambda_l;
            let c = StudyConfig {
                lambda_l,
                zeta,
                dzeta: step * zeta,
                ..base.clone()
            };
            rows.push(("lambda_l_over_l", fr, format!("{fr} (zeta = {zeta})"), c));
        }
        if self.fixed_area {
            for (v, fixed_area, label) in [(0.0, false, "fixed load"), (1.0, true, "fixed area")] {
                let c = StudyConfig {
                    fixed_area,
                    area_tol: fixed_area.then_some(HELD_AREA_REL_TOL),
                    ..base.clone()
                };
                rows.push(("control", v, label.to_string(), c));
            }
        }
        for &solver in &self.solvers {
            let v = solver.index() as f64;
            let c = StudyConfig {
                solver,
                ..base.clone()
            };
            rows.push(("solver", v, solver.name().to_string(), c));
        }
        for &h in self.hurst_values.iter().chain(&self.later_hurst_values) {
            let c = StudyConfig {
                hurst: Some(h),
                ..base.clone()
            };
            rows.push(("hurst", h, format!("H = {h}"), c));
        }
        for &a in &self.contact_areas {
            let c = StudyConfig {
                contact_area: a,
                ..base.clone()
            };
            rows.push(("contact_area", a, format!("a_r = {a}"), c));
        }
        if let Some(t) = &self.transition {
            let c = StudyConfig {
                n: t.n,
                lambda_l: t.lambda_l,
                lambda_s: t.lambda_s,
                contact_area: t.contact_area,
                zeta: t.zeta,
                dzeta: t.dzeta,
                hurst: Some(t.hurst),
                ..base.clone()
            };
            let label = format!(
                "H = {}, a_r = {}, zeta {} -> {} (n = {})",
                t.hurst,
                t.contact_area,
                t.zeta,
                t.zeta + t.dzeta,
                t.n
            );
            rows.push(("transition", t.contact_area, label, c));
        }
        rows
    }

    /// Every row the plan states, run or not (the steps in multiples of `step`).
    pub fn planned(&self, step: f64) -> Vec<PlannedRow> {
        self.rows(step)
            .into_iter()
            .map(|(parameter, value, label, _)| PlannedRow {
                parameter,
                value,
                label,
            })
            .collect()
    }

    /// The jobs: every distinct configuration once, for every seed.
    pub fn jobs(&self, step: f64) -> Vec<StudyJob> {
        let mut configs: Vec<StudyConfig> = Vec::new();
        for (_, _, _, c) in self.rows(step) {
            if !configs.contains(&c) {
                configs.push(c);
            }
        }
        configs
            .into_iter()
            .flat_map(|config| {
                self.seeds.iter().map(move |&seed| StudyJob {
                    seed,
                    config: config.clone(),
                })
            })
            .collect()
    }

    /// The rows from the jobs' results.
    pub fn conclude(
        &self,
        step: f64,
        results: &[(&StudyJob, &StudyResult)],
    ) -> Vec<SensitivityRow> {
        self.rows(step)
            .into_iter()
            .filter_map(|(parameter, value, label, config)| {
                let runs: Vec<&StudyResult> = results
                    .iter()
                    .filter(|(j, _)| j.config == config)
                    .map(|(_, r)| *r)
                    .collect();
                if runs.is_empty() {
                    return None;
                }
                let mean = |f: &dyn Fn(&StudyResult) -> f64| {
                    Estimate::mean_of(&runs.iter().map(|r| f(r)).collect::<Vec<_>>())
                };
                let of_contact = |x: f64, r: &StudyResult| x / r.a_r_old.max(f64::MIN_POSITIVE);
                let of_noncontact =
                    |r: &StudyResult| r.flux_in / (1.0 - r.a_r_old).max(f64::MIN_POSITIVE);
                let variances: Option<Vec<f64>> = runs.iter().map(|r| r.variance_added).collect();
                // A counting identity of any two contact sets, whatever the control.
                let residual = Some(mean(&|r| {
                    net_flow_residual(r.a_r_old, r.a_r_new, r.flux_in, r.flux_out)
                }));
                let modes: Option<Vec<u64>> = runs.iter().map(|r| r.modes_added).collect();
                Some(SensitivityRow {
                    parameter: parameter.to_string(),
                    value,
                    label,
                    config,
                    realizations: runs.len(),
                    flux_in: mean(&|r| r.flux_in),
                    flux_out: mean(&|r| r.flux_out),
                    flux_in_of_contact: mean(&|r| of_contact(r.flux_in, r)),
                    flux_out_of_contact: mean(&|r| of_contact(r.flux_out, r)),
                    contact_area: mean(&|r| r.a_r_old),
                    net_over_gross: Some(mean(&|r| net_over_gross(r.flux_in, r.flux_out))),
                    net_flow: Some(mean(&|r| r.flux_out - r.flux_in)),
                    net_flow_residual: residual,
                    flux_in_of_noncontact: Some(mean(&of_noncontact)),
                    variance_added: variances.map(|v| Estimate::mean_of(&v)),
                    modes_added: modes
                        .map(|m| m.iter().map(|&x| x as f64).sum::<f64>() / m.len() as f64),
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The headline's relative step in these tests.
    const STEP: f64 = 1.5 / 128.0;

    fn plan() -> SensitivityPlan {
        SensitivityPlan {
            n: 64,
            lambda_l: 32.0,
            lambda_s: 4.0,
            seeds: vec![1, 2],
            contact_area: 0.14,
            zeta: 4.0,
            tol: 1e-8,
            solver: SolverKind::Cg,
            tols: vec![1e-6, 1e-8],
            step_factors: vec![0.25, 1.0, 4.0],
            lambda_s_values: vec![2.0, 4.0],
            lambda_l_fractions: vec![0.25, 0.5],
            fixed_area: true,
            solvers: vec![SolverKind::Gfmd, SolverKind::Cg],
            hurst_values: vec![0.3],
            later_hurst_values: vec![0.5],
            contact_areas: vec![0.5],
            transition: Some(TransitionRow {
                n: 128,
                lambda_l: 64.0,
                lambda_s: 4.0,
                hurst: 0.5,
                contact_area: 0.01,
                zeta: 15.0,
                dzeta: 0.3,
            }),
        }
    }

    #[test]
    fn rows_vary_one_setting_and_share_the_base() {
        let p = plan();
        p.validate(0.8, STEP).unwrap();
        let rows = p.rows(STEP);
        assert_eq!(rows.len(), 2 + 3 + 2 + 2 + 2 + 2 + 1 + 1 + 1 + 1);
        // The base appears once per list; the jobs run it once.
        let base = p.base(STEP);
        assert_eq!(rows.iter().filter(|r| r.3 == base).count(), 6);
        let distinct = rows.len() - 6 + 1;
        assert_eq!(p.jobs(STEP).len(), distinct * p.seeds.len());
        // lambda_s = 2: the same surface on a grid half as fine.
        let coarse = &rows
            .iter()
            .find(|r| r.0 == "lambda_s" && r.1 == 2.0)
            .unwrap()
            .3;
        assert_eq!((coarse.n, coarse.lambda_l, coarse.zeta), (32, 16.0, 4.0));
        // lambda_l / L = 1/4: the step at the same place relative to zeta_max.
        let short = &rows
            .iter()
            .find(|r| r.0 == "lambda_l_over_l" && r.1 == 0.25)
            .unwrap()
            .3;
        assert_eq!((short.lambda_l, short.zeta), (16.0, 2.0));
        // The misprint hypotheses and the transition scene carry their own settings.
        let hurst = &rows.iter().find(|r| r.0 == "hurst").unwrap().3;
        assert_eq!((hurst.hurst, hurst.contact_area), (Some(0.3), 0.14));
        // A later exponent is a row as the others, after them.
        let exponents: Vec<Option<f64>> = rows
            .iter()
            .filter(|r| r.0 == "hurst")
            .map(|r| r.3.hurst)
            .collect();
        assert_eq!(exponents, [Some(0.3), Some(0.5)]);
        let planned = p.planned(STEP);
        assert_eq!(planned.len(), rows.len());
        assert!(planned
            .iter()
            .any(|m| (m.parameter, m.value, m.label.as_str()) == ("hurst", 0.5, "H = 0.5")));
        let area = &rows.iter().find(|r| r.0 == "contact_area").unwrap().3;
        assert_eq!((area.hurst, area.contact_area), (None, 0.5));
        let t = &rows.iter().find(|r| r.0 == "transition").unwrap().3;
        assert_eq!((t.n, t.hurst, t.zeta, t.dzeta), (128, Some(0.5), 15.0, 0.3));
    }

    #[test]
    fn a_transition_scene_beyond_its_grid_is_refused_by_name() {
        let mut p = plan();
        p.transition.as_mut().unwrap().zeta = 63.0;
        let e = p.validate(0.8, STEP).unwrap_err().to_string();
        assert!(e.contains("sensitivity.transition"), "{e}");
    }

    #[test]
    fn a_value_named_twice_is_refused_by_name() {
        let mut p = plan();
        p.contact_areas = vec![0.5, 0.5];
        let e = p.validate(0.8, STEP).unwrap_err().to_string();
        assert!(
            e.contains("sensitivity.contact_areas") && e.contains("once"),
            "{e}"
        );
        let mut p = plan();
        p.tols = vec![1e-6, 1e-8, 1e-6];
        let e = p.validate(0.8, STEP).unwrap_err().to_string();
        assert!(e.contains("sensitivity.tols") && e.contains("once"), "{e}");
    }

    #[test]
    fn a_later_exponent_already_in_the_plan_is_refused_by_name() {
        for later in [vec![0.3], vec![0.5, 0.5]] {
            let mut p = plan();
            p.later_hurst_values = later;
            let e = p.validate(0.8, STEP).unwrap_err().to_string();
            assert!(e.contains("sensitivity.later_hurst_values"), "{e}");
        }
        let mut p = plan();
        p.later_hurst_values = vec![1.0];
        let e = p.validate(0.8, STEP).unwrap_err().to_string();
        assert!(e.contains("sensitivity.later_hurst_values"), "{e}");
    }

    #[test]
    fn the_net_flow_identity_is_read_at_fixed_load_only() {
        // Steps whose contact areas count the points the fluxes count: a_r after = a_r
        // before + in - out (seed 1: in 0.001, out 0.003; seed 2: in 0.002, out 0.003).
        let p = plan();
        let jobs = p.jobs(STEP);
        let results: Vec<StudyResult> = jobs
            .iter()
            .map(|j| {
                let (a, fin, fout) = (0.14, 0.001 * j.seed as f64, 0.003);
                StudyResult {
                    a_r_old: a,
                    a_r_new: a + fin - fout,
                    flux_in: fin,
                    flux_out: fout,
                    max_residual: 0.0,
                    variance_added: None,
                    modes_added: None,
                }
            })
            .collect();
        let pairs: Vec<(&StudyJob, &StudyResult)> = jobs.iter().zip(&results).collect();
        let rows = p.conclude(STEP, &pairs);
        for r in &rows {
            let net = r.net_flow.unwrap();
            assert!((net.value - 0.0015).abs() < 1e-15, "{}: {net:?}", r.label);
            let e = r.net_flow_residual.expect("every row checks the identity");
            assert!(e.value.abs() < 1e-15, "{}: {e:?}", r.label);
        }
        assert_eq!(rows.iter().filter(|r| r.config.fixed_area).count(), 1);
        // The table shows both, the residual at fixed area too (a counting identity).
        let t = study(&rows);
        assert!(t
            .cell("control=1", "net_flow_residual")
            .unwrap()
            .estimate()
            .is_some());
        assert!(t
            .cell("control=0", "net_flow_residual")
            .unwrap()
            .estimate()
            .is_some());
        assert!(t
            .cell("hurst=0.5", "net_flow")
            .unwrap()
            .estimate()
            .is_some());
    }

    #[test]
    fn the_step_taken_counts_the_added_shells_only() {
        use crate::engine::surface::{Surface, SurfaceModel};
        let s = Surface::generate(&SurfaceModel::new(64, 0.8, 32.0, 2.0, 3)).unwrap();
        let shells = s.shells();
        let (v, m) = step_taken(&shells, 4.0, 1.0);
        let lo: f64 = shells.up_to(4.0).iter().map(|s| s.h2).sum();
        let hi: f64 = shells.up_to(5.0).iter().map(|s| s.h2).sum();
        assert!((v - (hi - lo) / lo).abs() < 1e-12 * v, "{v}");
        assert!(m > 0);
        // A step inside one gap between shells adds nothing.
        let (v0, m0) = step_taken(&shells, 4.0, 1e-9);
        assert_eq!((v0, m0), (0.0, 0));
    }

    #[test]
    fn rows_average_over_realizations_in_both_measures() {
        let p = plan();
        let jobs = p.jobs(STEP);
        let results: Vec<StudyResult> = jobs
            .iter()
            .map(|j| StudyResult {
                a_r_old: 0.1,
                a_r_new: 0.1,
                flux_in: 0.001 * j.seed as f64,
                flux_out: 0.002,
                max_residual: 0.0,
                variance_added: Some(0.01),
                modes_added: Some(8),
            })
            .collect();
        let pairs: Vec<(&StudyJob, &StudyResult)> = jobs.iter().zip(&results).collect();
        let rows = p.conclude(STEP, &pairs);
        assert_eq!(rows.len(), p.rows(STEP).len());
        let r = &rows[0];
        assert!((r.flux_in.value - 0.0015).abs() < 1e-15);
        assert!((r.flux_in_of_contact.value - 0.015).abs() < 1e-14);
        assert!((r.flux_out.std_error).abs() < 1e-15);
        // Share of the non-contact entering contact: flux in over the non-contact at zeta.
        assert!((r.flux_in_of_noncontact.unwrap().value - 0.0015 / 0.9).abs() < 1e-15);
        assert_eq!(r.variance_added.unwrap().value, 0.01);
        assert_eq!(r.modes_added, Some(8.0));
        let net = r.net_over_gross.unwrap().value;
        let expected = (net_over_gross(0.001, 0.002) + net_over_gross(0.002, 0.002)) / 2.0;
        assert!((net - expected).abs() < 1e-15);
    }
}
