//! The tables and figures of the single-mode validations: `E_norm` of every band against
//! magnification beside Persson's `S Theta(zeta - zeta_t)` (the paper's figures 11 and
//! 12), and, for (e), the asymptotes against `x = -d ln a_r / d ln zeta` with the paper's
//! law.

use super::stats::FrozenStats;
use super::stats::{Load, ModeEnsemble};
use super::ModeScene;
use crate::experiments::climb::step_of;
use crate::experiments::{figure, Table};
use crate::plot::{Axis, Figure, Series, Style};

/// Points of the curves of the asymptote law.
const LAW_POINTS: usize = 40;

/// The table of every ensemble `E_norm` (all loads, targets and steps).
pub fn curve_table(name: &str, scene: &ModeScene, loads: &[Load]) -> Table {
    let steps = scene.steps();
    let mut table = Table::new(
        name,
        &[
            "contact_area_full",
            "zeta_t",
            "zeta",
            "e_norm",
            "std_error",
            "persson_original",
            "persson_corrected",
            "contact_area",
        ],
    );
    for load in loads {
        for (t, &zt) in scene.targets.iter().enumerate() {
            let s = scene
                .correction
                .factor(load.contact_area_at(step_of(&steps, zt)).value);
            for (k, &z) in steps.iter().enumerate() {
                let e = load.e_norm(t, zt, k);
                let theta = if z >= zt { 1.0 } else { 0.0 };
                table.push(vec![
                    load.contact_area,
                    zt,
                    z,
                    e.value,
                    e.std_error,
                    theta,
                    s * theta,
                    load.contact_area_at(k).value,
                ]);
            }
        }
    }
    table
}

/// One figure per load: `E_norm` of every target against `zeta`, Persson's `S Theta` beside
/// it, and the measured contact area on the right axis (the paper's figures 11 and 12).
pub fn curve_figures(prefix: &str, scene: &ModeScene, loads: &[Load]) -> Vec<Figure> {
    let steps = scene.steps();
    let mut figures = Vec::new();
    for load in loads {
        let mut fig = figure(
            &format!("{prefix}_ar{}", load.contact_area),
            format!(
                "Normalised mode energy, H = {}, a_r = {} at full resolution",
                scene.hurst, load.contact_area
            ),
            Axis::log("magnification zeta"),
            Axis::linear("E_norm = E_exa / E_P (band around q_t)"),
        );
        fig.y2 = Some(Axis::linear("relative contact area a_r"));
        for (t, &zt) in scene.targets.iter().enumerate() {
            fig.series.push(Series::with_errors(
                format!("simulation, zeta_t = {zt}"),
                Style::LinePoints,
                steps.iter().enumerate().map(|(k, &z)| {
                    let e = load.e_norm(t, zt, k);
                    (z, e.value, e.std_error)
                }),
            ));
            let s = scene
                .correction
                .factor(load.contact_area_at(step_of(&steps, zt)).value);
            let (z0, z1) = (steps[0], steps[steps.len() - 1]);
            fig.series.push(Series::xy(
                format!("Persson S Theta(zeta - {zt})"),
                Style::Dashed,
                [(z0, 0.0), (zt, 0.0), (zt, s), (z1, s)],
            ));
        }
        fig.series.push(
            Series::with_errors(
                "contact area",
                Style::Line,
                steps.iter().enumerate().map(|(k, &z)| {
                    let a = load.contact_area_at(k);
                    (z, a.value, a.std_error)
                }),
            )
            .on_right(),
        );
        figures.push(fig);
    }
    figures
}

/// The change, asymptote and `x` of every load and target.
pub fn asymptote_table(scene: &ModeScene, s: &FrozenStats) -> Table {
    let mut table = Table::new(
        "asymptotes",
        &[
            "contact_area_full",
            "zeta_t",
            "change",
            "change_std_error",
            "asymptote",
            "asymptote_std_error",
            "x",
            "x_std_error",
        ],
    );
    for a in &s.after {
        table.push(vec![
            a.load,
            scene.targets[a.target],
            a.change.value,
            a.change.std_error,
            a.asymptote.value,
            a.asymptote.std_error,
            a.x.value,
            a.x.std_error,
        ]);
    }
    table
}

/// The asymptotes of the partial-contact loads against `x`, the fitted law and the
/// paper's.
/// The asymptotes with the fitted law and, where the definition states it, the paper's
/// `(K1, K2)`.
pub fn asymptote_figure(scene: &ModeScene, s: &FrozenStats, paper: Option<(f64, f64)>) -> Figure {
    let mut fig = figure(
        "asymptote",
        format!(
            "Asymptote of E_norm against x = -dln a_r / dln zeta, H = {}",
            scene.hurst
        ),
        Axis::linear("x = -d ln a_r / d ln zeta"),
        Axis::linear("asymptotic E_norm"),
    );
    fig.series.push(Series::xy(
        "simulation (partial contact)",
        Style::Points,
        s.k_points.iter().map(|&(x, y)| (x, y.exp())),
    ));
    let x_hi = s.k_points.iter().map(|p| p.0).fold(0.5, f64::max) * 1.1;
    let grid: Vec<f64> = (0..=LAW_POINTS)
        .map(|i| x_hi * i as f64 / LAW_POINTS as f64)
        .collect();
    if let Some(f) = s.k_fit {
        fig.series.push(Series::xy(
            "fit K1 exp(-K2 x)",
            Style::Line,
            grid.iter().map(|&x| (x, f.at(x).exp())),
        ));
    }
    if let Some((k1, k2)) = paper {
        fig.series.push(Series::xy(
            format!("paper, {k1} exp(-{k2} x)"),
            Style::Dashed,
            grid.iter().map(|&x| (x, k1 * (-k2 * x).exp())),
        ));
    }
    fig
}
