//! The mean gap at low load (paper section 4, tex 1103-1105: "for low pressures the mean
//! gap is approximately only logarithmic in pressure", as Persson's theory of the
//! interfacial separation has it, `u ~ -u0 ln(p0 / p_ref)`).
//!
//! Each job solves one realization of the scene's grid at full resolution at the plan's
//! low reduced pressures `p~0 = p0 / (E* g_bar)`, increasing, each solve warm-started from
//! the one before (the first from cold), and stores the mean gap `mean(u - h)` over the
//! realization's rms height at each. A law logarithmic in the pressure has one slope
//! `d(mean gap) / d ln p~0` over the whole ladder: the statistic is the relative change of
//! that slope between the lower and the upper half of the loads,
//! `s_lower / s_upper - 1`, per realization, then the mean over realizations (0 for a
//! logarithmic law; positive where the gap falls faster at the lowest loads).

use crate::experiments::keys::{DetailKey, Tag};
use serde::{Deserialize, Serialize};

use super::stats::AreaStats;
use super::AreaScene;
use crate::engine::contact::Model;
use crate::engine::solver::SolveOptions;
use crate::engine::surface::{Surface, SurfaceModel};
use crate::engine::sweep::Sweep;
use crate::error::{check_positive, Error, Result};
use crate::experiments::declared::{value_at, DetailTable};
use crate::experiments::scene::check_increasing;
use crate::experiments::{JobContext, Work};
use crate::stats::{Estimate, LineFit};

/// The mean gap study, as a scene states it (`[full.gap]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GapPlan {
    /// Hurst exponents (each one of the scene's).
    pub hursts: Vec<f64>,
    /// Low reduced pressures `p~0`, increasing (at least four: two to each half).
    pub reduced_pressures: Vec<f64>,
}

/// One realization's ladder of low loads, with everything its result depends on beyond
/// the scene's grid and tolerance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GapJob {
    /// Hurst exponent.
    pub hurst: f64,
    /// Seed.
    pub seed: u64,
    /// Reduced pressures `p~0`, increasing.
    pub reduced_pressures: Vec<f64>,
}

/// The mean gap at each load of a ladder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GapResult {
    /// Mean gap over the rms height of the surface, at each load.
    pub mean_gap: Vec<f64>,
    /// Contact area at each load.
    pub contact_area: Vec<f64>,
    /// Largest residual of the solves.
    pub max_residual: f64,
}

impl GapPlan {
    /// Checks the ranges against the scene; errors name the field.
    pub fn validate(&self, scene: &AreaScene) -> Result<()> {
        scene.check_some_hursts("gap.hursts", &self.hursts)?;
        check_increasing("gap.reduced_pressures", &self.reduced_pressures)?;
        if self.reduced_pressures.len() < 4 {
            return Err(Error::invalid(
                "gap.reduced_pressures",
                format!("{:?}", self.reduced_pressures),
                "at least four loads (a slope in each half)",
            ));
        }
        for &p in &self.reduced_pressures {
            check_positive("gap.reduced_pressures", p)?;
        }
        Ok(())
    }

    /// The jobs: every Hurst exponent, every realization of the scene.
    pub fn jobs(&self, seeds: &[u64]) -> Vec<GapJob> {
        self.hursts
            .iter()
            .flat_map(|&hurst| {
                seeds.iter().map(move |&seed| GapJob {
                    hurst,
                    seed,
                    reduced_pressures: self.reduced_pressures.clone(),
                })
            })
            .collect()
    }
}

impl GapJob {
    /// One solve per load on the scene's grid.
    pub fn work(&self, scene: &AreaScene) -> Work {
        Work {
            points: scene.n * scene.n,
            searches: 0.0,
            solves: self.reduced_pressures.len() as f64,
            shells: 0.0,
        }
    }

    /// Solves the ladder, warm-started, and records the mean gap at each load.
    pub fn run(&self, scene: &AreaScene, ctx: &JobContext) -> Result<GapResult> {
        let params = SurfaceModel::new(
            scene.n,
            self.hurst,
            scene.lambda_l,
            scene.lambda_s,
            self.seed,
        );
        let surface = Surface::generate(&params)?;
        let model = Model::new(surface.grid().clone(), 1.0)?;
        let g_bar = surface.rms_gradient(f64::INFINITY);
        let zeta = surface.zeta_max();
        let h_rms = surface.shells().rms_height(zeta);
        let mut sweep = Sweep::new(
            &surface,
            &model,
            ctx.solver,
            SolveOptions::with_tol(scene.tol),
        );
        let mut out = GapResult {
            mean_gap: Vec::new(),
            contact_area: Vec::new(),
            max_residual: 0.0,
        };
        for &p in &self.reduced_pressures {
            sweep.solve_at(zeta, p * g_bar * model.halfspace.e_star())?;
            let s = sweep.solution().expect("a solve keeps its solution");
            out.mean_gap.push(s.mean_gap(sweep.heights()) / h_rms);
            out.contact_area.push(s.contact_area());
            out.max_residual = out.max_residual.max(s.stats.residual.value());
        }
        Ok(out)
    }
}

/// One ladder's relative change of `d(mean gap) / d ln p~0` from the upper half of its
/// loads to the lower half, `s_lower / s_upper - 1` (the middle load, for an odd count,
/// in the lower half).
pub fn slope_change(job: &GapJob, r: &GapResult) -> Option<f64> {
    let ln_p: Vec<f64> = job.reduced_pressures.iter().map(|p| p.ln()).collect();
    let half = ln_p.len().div_ceil(2);
    let slope = |range: std::ops::Range<usize>| {
        LineFit::fit(&ln_p[range.clone()], &r.mean_gap[range]).map(|f| f.slope.value)
    };
    let (lower, upper) = (slope(0..half)?, slope(half..ln_p.len())?);
    Some(lower / upper - 1.0)
}

/// The key of the slope change at Hurst exponent `hurst`.
pub fn key(hurst: f64) -> DetailKey {
    DetailKey::new("gap_log_slope_change").at(Tag::Hurst, hurst)
}

/// The slope change at each of the plan's Hurst exponents: per realization, then the
/// mean over realizations.
pub fn slope_changes(plan: &GapPlan, results: &[(&GapJob, &GapResult)]) -> Vec<(f64, Estimate)> {
    plan.hursts
        .iter()
        .filter_map(|&h| {
            let changes: Vec<f64> = results
                .iter()
                .filter(|(j, _)| j.hurst == h)
                .filter_map(|(j, r)| slope_change(j, r))
                .collect();
            (!changes.is_empty()).then(|| (h, Estimate::mean_of(&changes)))
        })
        .collect()
}

/// Declares the slope change at each of the plan's Hurst exponents as a detail (written
/// where a realization gave one).
pub fn declare(t: &mut DetailTable<'_, AreaStats>, plan: &GapPlan) {
    let p = &plan.reduced_pressures;
    let half = p.len().div_ceil(2);
    for &hurst in &plan.hursts {
        t.row(
            key(hurst),
            format!(
                "d(mean gap)/d ln p~0 over p~0 = {:?} over that over p~0 = {:?}, minus 1, H = \
                 {hurst} (per realization, then over realizations; Persson's logarithmic law: 0)",
                &p[..half],
                &p[half..]
            ),
            move |s: &AreaStats| value_at(&s.gap_slope_changes, hurst),
        )
        .persson(0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ladder(gap: impl Fn(f64) -> f64) -> (GapJob, GapResult) {
        let job = GapJob {
            hurst: 0.8,
            seed: 1,
            reduced_pressures: vec![0.001, 0.002, 0.004, 0.008, 0.016, 0.03],
        };
        let mean_gap = job.reduced_pressures.iter().map(|&p| gap(p)).collect();
        let r = GapResult {
            mean_gap,
            contact_area: vec![0.01; 6],
            max_residual: 0.0,
        };
        (job, r)
    }

    #[test]
    fn a_logarithmic_gap_has_no_slope_change_and_a_power_law_has_one() {
        let (job, r) = ladder(|p| -0.4 * p.ln() + 1.0);
        assert!(slope_change(&job, &r).unwrap().abs() < 1e-12);
        // gap = p^-0.1: the slope in ln p is -0.1 p^-0.1, steeper at low load.
        let (job, r) = ladder(|p| p.powf(-0.1));
        let change = slope_change(&job, &r).unwrap();
        assert!(change > 0.1, "{change}");
        let plan = GapPlan {
            hursts: vec![0.8],
            reduced_pressures: job.reduced_pressures.clone(),
        };
        let (flat_job, flat) = ladder(|p| -0.4 * p.ln());
        let both = slope_changes(&plan, &[(&job, &r), (&flat_job, &flat)]);
        assert_eq!(both.len(), 1);
        assert!((both[0].1.value - change / 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_plan_names_its_fields() {
        let scene: AreaScene = crate::experiments::shipped_scenes::<AreaScene>("contact_area").1;
        let plan = GapPlan {
            hursts: vec![0.8],
            reduced_pressures: vec![0.001, 0.002, 0.004, 0.008],
        };
        plan.validate(&scene).unwrap();
        let e = |p: GapPlan| p.validate(&scene).unwrap_err().to_string();
        assert!(e(GapPlan {
            hursts: vec![0.7],
            ..plan.clone()
        })
        .contains("gap.hursts"));
        assert!(e(GapPlan {
            reduced_pressures: vec![0.001, 0.002, 0.004],
            ..plan
        })
        .contains("gap.reduced_pressures"));
    }
}
