//! The table and maps of the re-entry experiment: one row per history, and the contact
//! map at `zeta_max` and of the flux interval, coloured as the paper's figures.

use super::{ReentryResult, ReentryScene};
use crate::experiments::contact_change::{step_palette, unpack_categories};
use crate::experiments::ensemble::{LoadGroup, SeedLoad};
use crate::experiments::Table;
use crate::plot::Raster;

/// The colours of a map of histories, as the paper's re-entry figures: grey in contact
/// throughout, red re-entered contact, white out of contact and never back, blue out of
/// contact after having come back.
pub fn history_palette() -> Vec<([u8; 3], String)> {
    vec![
        ([150, 150, 150], "in contact throughout".into()),
        ([220, 40, 40], "in contact, re-entered".into()),
        ([255, 255, 255], "out of contact, never back".into()),
        ([40, 80, 220], "out of contact after re-entering".into()),
    ]
}

/// One row per history.
pub fn table(name: &str, scene: &ReentryScene, results: &[(SeedLoad, ReentryResult)]) -> Table {
    let mut table = Table::new(
        name,
        &[
            "contact_area_target",
            "seed",
            "a_r",
            "share",
            "share_after_first",
            "flux_in",
            "flux_out",
            // The column of `flux_in_of_noncontact`: the stored name is kept for the
            // committed results.
            "zero_bin_reentry",
            "shells",
            "iterations",
            "wall_s",
        ],
    );
    for &target in &scene.contact_areas {
        for (j, r) in results.iter().filter(|(j, _)| j.contact_area == target) {
            table.push(vec![
                target,
                j.seed as f64,
                r.a_r,
                r.share(),
                r.share_after_first(),
                r.flux_in,
                r.flux_out,
                r.flux_in_of_noncontact,
                r.shells as f64,
                r.iterations as f64,
                r.wall_s,
            ]);
        }
    }
    table
}

/// The contact map at `zeta_max` and the map of the flux interval, coloured as the
/// paper's figures, for the first seed at the headline load.
pub fn maps(scene: &ReentryScene, head: &LoadGroup<ReentryResult>) -> Vec<Raster> {
    let Some(r) = head.runs.iter().find(|r| r.map.is_some()) else {
        return Vec::new();
    };
    let n2 = scene.n * scene.n;
    let seed = scene.seeds[0];
    vec![
        Raster {
            name: "reentry_map".into(),
            title: format!(
                "Contact at zeta_max, a_r = {:.3} (seed {seed}): history of every point",
                r.a_r
            ),
            n: scene.n,
            pixels: unpack_categories(r.map.as_deref().unwrap_or(""), n2),
            palette: history_palette(),
        },
        Raster {
            name: "flux_map".into(),
            title: format!(
                "Changes between zeta = {} and {} (seed {seed})",
                scene.flux_zeta,
                scene.flux_zeta + scene.flux_dzeta,
            ),
            n: scene.n,
            pixels: unpack_categories(r.flux_map.as_deref().unwrap_or(""), n2),
            palette: step_palette(),
        },
    ]
}
