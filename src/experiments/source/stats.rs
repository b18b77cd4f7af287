//! The statistics, as pure functions of the counts: for each row of the scene and each
//! width of the zero-pressure bin, the points that rose above the bin in the step as a
//! share of the non-contact, of the contact and of the nominal area `A0` before the step
//! (and of the bin itself), each a mean over realizations with its standard error.

use super::{SourceJob, SourceResult, SourceScene, SourceStep};
use crate::error::{Error, Result};
use crate::stats::Estimate;

/// One bin width of one row: the points that rose above the bin, as shares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// The bin's width, units of `p0 / a_r` (0: the non-contact alone).
    pub width: f64,
    /// Over the non-contact before the step (`p = 0`).
    pub of_non_contact: Estimate,
    /// Over the contact before the step.
    pub of_contact: Estimate,
    /// Over every point (the nominal area `A0`).
    pub of_nominal: Estimate,
    /// Over the points in the bin before the step.
    pub of_bin: Estimate,
}

/// One row of the scene over its realizations.
#[derive(Debug, Clone, PartialEq)]
pub struct RowStats {
    /// The row.
    pub step: SourceStep,
    /// Realizations.
    pub realizations: usize,
    /// `a_r` before the step.
    pub contact_before: Estimate,
    /// `a_r` after it.
    pub contact_after: Estimate,
    /// One reading per bin width of the scene.
    pub readings: Vec<Reading>,
}

/// The statistics of a run: one entry per row of the scene, in its order.
#[derive(Debug, Clone, PartialEq)]
pub struct SourceStats {
    /// The rows.
    pub rows: Vec<RowStats>,
}

/// `num / den` per realization; NaN (left out of the mean) where `den` is 0.
fn share(num: u64, den: u64) -> f64 {
    if den == 0 {
        f64::NAN
    } else {
        num as f64 / den as f64
    }
}

/// The mean over realizations of the finite values of `f`.
fn mean_over(results: &[&SourceResult], f: impl Fn(&SourceResult) -> f64) -> Estimate {
    let v: Vec<f64> = results
        .iter()
        .map(|r| f(r))
        .filter(|v| v.is_finite())
        .collect();
    Estimate::mean_of(&v)
}

impl SourceStats {
    /// The statistics of every job's result (errors: a row without results, or counts
    /// that do not have one entry per bin width).
    pub fn of(scene: &SourceScene, results: &[(SourceJob, SourceResult)]) -> Result<Self> {
        let widths = scene.bin_widths.len();
        let mut rows = Vec::with_capacity(scene.steps.len());
        for step in &scene.steps {
            let here: Vec<&SourceResult> = results
                .iter()
                .filter(|(j, _)| j.step == *step)
                .map(|(_, r)| r)
                .collect();
            if here.is_empty() {
                return Err(Error::invalid(
                    "results",
                    step.label(),
                    "at least one realization of every row",
                ));
            }
            if here
                .iter()
                .any(|r| r.counts.rose.len() != widths || r.counts.in_bin.len() != widths)
            {
                return Err(Error::invalid(
                    "results",
                    step.label(),
                    format!("counts for each of the {widths} bin widths"),
                ));
            }
            let readings = scene
                .bin_widths
                .iter()
                .enumerate()
                .map(|(k, &width)| {
                    let over = |den: fn(&SourceResult, usize) -> u64| {
                        mean_over(&here, |r| share(r.counts.rose[k], den(r, k)))
                    };
                    Reading {
                        width,
                        of_non_contact: over(|r, _| r.counts.non_contact),
                        of_contact: over(|r, _| r.counts.contact),
                        of_nominal: over(|r, _| r.counts.points),
                        of_bin: over(|r, k| r.counts.in_bin[k]),
                    }
                })
                .collect();
            rows.push(RowStats {
                step: step.clone(),
                realizations: here.len(),
                contact_before: mean_over(&here, |r| r.a_r_before),
                contact_after: mean_over(&here, |r| r.a_r_after),
                readings,
            });
        }
        if rows.is_empty() {
            return Err(Error::invalid("steps", "[]", "at least one row"));
        }
        Ok(Self { rows })
    }

    /// The statistics of the scene's row `step`, if the run has it.
    pub fn row(&self, step: &SourceStep) -> Option<&RowStats> {
        self.rows.iter().find(|r| r.step == *step)
    }

    /// The headline: the share of the non-contact entering contact (width 0) in the first
    /// row.
    pub fn headline(&self) -> Estimate {
        self.rows[0].readings[0].of_non_contact
    }
}

#[cfg(test)]
mod tests {
    use super::super::BinCounts;
    use super::*;

    fn result(non_contact: u64, rose: [u64; 2], in_bin: u64) -> SourceResult {
        SourceResult {
            p0: 0.01,
            a_r_before: (100 - non_contact) as f64 / 100.0,
            a_r_after: 0.5,
            counts: BinCounts {
                points: 100,
                non_contact,
                contact: 100 - non_contact,
                in_bin: vec![non_contact, in_bin],
                rose: rose.to_vec(),
            },
            max_residual: 0.0,
        }
    }

    #[test]
    fn shares_are_means_over_realizations_of_each_denominator() {
        let (mut scene, _, _) = crate::experiments::shipped_scenes::<SourceScene>("c_source");
        scene.steps.truncate(1);
        scene.bin_widths = vec![0.0, 0.1];
        let step = scene.steps[0].clone();
        let job = |seed| SourceJob {
            step: step.clone(),
            seed,
        };
        // Seed 1: 50 out of contact, 1 enters; 60 in the wider bin, 3 rise above it.
        // Seed 2: 40 out of contact, 2 enter; 50 in the wider bin, 5 rise.
        let results = vec![
            (job(1), result(50, [1, 3], 60)),
            (job(2), result(40, [2, 5], 50)),
        ];
        let s = SourceStats::of(&scene, &results).unwrap();
        let r = &s.rows[0];
        assert_eq!(r.realizations, 2);
        let zero = r.readings[0];
        assert_eq!(zero.of_non_contact.value, (1.0 / 50.0 + 2.0 / 40.0) / 2.0);
        assert_eq!(zero.of_contact.value, (1.0 / 50.0 + 2.0 / 60.0) / 2.0);
        assert_eq!(zero.of_nominal.value, (1.0 / 100.0 + 2.0 / 100.0) / 2.0);
        assert_eq!(zero.of_bin, zero.of_non_contact);
        let wide = r.readings[1];
        assert_eq!(wide.of_bin.value, (3.0 / 60.0 + 5.0 / 50.0) / 2.0);
        assert_eq!(wide.of_non_contact.value, (3.0 / 50.0 + 5.0 / 40.0) / 2.0);
        // The standard error of two samples: half their difference.
        assert!((zero.of_nominal.std_error - 0.005).abs() < 1e-15);
        assert_eq!(s.headline(), zero.of_non_contact);
        // A row without results, or counts of another length, is refused.
        let mut two = scene.clone();
        two.steps.push(SourceStep {
            hurst: 0.3,
            ..step.clone()
        });
        assert!(SourceStats::of(&two, &results).is_err());
        two.steps.truncate(1);
        two.bin_widths.push(0.2);
        assert!(SourceStats::of(&two, &results).is_err());
    }
}
