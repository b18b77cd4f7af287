//! The counts of one realization's step: how many points lay in the zero-pressure bin
//! before the step, and how many of those lie above it after, for each width of the bin.

use serde::{Deserialize, Serialize};

use crate::experiments::contact_change::{above, across, ENTERED, NEITHER};

/// Counts of one step, for bins `[0, t)` of several widths `t` (`t = 0`: the non-contact,
/// `p = 0`). Counts, not shares, so that the statistics can form any share.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct BinCounts {
    /// Every point of the grid.
    pub points: u64,
    /// Points out of contact before the step (`p = 0`).
    pub non_contact: u64,
    /// Points in contact before the step (`p > 0`).
    pub contact: u64,
    /// For each width, the points in the bin before the step.
    pub in_bin: Vec<u64>,
    /// For each width, the points in the bin before the step and above it after (for
    /// `t = 0`: the points that entered contact).
    pub rose: Vec<u64>,
}

/// The counts of a step from the pressures `before` and `after` of every point, for the
/// bins below each of `thresholds` (pressures, each `>= 0`).
pub fn count(before: &[f64], after: &[f64], thresholds: &[f64]) -> BinCounts {
    assert_eq!(before.len(), after.len(), "one pressure per point at both");
    let mut c = BinCounts {
        points: before.len() as u64,
        non_contact: 0,
        contact: 0,
        in_bin: vec![0; thresholds.len()],
        rose: vec![0; thresholds.len()],
    };
    for (&b, &a) in before.iter().zip(after) {
        if above(b, 0.0) {
            c.contact += 1;
        } else {
            c.non_contact += 1;
        }
        for (k, &t) in thresholds.iter().enumerate() {
            match across(b, a, t) {
                ENTERED => {
                    c.in_bin[k] += 1;
                    c.rose[k] += 1;
                }
                NEITHER => c.in_bin[k] += 1,
                _ => {}
            }
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_follow_a_hand_made_step() {
        // Six points: two out of contact (one enters at 0.05, one stays out), a low one
        // (0.02) that rises to 0.3, a low one (0.04) that leaves, one at 0.5 that stays
        // high and one at 1.0 that falls to 0.08.
        let before = [0.0, 0.0, 0.02, 0.04, 0.5, 1.0];
        let after = [0.05, 0.0, 0.3, 0.0, 0.6, 0.08];
        let c = count(&before, &after, &[0.0, 0.1]);
        assert_eq!((c.points, c.non_contact, c.contact), (6, 2, 4));
        // t = 0: the bin holds the two out of contact, and the first entered contact.
        // t = 0.1: the bin [0, 0.1) holds the four points below 0.1; only 0.02 -> 0.3
        // rises above it (0 -> 0.05 stays in it, 0.04 -> 0 too).
        assert_eq!(c.in_bin, vec![2, 4]);
        assert_eq!(c.rose, vec![1, 1]);
        // A point that falls into the bin from above is not counted as rising.
        let c = count(&[1.0], &[0.0], &[0.0, 0.5]);
        assert_eq!((c.in_bin, c.rose), (vec![0, 0], vec![0, 0]));
    }
}
