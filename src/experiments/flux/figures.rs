//! The account and the figures of the one-step flux: the account of the headline steps,
//! the map of the first realization's step coloured as the paper's figure, and the flux
//! per step of the sensitivity study against the step.

use super::stats::StepStats;
use super::study::reading::{percent, step_rows, PaperFlux};
use super::study::sensitivity::SensitivityRow;
use super::{FluxResult, FluxScene};
use crate::experiments::contact_change::{step_palette, unpack_categories};
use crate::plot::{Axis, Figure, Point, Raster, Series, Style};
use crate::stats::Estimate;

/// The account, from the numbers.
pub fn account(scene: &FluxScene, s: &StepStats) -> String {
    format!(
        "{}, at the load that gives a_r = {:.3} at zeta = {}, the step to zeta = {} moves \
         {:.3}% of the nominal area into contact and {:.3}% out of it: {} points enter per \
         point that leaves, where Persson's absorbing boundary allows none. The net flux is \
         {} of the mean one-way flux; a_r goes from {:.4} to {:.4}.",
        scene.base().over(),
        s.a_before.value,
        scene.zeta,
        scene.zeta + scene.dzeta,
        100.0 * s.flux_in.value,
        100.0 * s.flux_out.value,
        s.ratio.text(1.0, 3, ""),
        s.net.text(1.0, 3, ""),
        s.a_before.value,
        s.a_after.value,
    )
}

/// The map of the first realization's step, coloured as the paper's figure.
pub fn flux_map(scene: &FluxScene, results: &[(u64, FluxResult)]) -> Option<Raster> {
    let (seed, r) = results.iter().find(|(_, r)| r.map.is_some())?;
    Some(Raster {
        name: "flux_map".into(),
        title: format!(
            "Contact changes from zeta = {} to {} (seed {seed}, a_r = {:.3})",
            scene.zeta,
            scene.zeta + scene.dzeta,
            r.a_r_old
        ),
        n: scene.n,
        pixels: unpack_categories(r.map.as_deref().unwrap_or(""), scene.n * scene.n),
        palette: step_palette(),
    })
}

/// Flux per step against the height variance the step adds (relative to the variance at
/// `zeta`), log-log: the step rows in both directions, the headline step where a step row
/// is the same step (`headline`: that row's index with the headline's fluxes), and the
/// paper's numbers at the variance of the stated step.
pub fn figure(
    rows: &[SensitivityRow],
    p: &PaperFlux,
    headline: Option<(usize, Estimate, Estimate)>,
) -> Figure {
    let steps = step_rows(rows);
    let with = |f: fn(&SensitivityRow) -> Estimate| {
        steps
            .iter()
            .map(|(r, v)| (*v, f(r).value, f(r).std_error))
            .collect::<Vec<_>>()
    };
    let n = steps.first().map_or(0, |(r, _)| r.config.n);
    let mut series = vec![
        Series::with_errors(
            format!("into contact ({n}x{n} study)"),
            Style::LinePoints,
            with(|r| r.flux_in),
        ),
        Series::with_errors(
            format!("out of contact ({n}x{n} study)"),
            Style::LinePoints,
            with(|r| r.flux_out),
        ),
    ];
    let variance_of = |i: usize| rows.get(i).and_then(|r| r.variance_added).map(|v| v.value);
    if let Some((x, fin, fout)) = headline.and_then(|(i, a, b)| Some((variance_of(i)?, a, b))) {
        series.push(Series {
            label: "headline step, into / out of contact".into(),
            style: Style::Points,
            side: Default::default(),
            points: [fin, fout]
                .iter()
                .map(|e| Point {
                    x,
                    y: e.value,
                    err: Some(e.std_error),
                })
                .collect(),
        });
    }
    let stated = steps.iter().find(|(r, _)| p.is_stated_step(r));
    if let Some((_, v)) = stated {
        series.push(Series::xy(
            format!(
                "paper: {} in, {} out, at the stated step",
                percent(p.flux_in),
                percent(p.flux_out)
            ),
            Style::Points,
            [(*v, p.flux_in), (*v, p.flux_out)],
        ));
    }
    let a_r = steps
        .first()
        .map_or(f64::NAN, |(r, _)| r.config.contact_area);
    Figure {
        name: "flux_vs_step".into(),
        title: format!("Flux per step against the height variance the step adds (a_r = {a_r})"),
        x: Axis::log("added height variance / variance at zeta"),
        y: Axis::log("flux per step (fraction of the nominal area)"),
        y2: None,
        series,
    }
}
