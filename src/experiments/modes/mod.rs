//! Single-mode analysis of the elastic energy: Persson's assumptions (d) and (e) ([`crate::conventions`],
//! section 6, rows d and e; paper section "Single-mode analysis of the elastic energy").
//!
//! Persson's theory gives a Fourier mode of the displacement elastic energy only once the
//! roughness of that wavevector is resolved, eq. (elasticEnergy_h_q),
//!
//! ```text
//!     E_P(p0, q) = (E*/4) q a_r(p0, q/q_l) |h~(q)|^2,
//! ```
//!
//! (times `S(a_r)` in the corrected theory), and keeps it unchanged when finer roughness is
//! added. The simulation's energy in the same mode at magnification `zeta` is
//! eq. (elasticEnergy_u_q), `E_exa(p0, q, zeta) = (E*/4) q |u~(p0, q, zeta)|^2`. For a
//! target wavenumber `q_t = zeta_t q_l` the two are compared through the normalised energy
//! of a band of nearby modes, eq. (elastic_energy_norm),
//!
//! ```text
//!     E_norm(p0, q_t, zeta) = sum_band q |u~(q, zeta)|^2 / sum_band q a_r(p0, q_t/q_l) |h~(q)|^2,
//! ```
//!
//! where the band holds every mode with `|q/q_t - 1| <= band` (the scene's relative
//! half-width). Persson predicts eq. (elastic_energy_norm_predicted),
//! `E_norm^pred = S Theta(zeta - zeta_t)`: zero before the band is resolved, the constant
//! `S` after (`S = 1` in the original theory).
//!
//! # Which `a_r` normalises
//!
//! The `a_r(p0, q_t/q_l)` of eq. (elastic_energy_norm) is the contact area *measured* in
//! the same realization's sweep at `zeta = zeta_t`, not Persson's prediction of it. With
//! the measured area, `E_norm` tests the mode assumption alone: the energy a mode holds
//! against what the theory would give it *if it knew the true contact area*. A predicted
//! `a_r` would mix in the contact-area error of the theory, which the contact-area
//! validation measures on its own (paper figure captions: the right axis is the measured
//! area). The same measured `a_r(zeta_t)` enters `S` in the prediction line, so that
//! prediction and normalisation stay consistent: `E_norm^pred = S(a_r(zeta_t))` after
//! resolution. `S` is taken at the mode's own resolution, as in `E_c(q) = E_P(q) S`; the
//! paper's `S(p0, zeta)` in eq. (elastic_energy_norm_predicted) would let a resolved mode's
//! energy drift with `zeta`, which is what the theory says does not happen.
//!
//! # Protocol
//!
//! Each job is one realization at one load. The load is stated as the contact area at full
//! resolution (`zeta_max = lambda_l / lambda_s`, as the paper labels its panels) and found
//! there ([`crate::experiments::climb`]); then, at that fixed `p0`, the sweep climbs from
//! `zeta_start` to `zeta_end` in log-spaced steps ([`crate::experiments::climb::ladder`]) that also include, for every
//! target, `zeta_t` (where `a_r(zeta_t)` is measured), the onset point
//! `onset_ratio * zeta_t` and the start of the frozen window `frozen_from * zeta_t`. Each
//! solve is warm-started from the previous step.
//!
//! # Statistics
//!
//! Ensemble values of `E_norm` are ratios of sums over realizations
//! ([`crate::stats::Estimate::ratio_of_sums`]).
//!
//! * (d) onset ([`ModeOnset`]): `E_norm` at `zeta = onset_ratio * zeta_t`, below the first
//!   mode of the band (Persson: 0). Headline: per realization the mean over targets at the
//!   headline load, then the mean over realizations.
//! * (e) frozen ([`ModeFrozen`]): the change `E_norm(zeta_end) - E_norm(frozen_from zeta_t)`
//!   after resolution (Persson: 0, the energy is frozen at `S`). Headline: the first
//!   (longest-wavelength) target at the lowest load, where the paper sees long wavelengths
//!   recede. The asymptote `E_inf` is extrapolated per realization by a straight line
//!   through the points of the frozen window. The paper calls the fall-off "linear with
//!   magnification" and extrapolates to `zeta -> infinity`; a line in `zeta` has no finite
//!   limit there, so the line is drawn in `1/zeta` (`E_norm = E_inf + b / zeta`), the
//!   variable in which `zeta -> infinity` is a point. It is set against
//!   `x = -d ln a_r / d ln zeta` (positive while the contact area shrinks), the slope of a
//!   line through `(ln zeta, ln a_r)` over the same window, and the points of all
//!   partial-contact loads and targets are fitted to the paper's `K1 exp(-K2 x)` by a line
//!   through `(x, ln E_inf)`. A scene may name a reference surface (another Hurst
//!   exponent, `reference`): the same sweeps on it, fitted to the same law, give the
//!   difference of the constants; those sweeps are the reference validation's own jobs
//!   and share their stored results.
//!
//! # Files
//!
//! * `mod.rs`: the scene and its jobs, each the load at full resolution, then the climb
//!   that records the contact area and the energy of every band;
//! * `band.rs`: a band of modes about a target and its energy, what a job measures;
//! * `stats.rs`: the ensemble values of a load both experiments read, and the statistics
//!   of (e): the asymptotes and the law fitted to them;
//! * `figures.rs`: the curves of `E_norm` both show, and the asymptotes of (e);
//! * `onset.rs`: experiment (d), its statistics, findings and account;
//! * `frozen.rs`: experiment (e), its findings, studies and account.

mod band;
mod figures;
mod frozen;
mod onset;
pub mod stats;

pub use band::{band_energies, Band};
pub use frozen::ModeFrozen;
pub use onset::{ModeOnset, OnsetStats};
pub use stats::FrozenStats;

use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

use super::climb::{check_steps_per_octave, climb, ladder, step_of, Recorder};
use super::ensemble::{check_headline, seed_load_jobs, SeedLoad};
use super::scene::{check_increasing, leaves_out_planned, scene, PLANNED};
use super::{JobContext, Jobs, Work};
use crate::engine::contact::{ContactSolution, Model};
use crate::engine::solver::SolverKind;
use crate::engine::tolerance::ZETA_SLACK;
use crate::error::{check_open, check_positive, Error, Result};
use crate::persson::Correction;

scene! {
    /// Scene of the single-mode experiments (d) and (e).
    pub struct ModeScene {
        /// Loads, as the relative contact area at full resolution, in (0, 1).
        pub contact_areas: Vec<f64>,
        /// The load of the onset headline (one of `contact_areas`).
        pub headline_contact_area: f64,
        /// Target magnifications `zeta_t = q_t / q_l`, increasing.
        pub targets: Vec<f64>,
        /// Relative half-width of each band: modes with `|q/q_t - 1| <= band`.
        pub band: f64,
        /// First magnification of the sweep.
        pub zeta_start: f64,
        /// Last magnification of the sweep (at most `lambda_l / lambda_s`).
        pub zeta_end: f64,
        /// Log-spaced sweep steps per octave of `zeta`.
        pub steps_per_octave: usize,
        /// Onset point `onset_ratio * zeta_t`, below the band (`< 1 - band`).
        pub onset_ratio: f64,
        /// The frozen window starts at `frozen_from * zeta_t` (`> 1 + band`).
        pub frozen_from: f64,
        /// The correction factor `S(a_r)` of the prediction line.
        #[serde(default)]
        pub correction: Correction,
        /// A narrower relative half-width: every sweep again with bands this wide, for
        /// the part of the peak's shift that the band's averaging makes (none: not run).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub narrow_band: Option<f64>,
        /// Another surface swept the same way, whose fitted law the constants are set
        /// against (another Hurst exponent; none: no comparison). Its sweeps are its own
        /// validation's jobs and share their stored results ([`Jobs::shared_job`]).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub reference: Option<ReferenceSurface>,
    }
}

/// The surface of a reference scene: the scene itself with these fields in place of its
/// own (every other field, the grid, the bands and the sweep, is the scene's).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSurface {
    /// Hurst exponent, in (0, 1).
    pub hurst: f64,
    /// Realizations.
    pub seeds: Vec<u64>,
    /// Loads, as the relative contact area at full resolution, in (0, 1).
    pub contact_areas: Vec<f64>,
    /// The load of the onset headline (one of `contact_areas`).
    pub headline_contact_area: f64,
}

/// A job: one realization's sweep at one load (stored bare, as before the narrow bands
/// existed), or the same sweep with the narrow bands.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ModeJob {
    /// A sweep with bands of relative half-width `band`.
    Narrow(NarrowJob),
    /// A sweep of the reference surface (keyed and stored as that scene's own sweep).
    Reference(SeedLoad),
    /// A sweep with the scene's bands.
    #[serde(untagged)]
    Sweep(SeedLoad),
}

/// A sweep with narrow bands.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NarrowJob {
    /// Relative half-width of the bands.
    pub band: f64,
    /// Seed.
    pub seed: u64,
    /// Load, as the relative contact area at full resolution.
    pub contact_area: f64,
}

impl NarrowJob {
    /// The realization and load it sweeps again.
    pub fn at(&self) -> SeedLoad {
        SeedLoad {
            seed: self.seed,
            contact_area: self.contact_area,
        }
    }
}

/// What a job measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ModeOutput {
    /// A sweep with narrow bands.
    Narrow(ModeResult),
    /// A sweep with the scene's bands.
    #[serde(untagged)]
    Sweep(ModeResult),
}

/// The results that `pick` keeps, as `(realization and load, sweep)`.
fn picked(
    results: &[(ModeJob, ModeOutput)],
    pick: fn(&ModeJob, &ModeOutput) -> Option<SeedLoad>,
) -> Vec<(SeedLoad, ModeResult)> {
    results
        .iter()
        .filter_map(|(j, r)| {
            let at = pick(j, r)?;
            let (ModeOutput::Sweep(r) | ModeOutput::Narrow(r)) = r;
            Some((at, r.clone()))
        })
        .collect()
}

/// The sweeps with the scene's bands among the results.
pub(super) fn sweeps(results: &[(ModeJob, ModeOutput)]) -> Vec<(SeedLoad, ModeResult)> {
    picked(results, |j, r| match (j, r) {
        (ModeJob::Sweep(j), ModeOutput::Sweep(_)) => Some(j.clone()),
        _ => None,
    })
}

/// The reference surface's sweeps among the results.
pub(super) fn reference_sweeps(results: &[(ModeJob, ModeOutput)]) -> Vec<(SeedLoad, ModeResult)> {
    picked(results, |j, r| match (j, r) {
        (ModeJob::Reference(j), ModeOutput::Sweep(_)) => Some(j.clone()),
        _ => None,
    })
}

/// The sweeps with the narrow bands among the results.
pub(super) fn narrow_sweeps(results: &[(ModeJob, ModeOutput)]) -> Vec<(SeedLoad, ModeResult)> {
    picked(results, |j, r| match (j, r) {
        (ModeJob::Narrow(j), ModeOutput::Narrow(_)) => Some(j.at()),
        _ => None,
    })
}

impl ModeScene {
    /// The scene with bands of relative half-width `band` (the narrow bands' sweeps).
    pub fn with_band(&self, band: f64) -> Self {
        Self {
            band,
            narrow_band: None,
            ..self.clone()
        }
    }

    /// The reference scene: this one on the reference surface, as its own validation
    /// states it (no narrow bands, no reference of its own).
    pub fn reference_scene(&self) -> Option<Self> {
        let r = self.reference.as_ref()?;
        Some(Self {
            hurst: r.hurst,
            seeds: r.seeds.clone(),
            contact_areas: r.contact_areas.clone(),
            headline_contact_area: r.headline_contact_area,
            narrow_band: None,
            reference: None,
            ..self.clone()
        })
    }

    /// The sweep's magnifications.
    pub fn steps(&self) -> Vec<f64> {
        let mut extra = Vec::new();
        for &t in &self.targets {
            extra.extend([t, self.onset_ratio * t, self.frozen_from * t]);
        }
        ladder(
            self.zeta_start,
            self.zeta_end,
            self.steps_per_octave,
            &extra,
        )
    }
}

impl Jobs for ModeScene {
    const FAMILY: &'static str = "modes";
    type Job = ModeJob;
    type JobResult = ModeOutput;

    fn validate(&self) -> Result<()> {
        let base = self.base();
        base.validate()?;
        check_headline(self.headline_contact_area, &self.contact_areas)?;
        check_open("band", self.band, 0.0, 0.5)?;
        check_positive("zeta_start", self.zeta_start)?;
        if !(self.zeta_end > self.zeta_start
            && self.zeta_end <= base.zeta_max() * (1.0 + ZETA_SLACK))
        {
            return Err(Error::invalid(
                "zeta_end",
                self.zeta_end,
                format!(
                    "in (zeta_start = {}, lambda_l / lambda_s = {}]",
                    self.zeta_start,
                    base.zeta_max()
                ),
            ));
        }
        check_steps_per_octave(self.steps_per_octave)?;
        check_open("onset_ratio", self.onset_ratio, 0.0, 1.0 - self.band)?;
        if !(self.frozen_from > 1.0 + self.band && self.frozen_from.is_finite()) {
            return Err(Error::invalid(
                "frozen_from",
                self.frozen_from,
                format!("> 1 + band = {}", 1.0 + self.band),
            ));
        }
        check_increasing("targets", &self.targets)?;
        for &t in &self.targets {
            if !(self.onset_ratio * t >= self.zeta_start && (1.0 + self.band) * t <= self.zeta_end)
            {
                return Err(Error::invalid(
                    "targets",
                    t,
                    format!(
                        "a magnification with onset_ratio * zeta_t >= zeta_start = {} and \
                         (1 + band) zeta_t <= zeta_end = {} (room below and after \
                         resolution)",
                        self.zeta_start, self.zeta_end
                    ),
                ));
            }
        }
        if let Some(narrow) = self.narrow_band {
            check_open("narrow_band", narrow, 0.0, self.band)?;
        }
        if let Some(reference) = self.reference_scene() {
            reference.validate().map_err(|e| e.within("reference"))?;
        }
        self.correction.validate()
    }

    /// The sweeps, then the same sweeps with the narrow bands.
    fn jobs(&self) -> Vec<ModeJob> {
        let sweeps = seed_load_jobs(&self.contact_areas, &self.all_seeds());
        let mut jobs: Vec<ModeJob> = sweeps.iter().cloned().map(ModeJob::Sweep).collect();
        if let Some(band) = self.narrow_band {
            jobs.extend(sweeps.into_iter().map(|j| {
                ModeJob::Narrow(NarrowJob {
                    band,
                    seed: j.seed,
                    contact_area: j.contact_area,
                })
            }));
        }
        if let Some(r) = &self.reference {
            jobs.extend(
                seed_load_jobs(&r.contact_areas, &r.seeds)
                    .into_iter()
                    .map(ModeJob::Reference),
            );
        }
        jobs
    }

    /// The planned realizations' sweeps ([`PLANNED`]).
    fn part(&self, job: &ModeJob) -> Option<String> {
        let seed = match job {
            ModeJob::Sweep(j) => j.seed,
            ModeJob::Narrow(j) => j.seed,
            ModeJob::Reference(_) => return None,
        };
        self.more_seeds.contains(&seed).then(|| PLANNED.into())
    }

    fn leave_out(&mut self, parts: &BTreeSet<String>) {
        if leaves_out_planned(parts) {
            self.more_seeds.clear();
        }
    }

    /// The narrow bands' sweeps read the headline solver's peaks only, and the reference
    /// surface's law is fitted on the headline solver's sweeps.
    fn headline_only(job: &ModeJob) -> bool {
        matches!(job, ModeJob::Narrow(_) | ModeJob::Reference(_))
    }

    /// The sweeps depend on the scene without the narrow bands and the reference: their
    /// keys are those of the scenes that had neither.
    fn key_scene(&self) -> serde_json::Value {
        let mut scene = self.clone();
        scene.narrow_band = None;
        scene.reference = None;
        serde_json::to_value(scene).expect("scenes serialise")
    }

    /// A reference sweep is the reference scene's own sweep.
    fn shared_job(&self, job: &ModeJob) -> Option<(serde_json::Value, ModeJob)> {
        match job {
            ModeJob::Reference(j) => Some((
                self.reference_scene()?.key_scene(),
                ModeJob::Sweep(j.clone()),
            )),
            _ => None,
        }
    }

    /// Every sweep climbs the same steps (the band changes what is recorded, not where).
    fn work(&self, _job: &ModeJob) -> Work {
        Work::search_then(self.n, self.steps().len(), 0)
    }

    fn run_job(&self, job: &ModeJob, ctx: &JobContext) -> Result<ModeOutput> {
        match job {
            ModeJob::Sweep(j) => run_sweep(self, j, ctx.solver).map(ModeOutput::Sweep),
            ModeJob::Narrow(j) => {
                run_sweep(&self.with_band(j.band), &j.at(), ctx.solver).map(ModeOutput::Narrow)
            }
            ModeJob::Reference(j) => {
                let reference = self.reference_scene().ok_or_else(|| {
                    Error::invalid("reference", "none", "a reference surface for its sweeps")
                })?;
                run_sweep(&reference, j, ctx.solver).map(ModeOutput::Sweep)
            }
        }
    }

    fn residual(result: &ModeOutput) -> f64 {
        match result {
            ModeOutput::Sweep(r) | ModeOutput::Narrow(r) => r.max_residual,
        }
    }
}

/// The sweep of one realization at one load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModeResult {
    /// The load `p0` found.
    pub p0: f64,
    /// Magnifications of the sweep.
    pub zetas: Vec<f64>,
    /// Measured contact area at each step.
    pub contact_area: Vec<f64>,
    /// `E_exa` of each target's band at each step: `[target][step]`.
    pub band_energy: Vec<Vec<f64>>,
    /// Full-contact energy `(E*/4) sum_band q |h~|^2` of each band.
    pub band_nominal: Vec<f64>,
    /// Largest residual of the solves.
    pub max_residual: f64,
}

impl ModeResult {
    /// `a_r(zeta_t) * nominal` of target `t`: the denominator of eq. (elastic_energy_norm).
    pub(super) fn denominator(&self, t: usize, zeta_t: f64) -> f64 {
        self.contact_area[step_of(&self.zetas, zeta_t)] * self.band_nominal[t]
    }

    /// `E_norm` of target `t` at every step.
    pub(super) fn e_norm(&self, t: usize, zeta_t: f64) -> Vec<f64> {
        let d = self.denominator(t, zeta_t);
        self.band_energy[t].iter().map(|e| e / d).collect()
    }
}

/// What a climb records for the single-mode analysis: the contact area and the energy of
/// every band at each step.
struct BandRecorder<'a> {
    model: &'a Model,
    bands: &'a [Band],
    contact_area: Vec<f64>,
    band_energy: Vec<Vec<f64>>,
}

impl Recorder for BandRecorder<'_> {
    fn record(&mut self, _step: usize, _zeta: f64, s: &ContactSolution) -> Result<()> {
        self.contact_area.push(s.contact_area());
        for (t, e) in band_energies(self.model, s, self.bands)
            .into_iter()
            .enumerate()
        {
            self.band_energy[t].push(e);
        }
        Ok(())
    }
}

/// Runs one job: the load at full resolution, then the climb at that load.
fn run_sweep(scene: &ModeScene, job: &SeedLoad, solver: SolverKind) -> Result<ModeResult> {
    let base = scene.base();
    let r = base.realization(job.seed)?;
    let e_star = r.model.halfspace.e_star();
    let bands = scene
        .targets
        .iter()
        .map(|&t| Band::new(&r.surface, t, scene.band, e_star))
        .collect::<Result<Vec<_>>>()?;
    let zetas = scene.steps();
    let mut recorder = BandRecorder {
        model: &r.model,
        bands: &bands,
        contact_area: Vec::with_capacity(zetas.len()),
        band_energy: vec![Vec::with_capacity(zetas.len()); bands.len()],
    };
    let climbed = climb(
        &base,
        solver,
        &r,
        job.contact_area,
        &zetas,
        &mut recorder,
        None,
    )?;
    Ok(ModeResult {
        p0: climbed.p0,
        zetas,
        contact_area: recorder.contact_area,
        band_energy: recorder.band_energy,
        band_nominal: bands.iter().map(|b| b.nominal).collect(),
        max_residual: climbed.max_residual,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::engine::solver::{SolveOptions, SolverKind};
    use crate::engine::sweep::Sweep;
    use crate::engine::testing::rough_contact;
    use crate::experiments::Criteria;

    #[test]
    fn full_contact_gives_persson_exactly() {
        // At a load far above the pressure fluctuations the contact stays complete: u = h
        // + const, so a band holds nothing before resolution and exactly its full-contact
        // energy once resolved, E_norm = Theta(zeta - zeta_t) with a_r = 1.
        let (surface, model) = rough_contact(64, 0.8, 3);
        let band = Band::new(&surface, 3.0, 0.1, 1.0).unwrap();
        assert!(band.zeta_lo < 3.0 && band.zeta_hi > 3.0 && band.modes.len() > 10);
        let mut sweep = Sweep::new(
            &surface,
            &model,
            SolverKind::Cg,
            SolveOptions::with_tol(1e-10),
        );
        let p0 = 6.0; // g_bar = 1: pressure fluctuations have rms 1/2.
        for (zeta, expected) in [
            (2.0, 0.0),
            (0.99 * band.zeta_lo, 0.0),
            (band.zeta_hi, 1.0),
            (6.0, 1.0),
            (8.0, 1.0),
        ] {
            let s = sweep.solve_at(zeta, p0).unwrap();
            assert_eq!(s.contact_area(), 1.0, "zeta = {zeta}");
            let e = band_energies(&model, s, std::slice::from_ref(&band))[0];
            let e_norm = e / band.nominal;
            assert!(
                (e_norm - expected).abs() < 1e-9,
                "zeta = {zeta}: E_norm = {e_norm:e}, expected {expected}"
            );
        }
    }

    /// The shipped scenes of `name` (`d_onset` or `e_frozen`), and its criteria.
    pub(crate) fn shipped(name: &str) -> (ModeScene, ModeScene, Criteria) {
        crate::experiments::shipped_scenes(name)
    }

    /// Synthetic sweeps with known answers: at load `l` the contact area falls as
    /// `a_r = a_l (zeta / zeta_end)^(-x_l)`, every band holds `onset` below resolution and
    /// `K1 exp(-K2 x_l) + b / zeta` in the frozen window.
    pub(crate) fn synthetic(
        scene: &ModeScene,
        k: (f64, f64),
        b: f64,
        onset: f64,
    ) -> Vec<(ModeJob, ModeOutput)> {
        let zetas = scene.steps();
        let mut out = Vec::new();
        for (l, &a_l) in scene.contact_areas.iter().enumerate() {
            let x = 0.1 * (l + 1) as f64;
            let area: Vec<f64> = zetas
                .iter()
                .map(|z| a_l * (z / scene.zeta_end).powf(-x))
                .collect();
            for &seed in &scene.seeds {
                let band_energy = scene
                    .targets
                    .iter()
                    .map(|&zt| {
                        let a_t = area[step_of(&zetas, zt)];
                        zetas
                            .iter()
                            .map(|&z| {
                                let e = if z < zt {
                                    onset
                                } else {
                                    k.0 * (-k.1 * x).exp() + b / z
                                };
                                // E_norm = energy / (a_r(zeta_t) nominal), nominal = 2.
                                e * a_t * 2.0
                            })
                            .collect()
                    })
                    .collect();
                out.push((
                    ModeJob::Sweep(SeedLoad {
                        seed,
                        contact_area: a_l,
                    }),
                    ModeOutput::Sweep(ModeResult {
                        p0: 0.1,
                        zetas: zetas.clone(),
                        contact_area: area.clone(),
                        band_energy,
                        band_nominal: vec![2.0; scene.targets.len()],
                        max_residual: 1e-9,
                    }),
                ));
            }
        }
        out
    }
}
