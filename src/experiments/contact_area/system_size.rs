//! The system size at fixed resolution (paper section 2, tex 160-163: "the ratio of system
//! size L and lambda_l is only relevant at very small loads").
//!
//! The scene's load ladder again on a grid `factor` times larger with the same `lambda_l`
//! and `lambda_s` (so the same `eps_c` and magnifications, `L / lambda_l` `factor` times
//! the scene's), every realization of the plan's Hurst exponents. Against the scene's own
//! ladders on the first grid, at each load `p~0 >= from_load`: `kappa(p~0) = a_r / p~0`
//! over realizations on the larger system over the same on the scene's, minus 1; the
//! statistic is the change of largest magnitude over those loads, with its error (the
//! two systems' realizations are independent surfaces).

use crate::experiments::keys::{DetailKey, Tag};
use serde::{Deserialize, Serialize};

use super::ladder::{solve_ladder, AreaJob, AreaResult};
use super::stats::AreaStats;
use super::AreaScene;
use crate::engine::surface::SurfaceModel;
use crate::error::{check_positive, Error, Result};
use crate::experiments::declared::{value_at, DetailTable};
use crate::experiments::{JobContext, Work};
use crate::stats::Estimate;

/// The study as a scene states it (`[full.system_size]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SizePlan {
    /// How many times the scene's grid the larger system is along each side (at least 2).
    pub factor: usize,
    /// Hurst exponents (each one of the scene's).
    pub hursts: Vec<f64>,
    /// The smallest reduced pressure compared.
    pub from_load: f64,
}

/// One realization's ladder on the larger system, with everything its result depends on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SizeJob {
    /// Points per side.
    pub n: usize,
    /// Hurst exponent.
    pub hurst: f64,
    /// Long-wavelength cutoff.
    pub lambda_l: f64,
    /// Short-wavelength cutoff.
    pub lambda_s: f64,
    /// Seed.
    pub seed: u64,
    /// Reduced pressures `p~0`, increasing.
    pub reduced_pressures: Vec<f64>,
}

impl SizePlan {
    /// Checks the ranges against the scene; errors name the field.
    pub fn validate(&self, scene: &AreaScene) -> Result<()> {
        if self.factor < 2 {
            return Err(Error::invalid("system_size.factor", self.factor, ">= 2"));
        }
        scene.check_some_hursts("system_size.hursts", &self.hursts)?;
        check_positive("system_size.from_load", self.from_load)?;
        if !scene.reduced_pressures.iter().any(|&p| p >= self.from_load) {
            return Err(Error::invalid(
                "system_size.from_load",
                self.from_load,
                format!(
                    "at most the largest reduced pressure {:?}",
                    scene.reduced_pressures.last()
                ),
            ));
        }
        Ok(())
    }

    /// The jobs: every Hurst exponent, every realization of the scene.
    pub fn jobs(&self, scene: &AreaScene) -> Vec<SizeJob> {
        self.hursts
            .iter()
            .flat_map(|&hurst| {
                scene.all_seeds().into_iter().map(move |seed| SizeJob {
                    n: scene.n * self.factor,
                    hurst,
                    lambda_l: scene.lambda_l,
                    lambda_s: scene.lambda_s,
                    seed,
                    reduced_pressures: scene.reduced_pressures.clone(),
                })
            })
            .collect()
    }
}

impl SizeJob {
    /// One solve per load on the larger grid.
    pub fn work(&self) -> Work {
        Work {
            points: self.n * self.n,
            searches: 0.0,
            solves: self.reduced_pressures.len() as f64,
            shells: 0.0,
        }
    }

    /// The ladder on the larger system.
    pub fn run(&self, tol: f64, ctx: &JobContext) -> Result<AreaResult> {
        let params = SurfaceModel::new(self.n, self.hurst, self.lambda_l, self.lambda_s, self.seed);
        solve_ladder(&params, &self.reduced_pressures, tol, ctx)
    }
}

/// The key of the change at Hurst exponent `hurst`.
pub fn key(hurst: f64) -> DetailKey {
    DetailKey::new("size_kappa_change").at(Tag::Hurst, hurst)
}

/// `kappa` at load `k` over the ladders: the mean of `a_r / p~0` over realizations.
fn kappa(pressures: &[f64], ladders: &[&AreaResult], k: usize) -> Estimate {
    Estimate::mean_of(
        &ladders
            .iter()
            .map(|r| r.contact_area[k] / pressures[k])
            .collect::<Vec<_>>(),
    )
}

/// At one Hurst exponent, over the loads `p~0 >= from_load`: `kappa` on the larger system
/// over `kappa` on the scene's first grid, minus 1, of largest magnitude (`None` without
/// ladders on either).
pub fn largest_change(
    plan: &SizePlan,
    pressures: &[f64],
    larger: &[&AreaResult],
    scene: &[&AreaResult],
) -> Option<Estimate> {
    if larger.is_empty() || scene.is_empty() {
        return None;
    }
    (0..pressures.len())
        .filter(|&k| pressures[k] >= plan.from_load)
        .map(|k| {
            let (big, own) = (kappa(pressures, larger, k), kappa(pressures, scene, k));
            let ratio = big.value / own.value;
            Estimate::new(
                ratio - 1.0,
                ratio * (big.std_error / big.value).hypot(own.std_error / own.value),
            )
        })
        .max_by(|a, b| a.value.abs().total_cmp(&b.value.abs()))
}

/// Declares the change at each of the plan's Hurst exponents as a detail (written where
/// both systems have ladders).
pub fn declare(t: &mut DetailTable<'_, AreaStats>, plan: &SizePlan, scene: &AreaScene) {
    for &hurst in &plan.hursts {
        t.row(
            key(hurst),
            label(plan, scene, hurst),
            move |s: &AreaStats| value_at(&s.size_changes, hurst),
        )
        .persson(0.0);
    }
}

/// The label of the change at Hurst exponent `hurst`.
fn label(plan: &SizePlan, scene: &AreaScene, hurst: f64) -> String {
    format!(
        "kappa(p~0) = a_r / p~0 on {0}x{0} over kappa(p~0) on {1}x{1} minus 1, both with \
             lambda_l = {2} and lambda_s = {3} (L / lambda_l = {4} against {5}), the largest \
             in magnitude over p~0 >= {6}, H = {hurst}",
        scene.n * plan.factor,
        scene.n,
        scene.lambda_l,
        scene.lambda_s,
        (scene.n * plan.factor) as f64 / scene.lambda_l,
        scene.n as f64 / scene.lambda_l,
        plan.from_load
    )
}

/// The scene's own ladders at Hurst exponent `hurst` on its first grid.
pub fn scene_ladders(ladders: &[(AreaJob, AreaResult)], hurst: f64) -> Vec<&AreaResult> {
    ladders
        .iter()
        .filter(|(j, _)| j.hurst == hurst && j.refine == 1)
        .map(|(_, r)| r)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn areas(a: &[f64]) -> AreaResult {
        AreaResult {
            contact_area: a.to_vec(),
            max_residual: 0.0,
        }
    }

    #[test]
    fn the_change_is_the_largest_over_the_loads_read() {
        let plan = SizePlan {
            factor: 2,
            hursts: vec![0.8],
            from_load: 0.1,
        };
        let p = [0.05, 0.1, 0.2];
        // The first load is below from_load: its 50% change is not read. At 0.1 kappa
        // grows by 10%, at 0.2 it falls by 5%.
        let (a, b) = (areas(&[0.15, 0.22, 0.38]), areas(&[0.15, 0.22, 0.38]));
        let (c, d) = (areas(&[0.1, 0.2, 0.4]), areas(&[0.1, 0.2, 0.4]));
        let change = largest_change(&plan, &p, &[&a, &b], &[&c, &d]).unwrap();
        assert!((change.value - 0.1).abs() < 1e-12, "{change:?}");
        assert_eq!(change.std_error, 0.0);
        assert_eq!(largest_change(&plan, &p, &[], &[&c]), None);
    }

    #[test]
    fn a_plan_names_its_fields() {
        let scene: AreaScene = crate::experiments::shipped_scenes::<AreaScene>("contact_area").1;
        let plan = SizePlan {
            factor: 2,
            hursts: vec![0.8],
            from_load: 0.016,
        };
        plan.validate(&scene).unwrap();
        let jobs = plan.jobs(&scene);
        assert_eq!(jobs.len(), scene.all_seeds().len());
        assert_eq!(
            (jobs[0].n, jobs[0].lambda_l, jobs[0].lambda_s),
            (2 * scene.n, scene.lambda_l, scene.lambda_s)
        );
        let e = |p: SizePlan| p.validate(&scene).unwrap_err().to_string();
        assert!(e(SizePlan {
            factor: 1,
            ..plan.clone()
        })
        .contains("system_size.factor"));
        assert!(e(SizePlan {
            from_load: 9.0,
            ..plan
        })
        .contains("system_size.from_load"));
    }
}
