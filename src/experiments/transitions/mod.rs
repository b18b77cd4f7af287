//! Pressure transitions between two magnifications: assumptions (a) pressure-independent
//! diffusion and (b) no drift ([`crate::conventions`], section 6, rows a and b; paper section 3.2 and the
//! Appendix).
//!
//! Persson's theory treats every interface point as a walker whose pressure diffuses as
//! the magnification grows, with the transition probability eq. (transitionFinal): a
//! Gaussian of width `Dp^2` (eq. broadening) about the old pressure, mirrored at the
//! absorbing boundary `p = 0`. Here each realization is solved at `zeta` (at the load that
//! gives the scene's contact area there) and again at `zeta + dzeta` (same load, warm
//! start). Walkers are binned by their old pressure in units of `p0 / a_r` (the mean
//! pressure inside contact), and each bin `n` is followed to the new magnification, points
//! that fall out of contact counting at `p = 0`:
//!
//! * the transition probabilities `Pr(p, zeta + dzeta | p', zeta)`, as histograms;
//! * the drift, `mu_n = (<p>_{n, zeta + dzeta} - <p>_{n, zeta}) / dzeta` (Appendix), and the
//!   contact-averaged drift `mu_c = (1/a_r) int Pr(p) mu(p) dp`, i.e. the mean change of
//!   pressure of all walkers in contact at `zeta`, per unit `zeta`;
//! * the diffusion coefficient by the Appendix's moment analysis: with `p' = <p>_{n,new}`
//!   and the bin's second moment `<p^2>_{n,new}`, the width `Dp_n` of the mirror Gaussian
//!   with those moments (eq. 2ndMoment, inverted from the start eq. approxDeltaPress by
//!   Newton's method, [`crate::persson::moments`]), minus the bin's own width
//!   `dp_n^2` (the variance of the old pressures in the bin):
//!   `D_n = (Dp_n^2 - dp_n^2) / dzeta`, compared with `D_P = Dp^2 / dzeta` from the shells
//!   of the same realization that the step adds ([`crate::persson::Broadening`]).
//!
//! Bins whose mean is below the broadening (`<p>_{n,zeta} < Dp_n`) are flagged as unsuited
//! for the moment analysis (the paper excludes its bins below 8 for the same reason): they
//! are reported, but not used for the diffusion statistics. Their drift is well defined
//! and is used.
//!
//! Error bars are standard errors over realizations: walkers of one realization are
//! correlated (neighbouring points feel the same added roughness), realizations are not.
//!
//! A scene may carry the paper's other scene of the same analysis (`other_scene`: its
//! first, fig. broadening, at another Hurst exponent, load and step): its realizations
//! run as jobs of their own, keyed as that scene's, and both validations report its
//! headline beside their own. With `contact_line_distances`, every realization is solved
//! again at `zeta` (the same load and solution) and each walker's distance to the nearest
//! point out of contact is binned by its pressure ([`crate::engine::distance`]): how close
//! to a contact line the walkers of low and of high pressure sit (paper sec. 3.1).
//!
//! Both validations share the scene and its jobs (one realization each), here in `mod.rs`.
//! The files:
//!
//! * `stats.rs`: the statistics of the bins, pure functions of the binned walkers;
//! * `figures.rs`: what both validations show: the table of the bins, the transition
//!   probabilities, the account of the runs and the pressure axis of their figures;
//! * `diffusion.rs`, `drift.rs`: one validation each, its statistics, then its findings
//!   (details, checks, golden values), then its account and figure.

mod diffusion;
mod drift;
mod figures;
mod stats;

pub use diffusion::{Diffusion, DiffusionStats};
pub use drift::{contact_drift, Drift, DriftStats};

use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

use super::scene::{leaves_out_planned, step_scene, Step, PLANNED};
use super::{JobContext, Jobs, Work};
use crate::engine::distance::squared_distance_to;
use crate::engine::solver::SolverKind;
use crate::error::{check_positive, Error, Result};
use crate::persson::Broadening;
use crate::stats::{Bins, Histogram};

step_scene! {
    /// Scene of the transition experiment.
    pub struct TransitionScene {
        /// Number of pressure bins.
        pub bins: usize,
        /// Bin width, in units of `p0 / a_r`.
        pub bin_width: f64,
        /// Bins with mean pressure below this (units of `p0 / a_r`) form the low-pressure region.
        pub low_pressure: f64,
        /// Bins with mean pressure above this (units of `p0 / a_r`) form the high-pressure region.
        pub high_pressure: f64,
        /// Bins with fewer walkers in a realization are not analysed for it.
        pub min_walkers: usize,
        /// The paper's other scene of the same analysis (none: not run): the same grid,
        /// bins and solver settings at another roughness, load and step.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub other_scene: Option<OtherStep>,
        /// Every realization solved again at `zeta` for how far each walker lies from the
        /// nearest point out of contact (false: not run).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        pub contact_line_distances: bool,
    }
}

/// The step of the other scene: the scene itself with these fields in place of its own.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OtherStep {
    /// Hurst exponent, in (0, 1).
    pub hurst: f64,
    /// Relative contact area at `zeta` (sets the load).
    pub contact_area: f64,
    /// Magnification before the step.
    pub zeta: f64,
    /// The step of magnification.
    pub dzeta: f64,
    /// Realizations.
    pub seeds: Vec<u64>,
}

/// A job: one realization of the scene (stored bare, as before the other jobs existed),
/// one of the other scene, or the distances of one realization's walkers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum TransitionJob {
    /// A realization of the other scene.
    Other(u64),
    /// The distances of the walkers of a realization of the scene.
    Distances(u64),
    /// A realization of the scene.
    #[serde(untagged)]
    Realization(u64),
}

/// What a job measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum TransitionOutput {
    /// The walkers' distances to the nearest point out of contact.
    Distances(DistanceResult),
    /// The transitions of a realization (of the scene or of the other scene).
    #[serde(untagged)]
    Transitions(TransitionResult),
}

/// The walkers of one realization at `zeta` by pressure bin: how many, and the sum of
/// their distances to the nearest point out of contact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DistanceResult {
    /// The load.
    pub p0: f64,
    /// Contact area at `zeta`.
    pub a_r: f64,
    /// `(walkers, sum of distances in grid spacings)` of each bin of pressure (in units of
    /// `p0 / a_r`, the scene's bins; the last collects the rest).
    pub bins: Vec<(f64, f64)>,
    /// Largest solver residual.
    pub max_residual: f64,
}

/// The transitions of the jobs `pick` selects among the results, by seed.
fn transitions(
    results: &[(TransitionJob, TransitionOutput)],
    pick: fn(&TransitionJob) -> Option<u64>,
) -> Vec<(u64, TransitionResult)> {
    results
        .iter()
        .filter_map(|(j, r)| match (pick(j), r) {
            (Some(seed), TransitionOutput::Transitions(r)) => Some((seed, r.clone())),
            _ => None,
        })
        .collect()
}

/// The scene's own realizations among the results, by seed.
pub(super) fn own(results: &[(TransitionJob, TransitionOutput)]) -> Vec<(u64, TransitionResult)> {
    transitions(results, |j| match j {
        TransitionJob::Realization(seed) => Some(*seed),
        _ => None,
    })
}

/// The other scene's realizations among the results, by seed.
pub(super) fn others(
    results: &[(TransitionJob, TransitionOutput)],
) -> Vec<(u64, TransitionResult)> {
    transitions(results, |j| match j {
        TransitionJob::Other(seed) => Some(*seed),
        _ => None,
    })
}

/// The walkers' distances among the results.
pub(super) fn distances(results: &[(TransitionJob, TransitionOutput)]) -> Vec<&DistanceResult> {
    results
        .iter()
        .filter_map(|(_, r)| match r {
            TransitionOutput::Distances(d) => Some(d),
            TransitionOutput::Transitions(_) => None,
        })
        .collect()
}

/// Sums over the walkers of one bin.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct BinSums {
    /// Walkers.
    pub count: f64,
    /// `sum p_old`.
    pub old: f64,
    /// `sum p_old^2`.
    pub old2: f64,
    /// `sum p_new`.
    pub new: f64,
    /// `sum p_new^2`.
    pub new2: f64,
    /// Walkers with `p_new = 0` (out of contact at the new magnification).
    pub lost: f64,
}

impl BinSums {
    fn add(&mut self, old: f64, new: f64) {
        self.count += 1.0;
        self.old += old;
        self.old2 += old * old;
        self.new += new;
        self.new2 += new * new;
        if new <= 0.0 {
            self.lost += 1.0;
        }
    }
}

/// One realization's transitions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TransitionResult {
    /// Load.
    pub p0: f64,
    /// Contact area at `zeta`.
    pub a_r_old: f64,
    /// Contact area at `zeta + dzeta`.
    pub a_r_new: f64,
    /// Persson's diffusion coefficient of the step, `D_P = Dp^2 / dzeta`.
    pub d_persson: f64,
    /// Walkers in contact at `zeta`, by bin of old pressure (the last bin collects the rest).
    pub bins: Vec<BinSums>,
    /// Walkers out of contact at `zeta`.
    pub zero: BinSums,
    /// Transition counts: row = old bin (0 = out of contact, then the bins), column = new
    /// pressure bin of the same width (0 = out of contact).
    pub histogram: Vec<Vec<u32>>,
    /// Largest solver residual.
    pub max_residual: f64,
}

impl Jobs for TransitionScene {
    const FAMILY: &'static str = "transition";
    type Job = TransitionJob;
    type JobResult = TransitionOutput;

    fn validate(&self) -> Result<()> {
        self.validate_one_step()?;
        if self.bins < 2 {
            return Err(Error::invalid("bins", self.bins, ">= 2"));
        }
        check_positive("bin_width", self.bin_width)?;
        check_positive("low_pressure", self.low_pressure)?;
        check_positive("high_pressure", self.high_pressure)?;
        if self.min_walkers < 2 {
            return Err(Error::invalid("min_walkers", self.min_walkers, ">= 2"));
        }
        if let Some(other) = self.other_step_scene() {
            other.validate().map_err(|e| e.within("other_scene"))?;
        }
        Ok(())
    }

    /// The realizations, then those of the other scene, then the walkers' distances.
    fn jobs(&self) -> Vec<TransitionJob> {
        let seeds = self.all_seeds();
        let own = seeds.iter().map(|&s| TransitionJob::Realization(s));
        let other = self.other_scene.iter().flat_map(|o| &o.seeds);
        let distances = seeds
            .iter()
            .filter(|_| self.contact_line_distances)
            .map(|&s| TransitionJob::Distances(s));
        own.chain(other.map(|&s| TransitionJob::Other(s)))
            .chain(distances)
            .collect()
    }

    /// The planned realizations' jobs ([`PLANNED`]).
    fn part(&self, job: &TransitionJob) -> Option<String> {
        match job {
            TransitionJob::Realization(s) | TransitionJob::Distances(s)
                if self.more_seeds.contains(s) =>
            {
                Some(PLANNED.into())
            }
            _ => None,
        }
    }

    fn leave_out(&mut self, parts: &BTreeSet<String>) {
        if leaves_out_planned(parts) {
            self.more_seeds.clear();
        }
    }

    /// The other scene and the distances are read on the headline solver's solutions.
    fn headline_only(job: &TransitionJob) -> bool {
        !matches!(job, TransitionJob::Realization(_))
    }

    /// The realizations depend on the scene without the other scene and the distances:
    /// their keys are those of the scenes that had neither.
    fn key_scene(&self) -> serde_json::Value {
        let mut scene = self.clone();
        scene.other_scene = None;
        scene.contact_line_distances = false;
        serde_json::to_value(scene).expect("scenes serialise")
    }

    /// A realization of the other scene is keyed as that scene's own realization, so its
    /// key follows the other scene's fields (and a validation of that scene alone would
    /// share it).
    fn shared_job(&self, job: &TransitionJob) -> Option<(serde_json::Value, TransitionJob)> {
        match job {
            TransitionJob::Other(seed) => Some((
                self.other_step_scene()?.key_scene(),
                TransitionJob::Realization(*seed),
            )),
            TransitionJob::Realization(_) | TransitionJob::Distances(_) => None,
        }
    }

    fn work(&self, _job: &TransitionJob) -> Work {
        // The load at zeta, then one step of dzeta.
        Work::search_then(self.n, 1, 0)
    }

    fn run_job(&self, job: &TransitionJob, ctx: &JobContext) -> Result<TransitionOutput> {
        match job {
            TransitionJob::Realization(seed) => {
                run_transition(self, *seed, ctx.solver).map(TransitionOutput::Transitions)
            }
            TransitionJob::Other(seed) => {
                let other = self.other_step_scene().ok_or_else(|| {
                    Error::invalid("other_scene", "none", "a scene for its realizations")
                })?;
                run_transition(&other, *seed, ctx.solver).map(TransitionOutput::Transitions)
            }
            TransitionJob::Distances(seed) => {
                run_distances(self, *seed, ctx.solver).map(TransitionOutput::Distances)
            }
        }
    }

    fn residual(result: &TransitionOutput) -> f64 {
        match result {
            TransitionOutput::Transitions(r) => r.max_residual,
            TransitionOutput::Distances(d) => d.max_residual,
        }
    }
}

impl TransitionScene {
    /// The other scene as a scene of its own (without an other scene).
    pub fn other_step_scene(&self) -> Option<Self> {
        let o = self.other_scene.as_ref()?;
        Some(Self {
            hurst: o.hurst,
            contact_area: o.contact_area,
            zeta: o.zeta,
            dzeta: o.dzeta,
            seeds: o.seeds.clone(),
            more_seeds: Vec::new(),
            other_scene: None,
            ..self.clone()
        })
    }

    /// The pressure bins, pressures in units of `unit` (`p0 / a_r` in pascals or `E*`; 1
    /// for pressures already in units of `p0 / a_r`): the last collects the rest.
    fn pressure_bins(&self, unit: f64) -> Bins {
        Bins::linear(0.0, self.bin_width * unit, self.bins)
    }
}

/// Solves one realization at `zeta` and `zeta + dzeta` and bins its walkers.
fn run_transition(
    scene: &TransitionScene,
    seed: u64,
    solver: SolverKind,
) -> Result<TransitionResult> {
    let r = scene.base().realization(seed)?;
    let Step {
        p0,
        before: old,
        after: new,
    } = scene.one_step(&r, solver)?;
    let a_r_old = old.contact_area();
    let walkers = Walkers::binned(scene, p0 / a_r_old, &old.pressure, &new.pressure);
    let broadening = Broadening::new(&r.surface.shells(), r.model.halfspace.e_star())?;
    Ok(TransitionResult {
        p0,
        a_r_old,
        a_r_new: new.contact_area(),
        d_persson: broadening.diffusion_coefficient(scene.zeta, scene.dzeta)?,
        bins: walkers.bins,
        zero: walkers.zero,
        histogram: walkers.histogram,
        max_residual: old.stats.residual.value().max(new.stats.residual.value()),
    })
}

/// Solves one realization at `zeta` (the load and solution of its transition job) and
/// bins its walkers' distances to the nearest point out of contact by pressure.
fn run_distances(scene: &TransitionScene, seed: u64, solver: SolverKind) -> Result<DistanceResult> {
    let r = scene.base().realization(seed)?;
    let (p0, s) = scene
        .base()
        .solve_at_load(&r, solver, scene.zeta, scene.contact_area)?;
    let a_r = s.contact_area();
    let grid = r.surface.grid();
    let out: Vec<bool> = s.pressure.iter().map(|&p| p <= 0.0).collect();
    let d2 = squared_distance_to(&out, grid.rows(), grid.cols());
    let axis = scene.pressure_bins(p0 / a_r);
    let mut bins = vec![(0.0, 0.0); scene.bins];
    for (&p, &d2) in s.pressure.iter().zip(&d2) {
        if p > 0.0 {
            let b = &mut bins[axis.index(p)];
            b.0 += 1.0;
            b.1 += d2.sqrt();
        }
    }
    Ok(DistanceResult {
        p0,
        a_r,
        bins,
        max_residual: s.stats.residual.value(),
    })
}

/// The walkers of one realization, binned: the parts of a [`TransitionResult`] that the
/// pressures fix.
struct Walkers {
    bins: Vec<BinSums>,
    zero: BinSums,
    histogram: Vec<Vec<u32>>,
}

impl Walkers {
    /// Bins the walkers by old pressure (`old`, in units where the mean contact pressure is
    /// `unit`) and counts their transitions to the new pressures `new`.
    fn binned(scene: &TransitionScene, unit: f64, old: &[f64], new: &[f64]) -> Self {
        let axis = scene.pressure_bins(unit);
        let mut bins = Histogram::<BinSums>::new(axis);
        let mut zero = BinSums::default();
        let mut histogram = vec![vec![0u32; scene.bins + 1]; scene.bins + 1];
        for (&po, &pn) in old.iter().zip(new) {
            let row = if po > 0.0 {
                bins.at(po).add(po, pn);
                axis.index(po) + 1
            } else {
                zero.add(po, pn);
                0
            };
            let col = if pn > 0.0 { axis.index(pn) + 1 } else { 0 };
            histogram[row][col] += 1;
        }
        Self {
            bins: bins.into_cells(),
            zero,
            histogram,
        }
    }
}

/// A realization with the given walkers, for tests of the statistics: `a_r_old = 1`, so
/// that the pressures are in units of `p0 / a_r = p0`.
#[cfg(test)]
fn synthetic(
    scene: &TransitionScene,
    p0: f64,
    d_persson: f64,
    walkers: &[(f64, f64)],
) -> TransitionResult {
    let (old, new): (Vec<f64>, Vec<f64>) = walkers.iter().copied().unzip();
    let w = Walkers::binned(scene, p0, &old, &new);
    TransitionResult {
        p0,
        a_r_old: 1.0,
        a_r_new: 1.0,
        d_persson,
        bins: w.bins,
        zero: w.zero,
        histogram: w.histogram,
        max_residual: 0.0,
    }
}

/// A scene of `bins` bins of width `bin_width`, a step of 0.5 and at least two walkers a
/// bin, for tests of the statistics.
#[cfg(test)]
fn synthetic_scene(bins: usize, bin_width: f64) -> TransitionScene {
    TransitionScene {
        n: 8,
        hurst: 0.8,
        lambda_l: 4.0,
        lambda_s: 2.0,
        seeds: vec![1],
        more_seeds: Vec::new(),
        tol: 1e-9,
        contact_area: 0.3,
        zeta: 1.0,
        dzeta: 0.5,
        bins,
        bin_width,
        low_pressure: 0.5,
        high_pressure: 1.0,
        min_walkers: 2,
        other_scene: None,
        contact_line_distances: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::{Experiment, Jobs};

    #[test]
    fn the_other_scene_is_keyed_as_its_own_and_leaves_the_scene_keys_alone() {
        let (_, full, _) = crate::experiments::shipped_scenes::<TransitionScene>("a_diffusion");
        let other = full
            .other_step_scene()
            .expect("an other scene at full scale");
        assert_eq!((other.hurst, other.contact_area), (0.5, 0.01));
        assert!(other.other_scene.is_none());
        let mut without = full.clone();
        without.other_scene = None;
        without.contact_line_distances = false;
        assert_eq!(full.key_scene(), without.key_scene());
        assert!(full.contact_line_distances);
        assert_eq!(
            full.jobs().len(),
            2 * full.all_seeds().len() + other.all_seeds().len(),
            "the realizations, the other scene's, then the distances"
        );
        for job in full.jobs() {
            match (job, full.shared_job(&job)) {
                (TransitionJob::Realization(_), None) => {}
                (TransitionJob::Distances(_), None) => {
                    assert!(TransitionScene::headline_only(&job));
                }
                (TransitionJob::Other(seed), Some((scene, keyed))) => {
                    assert_eq!(scene, other.key_scene());
                    assert_eq!(keyed, TransitionJob::Realization(seed));
                    assert!(TransitionScene::headline_only(&job));
                }
                (job, shared) => panic!("{job:?} shared as {shared:?}"),
            }
        }
        // Bare seeds are still read as the scene's realizations.
        let bare: TransitionJob = serde_json::from_str("3").unwrap();
        assert_eq!(bare, TransitionJob::Realization(3));
        let mut bad = full;
        bad.other_scene.as_mut().unwrap().zeta = 500.0;
        let e = bad.validate().unwrap_err().to_string();
        assert!(e.contains("other_scene."), "{e}");
    }

    #[test]
    fn the_other_scene_is_read_apart_from_the_scene() {
        // The scene's walkers do not move; the other scene's drift down by 0.1 p0/a_r
        // over the step: mu_c = -0.1 / dzeta there and 0 in the scene.
        let mut scene = synthetic_scene(8, 0.25);
        scene.other_scene = Some(OtherStep {
            hurst: 0.5,
            contact_area: 0.1,
            zeta: 1.0,
            dzeta: 0.5,
            seeds: vec![1, 2],
        });
        let still: Vec<(f64, f64)> = (0..40)
            .map(|k| (0.1 + 0.05 * k as f64, 0.1 + 0.05 * k as f64))
            .collect();
        let down: Vec<(f64, f64)> = still.iter().map(|&(p, _)| (p, p - 0.1)).collect();
        let results = vec![
            (
                TransitionJob::Realization(1),
                synthetic(&scene, 1.0, 1.0, &still),
            ),
            (
                TransitionJob::Realization(2),
                synthetic(&scene, 1.0, 1.0, &still),
            ),
            (TransitionJob::Other(1), synthetic(&scene, 1.0, 1.0, &down)),
            (TransitionJob::Other(2), synthetic(&scene, 1.0, 1.0, &down)),
        ];
        let (_, _, criteria) = crate::experiments::shipped_scenes::<TransitionScene>("b_drift");
        let results: Vec<(TransitionJob, TransitionOutput)> = results
            .into_iter()
            .map(|(j, r)| (j, TransitionOutput::Transitions(r)))
            .collect();
        let c = Drift::conclude(&criteria, &scene, &results).unwrap();
        assert!(c.measured.unwrap().value.abs() < 1e-12);
        let other = c.detail("other_scene_mu_c").unwrap().value;
        assert!((other.value + 0.1 / 0.5).abs() < 1e-9, "{other:?}");
    }
}
