//! Load ensembles: the seeds x contact areas job grid, and statistics over the
//! realizations at one load.
//!
//! The experiments that follow a realization at a fixed load (re-entry, single modes,
//! total energy) state each load as the relative contact area it gives at full
//! resolution, and run one job per realization and load ([`SeedLoad`]). Their ensemble
//! values are ratios of sums over realizations ([`Estimate::ratio_of_sums`], the
//! delta-method error of `sum a / sum b`) or means over realizations
//! ([`Estimate::mean_of`]), always load by load ([`LoadGroup`]).

use serde::{Deserialize, Serialize};

use crate::error::{check_open, Error, Result};
use crate::stats::Estimate;

/// One realization at one load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeedLoad {
    /// Seed of the realization.
    pub seed: u64,
    /// Load: the relative contact area at full resolution (`zeta_max`).
    pub contact_area: f64,
}

/// The jobs of every seed at every contact area, contact areas outermost.
pub fn seed_load_jobs(contact_areas: &[f64], seeds: &[u64]) -> Vec<SeedLoad> {
    contact_areas
        .iter()
        .flat_map(|&contact_area| {
            seeds
                .iter()
                .map(move |&seed| SeedLoad { seed, contact_area })
        })
        .collect()
}

/// Checks a list of contact areas: not empty, each in (0, 1), each named once (a
/// repeated load would run every realization at it twice, count each twice in its
/// ensemble and shrink the error bar for nothing).
pub fn check_contact_areas(contact_areas: &[f64]) -> Result<()> {
    if contact_areas.is_empty() {
        return Err(Error::invalid(
            "contact_areas",
            "[]",
            "at least one contact area in (0, 1)",
        ));
    }
    for (k, &a) in contact_areas.iter().enumerate() {
        check_open("contact_areas", a, 0.0, 1.0)?;
        if contact_areas[..k].contains(&a) {
            return Err(Error::invalid(
                "contact_areas",
                format!("{contact_areas:?}"),
                format!("each contact area once ({a} appears twice)"),
            ));
        }
    }
    Ok(())
}

/// Checks the scene's loads ([`check_contact_areas`]) and that the headline load is one
/// of them.
pub fn check_headline(headline: f64, contact_areas: &[f64]) -> Result<()> {
    check_contact_areas(contact_areas)?;
    if contact_areas.contains(&headline) {
        Ok(())
    } else {
        Err(Error::invalid(
            "headline_contact_area",
            headline,
            format!("one of contact_areas {contact_areas:?}"),
        ))
    }
}

/// The results of every realization at one load.
#[derive(Debug)]
pub struct LoadGroup<'a, R> {
    /// The load, as the contact area at full resolution.
    pub contact_area: f64,
    /// The realizations' results, in job order.
    pub runs: Vec<&'a R>,
}

/// Groups `results` by load, in the order of `contact_areas`.
pub fn by_load<'a, R>(
    contact_areas: &[f64],
    results: &'a [(SeedLoad, R)],
) -> Vec<LoadGroup<'a, R>> {
    contact_areas
        .iter()
        .map(|&a| LoadGroup {
            contact_area: a,
            runs: results
                .iter()
                .filter(|(j, _)| j.contact_area == a)
                .map(|(_, r)| r)
                .collect(),
        })
        .collect()
}

/// The group of load `contact_area`.
pub fn group<'g, 'a, R>(groups: &'g [LoadGroup<'a, R>], contact_area: f64) -> &'g LoadGroup<'a, R> {
    groups
        .iter()
        .find(|g| g.contact_area == contact_area)
        .expect("a load of the scene")
}

impl<R> LoadGroup<'_, R> {
    /// `sum_i a_i / sum_i b_i` over the realizations, `(a_i, b_i) = pair(run_i)`.
    pub fn ratio(&self, pair: impl Fn(&R) -> (f64, f64)) -> Estimate {
        let pairs: Vec<(f64, f64)> = self.runs.iter().map(|r| pair(r)).collect();
        Estimate::ratio_of_sums(&pairs)
    }

    /// The mean over the realizations of `value(run_i)`.
    pub fn mean(&self, value: impl Fn(&R) -> f64) -> Estimate {
        Estimate::mean_of(&self.runs.iter().map(|r| value(r)).collect::<Vec<_>>())
    }
}

/// The smallest and the largest of a list of loads.
pub fn load_range(contact_areas: &[f64]) -> (f64, f64) {
    let lowest = contact_areas.iter().copied().fold(f64::INFINITY, f64::min);
    let highest = contact_areas.iter().copied().fold(0.0, f64::max);
    (lowest, highest)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jobs_cover_every_load_and_seed_once_loads_outermost() {
        let jobs = seed_load_jobs(&[0.1, 0.5], &[3, 4, 5]);
        assert_eq!(jobs.len(), 6);
        assert_eq!(
            jobs[0],
            SeedLoad {
                seed: 3,
                contact_area: 0.1
            }
        );
        assert_eq!(
            jobs[3],
            SeedLoad {
                seed: 3,
                contact_area: 0.5
            }
        );
    }

    #[test]
    fn groups_hold_their_load_only_and_give_ratios_of_sums() {
        let jobs = seed_load_jobs(&[0.1, 0.5], &[1, 2]);
        let results: Vec<(SeedLoad, (f64, f64))> = jobs
            .into_iter()
            .map(|j| {
                let x = j.contact_area * j.seed as f64;
                (j, (2.0 * x, x))
            })
            .collect();
        let groups = by_load(&[0.1, 0.5], &results);
        assert_eq!(groups.len(), 2);
        assert!(groups.iter().all(|g| g.runs.len() == 2));
        let r = group(&groups, 0.5).ratio(|&(a, b)| (a, b));
        assert_eq!(r.value, 2.0);
        assert_eq!(r.std_error, 0.0);
        let m = group(&groups, 0.1).mean(|&(_, b)| b);
        assert!((m.value - 0.15).abs() < 1e-15);
        assert_eq!(load_range(&[0.3, 0.02, 0.8]), (0.02, 0.8));
    }

    #[test]
    fn headline_and_areas_are_checked_by_name() {
        assert!(check_contact_areas(&[])
            .unwrap_err()
            .to_string()
            .contains("contact_areas"));
        assert!(check_contact_areas(&[0.2, 1.0]).is_err());
        let e = check_contact_areas(&[0.14, 0.014, 0.14])
            .unwrap_err()
            .to_string();
        assert!(e.contains("contact_areas") && e.contains("once"), "{e}");
        assert!(check_contact_areas(&[0.14, 0.014, 0.88]).is_ok());
        let e = check_headline(0.3, &[0.2]).unwrap_err().to_string();
        assert!(e.contains("headline_contact_area"), "{e}");
    }
}
