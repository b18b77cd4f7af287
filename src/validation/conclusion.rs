//! From the jobs' results to a validation's outcome: each solver's conclusion
//! ([`Experiment::conclude`]), the cross-checks against the first solver, the claims judged
//! on the measures ([`claims`]), the headline verdict against the paper's, and the tables
//! and figures written beside the outcome. The runner ([`super::runner`]) calls it once
//! every job has a result.

use std::path::Path;

use super::claims::{ClaimOutcome, Measures};
use super::definition::{Definition, Scale, Verdict};
use super::outcome::{CrossCheck, MergeRecord, Outcome, PendingPart};
use super::source::Source;
use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};
use crate::experiments::{Conclusion, Experiment, JobOf, ResultOf};
use crate::stats::Estimate;

/// The jobs of one solver with their results, in job order.
pub(crate) type Results<E> = Vec<(JobOf<E>, ResultOf<E>)>;

/// The headline and the cross-checks from each solver's results (headline solver first),
/// the verdict, and the outcome of scene `scene_json` at `scale` and its files under `out`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn conclude<E: Experiment>(
    source: &Source,
    def: &Definition<E::Scene>,
    scene_json: &serde_json::Value,
    by_solver: Vec<(SolverKind, Results<E>)>,
    scale: Scale,
    out: &Path,
    wall_s: f64,
    merge: Option<MergeRecord>,
) -> Result<Outcome> {
    let conclusions = conclude_by_solver::<E>(source, def, by_solver, scale)?;
    let max_residual = conclusions
        .iter()
        .map(|(_, c, _)| c.max_residual)
        .fold(0.0, f64::max);
    let mut rest = conclusions.into_iter();
    let (solver, conclusion, measured) = rest.next().expect("at least one solver");
    let cross_checks: Vec<CrossCheck> = rest
        .map(|(s, _, m)| CrossCheck {
            solver: s.name().to_string(),
            value: m.value,
            std_error: m.std_error,
            agrees: def.verdict.agree(measured, m),
        })
        .collect();
    let verdict = def.verdict.judge(measured, conclusion.persson);
    let pending = merge.as_ref().map_or(&[][..], |m| &m.pending[..]);
    let claims = judge_claims(
        def,
        &conclusion,
        measured,
        &cross_checks,
        pending,
        (scene_json, scale),
    );
    let reproduced = reproduced(def, verdict);
    let files = write_files(out, &def.name, &conclusion)?;
    let outcome = Outcome {
        name: def.name.clone(),
        title: def.title.clone(),
        assumption: def.assumption.clone(),
        statistic: def.statistic.clone(),
        value: measured.value,
        std_error: measured.std_error,
        persson: conclusion.persson,
        persson_text: def.persson.clone(),
        paper: def.paper.finding.clone(),
        paper_value: def.paper.value,
        paper_range: def.paper.range,
        paper_verdict: def.paper.verdict,
        verdict,
        reproduced,
        rule: def.verdict,
        scale,
        scene: scene_json.clone(),
        definition_sha256: source.sha256(),
        wall_s,
        max_residual,
        details: conclusion.details,
        guards: conclusion.guards,
        account: conclusion.account,
        golden: conclusion.golden,
        claims,
        studies: conclusion.studies,
        files,
        threads: rayon::current_num_threads(),
        solver: solver.name().to_string(),
        cross_checks,
        merge,
    };
    let json = serde_json::to_vec_pretty(&outcome).expect("outcomes serialise");
    crate::io::write_atomic(&out.join(format!("{}.json", def.name)), &json)?;
    Ok(outcome)
}

/// The experiment's conclusion from each solver's results, headline solver first, with
/// its headline estimate.
fn conclude_by_solver<E: Experiment>(
    source: &Source,
    def: &Definition<E::Scene>,
    by_solver: Vec<(SolverKind, Results<E>)>,
    scale: Scale,
) -> Result<Vec<(SolverKind, Conclusion, Estimate)>> {
    let criteria = def.criteria();
    let scene = def.scene(scale);
    by_solver
        .iter()
        .map(|(solver, results)| {
            let c = E::conclude(&criteria, scene, results)
                .map_err(|e| Error::bad_file(&source.path, format!("[{}] {e}", solver.name())))?;
            let measured = c
                .measured
                .ok_or_else(|| Error::bad_file(&source.path, "the experiment measured nothing"))?;
            Ok((*solver, c, measured))
        })
        .collect()
}

/// Every claim of the definition judged on the headline solver's conclusion (and each
/// cross-check's headline, by its solver's name: `cross_check:SOLVER`), by the one rule of [`super::claims::ClaimSpec::judge`].
fn judge_claims<S>(
    def: &Definition<S>,
    conclusion: &Conclusion,
    measured: Estimate,
    cross_checks: &[CrossCheck],
    pending: &[PendingPart],
    (scene, scale): (&serde_json::Value, Scale),
) -> Vec<ClaimOutcome> {
    let measures = Measures {
        pending,
        scene,
        headline: measured,
        details: &conclusion.details,
        studies: &conclusion.studies,
        cross_checks: cross_checks
            .iter()
            .map(|c| (c.solver.clone(), Estimate::new(c.value, c.std_error)))
            .collect(),
    };
    def.claims
        .iter()
        .map(|c| c.judge(&measures, scale == Scale::Reduced, def.verdict.significance))
        .collect()
}

/// Whether the run's headline verdict is the paper's: Persson's assumption holds or is
/// violated as the paper finds. `None` when the verdict is inconclusive. Only the headline
/// decides it: each of the paper's statements is judged once, by its claim, and the claims
/// are counted apart, never folded into this.
fn reproduced<S>(def: &Definition<S>, verdict: Verdict) -> Option<bool> {
    (verdict != Verdict::Inconclusive).then(|| verdict == def.paper.verdict)
}

/// Writes the conclusion's tables (the first as `<out>/<name>.csv`, the others and the
/// figures under `<out>/<name>/`); the files written, relative to `out`.
fn write_files(out: &Path, name: &str, conclusion: &Conclusion) -> Result<Vec<String>> {
    let dir = out.join(name);
    let mut files = Vec::new();
    for (k, table) in conclusion.tables.iter().enumerate() {
        let path = if k == 0 {
            out.join(format!("{name}.csv"))
        } else {
            dir.join(format!("{}.csv", table.name))
        };
        table.write_csv(&path)?;
        files.push(path);
    }
    for figure in &conclusion.figures {
        files.extend(crate::plot::render(figure, &dir)?);
    }
    for waterfall in &conclusion.waterfalls {
        files.extend(crate::plot::render_waterfall(waterfall, &dir)?);
    }
    for raster in &conclusion.rasters {
        files.extend(crate::plot::render_raster(raster, &dir)?);
    }
    Ok(files.iter().map(|p| relative(out, p)).collect())
}

fn relative(base: &Path, path: &Path) -> String {
    path.strip_prefix(base)
        .unwrap_or(path)
        .to_string_lossy()
        .to_string()
}
