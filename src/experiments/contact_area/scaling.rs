//! Critical slowing-down of the solvers: iterations of a cold solve against the system
//! size (paper section 2.3, tex 408-409: GFMD in reciprocal space "reduces critical
//! slowing-down from O(L^2) to O(L^1/2)").
//!
//! One scene shape on grids of `n` points a side: `lambda_l = n / 2`, `lambda_s` fixed in
//! grid spacings, so the system holds `n / lambda_s` times more wavelengths as it grows, at
//! one reduced pressure `p~0 = p0 / (E* g_bar)` (about the same contact area on every
//! grid). Each job solves one realization from cold (flat body, zero displacement) to the
//! plan's tolerance and stores the iterations. The statistic is the exponent `k` of
//! `iterations ~ n^k`: the slope of `ln iterations` against `ln n`, fitted per realization,
//! averaged over realizations with its standard error. Plain damped dynamics in real space
//! gives `k = 2`; the paper's mass-weighted GFMD `k = 1/2`.

use serde::{Deserialize, Serialize};

use super::stats::AreaStats;
use crate::engine::contact::Model;
use crate::engine::solver::SolveOptions;
use crate::engine::surface::{Surface, SurfaceModel};
use crate::engine::sweep::Sweep;
use crate::error::{check_open, check_positive, Error, Result};
use crate::experiments::declared::DetailTable;
use crate::experiments::scene::check_increasing;
use crate::experiments::{JobContext, Work};
use crate::stats::{Estimate, LineFit};

/// The key of the fitted exponent.
pub const EXPONENT: &str = "iteration_exponent";

/// The scaling study, as a scene states it (`[full.scaling]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalingPlan {
    /// Points per side of the grids, increasing (at least two).
    pub ns: Vec<usize>,
    /// Hurst exponent.
    pub hurst: f64,
    /// Short-wavelength cutoff in grid spacings (`lambda_l = n / 2`).
    pub lambda_s: f64,
    /// Realizations.
    pub seeds: Vec<u64>,
    /// Reduced pressure `p~0`.
    pub reduced_pressure: f64,
    /// Residual tolerance of the solves.
    pub tol: f64,
}

/// One cold solve: one realization on one grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalingJob {
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
    /// Reduced pressure `p~0`.
    pub reduced_pressure: f64,
    /// Residual tolerance.
    pub tol: f64,
}

/// What a cold solve took.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalingResult {
    /// Solver iterations (GFMD: time steps).
    pub iterations: usize,
    /// Contact area reached.
    pub a_r: f64,
    /// Residual of the solution.
    pub max_residual: f64,
}

impl ScalingPlan {
    /// Checks the ranges; errors name the field.
    pub fn validate(&self) -> Result<()> {
        check_increasing("scaling.ns", &self.ns)?;
        if self.ns.len() < 2 {
            return Err(Error::invalid(
                "scaling.ns",
                format!("{:?}", self.ns),
                "at least two grids (an exponent needs two sizes)",
            ));
        }
        check_open("scaling.hurst", self.hurst, 0.0, 1.0)?;
        check_positive("scaling.lambda_s", self.lambda_s)?;
        crate::error::check_seeds(&self.seeds).map_err(|e| e.with_field("scaling.seeds"))?;
        check_positive("scaling.reduced_pressure", self.reduced_pressure)?;
        SolveOptions::with_tol(self.tol)
            .validate()
            .map_err(|e| e.with_field("scaling.tol"))?;
        for job in self.jobs() {
            let p = job.params();
            p.spectrum()
                .validate(&crate::engine::grid::Grid::new(p.n, 1.0)?)
                .map_err(|e| e.with_field("scaling.lambda_s"))?;
        }
        Ok(())
    }

    /// The jobs: every grid, every realization.
    pub fn jobs(&self) -> Vec<ScalingJob> {
        self.ns
            .iter()
            .flat_map(|&n| {
                self.seeds.iter().map(move |&seed| ScalingJob {
                    n,
                    hurst: self.hurst,
                    lambda_l: n as f64 / 2.0,
                    lambda_s: self.lambda_s,
                    seed,
                    reduced_pressure: self.reduced_pressure,
                    tol: self.tol,
                })
            })
            .collect()
    }
}

impl ScalingJob {
    fn params(&self) -> SurfaceModel {
        SurfaceModel::new(self.n, self.hurst, self.lambda_l, self.lambda_s, self.seed)
    }

    /// One cold solve on an `n x n` grid.
    pub fn work(&self) -> Work {
        Work {
            points: self.n * self.n,
            searches: 0.0,
            solves: 1.0,
            shells: 0.0,
        }
    }

    /// Solves the realization from cold at the plan's load.
    pub fn run(&self, ctx: &JobContext) -> Result<ScalingResult> {
        let surface = Surface::generate(&self.params())?;
        let model = Model::new(surface.grid().clone(), 1.0)?;
        let p0 =
            self.reduced_pressure * surface.rms_gradient(f64::INFINITY) * model.halfspace.e_star();
        let mut sweep = Sweep::new(
            &surface,
            &model,
            ctx.solver,
            SolveOptions::with_tol(self.tol),
        );
        // A sweep's first solve starts cold.
        let s = sweep.solve_at(surface.zeta_max(), p0)?;
        Ok(ScalingResult {
            iterations: s.stats.iterations,
            a_r: s.contact_area(),
            max_residual: s.stats.residual.value(),
        })
    }
}

/// The exponent `k` of `iterations ~ n^k`: fitted per realization over the grids it was
/// solved on, then the mean over realizations with its standard error (`None` without
/// results).
pub fn exponent(results: &[(&ScalingJob, &ScalingResult)]) -> Option<Estimate> {
    let mut seeds: Vec<u64> = results.iter().map(|(j, _)| j.seed).collect();
    seeds.sort_unstable();
    seeds.dedup();
    let slopes: Vec<f64> = seeds
        .iter()
        .filter_map(|&seed| {
            let (x, y): (Vec<f64>, Vec<f64>) = results
                .iter()
                .filter(|(j, _)| j.seed == seed)
                .map(|(j, r)| ((j.n as f64).ln(), (r.iterations.max(1) as f64).ln()))
                .unzip();
            LineFit::fit(&x, &y).map(|f| f.slope.value)
        })
        .collect();
    (!slopes.is_empty()).then(|| Estimate::mean_of(&slopes))
}

/// Declares the exponent as a detail, naming the grids (written where it was fitted).
pub fn declare(t: &mut DetailTable<'_, AreaStats>, plan: &ScalingPlan) {
    t.row(
        EXPONENT,
        format!(
            "exponent k of solver iterations ~ N^k, cold start to tol {:e}, N = {:?} \
             (lambda_l = N/2, lambda_s = {}, H = {}, p~0 = {})",
            plan.tol, plan.ns, plan.lambda_s, plan.hurst, plan.reduced_pressure
        ),
        |s: &AreaStats| s.iteration_exponent,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job(n: usize, seed: u64) -> ScalingJob {
        ScalingJob {
            n,
            hurst: 0.8,
            lambda_l: n as f64 / 2.0,
            lambda_s: 8.0,
            seed,
            reduced_pressure: 0.1,
            tol: 1e-8,
        }
    }

    fn took(iterations: usize) -> ScalingResult {
        ScalingResult {
            iterations,
            a_r: 0.2,
            max_residual: 0.0,
        }
    }

    #[test]
    fn the_exponent_is_the_mean_slope_over_realizations() {
        // Seed 1: iterations ~ n^0.5 exactly; seed 2: ~ n^1.
        let jobs = [job(64, 1), job(256, 1), job(64, 2), job(256, 2)];
        let results = [took(80), took(160), took(64), took(256)];
        let pairs: Vec<_> = jobs.iter().zip(&results).collect();
        let k = exponent(&pairs).unwrap();
        assert!((k.value - 0.75).abs() < 1e-12);
        assert!((k.std_error - 0.25).abs() < 1e-12);
        assert_eq!(exponent(&[]), None);
    }

    #[test]
    fn a_plan_needs_two_grids_and_names_its_fields() {
        let plan = ScalingPlan {
            ns: vec![64, 128],
            hurst: 0.8,
            lambda_s: 8.0,
            seeds: vec![1, 2],
            reduced_pressure: 0.1,
            tol: 1e-8,
        };
        plan.validate().unwrap();
        assert_eq!(plan.jobs().len(), 4);
        assert_eq!(plan.jobs()[0], job(64, 1));
        let one = ScalingPlan {
            ns: vec![64],
            ..plan.clone()
        };
        assert!(one
            .validate()
            .unwrap_err()
            .to_string()
            .contains("scaling.ns"));
        let bad = ScalingPlan {
            reduced_pressure: -1.0,
            ..plan
        };
        let e = bad.validate().unwrap_err().to_string();
        assert!(e.contains("scaling.reduced_pressure"), "{e}");
    }
}
