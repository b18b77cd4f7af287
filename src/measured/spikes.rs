//! Spikes and outliers of a scan, found before any solve: the points whose height lies
//! beyond [`SPIKE_RMS`] times the rms height from the mean ([`Outliers`]), and which share
//! of the contact at a load sits on them ([`spike_contact_share`]). A Gaussian scan of a
//! million points has none beyond 6 rms (two-sided probability `2e-9` a point); an
//! instrument's spike of tens of rms carries the whole load at small loads, and the
//! contact is then the spike's tip, not the surface's.
//!
//! [`despike`] (off by default) replaces spikes before the check: a point is a spike when
//! its height differs from the median of its (up to) eight neighbours by more than `k`
//! robust deviations, the deviation being `1.4826` times the median absolute deviation of
//! those differences over the scan (the normal-consistent MAD; Rousseeuw & Croux, J. Am.
//! Stat. Assoc. 88, 1273 (1993)); spikes are removed and filled as missing points are,
//! by harmonic interpolation from their neighbours ([`super::fill::harmonic`]). The local
//! median makes the rule blind to the scan's form (tilt, curvature) and to its
//! long-wavelength roughness.

use serde::{Deserialize, Serialize};

use super::fill::harmonic;
use super::psd::Shape;
use crate::error::{Error, Result};

/// The distance from the mean, in rms heights, beyond which a point counts as a spike or
/// an outlier in the diagnosis.
pub const SPIKE_RMS: f64 = 6.0;

/// The least despiking threshold, in robust deviations: below it the rule would remove
/// the tails of an ordinary rough surface (a Gaussian's share beyond 3 is 0.3%).
pub const DESPIKE_MIN: f64 = 3.0;

/// The normal-consistent scale of the median absolute deviation.
const MAD_TO_SIGMA: f64 = 1.4826;

/// The outliers of one scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outliers {
    /// The threshold, in rms heights ([`SPIKE_RMS`]).
    pub beyond_rms: f64,
    /// Points beyond it.
    pub count: usize,
    /// Their share of the scan's points.
    pub share: f64,
    /// The largest distance of a height from the mean, in rms heights.
    pub max_rms: f64,
    /// Points replaced by [`despike`] before the check (0 when not asked).
    pub despiked: usize,
    /// At each of the check's loads, the share of the headline solve's contact points
    /// that are outliers (`None` where that load failed).
    pub contact_share: Vec<Option<f64>>,
    /// The outliers' indices (row-major), for the contact share.
    #[serde(skip)]
    pub points: Vec<usize>,
}

impl Outliers {
    /// The outliers of the heights `h` (any unit; the mean is taken out).
    pub fn of(h: &[f64]) -> Self {
        let n = h.len().max(1) as f64;
        let mean = h.iter().sum::<f64>() / n;
        let rms = (h.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n).sqrt();
        let (points, max_rms) = if rms > 0.0 {
            let points: Vec<usize> = (0..h.len())
                .filter(|&k| (h[k] - mean).abs() > SPIKE_RMS * rms)
                .collect();
            let max = h.iter().map(|x| (x - mean).abs()).fold(0.0, f64::max);
            (points, max / rms)
        } else {
            (Vec::new(), 0.0)
        };
        Self {
            beyond_rms: SPIKE_RMS,
            count: points.len(),
            share: points.len() as f64 / n,
            max_rms,
            despiked: 0,
            contact_share: Vec::new(),
            points,
        }
    }

    /// One sentence: how many points lie beyond the threshold, and the largest height.
    pub fn summary(&self) -> String {
        let mut s = format!(
            "{} points ({}) beyond {} rms from the mean height, the largest at {:.1} rms",
            self.count,
            super::units::percent(self.share),
            self.beyond_rms,
            self.max_rms
        );
        if self.despiked > 0 {
            s.push_str(&format!(
                "; {} spike points were replaced before the check (despike)",
                self.despiked
            ));
        }
        s
    }
}

/// The share of the contact points (`pressure > 0`, the window's pressures in scan
/// order) that are among `points`; `None` without contact.
pub fn spike_contact_share(points: &[usize], pressure: &[f32]) -> Option<f64> {
    let contact = pressure.iter().filter(|&&p| p > 0.0).count();
    if contact == 0 {
        return None;
    }
    let on_spikes = points
        .iter()
        .filter(|&&k| pressure.get(k).is_some_and(|&p| p > 0.0))
        .count();
    Some(on_spikes as f64 / contact as f64)
}

/// Checks a despiking threshold: finite and at least [`DESPIKE_MIN`].
///
/// # Errors
///
/// [`Error::InvalidInput`] naming `despike` and the allowed range.
pub fn check_threshold(k: f64) -> Result<()> {
    if k.is_finite() && k >= DESPIKE_MIN {
        Ok(())
    } else {
        Err(Error::invalid(
            "despike",
            k,
            format!("a number of robust deviations >= {DESPIKE_MIN}"),
        ))
    }
}

/// The median of `v` (reordered); 0 for an empty slice.
fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mid = v.len() / 2;
    let (_, m, _) = v.select_nth_unstable_by(mid, f64::total_cmp);
    *m
}

/// The heights `h` of a `shape` scan (every point finite) with the spikes beyond `k`
/// robust deviations replaced (see the module docs), and how many were.
pub fn despike(h: &[f64], shape: Shape, k: f64) -> (Vec<f64>, usize) {
    let (rows, cols) = (shape.rows, shape.cols);
    let mut residual = vec![0.0; h.len()];
    let mut around = Vec::with_capacity(8);
    for r in 0..rows {
        for c in 0..cols {
            around.clear();
            for dr in -1i64..=1 {
                for dc in -1i64..=1 {
                    let (rr, cc) = (r as i64 + dr, c as i64 + dc);
                    if (dr, dc) == (0, 0)
                        || rr < 0
                        || cc < 0
                        || rr >= rows as i64
                        || cc >= cols as i64
                    {
                        continue;
                    }
                    around.push(h[rr as usize * cols + cc as usize]);
                }
            }
            residual[r * cols + c] = h[r * cols + c] - median(&mut around);
        }
    }
    let mut dev: Vec<f64> = residual.clone();
    let centre = median(&mut dev);
    let mut abs: Vec<f64> = residual.iter().map(|x| (x - centre).abs()).collect();
    let sigma = MAD_TO_SIGMA * median(&mut abs);
    let mut out = h.to_vec();
    if sigma.is_nan() || sigma <= 0.0 {
        return (out, 0);
    }
    let mut removed = 0;
    for (o, x) in out.iter_mut().zip(&residual) {
        if (x - centre).abs() > k * sigma {
            *o = f64::NAN;
            removed += 1;
        }
    }
    if removed > 0 && removed < out.len() {
        harmonic(&mut out, rows, cols);
    } else if removed > 0 {
        return (h.to_vec(), 0);
    }
    (out, removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn smooth(rows: usize, cols: usize) -> Vec<f64> {
        (0..rows * cols)
            .map(|k| {
                let (r, c) = ((k / cols) as f64, (k % cols) as f64);
                (0.3 * r).sin() + (0.2 * c).cos() + 0.01 * (1.7 * r * c).sin()
            })
            .collect()
    }

    #[test]
    fn a_spike_is_counted_with_its_height_in_rms() {
        let mut h = smooth(32, 32);
        h[100] += 40.0;
        let o = Outliers::of(&h);
        assert_eq!(o.count, 1, "one spike beyond {SPIKE_RMS} rms");
        assert_eq!(o.points, vec![100]);
        assert!(o.max_rms > 20.0, "the spike's height in rms: {}", o.max_rms);
        assert!(
            Outliers::of(&smooth(32, 32)).count == 0,
            "a smooth scan has none"
        );
    }

    #[test]
    fn the_contact_share_counts_the_contact_points_on_spikes() {
        let p = [0.0f32, 1.0, 2.0, 0.0, 3.0];
        assert_eq!(spike_contact_share(&[1, 3], &p), Some(1.0 / 3.0));
        assert_eq!(spike_contact_share(&[1], &[0.0f32; 3]), None);
    }

    #[test]
    fn despiking_replaces_the_spikes_and_nothing_else() {
        let shape = Shape { rows: 24, cols: 20 };
        let clean = smooth(24, 20);
        let mut h = clean.clone();
        h[5 * 20 + 7] += 30.0;
        h[17 * 20 + 2] -= 25.0;
        let (out, removed) = despike(&h, shape, 8.0);
        assert_eq!(removed, 2);
        for (k, (a, b)) in out.iter().zip(&clean).enumerate() {
            assert!(
                (a - b).abs() < 0.2,
                "point {k}: {a} against the clean {b} (filled from its neighbours)"
            );
        }
        assert_eq!(
            despike(&clean, shape, 8.0).1,
            0,
            "a smooth scan keeps every point"
        );
    }

    #[test]
    fn a_threshold_below_the_least_is_refused_naming_the_field() {
        let e = check_threshold(2.0).unwrap_err().to_string();
        assert!(e.contains("despike") && e.contains(">= 3"), "{e}");
        assert!(check_threshold(f64::NAN).is_err());
        assert!(check_threshold(5.0).is_ok());
    }
}
