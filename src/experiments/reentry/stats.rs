//! The statistics of the re-entry experiment, as pure functions of the histories: the
//! re-entry shares at every load and the flux of the interval at the headline load, means
//! over realizations.

use super::ReentryResult;
use crate::experiments::ensemble::LoadGroup;
use crate::stats::Estimate;

/// The shares of one load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Share {
    /// The load, as the contact area at `zeta_max`.
    pub load: f64,
    /// Points in contact at `zeta_max` that were out of contact at a lower `zeta`.
    pub share: Estimate,
    /// Of those, the points that left after the first shell and came back.
    pub after_first: Estimate,
    /// Of those, the points out of contact at the first shell only (`zeta = 1`, the
    /// surfaces having no modes below `q_l`).
    pub out_at_first: Estimate,
}

/// Every statistic of the re-entry experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct ReentryStats {
    /// The shares of every load, in the scene's order (the first is the headline).
    pub shares: Vec<Share>,
    /// Flux into contact over the interval at the headline load (fraction of `A0`).
    pub flux_in: Estimate,
    /// Flux out of contact over the interval.
    pub flux_out: Estimate,
    /// The net flux over the mean one-way flux.
    pub net_over_gross: Estimate,
    /// The share of non-contact that enters contact over the interval.
    pub flux_in_of_noncontact: Estimate,
    /// The shells a history adds one at a time: exact (error 0) when every history has
    /// the same count, else their mean over histories.
    pub shells: Estimate,
}

impl ReentryStats {
    /// The statistics of the loads' histories (the headline load first).
    pub fn of(loads: &[LoadGroup<ReentryResult>]) -> Self {
        let head = &loads[0];
        Self {
            shares: loads
                .iter()
                .map(|load| Share {
                    load: load.contact_area,
                    share: load.mean(ReentryResult::share),
                    after_first: load.mean(ReentryResult::share_after_first),
                    out_at_first: load.mean(ReentryResult::share_out_at_first),
                })
                .collect(),
            flux_in: head.mean(|r| r.flux_in),
            flux_out: head.mean(|r| r.flux_out),
            net_over_gross: head.mean(ReentryResult::net_over_gross),
            flux_in_of_noncontact: head.mean(|r| r.flux_in_of_noncontact),
            shells: shells(loads.iter().flat_map(|l| l.runs.iter().map(|r| r.shells))),
        }
    }
}

/// `part / whole` as a fraction, 0 when `whole` is 0 (no points to count): every share
/// of the histories (re-entered of the contact, stayed of the start, left soon of the
/// entered).
pub fn ratio(part: u64, whole: u64) -> f64 {
    part as f64 / whole.max(1) as f64
}

/// The count of shells of the histories: exact (error 0) when they agree, else their mean
/// over histories (NaN with none).
pub fn shells(counts: impl IntoIterator<Item = usize>) -> Estimate {
    let counts: Vec<f64> = counts.into_iter().map(|c| c as f64).collect();
    match counts.first() {
        Some(&c) if counts.iter().all(|&x| x == c) => Estimate::new(c, 0.0),
        _ => Estimate::mean_of(&counts),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_shell_counts_are_exact_and_unequal_ones_averaged() {
        assert_eq!(shells([4355, 4355, 4355]), Estimate::new(4355.0, 0.0));
        let mixed = shells([4354, 4356]);
        assert_eq!(mixed.value, 4355.0);
        assert!((mixed.std_error - 1.0).abs() < 1e-12);
        assert!(shells([]).value.is_nan());
    }
}
