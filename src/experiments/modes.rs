//! Single-mode analysis of the elastic energy: Persson's assumptions (d) and (e) (SPEC
//! section 5, rows d and e; paper section "Single-mode analysis of the elastic energy").
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
//! there ([`Sweep::find_load`]); then, at that fixed `p0`, the sweep climbs from
//! `zeta_start` to `zeta_end` in log-spaced steps ([`ladder`]) that also include, for every
//! target, `zeta_t` (where `a_r(zeta_t)` is measured), the onset point
//! `onset_ratio * zeta_t` and the start of the frozen window `frozen_from * zeta_t`. Each
//! solve is warm-started from the previous step.
//!
//! # Statistics
//!
//! Ensemble values of `E_norm` are ratios of sums over realizations
//! ([`Estimate::ratio_of_sums`]).
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
//!   through `(x, ln E_inf)`.

use serde::{Deserialize, Serialize};

use crate::engine::contact::{ContactSolution, Model};
use crate::engine::grid::Grid;
use crate::engine::solver::SolveOptions;
use crate::engine::solver::SolverKind;
use crate::engine::surface::{Surface, SurfaceParams};
use crate::engine::sweep::Sweep;
use crate::error::{check_open, check_positive, Error, Result};
use crate::persson::Correction;
use crate::plot::{Axis, Figure, Series, Style};
use crate::stats::{round_sig, Estimate, LineFit};
use crate::validation::{Check, Conclusion, Definition, Detail, Experiment, JobContext, Table};

/// The paper's asymptote law `K1 exp(-K2 x)` for `H = 0.8`: `(K1, K2)`.
pub const PAPER_K_H08: (f64, f64) = (0.9, 1.0);
/// The paper's asymptote law `K1 exp(-K2 x)` for `H = 0.3`: `(K1, K2)`.
pub const PAPER_K_H03: (f64, f64) = (0.7, 1.4);

/// A band of modes around a target wavenumber: the half-spectrum indices with
/// `|q/q_t - 1| <= half_width`, and their full-contact energy.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Target magnification `zeta_t = q_t / q_l`.
    pub zeta_t: f64,
    /// Half-spectrum indices of the band's modes.
    pub modes: Vec<usize>,
    /// Full-contact energy of the band, `(E*/4) sum_band q |h~(q)|^2` (full spectrum).
    pub nominal: f64,
    /// Magnification of the band's first mode (`min |q| / q_l`).
    pub zeta_lo: f64,
    /// Magnification of the band's last mode (`max |q| / q_l`).
    pub zeta_hi: f64,
}

impl Band {
    /// The band of `surface` around `zeta_t` with relative half-width `half_width`, on a
    /// half-space of modulus `e_star`. Errors name `zeta_t` when the band holds no mode
    /// with roughness.
    pub fn new(surface: &Surface, zeta_t: f64, half_width: f64, e_star: f64) -> Result<Self> {
        let grid: &Grid = surface.grid();
        let q_t = zeta_t * surface.q_l();
        let mut modes = Vec::new();
        let (mut nominal, mut lo, mut hi) = (0.0, f64::INFINITY, 0.0f64);
        for s in 0..grid.modes() {
            let q = grid.q(s);
            if grid.k2(s) == 0 || (q / q_t - 1.0).abs() > half_width {
                continue;
            }
            modes.push(s);
            let h2 = surface.modes()[s].norm_sqr();
            nominal += grid.weight_of(s) * 0.25 * e_star * q * h2;
            lo = lo.min(q / surface.q_l());
            hi = hi.max(q / surface.q_l());
        }
        if nominal <= 0.0 || !nominal.is_finite() {
            return Err(Error::invalid(
                "targets",
                zeta_t,
                format!("a magnification whose band (|q/q_t - 1| <= {half_width}) holds roughness"),
            ));
        }
        Ok(Self {
            zeta_t,
            modes,
            nominal,
            zeta_lo: lo,
            zeta_hi: hi,
        })
    }

    /// The band's share of the per-mode energies `energies` (weighted, as from
    /// [`HalfSpace::mode_energies`](crate::engine::elastic::HalfSpace::mode_energies)).
    pub fn energy(&self, energies: &[f64]) -> f64 {
        self.modes.iter().map(|&s| energies[s]).sum()
    }
}

/// The elastic energy `E_exa` of every band in `bands` for `solution`, eq.
/// (elasticEnergy_u_q) summed over each band.
pub fn band_energies(model: &Model, solution: &ContactSolution, bands: &[Band]) -> Vec<f64> {
    let u = solution.displacement_spectrum(model);
    let energies = model.halfspace.mode_energies(&model.grid, &u);
    bands.iter().map(|b| b.energy(&energies)).collect()
}

/// Magnification steps: `per_octave` log-spaced steps from `start` to `end` (both
/// included), merged with the `extra` points that lie in `[start, end]`, sorted, with
/// points closer than a relative `1e-9` merged.
pub fn ladder(start: f64, end: f64, per_octave: usize, extra: &[f64]) -> Vec<f64> {
    let octaves = (end / start).log2();
    let count = ((octaves * per_octave as f64).ceil() as usize).max(1);
    let mut z: Vec<f64> = (0..=count)
        .map(|k| start * (end / start).powf(k as f64 / count as f64))
        .collect();
    z.extend(
        extra
            .iter()
            .copied()
            .filter(|&x| x >= start * (1.0 - 1e-12) && x <= end * (1.0 + 1e-12)),
    );
    z.sort_by(f64::total_cmp);
    z.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
    z
}

/// Index of `zeta` in `steps` (to a relative `1e-9`).
fn step_of(steps: &[f64], zeta: f64) -> usize {
    steps
        .iter()
        .position(|&z| (z - zeta).abs() <= 1e-9 * zeta)
        .expect("the ladder holds every target's points")
}

/// Scene of the single-mode experiments (d) and (e).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModeScene {
    /// Points per side.
    pub n: usize,
    /// Hurst exponent.
    pub hurst: f64,
    /// Long-wavelength cutoff (grid units).
    pub lambda_l: f64,
    /// Short-wavelength cutoff (grid units).
    pub lambda_s: f64,
    /// Realizations.
    pub seeds: Vec<u64>,
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
    /// Solver.
    pub solver: SolverKind,
    /// Residual tolerance.
    pub tol: f64,
}

impl ModeScene {
    fn params(&self, seed: u64) -> SurfaceParams {
        SurfaceParams::new(self.n, self.hurst, self.lambda_l, self.lambda_s, seed)
    }

    fn zeta_max(&self) -> f64 {
        self.lambda_l / self.lambda_s
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

    fn validate(&self) -> Result<()> {
        let p = self.params(0);
        p.spectrum.validate(&Grid::new(p.n, 1.0)?)?;
        crate::error::check_seeds(&self.seeds)?;
        if self.contact_areas.is_empty() {
            return Err(Error::invalid(
                "contact_areas",
                "[]",
                "at least one contact area in (0, 1)",
            ));
        }
        for &a in &self.contact_areas {
            check_open("contact_areas", a, 0.0, 1.0)?;
        }
        if !self.contact_areas.contains(&self.headline_contact_area) {
            return Err(Error::invalid(
                "headline_contact_area",
                self.headline_contact_area,
                format!("one of contact_areas {:?}", self.contact_areas),
            ));
        }
        check_open("band", self.band, 0.0, 0.5)?;
        check_positive("zeta_start", self.zeta_start)?;
        if !(self.zeta_end > self.zeta_start && self.zeta_end <= self.zeta_max() * (1.0 + 1e-12)) {
            return Err(Error::invalid(
                "zeta_end",
                self.zeta_end,
                format!(
                    "in (zeta_start = {}, lambda_l / lambda_s = {}]",
                    self.zeta_start,
                    self.zeta_max()
                ),
            ));
        }
        if !(1..=64).contains(&self.steps_per_octave) {
            return Err(Error::invalid(
                "steps_per_octave",
                self.steps_per_octave,
                "an integer in [1, 64]",
            ));
        }
        check_open("onset_ratio", self.onset_ratio, 0.0, 1.0 - self.band)?;
        if !(self.frozen_from > 1.0 + self.band && self.frozen_from.is_finite()) {
            return Err(Error::invalid(
                "frozen_from",
                self.frozen_from,
                format!("> 1 + band = {}", 1.0 + self.band),
            ));
        }
        if self.targets.is_empty() || self.targets.windows(2).any(|w| w[1] <= w[0]) {
            return Err(Error::invalid(
                "targets",
                format!("{:?}", self.targets),
                "a non-empty increasing list",
            ));
        }
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
        self.correction.validate()?;
        SolveOptions::with_tol(self.tol).validate()
    }
}

/// One realization at one load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModeJob {
    /// Seed.
    pub seed: u64,
    /// Load: relative contact area at full resolution.
    pub contact_area: f64,
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
    fn denominator(&self, t: usize, zeta_t: f64) -> f64 {
        self.contact_area[step_of(&self.zetas, zeta_t)] * self.band_nominal[t]
    }

    /// `E_norm` of target `t` at every step.
    fn e_norm(&self, t: usize, zeta_t: f64) -> Vec<f64> {
        let d = self.denominator(t, zeta_t);
        self.band_energy[t].iter().map(|e| e / d).collect()
    }
}

/// Runs one job: the load at full resolution, then the sweep at that load.
fn run_sweep(scene: &ModeScene, job: &ModeJob) -> Result<ModeResult> {
    let surface = Surface::generate(&scene.params(job.seed))?;
    let model = Model::new(surface.grid().clone(), 1.0)?;
    let e_star = model.halfspace.e_star();
    let bands = scene
        .targets
        .iter()
        .map(|&t| Band::new(&surface, t, scene.band, e_star))
        .collect::<Result<Vec<_>>>()?;
    let mut sweep = Sweep::new(
        &surface,
        &model,
        scene.solver,
        SolveOptions::with_tol(scene.tol),
    );
    let p0 = sweep.find_load(surface.zeta_max(), job.contact_area)?;
    let mut max_residual = sweep.solution().map_or(0.0, |s| s.stats.residual.value());
    // The climb starts on a nearly flat surface: a cold start is closer than the
    // full-resolution solution.
    sweep.take_solution();
    let zetas = scene.steps();
    let mut contact_area = Vec::with_capacity(zetas.len());
    let mut band_energy = vec![Vec::with_capacity(zetas.len()); bands.len()];
    for &zeta in &zetas {
        let s = sweep.solve_at(zeta, p0)?;
        max_residual = max_residual.max(s.stats.residual.value());
        contact_area.push(s.contact_area());
        for (t, e) in band_energies(&model, s, &bands).into_iter().enumerate() {
            band_energy[t].push(e);
        }
    }
    Ok(ModeResult {
        p0,
        zetas,
        contact_area,
        band_energy,
        band_nominal: bands.iter().map(|b| b.nominal).collect(),
        max_residual,
    })
}

fn jobs_of(scene: &ModeScene) -> Vec<ModeJob> {
    let mut jobs = Vec::new();
    for &contact_area in &scene.contact_areas {
        for &seed in &scene.seeds {
            jobs.push(ModeJob { seed, contact_area });
        }
    }
    jobs
}

/// The ensemble at one load.
struct Load<'a> {
    contact_area: f64,
    runs: Vec<&'a ModeResult>,
}

fn loads<'a>(scene: &ModeScene, results: &'a [(ModeJob, ModeResult)]) -> Vec<Load<'a>> {
    scene
        .contact_areas
        .iter()
        .map(|&a| Load {
            contact_area: a,
            runs: results
                .iter()
                .filter(|(j, _)| j.contact_area == a)
                .map(|(_, r)| r)
                .collect(),
        })
        .collect()
}

impl Load<'_> {
    /// Ensemble `E_norm` of target `t` at step `k`.
    fn e_norm(&self, t: usize, zeta_t: f64, k: usize) -> Estimate {
        let pairs: Vec<(f64, f64)> = self
            .runs
            .iter()
            .map(|r| (r.band_energy[t][k], r.denominator(t, zeta_t)))
            .collect();
        Estimate::ratio_of_sums(&pairs)
    }

    /// Ensemble contact area at step `k`.
    fn contact_area_at(&self, k: usize) -> Estimate {
        Estimate::mean_of(
            &self
                .runs
                .iter()
                .map(|r| r.contact_area[k])
                .collect::<Vec<_>>(),
        )
    }

    /// Ensemble change `E_norm(k1) - E_norm(k0)` of target `t`.
    fn change(&self, t: usize, zeta_t: f64, k0: usize, k1: usize) -> Estimate {
        let pairs: Vec<(f64, f64)> = self
            .runs
            .iter()
            .map(|r| {
                let e = &r.band_energy[t];
                (e[k1] - e[k0], r.denominator(t, zeta_t))
            })
            .collect();
        Estimate::ratio_of_sums(&pairs)
    }
}

fn max_residual(results: &[(ModeJob, ModeResult)]) -> f64 {
    results.iter().map(|r| r.1.max_residual).fold(0.0, f64::max)
}

/// The table of every ensemble `E_norm` (all loads, targets and steps).
fn curve_table(name: &str, scene: &ModeScene, loads: &[Load]) -> Table {
    let steps = scene.steps();
    let mut table = Table::new(
        name,
        &[
            "contact_area_full",
            "zeta_t",
            "zeta",
            "e_norm",
            "std_error",
            "persson_original",
            "persson_corrected",
            "contact_area",
        ],
    );
    for load in loads {
        for (t, &zt) in scene.targets.iter().enumerate() {
            let s = scene
                .correction
                .factor(load.contact_area_at(step_of(&steps, zt)).value);
            for (k, &z) in steps.iter().enumerate() {
                let e = load.e_norm(t, zt, k);
                let theta = if z >= zt { 1.0 } else { 0.0 };
                table.push(vec![
                    load.contact_area,
                    zt,
                    z,
                    e.value,
                    e.std_error,
                    theta,
                    s * theta,
                    load.contact_area_at(k).value,
                ]);
            }
        }
    }
    table
}

/// One figure per load: `E_norm` of every target against `zeta`, Persson's `S Theta` beside
/// it, and the measured contact area on the right axis (the paper's figures 11 and 12).
fn curve_figures(prefix: &str, scene: &ModeScene, loads: &[Load]) -> Vec<Figure> {
    let steps = scene.steps();
    let mut figures = Vec::new();
    for load in loads {
        let mut fig = Figure {
            name: format!("{prefix}_ar{}", load.contact_area),
            title: format!(
                "Normalised mode energy, H = {}, a_r = {} at full resolution",
                scene.hurst, load.contact_area
            ),
            x: Axis::log("magnification zeta"),
            y: Axis::linear("E_norm = E_exa / E_P (band around q_t)"),
            y2: Some(Axis::linear("relative contact area a_r")),
            series: Vec::new(),
        };
        for (t, &zt) in scene.targets.iter().enumerate() {
            fig.series.push(Series::with_errors(
                format!("simulation, zeta_t = {zt}"),
                Style::LinePoints,
                steps.iter().enumerate().map(|(k, &z)| {
                    let e = load.e_norm(t, zt, k);
                    (z, e.value, e.std_error)
                }),
            ));
            let s = scene
                .correction
                .factor(load.contact_area_at(step_of(&steps, zt)).value);
            let (z0, z1) = (steps[0], steps[steps.len() - 1]);
            fig.series.push(Series::xy(
                format!("Persson S Theta(zeta - {zt})"),
                Style::Dashed,
                [(z0, 0.0), (zt, 0.0), (zt, s), (z1, s)],
            ));
        }
        fig.series.push(
            Series::with_errors(
                "contact area",
                Style::Line,
                steps.iter().enumerate().map(|(k, &z)| {
                    let a = load.contact_area_at(k);
                    (z, a.value, a.std_error)
                }),
            )
            .on_right(),
        );
        figures.push(fig);
    }
    figures
}

/// A golden value of `E_norm`: two significant digits, and no digits below `1e-4` (an
/// onset of a few `1e-6` near full contact is solver noise, not a result).
fn golden(x: f64) -> f64 {
    if x.abs() < 1e-3 {
        (x * 1e4).round() / 1e4
    } else {
        round_sig(x, 2)
    }
}

fn z_text(e: Estimate, reference: f64) -> String {
    format!("{:.1}", e.z_score(reference))
}

/// Assumption (d): a mode holds no energy before it is resolved.
pub struct ModeOnset;

impl Experiment for ModeOnset {
    const FAMILY: &'static str = "modes";
    type Scene = ModeScene;
    type Job = ModeJob;
    type JobResult = ModeResult;

    fn validate(scene: &ModeScene) -> Result<()> {
        scene.validate()
    }

    fn jobs(scene: &ModeScene) -> Vec<ModeJob> {
        jobs_of(scene)
    }

    fn run_job(scene: &ModeScene, job: &ModeJob, _ctx: &JobContext) -> Result<ModeResult> {
        run_sweep(scene, job)
    }

    fn conclude(
        def: &Definition<ModeScene>,
        scene: &ModeScene,
        results: &[(ModeJob, ModeResult)],
    ) -> Result<Conclusion> {
        let steps = scene.steps();
        let loads = loads(scene, results);
        let mut c = Conclusion {
            persson: 0.0,
            max_residual: max_residual(results),
            ..Default::default()
        };
        let onset_of = |zt: f64| step_of(&steps, scene.onset_ratio * zt);
        // Headline: per realization, the mean over targets of E_norm at the onset point.
        let headline = loads
            .iter()
            .find(|l| l.contact_area == scene.headline_contact_area)
            .expect("validated");
        let per_run: Vec<f64> = headline
            .runs
            .iter()
            .map(|r| {
                scene
                    .targets
                    .iter()
                    .enumerate()
                    .map(|(t, &zt)| r.e_norm(t, zt)[onset_of(zt)])
                    .sum::<f64>()
                    / scene.targets.len() as f64
            })
            .collect();
        let measured = Estimate::mean_of(&per_run);
        c.measured = Some(measured);
        c.golden
            .insert("onset_headline".into(), round_sig(measured.value, 2));

        // The paper's two-sided finding: near full contact Persson's step is essentially
        // exact; as contact becomes partial, bands fill before they are resolved.
        let lowest = scene
            .contact_areas
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let highest = scene.contact_areas.iter().copied().fold(0.0, f64::max);
        let z = def.verdict.significance;
        let (mut negligible, mut grows) = (true, true);
        let (mut high_text, mut grow_text) = (Vec::new(), Vec::new());
        for (t, &zt) in scene.targets.iter().enumerate() {
            let k = onset_of(zt);
            let at = |a: f64| {
                let load = loads.iter().find(|l| l.contact_area == a).expect("a load");
                (load.e_norm(t, zt, k), load.contact_area_at(k))
            };
            let (high, a_high) = at(highest);
            let (low, _) = at(lowest);
            negligible &= high.value + z * high.std_error < def.verdict.resolution;
            grows &= low.value - high.value > z * low.std_error.hypot(high.std_error);
            high_text.push(format!(
                "zeta_t = {zt}: {:.4} +- {:.4} (a_r = {:.3} at the onset point)",
                high.value, high.std_error, a_high.value
            ));
            grow_text.push(format!(
                "zeta_t = {zt}: {:.3} +- {:.3} against {:.4} +- {:.4}",
                low.value, low.std_error, high.value, high.std_error
            ));
        }
        for load in &loads {
            for (t, &zt) in scene.targets.iter().enumerate() {
                let k = onset_of(zt);
                let e = load.e_norm(t, zt, k);
                let a = load.contact_area_at(k);
                c.details.push(Detail {
                    name: format!(
                        "E_norm at zeta = {:.3} (zeta_t = {zt}), a_r = {} at full resolution \
                         ({:.3} measured at that zeta)",
                        steps[k], load.contact_area, a.value
                    ),
                    value: e,
                    persson: Some(0.0),
                    paper: None,
                    grid: None,
                });
                c.golden.insert(
                    format!("onset_ar{}_zt{zt}", load.contact_area),
                    golden(e.value),
                );
            }
        }
        if highest > lowest {
            c.checks.push(Check {
                name: format!(
                    "near full contact (a_r = {highest} at full resolution) the onset is \
                     negligible: E_norm + {z} standard errors below {}",
                    def.verdict.resolution
                ),
                passed: negligible,
                detail: high_text.join("; "),
            });
            c.checks.push(Check {
                name: format!(
                    "the onset grows as contact becomes partial: E_norm at a_r = {lowest} \
                     exceeds that at a_r = {highest} by {z} combined standard errors"
                ),
                passed: grows,
                detail: grow_text.join("; "),
            });
        }
        c.account = format!(
            "Over {} realizations (H = {}, {}x{} grid, lambda_l = {}, lambda_s = {}), at the \
             load that gives a_r = {} at full resolution, bands of modes within {:.0}% of \
             q_t = zeta_t q_l (zeta_t = {:?}) hold, at zeta = {} zeta_t (before any mode of the \
             band is resolved), on average E_norm = {:.3} +- {:.3} of the energy Persson's \
             theory assigns them once resolved (z = {} against Persson's 0). At the lowest \
             load (a_r = {lowest}) the onset is {}; at the highest (a_r = {highest}) it is {}. \
             A mode's energy is thus populated before its roughness is resolved once contact is \
             partial, as the paper reports (the pressure of a partial contact has Fourier \
             components at every wavevector), while near full contact Persson's step holds.",
            scene.seeds.len(),
            scene.hurst,
            scene.n,
            scene.n,
            scene.lambda_l,
            scene.lambda_s,
            scene.headline_contact_area,
            100.0 * scene.band,
            scene.targets,
            scene.onset_ratio,
            measured.value,
            measured.std_error,
            z_text(measured, 0.0),
            grow_text
                .iter()
                .map(|t| t.split(" against ").next().unwrap_or_default())
                .collect::<Vec<_>>()
                .join(", "),
            high_text.join(", "),
        );
        c.tables.push(curve_table(&def.name, scene, &loads));
        c.figures = curve_figures("e_norm", scene, &loads);
        Ok(c)
    }
}

/// Per-realization asymptote `E_inf` (intercept of `E_norm` against `1/zeta`) and
/// `x = -d ln a_r / d ln zeta` over the frozen window of target `t`.
fn asymptote(scene: &ModeScene, run: &ModeResult, t: usize) -> Option<(f64, f64)> {
    let zt = scene.targets[t];
    let from = step_of(&run.zetas, scene.frozen_from * zt);
    let e = run.e_norm(t, zt);
    let inv: Vec<f64> = run.zetas[from..].iter().map(|z| 1.0 / z).collect();
    let fit = LineFit::fit(&inv, &e[from..])?;
    let ln_z: Vec<f64> = run.zetas[from..].iter().map(|z| z.ln()).collect();
    let ln_a: Vec<f64> = run.contact_area[from..].iter().map(|a| a.ln()).collect();
    let slope = LineFit::fit(&ln_z, &ln_a)?;
    Some((fit.intercept.value, -slope.slope.value))
}

/// Assumption (e): a resolved mode's energy no longer changes.
pub struct ModeFrozen;

impl Experiment for ModeFrozen {
    const FAMILY: &'static str = "modes";
    type Scene = ModeScene;
    type Job = ModeJob;
    type JobResult = ModeResult;

    fn validate(scene: &ModeScene) -> Result<()> {
        scene.validate()?;
        for &t in &scene.targets {
            if scene.frozen_from * t * (1.0 + 1e-12) >= scene.zeta_end {
                return Err(Error::invalid(
                    "targets",
                    t,
                    format!(
                        "a magnification with frozen_from * zeta_t < zeta_end = {} (a frozen \
                         window after resolution)",
                        scene.zeta_end
                    ),
                ));
            }
        }
        Ok(())
    }

    fn jobs(scene: &ModeScene) -> Vec<ModeJob> {
        jobs_of(scene)
    }

    fn run_job(scene: &ModeScene, job: &ModeJob, _ctx: &JobContext) -> Result<ModeResult> {
        run_sweep(scene, job)
    }

    fn conclude(
        def: &Definition<ModeScene>,
        scene: &ModeScene,
        results: &[(ModeJob, ModeResult)],
    ) -> Result<Conclusion> {
        let steps = scene.steps();
        let end = steps.len() - 1;
        let loads = loads(scene, results);
        let mut c = Conclusion {
            persson: 0.0,
            max_residual: max_residual(results),
            ..Default::default()
        };
        let from_of = |zt: f64| step_of(&steps, scene.frozen_from * zt);
        // Changes after resolution, asymptotes and contact-area slopes.
        let mut k_points = Vec::new();
        let mut asym_table = Table::new(
            "asymptotes",
            &[
                "contact_area_full",
                "zeta_t",
                "change",
                "change_std_error",
                "asymptote",
                "asymptote_std_error",
                "x",
                "x_std_error",
            ],
        );
        let mut changes = Vec::new();
        for load in &loads {
            for (t, &zt) in scene.targets.iter().enumerate() {
                let k0 = from_of(zt);
                let change = load.change(t, zt, k0, end);
                let fits: Vec<(f64, f64)> = load
                    .runs
                    .iter()
                    .filter_map(|r| asymptote(scene, r, t))
                    .collect();
                let e_inf = Estimate::mean_of(&fits.iter().map(|f| f.0).collect::<Vec<_>>());
                let x = Estimate::mean_of(&fits.iter().map(|f| f.1).collect::<Vec<_>>());
                let s = scene
                    .correction
                    .factor(load.contact_area_at(step_of(&steps, zt)).value);
                asym_table.push(vec![
                    load.contact_area,
                    zt,
                    change.value,
                    change.std_error,
                    e_inf.value,
                    e_inf.std_error,
                    x.value,
                    x.std_error,
                ]);
                c.details.push(Detail {
                    name: format!(
                        "change of E_norm from zeta = {:.3} to {:.3} (zeta_t = {zt}, a_r = {} at \
                         full resolution)",
                        steps[k0], steps[end], load.contact_area
                    ),
                    value: change,
                    persson: Some(0.0),
                    paper: None,
                    grid: None,
                });
                c.details.push(Detail {
                    name: format!(
                        "asymptote of E_norm, zeta -> infinity (zeta_t = {zt}, a_r = {}), at \
                         x = -dln a_r/dln zeta = {:.3} +- {:.3}",
                        load.contact_area, x.value, x.std_error
                    ),
                    value: e_inf,
                    persson: Some(s),
                    paper: None,
                    grid: None,
                });
                c.golden.insert(
                    format!("change_ar{}_zt{zt}", load.contact_area),
                    round_sig(change.value, 2),
                );
                // Full contact (x ~ 0, a_r ~ 1) is left out of the fit, as in the paper.
                let a_end = load.contact_area_at(end).value;
                if e_inf.value > 0.0 && a_end < 0.99 {
                    k_points.push((x.value, e_inf.value.ln()));
                }
                changes.push((load.contact_area, t, change));
            }
        }
        // Headline: the longest-wavelength target at the lowest load.
        let lowest = scene
            .contact_areas
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let highest = scene.contact_areas.iter().copied().fold(0.0, f64::max);
        let pick = |a: f64, t: usize| {
            changes
                .iter()
                .find(|(ca, tt, _)| *ca == a && *tt == t)
                .expect("every load and target")
                .2
        };
        let measured = pick(lowest, 0);
        c.measured = Some(measured);
        c.golden
            .insert("change_headline".into(), round_sig(measured.value, 2));

        // The paper: the reduction is stronger for long than for short wavelengths.
        if scene.targets.len() > 1 {
            let last = scene.targets.len() - 1;
            let low_load = loads
                .iter()
                .find(|l| l.contact_area == lowest)
                .expect("every load");
            let diffs: Vec<f64> = low_load
                .runs
                .iter()
                .filter_map(|r| Some(asymptote(scene, r, 0)?.0 - asymptote(scene, r, last)?.0))
                .collect();
            let d = Estimate::mean_of(&diffs);
            c.details.push(Detail {
                name: format!(
                    "asymptote of zeta_t = {} minus that of zeta_t = {} at a_r = {lowest} \
                     (paper: negative, long wavelengths lose more)",
                    scene.targets[0], scene.targets[last]
                ),
                value: d,
                persson: Some(0.0),
                paper: None,
                grid: None,
            });
            c.golden
                .insert("asymptote_long_minus_short".into(), round_sig(d.value, 2));
        }

        // The paper's law for the asymptote.
        let paper_k = if (scene.hurst - 0.8).abs() < 0.05 {
            Some(PAPER_K_H08)
        } else if (scene.hurst - 0.3).abs() < 0.05 {
            Some(PAPER_K_H03)
        } else {
            None
        };
        let xs: Vec<f64> = k_points.iter().map(|p| p.0).collect();
        let ys: Vec<f64> = k_points.iter().map(|p| p.1).collect();
        let k_fit = LineFit::fit(&xs, &ys);
        let mut k_text = String::from("too few partial-contact points to fit K1 exp(-K2 x)");
        if let Some(f) = k_fit {
            let k1 = Estimate::new(
                f.intercept.value.exp(),
                f.intercept.std_error * f.intercept.value.exp(),
            );
            let k2 = Estimate::new(-f.slope.value, f.slope.std_error);
            c.details.push(Detail {
                name: "K1 of the asymptote law K1 exp(-K2 x)".into(),
                value: k1,
                persson: None,
                paper: paper_k.map(|k| k.0),
                grid: None,
            });
            c.details.push(Detail {
                name: "K2 of the asymptote law K1 exp(-K2 x)".into(),
                value: k2,
                persson: None,
                paper: paper_k.map(|k| k.1),
                grid: None,
            });
            c.golden.insert("k1".into(), round_sig(k1.value, 2));
            c.golden.insert("k2".into(), round_sig(k2.value, 2));
            k_text = format!(
                "A fit of the asymptotes to K1 exp(-K2 x) over {} partial-contact points gives \
                 K1 = {:.2} +- {:.2}, K2 = {:.2} +- {:.2}{}.",
                k_points.len(),
                k1.value,
                k1.std_error,
                k2.value,
                k2.std_error,
                match paper_k {
                    Some((a, b)) => format!(" (paper, H = {}: K1 = {a}, K2 = {b})", scene.hurst),
                    None => String::new(),
                }
            );
            c.checks.push(Check {
                name: "the asymptote falls as the contact area shrinks faster (K2 > 0)".into(),
                passed: k2.value > 0.0,
                detail: format!("K2 = {:.3} +- {:.3}", k2.value, k2.std_error),
            });
        }

        // The paper: long wavelengths recede at low load; near full contact the mode is
        // frozen (Persson's assumption nearly holds).
        let low = pick(lowest, 0);
        c.checks.push(Check {
            name: "long-wavelength energy recedes after resolution at the lowest load".into(),
            passed: low.value < 0.0 && -low.value > def.verdict.significance * low.std_error,
            detail: format!(
                "change {:.3} +- {:.3} at a_r = {lowest}, zeta_t = {}",
                low.value, low.std_error, scene.targets[0]
            ),
        });
        if highest > lowest {
            let high = pick(highest, 0);
            c.checks.push(Check {
                name: "the change is smaller near full contact than at the lowest load".into(),
                passed: high.value.abs() < low.value.abs(),
                detail: format!(
                    "|change| {:.3} at a_r = {highest} against {:.3} at a_r = {lowest}",
                    high.value.abs(),
                    low.value.abs()
                ),
            });
        }
        c.account = format!(
            "Over {} realizations (H = {}, {}x{} grid, lambda_l = {}, lambda_s = {}), after a \
             band of modes around zeta_t = {} is resolved its normalised energy changes by \
             {:.3} +- {:.3} between zeta = {} zeta_t and zeta = {} at the lowest load \
             (a_r = {lowest} at full resolution), z = {} against Persson's frozen energy. {}",
            scene.seeds.len(),
            scene.hurst,
            scene.n,
            scene.n,
            scene.lambda_l,
            scene.lambda_s,
            scene.targets[0],
            measured.value,
            measured.std_error,
            scene.frozen_from,
            scene.zeta_end,
            z_text(measured, 0.0),
            k_text,
        );
        c.tables.push(curve_table(&def.name, scene, &loads));
        c.tables.push(asym_table);
        c.figures = curve_figures("e_norm", scene, &loads);
        let mut fig = Figure {
            name: "asymptote".into(),
            title: format!(
                "Asymptote of E_norm against x = -dln a_r / dln zeta, H = {}",
                scene.hurst
            ),
            x: Axis::linear("x = -d ln a_r / d ln zeta"),
            y: Axis::linear("asymptotic E_norm"),
            y2: None,
            series: vec![Series::xy(
                "simulation (partial contact)",
                Style::Points,
                k_points.iter().map(|&(x, y)| (x, y.exp())),
            )],
        };
        let x_hi = xs.iter().copied().fold(0.5, f64::max) * 1.1;
        let grid: Vec<f64> = (0..=40).map(|i| x_hi * i as f64 / 40.0).collect();
        if let Some(f) = k_fit {
            fig.series.push(Series::xy(
                "fit K1 exp(-K2 x)",
                Style::Line,
                grid.iter().map(|&x| (x, f.at(x).exp())),
            ));
        }
        if let Some((k1, k2)) = paper_k {
            fig.series.push(Series::xy(
                format!("paper, {k1} exp(-{k2} x)"),
                Style::Dashed,
                grid.iter().map(|&x| (x, k1 * (-k2 * x).exp())),
            ));
        }
        c.figures.push(fig);
        Ok(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ladder_merges_extra_points_and_keeps_the_ends() {
        let z = ladder(1.0, 8.0, 2, &[3.0, 2.0, 20.0]);
        assert_eq!(z.first(), Some(&1.0));
        assert!((z.last().unwrap() - 8.0).abs() < 1e-12);
        // 2^(k/2) for k = 0..6, plus 3 (2 is already there, 20 is outside).
        assert_eq!(z.len(), 8);
        assert!(z.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn full_contact_gives_persson_exactly() {
        // At a load far above the pressure fluctuations the contact stays complete: u = h
        // + const, so a band holds nothing before resolution and exactly its full-contact
        // energy once resolved, E_norm = Theta(zeta - zeta_t) with a_r = 1.
        let surface = Surface::generate(&SurfaceParams::new(64, 0.8, 32.0, 4.0, 3)).unwrap();
        let model = Model::new(surface.grid().clone(), 1.0).unwrap();
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

    /// A built-in definition of the single-mode experiments.
    fn definition(name: &str) -> Definition<ModeScene> {
        crate::validation::builtin::builtin_sources()
            .into_iter()
            .find(|s| s.header().unwrap().0 == name)
            .unwrap()
            .parse()
            .unwrap()
    }

    /// Synthetic sweeps with known answers: at load `l` the contact area falls as
    /// `a_r = a_l (zeta / zeta_end)^(-x_l)`, every band holds `onset` below resolution and
    /// `K1 exp(-K2 x_l) + b / zeta` in the frozen window.
    fn synthetic(
        scene: &ModeScene,
        k: (f64, f64),
        b: f64,
        onset: f64,
    ) -> Vec<(ModeJob, ModeResult)> {
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
                    ModeJob {
                        seed,
                        contact_area: a_l,
                    },
                    ModeResult {
                        p0: 0.1,
                        zetas: zetas.clone(),
                        contact_area: area.clone(),
                        band_energy,
                        band_nominal: vec![2.0; scene.targets.len()],
                        max_residual: 1e-9,
                    },
                ));
            }
        }
        out
    }

    #[test]
    fn shipped_scenes_are_valid_at_both_scales() {
        for (name, frozen) in [("d_onset", false), ("e_frozen", true)] {
            let def = definition(name);
            for scene in [&def.reduced, &def.full] {
                if frozen {
                    ModeFrozen::validate(scene).unwrap();
                } else {
                    ModeOnset::validate(scene).unwrap();
                }
            }
        }
        let mut scene = definition("e_frozen").reduced;
        scene.frozen_from = 1.05;
        let e = ModeFrozen::validate(&scene).unwrap_err().to_string();
        assert!(e.contains("frozen_from"), "{e}");
        scene.frozen_from = 5.0;
        let e = ModeFrozen::validate(&scene).unwrap_err().to_string();
        assert!(e.contains("targets") && e.contains("zeta_end"), "{e}");
    }

    #[test]
    fn frozen_statistics_recover_a_known_asymptote_law() {
        let def = definition("e_frozen");
        let scene = &def.reduced;
        let (k, b) = ((0.9, 1.0), 0.8);
        let results = synthetic(scene, k, b, 0.0);
        let c = ModeFrozen::conclude(&def, scene, &results).unwrap();
        // Headline: first target, lowest load, from frozen_from zeta_t to zeta_end.
        let zt = scene.targets[0];
        let expect = b / scene.zeta_end - b / (scene.frozen_from * zt);
        let m = c.measured.unwrap();
        assert!((m.value - expect).abs() < 1e-12, "{m:?} vs {expect}");
        let k1 = c.details.iter().find(|d| d.name.starts_with("K1")).unwrap();
        let k2 = c.details.iter().find(|d| d.name.starts_with("K2")).unwrap();
        assert!((k1.value.value - k.0).abs() < 1e-9, "{k1:?}");
        assert!((k2.value.value - k.1).abs() < 1e-9, "{k2:?}");
        // The figure of each load carries the contact area on the right axis.
        let fig = &c.figures[0];
        assert!(fig.y2.is_some());
        assert!(fig
            .series
            .iter()
            .any(|s| s.side == crate::plot::Side::Right));
    }

    #[test]
    fn onset_statistic_is_the_band_energy_below_resolution() {
        let def = definition("d_onset");
        let scene = &def.reduced;
        let results = synthetic(scene, (0.9, 1.0), 0.0, 0.25);
        let c = ModeOnset::conclude(&def, scene, &results).unwrap();
        let m = c.measured.unwrap();
        assert!((m.value - 0.25).abs() < 1e-12, "{m:?}");
        // Equal onset at every load: it does not grow as contact becomes partial.
        assert!(!c.checks[1].passed, "{:?}", c.checks[1]);
    }

    #[test]
    fn band_energy_is_the_full_contact_energy_of_its_shells() {
        let surface = Surface::generate(&SurfaceParams::new(64, 0.5, 32.0, 4.0, 5)).unwrap();
        let band = Band::new(&surface, 4.0, 0.15, 2.0).unwrap();
        let shells: f64 = surface
            .shells()
            .shells
            .iter()
            .filter(|s| (s.zeta / 4.0 - 1.0).abs() <= 0.15)
            .map(|s| s.full_contact_energy(2.0))
            .sum();
        assert!((band.nominal - shells).abs() < 1e-12 * shells);
        let e = Band::new(&surface, 40.0, 0.1, 1.0).unwrap_err().to_string();
        assert!(e.contains("targets"), "{e}");
    }
}
