//! The re-entry share against the range of magnification (paper, tex 774-779: "when
//! taking into account a larger range of magnifications more points are bound to
//! experience re-entry"): the headline's share at `zeta_max` minus the share of the
//! tolerance study's histories over a smaller range at the same `eps_c` and tolerance
//! (a range extended at its upper end: finer roughness, the same `lambda_l / L`).
//!
//! The same grids serve a variant of other `lambda_l / L` (tex 790-794: "the numbers do
//! not depend much on lambda_l / L either"): a variant with a grid's cutoffs `lambda_l`,
//! `lambda_s` and tolerance, on another number of points, is set against that grid's
//! shares ([`same_cutoffs`]).

use super::stats::ReentryStats;
use super::tolerance::ToleranceGrid;
use super::variants::Variant;
use super::{ReentryJob, ReentryOutput, ReentryScene, RunStats};
use crate::experiments::declared::DetailTable;
use crate::experiments::keys::{DetailKey, Tag};
use crate::stats::Estimate;

/// The share over the headline's range against a smaller one at the same `eps_c`.
pub struct RangeGain {
    /// The load.
    pub load: f64,
    /// `zeta_max` of the smaller range.
    pub zeta_max: f64,
    /// Headline share minus the smaller range's.
    pub gain: Estimate,
}

/// The key of the gain at load `load`.
pub fn gain_key(load: f64) -> DetailKey {
    DetailKey::new("range_gain").at(Tag::ContactArea, load)
}

/// The tolerance study's grid of a smaller range at the headline's `lambda_s` and
/// tolerance, if the scene plans one.
pub fn smaller_range(scene: &ReentryScene) -> Option<&ToleranceGrid> {
    let plan = scene.tolerance.as_ref()?;
    let zeta_max = scene.base().zeta_max();
    plan.grids.iter().find(|g| {
        g.lambda_s == scene.lambda_s
            && g.lambda_l / g.lambda_s < zeta_max
            && plan.tols.contains(&scene.tol)
    })
}

/// Declares the gain at every headline load where the tolerance study has a grid of a
/// smaller range ([`smaller_range`]); a load whose grid has no history has none.
pub fn declare(t: &mut DetailTable<'_, RunStats>, scene: &ReentryScene) {
    let Some(grid) = smaller_range(scene) else {
        return;
    };
    let (zeta_max, smaller) = (scene.base().zeta_max(), grid.lambda_l / grid.lambda_s);
    for &a in &scene.contact_areas {
        t.row(
            gain_key(a),
            format!(
                "re-entry share at a_r = {a} over zeta 1 -> {zeta_max} minus over 1 -> \
                 {smaller} (same eps_c, independent realizations)"
            ),
            move |s: &RunStats| s.range_gain.iter().find(|g| g.load == a).map(|g| g.gain),
        );
    }
}

/// The share gains over the headline's range against the tolerance study's grids of a
/// smaller range at the headline's `lambda_s` and tolerance.
pub fn range_gains(
    scene: &ReentryScene,
    results: &[(ReentryJob, ReentryOutput)],
    stats: &ReentryStats,
) -> Vec<RangeGain> {
    let Some(grid) = smaller_range(scene) else {
        return Vec::new();
    };
    stats
        .shares
        .iter()
        .filter_map(|share| {
            let smaller = grid_share(grid, share.load, scene.tol, results)?;
            Some(RangeGain {
                load: share.load,
                zeta_max: grid.lambda_l / grid.lambda_s,
                gain: Estimate::difference(share.share, smaller),
            })
        })
        .collect()
}

/// The tolerance study's grid with `variant`'s cutoffs, Hurst exponent and tolerance on
/// another number of points, if the scene plans one: the system-size reference of the
/// variant.
pub fn same_cutoffs_grid<'a>(
    scene: &'a ReentryScene,
    variant: &Variant,
) -> Option<&'a ToleranceGrid> {
    let plan = scene.tolerance.as_ref()?;
    if variant.hurst != scene.hurst || variant.zeta_from != 0.0 || !plan.tols.contains(&variant.tol)
    {
        return None;
    }
    plan.grids.iter().find(|g| {
        (g.lambda_l, g.lambda_s) == (variant.lambda_l, variant.lambda_s) && g.n != variant.n
    })
}

/// The shares of the reference grid ([`same_cutoffs_grid`]) at each load of `variant`
/// that it holds: `(n of the grid, [(load, share)])`, means over its realizations.
pub fn same_cutoffs(
    scene: &ReentryScene,
    variant: &Variant,
    results: &[(ReentryJob, ReentryOutput)],
) -> Option<(usize, Vec<(f64, Estimate)>)> {
    let grid = same_cutoffs_grid(scene, variant)?;
    let shares = variant
        .contact_areas
        .iter()
        .filter_map(|&load| Some((load, grid_share(grid, load, variant.tol, results)?)))
        .collect();
    Some((grid.n, shares))
}

/// The mean share of `grid`'s histories at `load` and `tol` over the realizations that
/// have a result (`None` without one).
fn grid_share(
    grid: &ToleranceGrid,
    load: f64,
    tol: f64,
    results: &[(ReentryJob, ReentryOutput)],
) -> Option<Estimate> {
    let samples: Vec<f64> = grid
        .seeds
        .iter()
        .filter_map(|&seed| {
            let job = grid.job(seed, load, tol);
            results.iter().find_map(|(j, r)| match (j, r) {
                (ReentryJob::Tolerance(j), ReentryOutput::Tolerance(r)) if *j == job => {
                    Some(r.share())
                }
                _ => None,
            })
        })
        .collect();
    (!samples.is_empty()).then(|| Estimate::mean_of(&samples))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::reentry::Reentry;

    #[test]
    fn a_variant_finds_the_grid_of_its_cutoffs_on_another_size_only() {
        let (_, full) = crate::experiments::shipped_valid::<Reentry>("c_reentry");
        let quarter = full.variants.iter().find(|v| v.name == "quarter").unwrap();
        let grid = same_cutoffs_grid(&full, quarter).expect("the 512^2 grid");
        assert_eq!((grid.n, grid.lambda_l, grid.lambda_s), (512, 256.0, 8.0));
        // Another tolerance, Hurst exponent or a later start has no reference; nor has a
        // variant on the grid's own size.
        for v in [
            Variant {
                tol: 1e-3,
                ..quarter.clone()
            },
            Variant {
                hurst: 0.3,
                ..quarter.clone()
            },
            Variant {
                zeta_from: 2.0,
                ..quarter.clone()
            },
            Variant {
                n: 512,
                ..quarter.clone()
            },
        ] {
            assert!(same_cutoffs_grid(&full, &v).is_none(), "{v:?}");
        }
        // The headline's other variants have none either.
        for v in full.variants.iter().filter(|v| v.name != "quarter") {
            assert!(same_cutoffs_grid(&full, v).is_none(), "{}", v.name);
        }
    }
}
