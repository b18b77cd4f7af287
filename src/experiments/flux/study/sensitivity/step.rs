//! One job of the sensitivity study: the load that gives the contact area at `zeta`, then
//! the step at that load (or at that contact area), with the step actually taken.

use super::{StudyJob, StudyResult};
use crate::engine::load::{AreaSearch, HELD_AREA_REL_TOL};
use crate::engine::spectrum::ShellSpectrum;
use crate::error::Result;
use crate::experiments::contact_change::categories;
use crate::experiments::scene::Base;

/// Runs one study job: the load that gives the contact area at `zeta`, then the step at
/// that load (or at that contact area).
pub fn run(hurst: f64, job: &StudyJob) -> Result<StudyResult> {
    let c = &job.config;
    let seeds = [job.seed];
    let base = Base::new(
        c.n,
        c.hurst.unwrap_or(hurst),
        c.lambda_l,
        c.lambda_s,
        &seeds,
        c.tol,
    );
    let r = base.realization(job.seed)?;
    let mut sweep = base.sweep(&r, c.solver);
    let p0 = sweep.find_load(c.zeta, c.contact_area)?;
    let old = sweep
        .solution()
        .expect("find_load keeps its solution")
        .clone();
    let new = if c.fixed_area {
        // The contact area before the step, held: matched far more tightly than the
        // change a step makes at fixed load.
        let search = AreaSearch {
            rel_tol: c.area_tol.unwrap_or(HELD_AREA_REL_TOL),
            ..AreaSearch::held()
        };
        sweep.find_load_within(c.zeta + c.dzeta, old.contact_area(), &search)?;
        sweep.solution().expect("find_load keeps its solution")
    } else {
        sweep.solve_at(c.zeta + c.dzeta, p0)?
    };
    let categories = categories(&old.pressure, &new.pressure);
    let (flux_in, flux_out) = crate::experiments::flux::fluxes(&categories);
    let (variance_added, modes_added) = step_taken(&r.surface.shells(), c.zeta, c.dzeta);
    Ok(StudyResult {
        a_r_old: old.contact_area(),
        a_r_new: new.contact_area(),
        flux_in,
        flux_out,
        max_residual: old.stats.residual.value().max(new.stats.residual.value()),
        variance_added: Some(variance_added),
        modes_added: Some(modes_added),
    })
}

/// The step actually taken from `zeta` to `zeta + dzeta`: the height variance of the modes
/// it adds over the height variance at `zeta`, and how many modes it adds.
pub fn step_taken(shells: &ShellSpectrum, zeta: f64, dzeta: f64) -> (f64, u64) {
    let before = shells.up_to(zeta);
    let after = shells.up_to(zeta + dzeta);
    let added = &after[before.len()..];
    let variance: f64 = before.iter().map(|s| s.h2).sum();
    let variance_added: f64 = added.iter().map(|s| s.h2).sum();
    let modes = added.iter().map(|s| u64::from(s.modes)).sum();
    (variance_added / variance.max(f64::MIN_POSITIVE), modes)
}
