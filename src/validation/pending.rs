//! The optional parts of a scene (a re-entry variant, [`Jobs::part`]) that a partial merge
//! (`validate --merge --partial`) leaves out because some of their jobs have no stored
//! result: each with its progress, the plan's cost of the rest, and the measures only it
//! gives ([`PendingPart`]), which the claims that read them report as pending.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use super::definition::Scale;
use super::measures::{Measure, PendingPart};
use super::source::Source;
use super::store;
use crate::error::Result;
use crate::experiments::{keys_of, Experiment, Jobs, Keys};

/// One job as the pending parts see it: its part ([`Jobs::part`]), its result file, and
/// the plan's estimate of it, seconds on one core.
pub(crate) struct PartJob<'a> {
    pub part: Option<&'a str>,
    pub path: &'a Path,
    pub cost: f64,
}

/// The optional parts of `scene` (of `source` at `scale`) that some of `jobs` has no stored
/// result for: each with its jobs, those done, the plan's cost of the rest, and the
/// measures only it gives (the keys its experiment declares with it and not without it).
pub(crate) fn pending_parts<E: Experiment>(
    source: &Source,
    scene: &E::Scene,
    jobs: &[PartJob],
    scale: Scale,
) -> Result<Vec<PendingPart>> {
    let mut parts: BTreeMap<&str, PendingPart> = BTreeMap::new();
    for u in jobs {
        let Some(name) = u.part else {
            continue;
        };
        let p = parts.entry(name).or_insert_with(|| PendingPart {
            name: name.to_string(),
            jobs: 0,
            done: 0,
            core_hours_left: 0.0,
            measures: Vec::new(),
        });
        p.jobs += 1;
        if store::load_run(u.path).is_some() {
            p.done += 1;
        } else {
            p.core_hours_left += u.cost / 3600.0;
        }
    }
    let with = measure_names(&keys_of::<E>(scene));
    let mut pending = Vec::new();
    for (name, mut p) in parts.into_iter().filter(|(_, p)| p.done < p.jobs) {
        let mut def = source.parse::<E::Scene>()?;
        def.scene_mut(scale)
            .leave_out(&BTreeSet::from([name.to_string()]));
        let without = measure_names(&keys_of::<E>(def.scene(scale)));
        p.measures = with
            .iter()
            .filter(|m| !without.contains(*m))
            .cloned()
            .collect();
        pending.push(p);
    }
    Ok(pending)
}

/// The measures `keys` declare as a claim names them, without grids or study cells
/// ([`Measure::family`]): `detail:KEY` and `study:KEY`.
fn measure_names(keys: &Keys) -> BTreeSet<String> {
    let details = keys
        .detail_keys()
        .filter_map(|k| Measure::detail(k.clone()).family());
    let studies = keys.study_names().into_iter().map(|k| format!("study:{k}"));
    details.chain(studies).collect()
}
