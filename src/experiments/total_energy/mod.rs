//! The integrated elastic energy against Persson's theory ([`crate::conventions`], section 6, row "total
//! energy"; paper section "Analysis of the integrated elastic energy").
//!
//! Only the net elastic energy enters contact stiffness and mean gap. The simulation's
//! total, eq. (elasticEnergy_u_tot), `E_exa(p0, zeta) = sum_q (E*/4) q |u~(p0, q, zeta)|^2`,
//! is compared with Persson's totals up to `zeta`, eq. (elasticEnergy_h_tot),
//! `E_P(p0) = sum_q (E*/4) q a_r(p0, |q|/q_l) |h~(q)|^2` (original theory, `S = 1`), and
//! eq. (elasticEnergy_h_tot_wS), `E_c(p0) = sum_q E_P(p0, q) S(a_r(p0, |q|/q_l))` with `S`
//! from eq. (gamma) (corrected theory). The paper's integrated normalised energy is
//! `E_norm(p0, zeta) = E_exa(p0, zeta) / E_P(p0, zeta)`, here for both theories.
//!
//! # Which `a_r`
//!
//! These are predictions of the theory, so each theory uses its *own* contact area
//! `a_r(p0, zeta)` at the load `p0` of the simulation: the original theory's
//! `erf(p0 / (sqrt2 Dp_tot))` inside `E_P`, the corrected theory's self-consistent area
//! inside `E_c` and its `S` ([`Prediction`]). The measured contact area only labels the
//! loads (as in the paper's figures).
//!
//! # Incremental correction factor
//!
//! Eq. (S_q_numerical): `S~(p0, zeta) = [E_exa(zeta) - E_exa(zeta - dzeta)] /
//! [E_P(zeta) - E_P(zeta - dzeta)]`, with `dzeta` the smallest step the grid allows: from
//! one shell of equal `|q|` to the next (every new wavenumber solved separately, as the
//! paper does). If each mode took its energy exactly on resolution and kept it, `S~` would
//! be the correction factor itself; it is compared with `S(a_r)` of eq. (gamma) at the
//! original theory's `a_r(p0, zeta)`, the area inside the denominator `E_P`. The scene
//! names windows of consecutive shells (`increments` shells from the last shell at or below
//! each `increments_at`); per shell, `S~` is a ratio of sums over realizations, and per
//! window the mean over its shells, averaged over realizations.
//!
//! # Protocol
//!
//! Each job is one realization at one load; the load is the one that gives the scene's
//! contact area at full resolution (`zeta_max`, where the paper's figure of `E_norm`
//! against `a_r` is taken). At that fixed `p0` the sweep climbs from `zeta_start` to
//! `zeta_max` in log-spaced steps merged with the shells of the increment windows, every
//! solve warm-started from the previous one. Ensemble ratios are ratios of sums over
//! realizations ([`crate::stats::Estimate::ratio_of_sums`]). The headline is `E_exa / E_c` at full
//! resolution and the headline load.

mod figures;
pub mod stats;

use serde::{Deserialize, Serialize};

use self::stats::{
    corrected_drift, deviation_growth, measured_area, original_area, ratio, two_octaves_below_end,
    window_mean, Load, Theory,
};
use super::climb::{climb, ladder, step_of, Recorder};
use super::ensemble::{
    by_load, check_contact_areas, check_headline, group, load_range, seed_load_jobs, SeedLoad,
};
use super::scene::scene;
use super::{
    max_residual, Check, Conclusion, Criteria, Detail, Experiment, JobContext, Jobs, Work,
};
use crate::engine::contact::{ContactSolution, Model};
use crate::engine::solver::SolverKind;
use crate::engine::surface::Surface;
use crate::engine::sweep::shell_steps;
use crate::error::{check_positive, Error, Result};
use crate::persson::{Broadening, Correction, Prediction};
use crate::stats::round_sig;

/// Below this measured contact area the paper finds that the corrected theory fails.
pub const PAPER_FAILURE_AREA: f64 = 0.05;

scene! {
    /// Scene of the total-energy experiment.
    pub struct EnergyScene {
        /// Loads, as the relative contact area at full resolution, in (0, 1).
        pub contact_areas: Vec<f64>,
        /// The load of the headline (one of `contact_areas`).
        pub headline_contact_area: f64,
        /// More realizations, distinct from `seeds`, run only at the lowest load when it is
        /// below `a_r = 0.05`: the load of the low-load check, where the spread over
        /// realizations is largest.
        #[serde(default)]
        pub low_load_seeds: Vec<u64>,
        /// First magnification of the sweep.
        pub zeta_start: f64,
        /// Log-spaced sweep steps per octave of `zeta`.
        pub steps_per_octave: usize,
        /// Magnifications at which windows of single-shell increments start.
        pub increments_at: Vec<f64>,
        /// Shells added one at a time in each window.
        pub increments: usize,
        /// The correction factor `S(a_r)` of the corrected theory.
        #[serde(default)]
        pub correction: Correction,
    }
}

/// The sweep of one realization at one load, with the theory beside it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnergyResult {
    /// The load `p0` found.
    pub p0: f64,
    /// Magnifications of the sweep.
    pub zetas: Vec<f64>,
    /// Measured contact area at each step.
    pub contact_area: Vec<f64>,
    /// `E_exa(p0, zeta)`, eq. (elasticEnergy_u_tot).
    pub e_exa: Vec<f64>,
    /// `E_P(p0, zeta)`, eq. (elasticEnergy_h_tot), original theory.
    pub e_p: Vec<f64>,
    /// `E_c(p0, zeta)`, eq. (elasticEnergy_h_tot_wS), corrected theory.
    pub e_c: Vec<f64>,
    /// The original theory's `a_r(p0, zeta)`.
    pub area_original: Vec<f64>,
    /// The corrected theory's `a_r(p0, zeta)`.
    pub area_corrected: Vec<f64>,
    /// For each increment window, the indices into `zetas` of its consecutive shells (the
    /// base shell first).
    pub windows: Vec<Vec<usize>>,
    /// Largest residual of the solves.
    pub max_residual: f64,
}

/// The magnifications of the increment windows: for each start, the last shell at or
/// below it and the next `increments` shells.
fn window_shells(surface: &Surface, scene: &EnergyScene) -> Vec<Vec<f64>> {
    let all = shell_steps(surface, 0.0, scene.base().zeta_max());
    scene
        .increments_at
        .iter()
        .map(|&z| {
            let base = all.partition_point(|&s| s <= z * (1.0 + 1e-12));
            let first = base.saturating_sub(1);
            all[first..(base + scene.increments).min(all.len())].to_vec()
        })
        .collect()
}

/// What a climb records for the total energy: the measured energy and contact area, and
/// both theories' energies and contact areas at the same load, at every step.
struct EnergyRecorder<'a> {
    model: &'a Model,
    broadening: Broadening,
    correction: Correction,
    theories: Option<(Prediction, Prediction)>,
    r: EnergyResult,
}

impl Recorder for EnergyRecorder<'_> {
    fn start(&mut self, p0: f64) -> Result<()> {
        self.theories = Some((
            Prediction::original(&self.broadening, p0)?,
            Prediction::corrected(&self.broadening, p0, self.correction)?,
        ));
        self.r.p0 = p0;
        Ok(())
    }

    fn record(&mut self, _step: usize, zeta: f64, s: &ContactSolution) -> Result<()> {
        let (original, corrected) = self.theories.as_ref().expect("started");
        let r = &mut self.r;
        r.contact_area.push(s.contact_area());
        let u = s.displacement_spectrum(self.model);
        r.e_exa
            .push(self.model.halfspace.energy_fourier(&self.model.grid, &u));
        r.e_p.push(original.elastic_energy(zeta));
        r.e_c.push(corrected.elastic_energy(zeta));
        r.area_original.push(original.contact_area(zeta));
        r.area_corrected.push(corrected.contact_area(zeta));
        Ok(())
    }
}

fn run_sweep(scene: &EnergyScene, job: &SeedLoad, solver: SolverKind) -> Result<EnergyResult> {
    let base = scene.base();
    let real = base.realization(job.seed)?;
    let zeta_max = real.surface.zeta_max();
    let windows = window_shells(&real.surface, scene);
    let extra: Vec<f64> = windows.iter().flatten().copied().collect();
    let zetas = ladder(scene.zeta_start, zeta_max, scene.steps_per_octave, &extra);
    let windows: Vec<Vec<usize>> = windows
        .iter()
        .map(|w| w.iter().map(|&z| step_of(&zetas, z)).collect())
        .collect();
    let mut recorder = EnergyRecorder {
        model: &real.model,
        broadening: Broadening::new(&real.surface.shells(), real.model.halfspace.e_star())?,
        correction: scene.correction,
        theories: None,
        r: EnergyResult {
            p0: f64::NAN,
            zetas: zetas.clone(),
            contact_area: Vec::new(),
            e_exa: Vec::new(),
            e_p: Vec::new(),
            e_c: Vec::new(),
            area_original: Vec::new(),
            area_corrected: Vec::new(),
            windows,
            max_residual: 0.0,
        },
    };
    let climbed = climb(
        &base,
        solver,
        &real,
        job.contact_area,
        &zetas,
        &mut recorder,
        None,
    )?;
    let mut r = recorder.r;
    r.max_residual = climbed.max_residual;
    Ok(r)
}

/// The integrated elastic energy against Persson's theory.
pub struct TotalEnergy;

impl Jobs for EnergyScene {
    const FAMILY: &'static str = "total_energy";
    type Job = SeedLoad;
    type JobResult = EnergyResult;

    fn validate(&self) -> Result<()> {
        let scene = self;
        let base = scene.base();
        base.validate()?;
        let all: Vec<u64> = scene
            .seeds
            .iter()
            .chain(&scene.low_load_seeds)
            .copied()
            .collect();
        crate::error::check_seeds(&all).map_err(|e| e.with_field("low_load_seeds"))?;
        check_contact_areas(&scene.contact_areas)?;
        check_headline(scene.headline_contact_area, &scene.contact_areas)?;
        check_positive("zeta_start", scene.zeta_start)?;
        if scene.zeta_start >= base.zeta_max() {
            return Err(Error::invalid(
                "zeta_start",
                scene.zeta_start,
                format!("< lambda_l / lambda_s = {}", base.zeta_max()),
            ));
        }
        if !(1..=64).contains(&scene.steps_per_octave) {
            return Err(Error::invalid(
                "steps_per_octave",
                scene.steps_per_octave,
                "an integer in [1, 64]",
            ));
        }
        for &z in &scene.increments_at {
            if !(z >= scene.zeta_start && z < base.zeta_max()) {
                return Err(Error::invalid(
                    "increments_at",
                    z,
                    format!(
                        "in [zeta_start = {}, lambda_l / lambda_s = {})",
                        scene.zeta_start,
                        base.zeta_max()
                    ),
                ));
            }
        }
        if !(1..=1000).contains(&scene.increments) {
            return Err(Error::invalid(
                "increments",
                scene.increments,
                "an integer in [1, 1000]",
            ));
        }
        scene.correction.validate()
    }

    fn jobs(&self) -> Vec<SeedLoad> {
        let (lowest, _) = load_range(&self.contact_areas);
        let mut jobs = Vec::new();
        for &a in &self.contact_areas {
            jobs.extend(seed_load_jobs(&[a], &self.seeds));
            if a == lowest && a < PAPER_FAILURE_AREA {
                jobs.extend(seed_load_jobs(&[a], &self.low_load_seeds));
            }
        }
        jobs
    }

    fn work(&self, _job: &SeedLoad) -> Work {
        // The ladder's steps plus the windows of single-shell increments.
        let zeta_max = self.base().zeta_max();
        let ladder = (zeta_max / self.zeta_start).log2() * self.steps_per_octave as f64;
        let windows = self.increments_at.len() * (self.increments + 1);
        Work::climb(self.n, ladder.ceil() as usize + 1, windows)
    }

    fn run_job(&self, job: &SeedLoad, ctx: &JobContext) -> Result<EnergyResult> {
        run_sweep(self, job, ctx.solver)
    }
}

impl Experiment for TotalEnergy {
    type Scene = EnergyScene;

    fn conclude(
        criteria: &Criteria,
        scene: &EnergyScene,
        results: &[(SeedLoad, EnergyResult)],
    ) -> Result<Conclusion> {
        let first = &results.first().expect("jobs ran").1;
        let zetas = &first.zetas;
        if results.iter().any(|(_, r)| r.zetas != *zetas) {
            return Err(Error::invalid(
                "sweep steps",
                "different between realizations",
                "the same magnifications in every job",
            ));
        }
        let end = zetas.len() - 1;
        let loads = by_load(&scene.contact_areas, results);
        let mut c = Conclusion {
            persson: 1.0,
            max_residual: max_residual(results, |r| r.max_residual),
            ..Default::default()
        };
        for load in &loads {
            load_details(&mut c, scene, load, zetas, &first.windows);
        }

        // Headline: E_exa / E_c at full resolution and the headline load.
        let headline = group(&loads, scene.headline_contact_area);
        let measured = ratio(headline, end, Theory::Corrected);
        let original = ratio(headline, end, Theory::Original);
        c.measured = Some(measured);
        c.golden
            .insert("corrected_headline".into(), round_sig(measured.value, 2));
        let a_head = measured_area(headline, end);
        // How the headline still moves with magnification: its change over the last two
        // octaves (per realization).
        let quarter = two_octaves_below_end(zetas);
        let drift = corrected_drift(headline, quarter);
        c.details.push(
            Detail::new(
                "corrected_headline_drift",
                format!(
                    "change of E_exa / E_c at the headline load from zeta = {:.3} to {:.3}",
                    zetas[quarter], zetas[end]
                ),
                drift,
            )
            .persson(0.0),
        );
        c.golden
            .insert("corrected_headline_drift".into(), round_sig(drift.value, 1));
        c.checks.push(Check::new(
            "correction_brings_energy_closer",
            "the correction factor brings the total energy closer to the measurement than \
             S = 1",
            (measured.value - 1.0).abs() < (original.value - 1.0).abs(),
            format!(
                "E_exa / E_c = {:.3} +- {:.3}, E_exa / E_P = {:.3} +- {:.3} at a_r = {:.3}",
                measured.value,
                measured.std_error,
                original.value,
                original.std_error,
                a_head.value
            ),
        ));
        // The paper: below a_r ~ 0.05 the corrected theory's deviation from the measurement
        // grows dramatically (its figure of the energy against a_r).
        let lowest = loads
            .iter()
            .min_by(|a, b| a.contact_area.total_cmp(&b.contact_area))
            .expect("validated non-empty");
        let a_low = measured_area(lowest, end);
        let low = ratio(lowest, end, Theory::Corrected);
        let low_text = if a_low.value < PAPER_FAILURE_AREA {
            let growth = deviation_growth(low, measured);
            c.checks.push(Check::new(
                "correction_fails_at_low_load",
                format!(
                    "below a_r = {PAPER_FAILURE_AREA} the corrected energy deviates from the \
                     measurement more than at the headline load (by {} combined standard \
                     errors)",
                    criteria.significance
                ),
                growth.value > criteria.significance * growth.std_error,
                format!(
                    "E_exa / E_c = {:.3} +- {:.3} at a_r = {:.4} against {:.3} +- {:.3} at \
                     a_r = {:.3}: |deviation| grows by {:.3} +- {:.3}",
                    low.value,
                    low.std_error,
                    a_low.value,
                    measured.value,
                    measured.std_error,
                    a_head.value,
                    growth.value,
                    growth.std_error
                ),
            ));
            format!(
                " At the lowest load (a_r = {:.4}, {} realizations) E_exa / E_c = {:.3} +- \
                 {:.3}.",
                a_low.value,
                lowest.runs.len(),
                low.value,
                low.std_error
            )
        } else {
            String::new()
        };
        c.account = format!(
            "Over {} realizations (H = {}, {}x{} grid, lambda_l = {}, lambda_s = {}), at the \
             load that gives a_r = {:.3} at full resolution (zeta = {}), the measured total \
             elastic energy is {:.3} +- {:.3} of the corrected theory's E_c (eq. gamma) and \
             {:.3} +- {:.3} of the original theory's E_P: the corrected theory's energy \
             exceeds the measurement by {:+.1}% (z = {:.1} against Persson's 1), the original \
             theory's by {:+.0}%.{} Each theory uses its own a_r(p0, zeta).",
            scene.seeds.len(),
            scene.hurst,
            scene.n,
            scene.n,
            scene.lambda_l,
            scene.lambda_s,
            a_head.value,
            round_sig(zetas[end], 4),
            measured.value,
            measured.std_error,
            original.value,
            original.std_error,
            100.0 * (1.0 / measured.value - 1.0),
            measured.z_score(1.0),
            100.0 * (1.0 / original.value - 1.0),
            low_text,
        );
        c.tables
            .push(figures::curve_table(&criteria.name, &loads, zetas));
        c.tables.push(figures::s_tilde_table(
            &loads,
            zetas,
            &first.windows,
            scene.correction,
        ));
        c.figures = figures::figures(scene.hurst, &loads, zetas, &first.windows, scene.correction);
        Ok(c)
    }
}

/// The details of one load: both theories' ratios at full resolution, and `S~` averaged
/// over each window of single-shell increments.
fn load_details(
    c: &mut Conclusion,
    scene: &EnergyScene,
    load: &Load,
    zetas: &[f64],
    windows: &[Vec<usize>],
) {
    let end = zetas.len() - 1;
    let a = measured_area(load, end);
    let o = ratio(load, end, Theory::Original);
    let q = ratio(load, end, Theory::Corrected);
    c.details.push(
        Detail::new(
            format!("original_ar{}", load.contact_area),
            format!(
                "E_exa / E_P (S = 1) at full resolution, a_r = {} ({:.4} measured)",
                load.contact_area, a.value
            ),
            o,
        )
        .persson(1.0),
    );
    c.details.push(
        Detail::new(
            format!("corrected_ar{}", load.contact_area),
            format!(
                "E_exa / E_c (S of eq. gamma) at full resolution, a_r = {} ({:.4} measured)",
                load.contact_area, a.value
            ),
            q,
        )
        .persson(1.0),
    );
    c.golden.insert(
        format!("original_ar{}", load.contact_area),
        round_sig(o.value, 2),
    );
    c.golden.insert(
        format!("corrected_ar{}", load.contact_area),
        round_sig(q.value, 2),
    );
    for (w, window) in windows.iter().enumerate() {
        let s_w = load.mean(|r| window_mean(r, &r.windows[w]));
        let last = *window.last().expect("non-empty window");
        let s_p = scene.correction.factor(original_area(load, last).value);
        c.details.push(
            Detail::new(
                format!("s_tilde_ar{}_window{w}", load.contact_area),
                format!(
                    "S~ over {} single-shell increments from zeta = {:.3} to {:.3}, \
                     a_r = {} at full resolution (Persson: S(a_r) of eq. gamma)",
                    window.len() - 1,
                    zetas[window[0]],
                    zetas[last],
                    load.contact_area
                ),
                s_w,
            )
            .persson(s_p),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::solver::{SolveOptions, SolverKind};
    use crate::engine::surface::SurfaceParams;
    use crate::engine::sweep::Sweep;

    #[test]
    fn full_contact_energy_is_persson_s_exactly() {
        // At a load far above the pressure fluctuations, u = h + const: the total energy
        // equals E_P = E_c (a_r = 1, S = 1) at every magnification.
        let surface = Surface::generate(&SurfaceParams::new(64, 0.5, 32.0, 4.0, 2)).unwrap();
        let model = Model::new(surface.grid().clone(), 1.0).unwrap();
        let b = Broadening::new(&surface.shells(), 1.0).unwrap();
        let p0 = 8.0;
        let original = Prediction::original(&b, p0).unwrap();
        let corrected = Prediction::corrected(&b, p0, Correction::default()).unwrap();
        let mut sweep = Sweep::new(
            &surface,
            &model,
            SolverKind::Cg,
            SolveOptions::with_tol(1e-10),
        );
        for zeta in [1.0, 2.5, 5.0, 8.0] {
            let s = sweep.solve_at(zeta, p0).unwrap();
            assert_eq!(s.contact_area(), 1.0);
            let u = s.displacement_spectrum(&model);
            let e = model.halfspace.energy_fourier(&model.grid, &u);
            let (ep, ec) = (
                original.elastic_energy(zeta),
                corrected.elastic_energy(zeta),
            );
            // Persson's a_r at p0 = 8 g_bar differs from one by erfc(8 sqrt2) ~ 1e-29.
            assert!((e - ep).abs() < 1e-9 * ep, "zeta = {zeta}: {e} vs {ep}");
            assert!((e - ec).abs() < 1e-9 * ec, "zeta = {zeta}: {e} vs {ec}");
        }
    }

    #[test]
    fn ratios_and_increments_of_known_energies() {
        // E_P = zeta, E_c = 0.8 zeta, E_exa = 0.72 zeta: E_exa / E_c = 0.9, E_exa / E_P =
        // 0.72, and every increment S~ = 0.72.
        let (scene, _, criteria) =
            crate::experiments::shipped_scenes::<EnergyScene>("total_energy");
        let scene = &scene;
        let zetas = ladder(scene.zeta_start, scene.base().zeta_max(), 2, &[]);
        let n = zetas.len();
        let results: Vec<(SeedLoad, EnergyResult)> = scene
            .contact_areas
            .iter()
            .flat_map(|&a| scene.seeds.iter().map(move |&seed| (seed, a)))
            .map(|(seed, a)| {
                let wobble = 1.0 + 0.01 * seed as f64;
                (
                    SeedLoad {
                        seed,
                        contact_area: a,
                    },
                    EnergyResult {
                        p0: 0.1,
                        zetas: zetas.clone(),
                        contact_area: vec![a; n],
                        e_exa: zetas.iter().map(|z| 0.72 * z * wobble).collect(),
                        e_p: zetas.iter().map(|z| z * wobble).collect(),
                        e_c: zetas.iter().map(|z| 0.8 * z * wobble).collect(),
                        area_original: vec![a; n],
                        area_corrected: vec![a; n],
                        windows: vec![vec![1, 2, 3]; scene.increments_at.len()],
                        max_residual: 1e-9,
                    },
                )
            })
            .collect();
        let c = TotalEnergy::conclude(&criteria, scene, &results).unwrap();
        let m = c.measured.unwrap();
        assert!(
            (m.value - 0.9).abs() < 1e-12 && m.std_error < 1e-12,
            "{m:?}"
        );
        for d in c.details.iter().filter(|d| d.key.starts_with("s_tilde")) {
            assert!((d.value.value - 0.72).abs() < 1e-12, "{d:?}");
        }
        // The correction brings the energy closer (0.9 against 0.72).
        assert!(c.check("correction_brings_energy_closer").unwrap().passed);
        assert_eq!(c.figures.len(), 3);
    }

    #[test]
    fn shipped_scenes_are_valid_and_ranges_are_named() {
        let (reduced, full, _) = crate::experiments::shipped_scenes::<EnergyScene>("total_energy");
        reduced.validate().unwrap();
        full.validate().unwrap();
        let mut scene = reduced.clone();
        scene.headline_contact_area = 0.25;
        let e = scene.validate().unwrap_err().to_string();
        assert!(e.contains("headline_contact_area"), "{e}");
        scene = reduced.clone();
        scene.increments_at = vec![100.0];
        let e = scene.validate().unwrap_err().to_string();
        assert!(e.contains("increments_at"), "{e}");
    }

    #[test]
    fn increment_windows_are_consecutive_shells() {
        let surface = Surface::generate(&SurfaceParams::new(64, 0.8, 32.0, 4.0, 1)).unwrap();
        let scene = EnergyScene {
            n: 64,
            hurst: 0.8,
            lambda_l: 32.0,
            lambda_s: 4.0,
            seeds: vec![1],
            contact_areas: vec![0.3],
            headline_contact_area: 0.3,
            low_load_seeds: Vec::new(),
            zeta_start: 1.0,
            steps_per_octave: 2,
            increments_at: vec![3.0],
            increments: 4,
            correction: Correction::default(),
            tol: 1e-8,
        };
        let w = &window_shells(&surface, &scene)[0];
        // Shells k2 = m^2 + n^2 with |k| = 2 zeta: the last at or below zeta = 3 is k2 = 36,
        // then 37, 40, 41, 45.
        let k2: Vec<f64> = w.iter().map(|z| (2.0 * z).powi(2)).collect();
        let expect = [36.0, 37.0, 40.0, 41.0, 45.0];
        assert_eq!(k2.len(), expect.len());
        for (a, b) in k2.iter().zip(expect) {
            assert!((a - b).abs() < 1e-9, "{k2:?}");
        }
    }
}
