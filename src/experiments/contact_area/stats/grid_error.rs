//! The grid's error: `a_r` on three grids at the finer grid's loads (the order of the
//! grid error the extrapolation assumes), and the fall of `a_r / p~0` at low load on each
//! grid (whether the grid or the size of the contact spots could explain it).

use super::{richardson, Curves, CORRECTION_LOADS};
use crate::experiments::contact_area::AreaScene;
use crate::stats::Estimate;

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
