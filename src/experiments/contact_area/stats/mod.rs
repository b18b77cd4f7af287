//! The statistics of the contact-area law, as pure functions of the realizations' curves
//! `a_r(p~0)`: the low-load slope and the Richardson extrapolation to the continuum here,
//! the largest deviation from eq. (contactArea) in [`deviation`], the law's shape (spread
//! over `H`, `c1`, `c2`, the order of the leading correction) in [`shape`], and the grid's
//! error (its order on three grids, the fall of `a_r / p~0` on each) in [`grid_error`].

pub mod deviation;
pub mod grid_error;
pub mod shape;

pub use self::deviation::{Denominator, LawDeviation};
pub use self::grid_error::{GridOrder, KappaFall};
pub use self::shape::{
    c2_for, correction_exponent, HurstSpread, LawShape, CORRECTION_LOADS, PARTIAL_RANGE,
};
use super::{AreaJob, AreaResult, AreaScene};
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
        let kappa = Estimate::mean_of(
            &pairs(scene)
                .map(|(h, s)| curves.kappa(&curves.extrapolated(h, s)))
                .collect::<Vec<_>>(),
        );
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
        let mut readings = grid_readings(scene, &curves, &hursts);
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
        readings.extend(deviation::finer_grid_readings(scene, &grid_order));
        Self {
            kappa,
            on_grid: on_grid(scene, &curves),
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

/// Every (Hurst exponent, seed) of the scene.
fn pairs(scene: &AreaScene) -> impl Iterator<Item = (f64, u64)> + '_ {
    scene
        .hursts
        .iter()
        .flat_map(|&h| scene.seeds.iter().map(move |&s| (h, s)))
}

/// The low-load slope on each grid over all Hurst exponents and realizations:
/// (refinement, slope).
fn on_grid(scene: &AreaScene, curves: &Curves) -> Vec<(usize, Estimate)> {
    scene
        .refinements
        .iter()
        .map(|&refine| {
            let per: Vec<f64> = pairs(scene)
                .map(|(h, s)| curves.kappa(curves.curve(h, s, refine)))
                .collect();
            (refine, Estimate::mean_of(&per))
        })
        .collect()
}

/// The law's deviation read relative to the law's `a_r` (extrapolated) and on each grid
/// alone: `(key, label, deviation)`.
fn grid_readings(
    scene: &AreaScene,
    curves: &Curves,
    hursts: &[HurstStats],
) -> Vec<(String, String, LawDeviation)> {
    let p = &scene.reduced_pressures;
    let mut readings = vec![(
        "extrapolated_over_law".to_string(),
        "extrapolated a_r, |a_r - law| / law".to_string(),
        LawDeviation::over(p, hursts, Denominator::Law, scene.law_range),
    )];
    for &refine in &scene.refinements {
        let on: Vec<HurstStats> = scene
            .hursts
            .iter()
            .map(|&h| hurst_stats_on(scene, curves, h, refine))
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
    readings
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
    use crate::persson::ContactAreaLaw;

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
