//! The largest deviation of the measured `a_r` from eq. (contactArea) over the loads in
//! the scene's `law_range`, relative to the measured `a_r`, the law's, or the non-contact
//! `1 - a_r`; and the deviation read on the finer grid's loads alone.

use super::{GridOrder, HurstStats};
use crate::experiments::contact_area::AreaScene;
use crate::persson::ContactAreaLaw;
use crate::stats::Estimate;

/// The largest relative deviation of the measured `a_r` from eq. (contactArea) over the
/// loads whose `a_r` lies in the scene's `law_range`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawDeviation {
    /// `|a_r - law| / a_r` at the worst load (0 when no load is in range).
    pub worst: f64,
    /// Its standard error, from that of `a_r` (0 when no load is in range).
    pub std_error: f64,
    /// Hurst exponent, reduced pressure and `a_r` of the worst load (NaN when none).
    pub at: (f64, f64, f64),
}

/// What a deviation from eq. (contactArea) is relative to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Denominator {
    /// The measured `a_r`: `|a_r - law| / a_r`.
    Measured,
    /// The law's `a_r`: `|a_r - law| / law`.
    Law,
    /// The measured non-contact: `|(1 - a_r) - (1 - law)| / (1 - a_r)`.
    Complement,
}

impl Denominator {
    /// The deviation of `a` (with its error) from `law`, and its standard error.
    fn deviation(self, a: Estimate, law: f64) -> (f64, f64) {
        let diff = (a.value - law).abs();
        match self {
            // d/da |a - law| / a = +- law / a^2.
            Denominator::Measured => (diff / a.value, a.std_error * law / (a.value * a.value)),
            Denominator::Law => (diff / law, a.std_error / law),
            // d/da |a - law| / (1 - a) = +- (1 - law) / (1 - a)^2.
            Denominator::Complement => {
                let c = 1.0 - a.value;
                (diff / c, a.std_error * (1.0 - law) / (c * c))
            }
        }
    }
}

impl LawDeviation {
    /// The worst deviation over `hursts`, at the scene's pressures, relative to the
    /// measured `a_r` over the scene's `law_range`.
    pub fn of(scene: &AreaScene, hursts: &[HurstStats]) -> Self {
        Self::over(
            &scene.reduced_pressures,
            hursts,
            Denominator::Measured,
            scene.law_range,
        )
    }

    /// The worst deviation over `hursts` at `pressures`, relative to `denominator`, over
    /// the loads whose `a_r` lies in `range`.
    pub fn over(
        pressures: &[f64],
        hursts: &[HurstStats],
        denominator: Denominator,
        range: (f64, f64),
    ) -> Self {
        let mut law = LawDeviation {
            worst: 0.0,
            std_error: 0.0,
            at: (f64::NAN, f64::NAN, f64::NAN),
        };
        for h in hursts {
            for (&p, &a) in pressures.iter().zip(&h.areas) {
                if a.value < range.0 || a.value > range.1 {
                    continue;
                }
                let (dev, std_error) =
                    denominator.deviation(a, ContactAreaLaw::PAPER.contact_area(p));
                if dev > law.worst {
                    law = LawDeviation {
                        worst: dev,
                        std_error,
                        at: (h.hurst, p, a.value),
                    };
                }
            }
        }
        law
    }

    /// The deviation as an estimate, for deciding the check.
    pub fn estimate(&self) -> Estimate {
        Estimate::new(self.worst, self.std_error)
    }
}

/// The law's deviation on the finer grid's loads only, relative to the measured `a_r`,
/// extrapolated from the coarser and from the finer pair of its three grids: `(key,
/// label, deviation)` (none without a finer grid).
pub(super) fn finer_grid_readings(
    scene: &AreaScene,
    grid_order: &[GridOrder],
) -> Vec<(String, String, LawDeviation)> {
    let mut readings = Vec::new();
    for (pair, label) in [(0, "coarser"), (1, "finer")] {
        let worst = grid_order
            .iter()
            .filter(|g| {
                (scene.law_range.0..=scene.law_range.1).contains(&g.extrapolated[pair].value)
            })
            .map(|g| {
                let a = g.extrapolated[pair];
                let (dev, err) = Denominator::Measured
                    .deviation(a, ContactAreaLaw::PAPER.contact_area(g.pressure));
                LawDeviation {
                    worst: dev,
                    std_error: err,
                    at: (g.hurst, g.pressure, a.value),
                }
            })
            .max_by(|a, b| a.worst.total_cmp(&b.worst));
        if let (Some(w), Some(g)) = (worst, grid_order.first()) {
            let grids = if pair == 0 { [0, 1] } else { [1, 2] };
            readings.push((
                format!("finer_grid_{label}_pair"),
                format!(
                    "the finer grid's loads only, extrapolated from the {label} pair ({}^2 \
                     and {}^2), |a_r - law| / a_r",
                    scene.n * g.refinements[grids[0]],
                    scene.n * g.refinements[grids[1]]
                ),
                w,
            ));
        }
    }
    readings
}
