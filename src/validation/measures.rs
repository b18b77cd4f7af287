//! Where a claim finds its numbers ([`Measures`]: a run's headline, details, studies and
//! cross-checks, read by a [`Measure`]), and the check at load that every
//! measure a claim names is one its experiment declares for the scene
//! ([`super::claims::check_declared`]), so that a mistyped key is an error, not "not measured";
//! and the measures a merge could not have yet ([`PendingPart`]: an optional part of the
//! scene whose jobs are not all in), which a claim reads as pending.

use serde::{Deserialize, Serialize};

pub use super::measure::Measure;
use crate::experiments::keys::closest;
use crate::experiments::study::{self, Study};
use crate::experiments::{Detail, Keys};
use crate::stats::Estimate;

/// Where a claim finds its numbers: a run's headline, details, studies and cross-checks.
pub struct Measures<'a> {
    /// The headline statistic.
    pub headline: Estimate,
    /// The secondary statistics.
    pub details: &'a [Detail],
    /// The studies.
    pub studies: &'a [Study],
    /// The other solvers' headlines: (solver, estimate).
    pub cross_checks: Vec<(String, Estimate)>,
    /// The optional parts of the scene a merge left out, with the measures only they give
    /// ([`PendingPart`]).
    pub pending: &'a [PendingPart],
    /// The scene as run, where the realizations behind each measure are listed (`Null`
    /// where not known).
    pub scene: &'a serde_json::Value,
}

impl Measures<'_> {
    /// How many realizations the seed lists at `paths` of the scene hold: the shortest
    /// (`None` where the scene is not known or a path does not resolve).
    pub fn realizations(&self, paths: &[String]) -> Option<usize> {
        paths
            .iter()
            .map(|p| realizations_at(self.scene, p))
            .collect::<Option<Vec<usize>>>()?
            .into_iter()
            .min()
    }

    /// The estimate a measure names, if the run has it.
    pub fn get(&self, measure: &Measure) -> Option<Estimate> {
        match measure {
            Measure::Headline => Some(self.headline),
            Measure::Detail { key, grid } => self
                .details
                .iter()
                .find(|d| &d.key == key && (grid.is_none() || d.grid == *grid))
                .map(|d| d.value),
            Measure::Study { study, row, column } => study::find(self.studies, study)?
                .cell(row, column)?
                .estimate(),
            Measure::CrossCheck(solver) => self
                .cross_checks
                .iter()
                .find(|(s, _)| s == solver.name())
                .map(|(_, e)| *e),
        }
    }
}

/// The realizations listed at `path` of `scene`: dot-separated keys, where a list of
/// named tables (`variants`, `resolutions`) is entered by the table's `name`; a list of
/// seeds counts its entries, a single seed counts one, and a plan with a `seed` and
/// `more_seeds` (the waterfall's) counts both.
pub fn realizations_at(scene: &serde_json::Value, path: &str) -> Option<usize> {
    // A list's planned realizations (`more_seeds`) count with it.
    let folded = crate::experiments::scene::planned_folded(scene.clone());
    let mut at = &folded;
    for part in path.split('.') {
        at = match at {
            serde_json::Value::Object(map) => map.get(part)?,
            serde_json::Value::Array(items) => items
                .iter()
                .find(|t| t.get("name").and_then(|n| n.as_str()) == Some(part))?,
            _ => return None,
        };
    }
    match at {
        serde_json::Value::Array(seeds) => Some(seeds.len()),
        serde_json::Value::Number(_) => Some(1),
        // A plan of one seed and its further ones (the waterfall's).
        serde_json::Value::Object(plan) if plan.get("seed").is_some_and(|s| s.is_u64()) => Some(
            1 + plan
                .get("more_seeds")
                .and_then(|m| m.as_array())
                .map_or(0, Vec::len),
        ),
        _ => None,
    }
}

/// Whether a run of a scene whose experiment declares `keys` has the measure `measure`
/// (of a checked form): a declared detail (on the grid it names), a declared study and
/// column (the rows of a study are known from its results only), or the cross-check of a
/// known solver where the scene does not fix its solver (`fixed_solver`). `Err` says what
/// is allowed instead.
pub(super) fn declared(
    measure: &Measure,
    keys: &Keys,
    fixed_solver: bool,
) -> std::result::Result<(), String> {
    let listed = |what: &str, name: &str, names: &[String]| {
        format!(
            "{what} the experiment declares for this scene; the closest: {}",
            closest(name, names).join(", ")
        )
    };
    match measure {
        Measure::Detail { key, grid } => {
            if keys.has_detail(key, *grid) {
                Ok(())
            } else {
                let named = match grid {
                    Some(n) => format!("{key}@{n}"),
                    None => key.to_string(),
                };
                Err(listed("a detail", &named, &keys.detail_names()))
            }
        }
        Measure::Study { study, column, .. } => match keys.study_columns(study) {
            None => Err(listed("a study", study, &keys.study_names())),
            Some(columns) if !columns.iter().any(|k| k == column) => {
                Err(format!("a column of study {study}: {}", columns.join(", ")))
            }
            Some(_) => Ok(()),
        },
        Measure::CrossCheck(_) if fixed_solver => {
            Err("no cross-check: the scene fixes its solver, so a run has none".into())
        }
        Measure::CrossCheck(_) | Measure::Headline => Ok(()),
    }
}

/// An optional part of a scene (a re-entry variant) that a merge left out because not all
/// of its jobs have results yet.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PendingPart {
    /// The part's name (a variant's).
    pub name: String,
    /// Its jobs, over every solver run.
    pub jobs: usize,
    /// Those with a result.
    pub done: usize,
    /// The plan's estimate of what the others cost, core-hours.
    pub core_hours_left: f64,
    /// The measures a claim can name that only the part gives (`detail:KEY`,
    /// `study:KEY`).
    pub measures: Vec<String>,
}

impl PendingPart {
    /// Whether the claim measure `measure` (a detail or a study cell) is one of the part's.
    pub fn gives(&self, measure: &Measure) -> bool {
        measure.family().is_some_and(|f| self.measures.contains(&f))
    }

    /// Why a claim that reads the part's measure is not measured yet.
    pub fn why(&self) -> String {
        format!(
            "pending: the scene's part {} is left out of this merge until its jobs are in \
             ({} of {} have results; the plan costs the rest {:.1} core-hours)",
            self.name, self.done, self.jobs, self.core_hours_left
        )
    }
}
