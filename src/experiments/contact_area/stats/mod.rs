//! The statistics of the contact-area law, as pure functions of the realizations' curves
//! `a_r(p~0)`: the low-load slope, the Richardson extrapolation to the continuum, the
//! largest deviation from eq. (contactArea), and the law's shape (spread over `H`, `c1`,
//! `c2`, the order of the leading correction).

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

/// The loads of the exponent of the leading correction to `a_r ~ kappa p~0` (geometric:
/// each twice the last): where the correction is large enough to measure and `a_r < 0.25`.
pub const CORRECTION_LOADS: [f64; 3] = [0.03, 0.06, 0.12];

/// The range of `a_r` of the mean low-to-partial-load slope: the loads of the paper's own
/// figures (`a_r` up to 0.32).
pub const PARTIAL_RANGE: (f64, f64) = (0.01, 0.35);

/// The largest spread over Hurst exponents of `kappa_H(p) = a_r / p~0` at one load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HurstSpread {
    /// `max_H kappa_H - min_H kappa_H` at the worst load, with the two Hurst exponents'
    /// standard errors combined.
    pub spread: Estimate,
    /// The reduced pressure of the worst load and the Hurst exponents of the largest and
    /// the smallest `kappa` there (NaN when no load qualifies).
    pub at: (f64, f64, f64),
}

impl HurstSpread {
    /// The worst load over `pressures` among those where every Hurst exponent's `a_r` lies
    /// in `range`.
    pub fn over(pressures: &[f64], hursts: &[HurstStats], range: (f64, f64)) -> Self {
        let mut worst = HurstSpread {
            spread: Estimate::new(f64::NAN, f64::NAN),
            at: (f64::NAN, f64::NAN, f64::NAN),
        };
        for (k, &p) in pressures.iter().enumerate() {
            let inside = |h: &HurstStats| (range.0..=range.1).contains(&h.areas[k].value);
            if hursts.is_empty() || !hursts.iter().all(inside) {
                continue;
            }
            let kappa = |h: &HurstStats| h.areas[k].value / p;
            let by = |a: &&HurstStats, b: &&HurstStats| kappa(a).total_cmp(&kappa(b));
            let hi = hursts.iter().max_by(by).expect("non-empty");
            let lo = hursts.iter().min_by(by).expect("non-empty");
            let spread = Estimate::new(
                kappa(hi) - kappa(lo),
                hi.areas[k].std_error.hypot(lo.areas[k].std_error) / p,
            );
            if worst.spread.value.is_nan() || spread.value > worst.spread.value {
                worst = HurstSpread {
                    spread,
                    at: (p, hi.hurst, lo.hurst),
                };
            }
        }
        worst
    }
}

/// `c2` of eq. (contactArea) with `c1` fixed such that the law gives `a_r` at `p~0`
/// (bisection on `c2` in `[0.8, 2]`, where the law's `a_r` grows with `c2` for
/// `p~0 >= 0.5`); NaN when `a_r` is outside what that interval gives.
pub fn c2_for(c1: f64, p_reduced: f64, a_r: f64) -> f64 {
    let excess = |c2: f64| ContactAreaLaw { c1, c2 }.contact_area(p_reduced) - a_r;
    let (mut lo, mut hi) = (0.8, 2.0);
    if excess(lo) * excess(hi) > 0.0 {
        return f64::NAN;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if excess(mid) * excess(lo) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-14 {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// The exponent `m` of a leading correction `kappa(0) - kappa(p) ~ p^m` from `kappa` at
/// three loads each `ratio` times the last: `m = ln[(k1 - k2) / (k0 - k1)] / ln ratio`
/// (`m = 2` for a correction third order in `p~0` to `a_r`, `m = 1` for second order).
pub fn correction_exponent(kappa: [f64; 3], ratio: f64) -> f64 {
    ((kappa[1] - kappa[2]) / (kappa[0] - kappa[1])).ln() / ratio.ln()
}

/// The statistics of the law's shape: how far `a_r` depends on `H` at equal `p~0`, the
/// coefficients `c1` and `c2`, the order of the leading correction and the mean slope
/// over partial contact, all from the extrapolated curves.
#[derive(Debug, Clone, PartialEq)]
pub struct LawShape {
    /// The largest spread of `kappa` over Hurst exponents at one load with every `a_r` in
    /// the scene's `law_range`.
    pub spread: HurstSpread,
    /// `c2` of eq. (contactArea) with the paper's `c1` for `a_r` pooled over Hurst
    /// exponents and realizations at the highest load; standard error from `c2` per
    /// realization.
    pub c2: Estimate,
    /// `c1 = kappa / 2`.
    pub c1: Estimate,
    /// The exponent of the leading correction at [`CORRECTION_LOADS`], `kappa` pooled over
    /// Hurst exponents; jackknife over realizations (NaN when a load is not the scene's).
    pub correction: Estimate,
    /// `a_r / p~0` averaged over Hurst exponents and the loads whose mean `a_r` lies in
    /// [`PARTIAL_RANGE`]; standard error over realizations.
    pub partial_kappa: Estimate,
}

impl LawShape {
    /// The shape of `curves[seed][hurst][load]` (the extrapolated curves) at `pressures`,
    /// with `hursts` their means and `kappa` the headline slope.
    pub fn of(
        pressures: &[f64],
        curves: &[Vec<Vec<f64>>],
        hursts: &[HurstStats],
        kappa: Estimate,
        law_range: (f64, f64),
    ) -> Self {
        let last = pressures.len() - 1;
        let top = pressures[last];
        let c1 = ContactAreaLaw::PAPER.c1;
        // a_r at the highest load, averaged over Hurst exponents, per realization.
        let top_area: Vec<f64> = curves
            .iter()
            .map(|by_h| by_h.iter().map(|a| a[last]).sum::<f64>() / by_h.len() as f64)
            .collect();
        let pooled = top_area.iter().sum::<f64>() / top_area.len() as f64;
        let per_seed: Vec<f64> = top_area.iter().map(|&a| c2_for(c1, top, a)).collect();
        let c2 = Estimate::new(
            c2_for(c1, top, pooled),
            Estimate::mean_of(&per_seed).std_error,
        );
        let at: Vec<Option<usize>> = CORRECTION_LOADS
            .iter()
            .map(|&p| pressures.iter().position(|&q| q == p))
            .collect();
        let correction = match at[..] {
            [Some(i0), Some(i1), Some(i2)] => Estimate::jackknife(curves.len(), |leave| {
                let kappa_at = |i: usize| {
                    let kept: Vec<f64> = curves
                        .iter()
                        .enumerate()
                        .filter(|&(s, _)| Some(s) != leave)
                        .flat_map(|(_, by_h)| by_h.iter().map(move |a| a[i] / pressures[i]))
                        .collect();
                    kept.iter().sum::<f64>() / kept.len() as f64
                };
                correction_exponent(
                    [kappa_at(i0), kappa_at(i1), kappa_at(i2)],
                    CORRECTION_LOADS[1] / CORRECTION_LOADS[0],
                )
            }),
            _ => Estimate::new(f64::NAN, f64::NAN),
        };
        let partial: Vec<(usize, usize)> = hursts
            .iter()
            .enumerate()
            .flat_map(|(h, stats)| {
                stats
                    .areas
                    .iter()
                    .enumerate()
                    .filter(|(_, a)| (PARTIAL_RANGE.0..=PARTIAL_RANGE.1).contains(&a.value))
                    .map(move |(k, _)| (h, k))
            })
            .collect();
        let partial_kappa = Estimate::mean_of(
            &curves
                .iter()
                .map(|by_h| {
                    partial
                        .iter()
                        .map(|&(h, k)| by_h[h][k] / pressures[k])
                        .sum::<f64>()
                        / partial.len() as f64
                })
                .collect::<Vec<_>>(),
        );
        Self {
            spread: HurstSpread::over(pressures, hursts, law_range),
            c2,
            c1: Estimate::new(kappa.value / 2.0, kappa.std_error / 2.0),
            correction,
            partial_kappa,
        }
    }
}

/// The fall of `a_r / p~0` from the lowest load to the first of [`CORRECTION_LOADS`] on
/// one grid (or extrapolated) for one Hurst exponent: whether the grid or the size of the
/// contact spots could explain it.
#[derive(Debug, Clone, PartialEq)]
pub struct KappaFall {
    /// Hurst exponent.
    pub hurst: f64,
    /// Points per side of the grid (none: extrapolated to `eps_c -> 0`).
    pub grid: Option<usize>,
    /// `a_r / p~0` at the lowest load, over realizations.
    pub kappa_lowest: Estimate,
    /// `a_r / p~0` at the first of [`CORRECTION_LOADS`].
    pub kappa_at: Estimate,
    /// `1 - kappa_at / kappa_lowest` per realization, over realizations.
    pub fall: Estimate,
    /// Points in contact at the lowest load (none when extrapolated).
    pub contact_points: Option<Estimate>,
}

impl KappaFall {
    /// The rows of every Hurst exponent on every grid and extrapolated (none when the
    /// scene's lowest load is not below the first of [`CORRECTION_LOADS`], or that load
    /// is not the scene's).
    pub fn of(scene: &AreaScene, curves: &Curves) -> Vec<Self> {
        let p = &scene.reduced_pressures;
        let Some(j) = p.iter().position(|&q| q == CORRECTION_LOADS[0]) else {
            return Vec::new();
        };
        if j == 0 {
            return Vec::new();
        }
        let mut rows = Vec::new();
        for &hurst in &scene.hursts {
            let grids = scene
                .refinements
                .iter()
                .map(|&r| Some(r))
                .chain(std::iter::once(None));
            for refine in grids {
                let per_seed: Vec<Vec<f64>> = scene
                    .seeds
                    .iter()
                    .map(|&s| match refine {
                        Some(r) => curves.curve(hurst, s, r).to_vec(),
                        None => curves.extrapolated(hurst, s),
                    })
                    .collect();
                let over = |f: &dyn Fn(&[f64]) -> f64| {
                    Estimate::mean_of(&per_seed.iter().map(|a| f(a)).collect::<Vec<_>>())
                };
                rows.push(KappaFall {
                    hurst,
                    grid: refine.map(|r| scene.n * r),
                    kappa_lowest: over(&|a| a[0] / p[0]),
                    kappa_at: over(&|a| a[j] / p[j]),
                    fall: over(&|a| 1.0 - (a[j] / p[j]) / (a[0] / p[0])),
                    contact_points: refine.map(|r| {
                        let points = (scene.n * r * scene.n * r) as f64;
                        over(&|a| a[0] * points)
                    }),
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
    /// The law's shape: `H` spread, `c1`, `c2`, the order of the correction.
    pub shape: LawShape,
    /// The fall of `a_r / p~0` at low load on every grid.
    pub fall: Vec<KappaFall>,
    /// The exponent of the solver's iterations against the system size, where the scene
    /// plans the scaling study ([`super::scaling`]).
    pub iteration_exponent: Option<Estimate>,
    /// The relative change of `d(mean gap) / d ln p~0` between the halves of the low
    /// loads, at each Hurst exponent of the scene's gap study ([`super::gap`]).
    pub gap_slope_changes: Vec<(f64, Estimate)>,
    /// The change of `kappa(p~0)` on the larger system, at each Hurst exponent of the
    /// scene's system-size study ([`super::system_size`]).
    pub size_changes: Vec<(f64, Estimate)>,
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
        let extrapolated: Vec<Vec<Vec<f64>>> = scene
            .seeds
            .iter()
            .map(|&s| {
                scene
                    .hursts
                    .iter()
                    .map(|&h| curves.extrapolated(h, s))
                    .collect()
            })
            .collect();
        let shape = LawShape::of(p, &extrapolated, &hursts, kappa, scene.law_range);
        let fall = KappaFall::of(scene, &curves);
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
            shape,
            fall,
            iteration_exponent: None,
            gap_slope_changes: Vec::new(),
            size_changes: Vec::new(),
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

    /// `curves[seed][hurst][load]` for the shipped reduced scene's pressures: `a_r =
    /// kappa_H p~0 (1 - b p~0^2)` (a third-order correction), realization `s` shifted by
    /// `shift[s]` in `kappa`.
    fn synthetic(p: &[f64], kappa: &[f64], shift: &[f64]) -> Vec<Vec<Vec<f64>>> {
        shift
            .iter()
            .map(|d| {
                kappa
                    .iter()
                    .map(|k| {
                        p.iter()
                            .map(|&p| (k + d) * p * (1.0 - 0.5 * p * p))
                            .collect()
                    })
                    .collect()
            })
            .collect()
    }

    fn means(p: &[f64], hursts: &[f64], curves: &[Vec<Vec<f64>>]) -> Vec<HurstStats> {
        hursts
            .iter()
            .enumerate()
            .map(|(h, &hurst)| HurstStats {
                hurst,
                kappa: Estimate::new(f64::NAN, f64::NAN),
                areas: (0..p.len())
                    .map(|k| Estimate::mean_of(&curves.iter().map(|c| c[h][k]).collect::<Vec<_>>()))
                    .collect(),
            })
            .collect()
    }

    #[test]
    fn the_correction_exponent_is_two_for_a_third_order_correction() {
        let p = [0.001, 0.03, 0.06, 0.12, 0.25];
        let curves = synthetic(&p, &[2.0, 2.1], &[-0.01, 0.0, 0.02]);
        let hursts = means(&p, &[0.3, 0.8], &curves);
        let shape = LawShape::of(&p, &curves, &hursts, Estimate::new(2.2, 0.02), (0.0, 1.0));
        // kappa(0) - kappa(p) = kappa b p^2 whatever the shift: m = 2 in every subset.
        assert!((shape.correction.value - 2.0).abs() < 1e-9, "{shape:?}");
        assert!(shape.correction.std_error < 1e-9);
        assert!(
            (correction_exponent([2.0 - 0.03, 2.0 - 0.06, 2.0 - 0.12], 2.0) - 1.0).abs() < 1e-12
        );
        assert_eq!(shape.c1, Estimate::new(1.1, 0.01));
    }

    #[test]
    fn the_hurst_spread_is_the_widest_gap_in_kappa_at_one_load_in_range() {
        let p = [0.01, 0.1];
        let h = |hurst, a: [f64; 2], e: [f64; 2]| HurstStats {
            hurst,
            kappa: Estimate::new(f64::NAN, f64::NAN),
            areas: vec![Estimate::new(a[0], e[0]), Estimate::new(a[1], e[1])],
        };
        let hursts = [
            h(0.3, [0.005, 0.23], [0.0001, 0.003]),
            h(0.5, [0.021, 0.21], [0.0001, 0.002]),
            h(0.8, [0.020, 0.20], [0.0001, 0.004]),
        ];
        // The first load is out of range for H = 0.3 (a_r < 0.01).
        let spread = HurstSpread::over(&p, &hursts, (0.01, 0.9));
        assert!((spread.spread.value - 0.3).abs() < 1e-12, "{spread:?}");
        assert!((spread.spread.std_error - 0.05).abs() < 1e-12);
        assert_eq!(spread.at, (0.1, 0.3, 0.8));
        let none = HurstSpread::over(&p, &hursts, (0.5, 0.9));
        assert!(none.spread.value.is_nan() && none.at.0.is_nan());
    }

    #[test]
    fn c2_for_inverts_the_law_and_the_partial_slope_keeps_the_loads_in_range() {
        let law = ContactAreaLaw {
            c1: 1.075,
            c2: 1.04,
        };
        for p in [0.5, 0.8, 1.2] {
            let c2 = c2_for(1.075, p, law.contact_area(p));
            assert!((c2 - 1.04).abs() < 1e-9, "p~0 = {p}: {c2}");
        }
        assert!(c2_for(1.075, 1.2, 0.5).is_nan());
        // Two realizations, one Hurst exponent, a_r = kappa p~0 with kappa 2 and 2.2: of
        // the loads, 0.001 (a_r < 0.01) and 0.25 (a_r > 0.35) are left out.
        let p = [0.001, 0.03, 0.06, 1.2];
        let curves: Vec<Vec<Vec<f64>>> = [2.0, 2.2]
            .iter()
            .map(|k| {
                let mut a: Vec<f64> = p.iter().map(|p| k * p).collect();
                a[3] = law.contact_area(1.2);
                vec![a]
            })
            .collect();
        let hursts = means(&p, &[0.8], &curves);
        let shape = LawShape::of(&p, &curves, &hursts, Estimate::new(2.1, 0.1), (0.01, 0.9));
        assert!((shape.partial_kappa.value - 2.1).abs() < 1e-12, "{shape:?}");
        assert!((shape.partial_kappa.std_error - 0.1).abs() < 1e-12);
        assert!((shape.c2.value - 1.04).abs() < 1e-9);
        assert!(shape.c2.std_error.abs() < 1e-9);
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
