//! The load ladder of one realization (paper section 3.1): at one Hurst exponent and grid
//! refinement, `a_r` at every reduced pressure `p~0 = p0 / (E* g_bar)`, the load raised
//! step by step (each solve warm-started from the previous one), and the finer grid that
//! some Hurst exponents and loads are also solved on.

use serde::{Deserialize, Serialize};

use super::AreaScene;
use crate::engine::contact::Model;
use crate::engine::solver::SolveOptions;
use crate::engine::surface::{Surface, SurfaceModel};
use crate::engine::sweep::Sweep;
use crate::error::{Error, Result};
use crate::experiments::scene::check_increasing;
use crate::experiments::{JobContext, Work};

/// A grid finer than the scene's finest, run for a subset of its Hurst exponents and loads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FinerGrid {
    /// Refinement factor, above the scene's last refinement.
    pub refine: usize,
    /// Hurst exponents, each one of the scene's.
    pub hursts: Vec<f64>,
    /// Reduced pressures `p~0`, increasing, each one of the scene's.
    pub reduced_pressures: Vec<f64>,
}

/// One realization at one Hurst exponent and one grid refinement.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AreaJob {
    /// Hurst exponent.
    pub hurst: f64,
    /// Seed.
    pub seed: u64,
    /// Refinement factor.
    pub refine: usize,
}

/// Contact area at each load of one realization.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AreaResult {
    /// `a_r` at each of the scene's reduced pressures.
    pub contact_area: Vec<f64>,
    /// Largest residual of the solves.
    pub max_residual: f64,
}

impl AreaScene {
    /// Every realization: `seeds`, then `more_seeds`.
    pub fn all_seeds(&self) -> Vec<u64> {
        self.seeds.iter().chain(&self.more_seeds).copied().collect()
    }

    pub(super) fn params(&self, job: &AreaJob) -> SurfaceModel {
        let r = job.refine as f64;
        SurfaceModel::new(
            self.n * job.refine,
            job.hurst,
            self.lambda_l * r,
            self.lambda_s * r,
            job.seed,
        )
    }

    /// The reduced pressures of a job: the finer grid's on that grid, else the scene's.
    pub fn pressures(&self, job: &AreaJob) -> &[f64] {
        match &self.finer_grid {
            Some(f) if f.refine == job.refine => &f.reduced_pressures,
            _ => &self.reduced_pressures,
        }
    }

    /// Checks a study's Hurst exponents (the field `field`): at least one, each one of
    /// the scene's.
    pub(super) fn check_some_hursts(&self, field: &str, hursts: &[f64]) -> Result<()> {
        if hursts.is_empty() {
            return Err(Error::invalid(field, "[]", "at least one Hurst exponent"));
        }
        match hursts.iter().find(|h| !self.hursts.contains(h)) {
            Some(&h) => Err(Error::invalid(
                field,
                h,
                format!("one of the scene's hursts {:?}", self.hursts),
            )),
            None => Ok(()),
        }
    }

    pub(super) fn validate_finer_grid(&self, f: &FinerGrid) -> Result<()> {
        let last = *self.refinements.last().expect("validated non-empty");
        if f.refine <= last {
            return Err(Error::invalid(
                "finer_grid.refine",
                f.refine,
                format!("a refinement above the last of refinements ({last})"),
            ));
        }
        self.check_some_hursts("finer_grid.hursts", &f.hursts)?;
        for &h in &f.hursts {
            let p = self.params(&AreaJob {
                hurst: h,
                seed: 0,
                refine: f.refine,
            });
            p.spectrum()
                .validate(&crate::engine::grid::Grid::new(p.n, 1.0)?)?;
        }
        check_increasing("finer_grid.reduced_pressures", &f.reduced_pressures)?;
        for &p in &f.reduced_pressures {
            if !self.reduced_pressures.contains(&p) {
                return Err(Error::invalid(
                    "finer_grid.reduced_pressures",
                    p,
                    format!("one of reduced_pressures {:?}", self.reduced_pressures),
                ));
            }
        }
        Ok(())
    }

    /// The load ladders: every refinement, Hurst exponent and realization, then the finer
    /// grid's.
    pub(super) fn ladders(&self) -> Vec<AreaJob> {
        let seeds = self.all_seeds();
        let mut jobs = Vec::new();
        for &refine in &self.refinements {
            for &hurst in &self.hursts {
                for &seed in &seeds {
                    jobs.push(AreaJob {
                        hurst,
                        seed,
                        refine,
                    });
                }
            }
        }
        if let Some(f) = &self.finer_grid {
            for &hurst in &f.hursts {
                for &seed in &seeds {
                    jobs.push(AreaJob {
                        hurst,
                        seed,
                        refine: f.refine,
                    });
                }
            }
        }
        jobs
    }

    pub(super) fn ladder_work(&self, job: &AreaJob) -> Work {
        // One solve per load, each from the previous one (the first from cold).
        let n = self.n * job.refine;
        Work {
            points: n * n,
            searches: 0.0,
            solves: self.pressures(job).len() as f64,
            shells: 0.0,
        }
    }

    pub(super) fn run_ladder(&self, job: &AreaJob, ctx: &JobContext) -> Result<AreaResult> {
        solve_ladder(&self.params(job), self.pressures(job), self.tol, ctx)
    }
}

/// The realization `params` at full resolution at each reduced pressure `p~0` in turn,
/// each solve warm-started from the one before (the first from cold): its contact areas.
pub(super) fn solve_ladder(
    params: &SurfaceModel,
    reduced_pressures: &[f64],
    tol: f64,
    ctx: &JobContext,
) -> Result<AreaResult> {
    let surface = Surface::generate(params)?;
    let model = Model::new(surface.grid().clone(), 1.0)?;
    let g_bar = surface.rms_gradient(f64::INFINITY);
    let zeta = surface.zeta_max();
    let mut sweep = Sweep::new(&surface, &model, ctx.solver, SolveOptions::with_tol(tol));
    let mut contact_area = Vec::new();
    let mut max_residual = 0.0f64;
    for &p in reduced_pressures {
        let s = sweep.solve_at(zeta, p * g_bar * model.halfspace.e_star())?;
        contact_area.push(s.contact_area());
        max_residual = max_residual.max(s.stats.residual.value());
    }
    Ok(AreaResult {
        contact_area,
        max_residual,
    })
}

#[cfg(test)]
mod tests {
    use super::super::ContactArea;
    use super::*;

    #[test]
    fn the_finer_grid_adds_its_jobs_at_its_loads_and_is_checked() {
        let (_, full) = crate::experiments::shipped_valid::<ContactArea>("contact_area");
        let f = full
            .finer_grid
            .clone()
            .expect("the full scene has a finer grid");
        let finer: Vec<AreaJob> = full
            .ladders()
            .into_iter()
            .filter(|j| j.refine == f.refine)
            .collect();
        assert_eq!(finer.len(), f.hursts.len() * full.all_seeds().len());
        assert_eq!(full.pressures(&finer[0]), &f.reduced_pressures[..]);
        let coarse = AreaJob {
            refine: 1,
            ..finer[0].clone()
        };
        assert_eq!(full.pressures(&coarse), &full.reduced_pressures[..]);
        let refused = |edit: fn(&mut FinerGrid), field: &str| {
            let mut scene = full.clone();
            edit(scene.finer_grid.as_mut().unwrap());
            crate::experiments::assert_refused::<ContactArea>(&scene, field);
        };
        refused(|f| f.refine = 2, "finer_grid.refine");
        refused(|f| f.hursts = vec![0.4], "finer_grid.hursts");
        refused(
            |f| f.reduced_pressures = vec![0.13],
            "finer_grid.reduced_pressures",
        );
        refused(
            |f| f.reduced_pressures = vec![0.5, 0.25],
            "finer_grid.reduced_pressures",
        );
    }
}
