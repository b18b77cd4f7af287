//! The statistics of the contact-area law, as pure functions of the realizations' curves
//! `a_r(p~0)`: the low-load slope, the Richardson extrapolation to the continuum, and the
//! largest deviation from eq. (contactArea).

use super::{AreaJob, AreaResult, AreaScene};
use crate::persson::ContactAreaLaw;
use crate::stats::Estimate;

/// The low-load slope `kappa = a_r / p~0`, averaged over the loads `low` (indices into
/// `pressures` and `contact_area`).
pub fn low_load_slope(pressures: &[f64], contact_area: &[f64], low: &[usize]) -> f64 {
    low.iter()
        .map(|&k| contact_area[k] / pressures[k])
        .sum::<f64>()
        / low.len() as f64
}

/// First-order Richardson extrapolation of a value `x1` measured on a grid refined `r1`
/// times and `x2` on a grid refined `r2 > r1` times, for an error proportional to the
/// grid spacing: `x_inf = (r2 x2 - r1 x1) / (r2 - r1)`.
pub fn richardson(r1: f64, x1: f64, r2: f64, x2: f64) -> f64 {
    (r2 * x2 - r1 * x1) / (r2 - r1)
}

/// `count` points spaced evenly in `ln x` from `lo` to `hi`.
pub fn log_grid(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| (lo.ln() + (hi.ln() - lo.ln()) * k as f64 / (count - 1) as f64).exp())
        .collect()
}

/// The realizations' curves `a_r(p~0)`, by Hurst exponent, seed and grid refinement.
pub struct Curves<'a> {
    scene: &'a AreaScene,
    results: &'a [(AreaJob, AreaResult)],
    /// The loads of the low-load slope (`p~0 <= low_load`).
    low: Vec<usize>,
}

impl<'a> Curves<'a> {
    /// The curves of `results`.
    pub fn new(scene: &'a AreaScene, results: &'a [(AreaJob, AreaResult)]) -> Self {
        let p = &scene.reduced_pressures;
        let low = (0..p.len()).filter(|&k| p[k] <= scene.low_load).collect();
        Self {
            scene,
            results,
            low,
        }
    }

    /// The curve of one job.
    pub fn curve(&self, hurst: f64, seed: u64, refine: usize) -> &'a [f64] {
        &self
            .results
            .iter()
            .find(|(j, _)| j.hurst == hurst && j.seed == seed && j.refine == refine)
            .expect("every job ran")
            .1
            .contact_area
    }

    /// The curve extrapolated from the two finest grids (the finest grid's, with one).
    pub fn extrapolated(&self, hurst: f64, seed: u64) -> Vec<f64> {
        let refinements = &self.scene.refinements;
        let finest = *refinements.last().expect("validated non-empty");
        let fine = self.curve(hurst, seed, finest);
        if refinements.len() < 2 {
            return fine.to_vec();
        }
        let r1 = refinements[refinements.len() - 2];
        let coarse = self.curve(hurst, seed, r1);
        fine.iter()
            .zip(coarse)
            .map(|(&f, &c)| richardson(r1 as f64, c, finest as f64, f))
            .collect()
    }

    /// The low-load slope of a curve.
    pub fn kappa(&self, contact_area: &[f64]) -> f64 {
        low_load_slope(&self.scene.reduced_pressures, contact_area, &self.low)
    }
}

/// The extrapolated statistics of one Hurst exponent.
#[derive(Debug, Clone, PartialEq)]
pub struct HurstStats {
    /// The Hurst exponent.
    pub hurst: f64,
    /// Its low-load slope over realizations.
    pub kappa: Estimate,
    /// `a_r` at each reduced pressure, over realizations.
    pub areas: Vec<Estimate>,
}

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

/// One load of the finer grid's study: `a_r` on three grids and the order of the grid
/// error.
#[derive(Debug, Clone, PartialEq)]
pub struct GridOrder {
    /// Hurst exponent.
    pub hurst: f64,
    /// Reduced pressure.
    pub pressure: f64,
    /// The three refinements: the scene's last two and the finer grid's.
    pub refinements: [usize; 3],
    /// `a_r` on each, over realizations.
    pub areas: [Estimate; 3],
    /// `(a_1 - a_2) / (a_2 - a_3)` per realization: 2 for an error proportional to the grid
    /// spacing at refinements 1, 2, 4; 4 for a second-order error.
    pub ratio: Estimate,
    /// What `ratio` is for a first-order error at these refinements.
    pub first_order: f64,
    /// The first-order extrapolation from the coarser pair and from the finer pair.
    pub extrapolated: [Estimate; 2],
}

impl GridOrder {
    /// Every load of the scene's finer grid (none without one).
    pub fn of(scene: &AreaScene, curves: &Curves) -> Vec<Self> {
        let Some(f) = &scene.finer_grid else {
            return Vec::new();
        };
        let k = scene.refinements.len();
        if k < 2 {
            return Vec::new();
        }
        let r = [scene.refinements[k - 2], scene.refinements[k - 1], f.refine];
        let [r1, r2, r3] = r.map(|x| x as f64);
        let mut rows = Vec::new();
        for &hurst in &f.hursts {
            for (j, &p) in f.reduced_pressures.iter().enumerate() {
                let i = scene
                    .reduced_pressures
                    .iter()
                    .position(|&q| q == p)
                    .expect("validated: a pressure of the scene");
                let per_seed: Vec<[f64; 3]> = scene
                    .seeds
                    .iter()
                    .map(|&s| {
                        [
                            curves.curve(hurst, s, r[0])[i],
                            curves.curve(hurst, s, r[1])[i],
                            curves.curve(hurst, s, r[2])[j],
                        ]
                    })
                    .collect();
                let over = |f: &dyn Fn(&[f64; 3]) -> f64| {
                    Estimate::mean_of(&per_seed.iter().map(f).collect::<Vec<_>>())
                };
                rows.push(GridOrder {
                    hurst,
                    pressure: p,
                    refinements: r,
                    areas: [over(&|a| a[0]), over(&|a| a[1]), over(&|a| a[2])],
                    ratio: over(&|a| (a[0] - a[1]) / (a[1] - a[2])),
                    first_order: (1.0 / r1 - 1.0 / r2) / (1.0 / r2 - 1.0 / r3),
                    extrapolated: [
                        over(&|a| richardson(r1, a[0], r2, a[1])),
                        over(&|a| richardson(r2, a[1], r3, a[2])),
                    ],
                });
            }
        }
        rows
    }
}

/// Every statistic of the contact-area law.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaStats {
    /// The low-load slope over all Hurst exponents and realizations, extrapolated: the
    /// headline.
    pub kappa: Estimate,
    /// The low-load slope on each grid: (refinement, slope).
    pub on_grid: Vec<(usize, Estimate)>,
    /// Each Hurst exponent, extrapolated.
    pub hursts: Vec<HurstStats>,
    /// The largest deviation from eq. (contactArea).
    pub law: LawDeviation,
    /// The largest deviation of the non-contact `1 - a_r` from the law's, near full
    /// contact ([`NEAR_FULL_CONTACT`] and above).
    pub complement: LawDeviation,
    /// The law's deviation read other ways: `(key, label, deviation)`.
    pub readings: Vec<(String, String, LawDeviation)>,
    /// The finer grid's loads on three grids.
    pub grid_order: Vec<GridOrder>,
}

/// Loads at and above this `a_r` are near full contact, where the law's complementary
/// term dominates: the range of the `1 - a_r` deviation (up to the top of `law_range`).
pub const NEAR_FULL_CONTACT: f64 = 0.5;

impl AreaStats {
    /// The statistics of the jobs' results.
    pub fn of(scene: &AreaScene, results: &[(AreaJob, AreaResult)]) -> Self {
        let curves = Curves::new(scene, results);
        let pairs = || {
            scene
                .hursts
                .iter()
                .flat_map(|&h| scene.seeds.iter().map(move |&s| (h, s)))
        };
        let kappa = Estimate::mean_of(
            &pairs()
                .map(|(h, s)| curves.kappa(&curves.extrapolated(h, s)))
                .collect::<Vec<_>>(),
        );
        let on_grid = scene
            .refinements
            .iter()
            .map(|&refine| {
                let per: Vec<f64> = pairs()
                    .map(|(h, s)| curves.kappa(curves.curve(h, s, refine)))
                    .collect();
                (refine, Estimate::mean_of(&per))
            })
            .collect();
        let hursts: Vec<HurstStats> = scene
            .hursts
            .iter()
            .map(|&hurst| hurst_stats(scene, &curves, hurst))
            .collect();
        let p = &scene.reduced_pressures;
        let complement = LawDeviation::over(
            p,
            &hursts,
            Denominator::Complement,
            (NEAR_FULL_CONTACT.max(scene.law_range.0), scene.law_range.1),
        );
        let mut readings = vec![(
            "extrapolated_over_law".to_string(),
            "extrapolated a_r, |a_r - law| / law".to_string(),
            LawDeviation::over(p, &hursts, Denominator::Law, scene.law_range),
        )];
        for &refine in &scene.refinements {
            let on: Vec<HurstStats> = scene
                .hursts
                .iter()
                .map(|&h| hurst_stats_on(scene, &curves, h, refine))
                .collect();
            readings.push((
                format!("grid_{}", scene.n * refine),
                format!(
                    "the {0}x{0} grid alone, |a_r - law| / a_r",
                    scene.n * refine
                ),
                LawDeviation::over(p, &on, Denominator::Measured, scene.law_range),
            ));
        }
        let grid_order = GridOrder::of(scene, &curves);
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
        Self {
            kappa,
            on_grid,
            law: LawDeviation::of(scene, &hursts),
            complement,
            readings,
            grid_order,
            hursts,
        }
    }
}

/// The extrapolated slope and areas of one Hurst exponent over the realizations.
fn hurst_stats(scene: &AreaScene, curves: &Curves, hurst: f64) -> HurstStats {
    curve_stats(scene, curves, hurst, |s| curves.extrapolated(hurst, s))
}

/// The slope and areas of one Hurst exponent on the grid refined `refine` times.
pub fn hurst_stats_on(scene: &AreaScene, curves: &Curves, hurst: f64, refine: usize) -> HurstStats {
    curve_stats(scene, curves, hurst, |s| {
        curves.curve(hurst, s, refine).to_vec()
    })
}

/// The slope and areas over the realizations of the curves `curve(seed)`.
fn curve_stats(
    scene: &AreaScene,
    curves: &Curves,
    hurst: f64,
    curve: impl Fn(u64) -> Vec<f64>,
) -> HurstStats {
    let extrapolated: Vec<Vec<f64>> = scene.seeds.iter().map(|&s| curve(s)).collect();
    let kappa = Estimate::mean_of(
        &extrapolated
            .iter()
            .map(|a| curves.kappa(a))
            .collect::<Vec<_>>(),
    );
    let areas = (0..scene.reduced_pressures.len())
        .map(|k| Estimate::mean_of(&extrapolated.iter().map(|r| r[k]).collect::<Vec<_>>()))
        .collect();
    HurstStats {
        hurst,
        kappa,
        areas,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn richardson_removes_an_error_proportional_to_the_spacing() {
        // x(h) = 2 + 0.5 h with h = 1 / r: exact from the two grids.
        let x = |r: f64| 2.0 + 0.5 / r;
        assert!((richardson(1.0, x(1.0), 2.0, x(2.0)) - 2.0).abs() < 1e-15);
        assert!((richardson(2.0, x(2.0), 4.0, x(4.0)) - 2.0).abs() < 1e-15);
    }

    #[test]
    fn low_load_slope_averages_a_r_over_p_at_the_chosen_loads() {
        let p = [0.01, 0.02, 0.5];
        let a = [0.02, 0.05, 0.4];
        assert!((low_load_slope(&p, &a, &[0, 1]) - 2.25).abs() < 1e-15);
    }

    #[test]
    fn the_law_deviation_is_the_worst_load_in_range_with_its_error() {
        let (scene, _, _) = crate::experiments::shipped_scenes::<AreaScene>("contact_area");
        let p = &scene.reduced_pressures;
        // Eq. (contactArea) itself, but 20% high at the third load and 30% high at the
        // last, whose a_r lies outside the law's range.
        let areas: Vec<Estimate> = p
            .iter()
            .enumerate()
            .map(|(k, &p)| {
                let law = ContactAreaLaw::PAPER.contact_area(p);
                let bump = match k {
                    2 => 0.2,
                    9 => 0.3,
                    _ => 0.0,
                };
                Estimate::new(law * (1.0 + bump), 0.01)
            })
            .collect();
        let h = HurstStats {
            hurst: 0.8,
            kappa: Estimate::new(2.0, 0.1),
            areas: areas.clone(),
        };
        let law = LawDeviation::of(&scene, &[h]);
        assert!((law.worst - 0.2 / 1.2).abs() < 1e-12, "{law:?}");
        assert_eq!(law.at.1, p[2]);
        let a = areas[2].value;
        let expect = 0.01 * ContactAreaLaw::PAPER.contact_area(p[2]) / (a * a);
        assert!((law.std_error - expect).abs() < 1e-12 * expect);
    }
}
