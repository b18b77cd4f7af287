//! The law's shape: how far `a_r` depends on `H` at equal `p~0`, the coefficients `c1`
//! and `c2` of eq. (contactArea), the exponent of the leading correction to
//! `a_r ~ kappa p~0` and the mean slope over partial contact.

use super::HurstStats;
use crate::persson::ContactAreaLaw;
use crate::stats::Estimate;

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
