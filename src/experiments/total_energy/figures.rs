//! The account, tables and figures of the total-energy experiment: the paper's figures of
//! the integrated normalised energy against magnification and against contact area, and of
//! the incremental correction factor `S~`.

use super::stats::{
    corrected_area, measured_area, original_area, ratio, s_tilde, Headline, Load, Theory,
};
use super::{EnergyScene, FAILS_BELOW};
use crate::experiments::{figure, Criteria, Table};
use crate::persson::Correction;
use crate::plot::{Axis, Figure, Series, Style};
use crate::stats::{realizations, round_sig};

/// Every ensemble ratio at every step of every load.
pub fn curve_table(name: &str, loads: &[Load], zetas: &[f64]) -> Table {
    let mut table = Table::new(
        name,
        &[
            "contact_area_full",
            "zeta",
            "contact_area",
            "e_exa_over_e_p",
            "e_exa_over_e_p_std_error",
            "e_exa_over_e_c",
            "e_exa_over_e_c_std_error",
            "persson_area",
            "corrected_area",
        ],
    );
    for load in loads {
        for (k, &z) in zetas.iter().enumerate() {
            let o = ratio(load, k, Theory::Original);
            let q = ratio(load, k, Theory::Corrected);
            table.push(vec![
                load.contact_area,
                z,
                measured_area(load, k).value,
                o.value,
                o.std_error,
                q.value,
                q.std_error,
                original_area(load, k).value,
                corrected_area(load, k).value,
            ]);
        }
    }
    table
}

/// `S~` of every single-shell increment of every window, beside `S(a_r)` of eq. (gamma).
pub fn s_tilde_table(
    loads: &[Load],
    zetas: &[f64],
    windows: &[Vec<usize>],
    correction: Correction,
) -> Table {
    let mut table = Table::new(
        "s_tilde",
        &[
            "contact_area_full",
            "zeta",
            "s_tilde",
            "std_error",
            "persson_s",
            "contact_area",
        ],
    );
    for load in loads {
        for window in windows {
            for pair in window.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                let s = s_tilde(load, a, b);
                table.push(vec![
                    load.contact_area,
                    zetas[b],
                    s.value,
                    s.std_error,
                    correction.factor(original_area(load, b).value),
                    measured_area(load, b).value,
                ]);
            }
        }
    }
    table
}

/// The normalised energy against magnification, against the measured contact area at
/// the end of the sweep, and the incremental correction factor.
pub fn figures(
    hurst: f64,
    loads: &[Load],
    zetas: &[f64],
    windows: &[Vec<usize>],
    correction: Correction,
) -> Vec<Figure> {
    vec![
        energy_vs_zeta(hurst, loads, zetas),
        energy_vs_area(hurst, loads, zetas),
        s_tilde_figure(hurst, loads, zetas, windows, correction),
    ]
}

/// The line of exact agreement, `E_exa / E = 1`, across `[min(zeta_0, 1e-3), max(zeta_end,
/// 1)]` (wide enough for both axes: magnification and contact area).
fn exact_agreement(zetas: &[f64]) -> Series {
    let lo = zetas[0].min(1e-3);
    let hi = zetas[zetas.len() - 1].max(1.0);
    Series::xy("exact agreement", Style::Line, [(lo, 1.0), (hi, 1.0)])
}

/// A figure of `y` against magnification (log axis).
fn against_zeta(name: &str, title: String, y: &str) -> Figure {
    figure(
        name,
        title,
        Axis::log("magnification zeta"),
        Axis::linear(y),
    )
}

/// `E_exa / E` of both theories against magnification, every load.
fn energy_vs_zeta(hurst: f64, loads: &[Load], zetas: &[f64]) -> Figure {
    let title = format!("Integrated normalised elastic energy against magnification, H = {hurst}");
    let mut fig = against_zeta("energy_vs_zeta", title, "E_exa / E_P");
    for load in loads {
        for (theory, label, style) in [
            (
                Theory::Original,
                format!("S = 1, a_r = {} at full resolution", load.contact_area),
                Style::Line,
            ),
            (
                Theory::Corrected,
                format!("S of eq. (gamma), a_r = {}", load.contact_area),
                Style::Dashed,
            ),
        ] {
            fig.series.push(Series::with_errors(
                label,
                style,
                zetas.iter().enumerate().map(|(k, &z)| {
                    let e = ratio(load, k, theory);
                    (z, e.value, e.std_error)
                }),
            ));
        }
    }
    fig.series.push(exact_agreement(zetas));
    fig
}

/// `E_exa / E` of both theories at full resolution against the measured contact area.
fn energy_vs_area(hurst: f64, loads: &[Load], zetas: &[f64]) -> Figure {
    let end = zetas.len() - 1;
    let mut fig = figure(
        "energy_vs_area",
        format!(
            "Integrated normalised elastic energy against contact area at zeta = {}, H = {}",
            round_sig(zetas[end], 4),
            hurst
        ),
        Axis::log("relative contact area a_r"),
        Axis::linear("E_exa / E_P"),
    );
    for (theory, label) in [
        (Theory::Original, "S = 1"),
        (Theory::Corrected, "S of eq. (gamma)"),
    ] {
        let points = loads.iter().map(|load| {
            let a = measured_area(load, end);
            let e = ratio(load, end, theory);
            (a.value, e.value, e.std_error)
        });
        fig.series
            .push(Series::with_errors(label, Style::LinePoints, points));
    }
    fig.series.push(exact_agreement(zetas));
    fig
}

/// `S~` of every single-shell increment beside `S(a_r)` of eq. (gamma), every load.
fn s_tilde_figure(
    hurst: f64,
    loads: &[Load],
    zetas: &[f64],
    windows: &[Vec<usize>],
    correction: Correction,
) -> Figure {
    let title = format!("Incremental correction factor S~ (eq. S_q_numerical), H = {hurst}");
    let mut fig = against_zeta("s_tilde", title, "S~");
    for load in loads {
        let mut pts = Vec::new();
        let mut theory = Vec::new();
        for window in windows {
            for pair in window.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                let s = s_tilde(load, a, b);
                pts.push((zetas[b], s.value, s.std_error));
                theory.push((zetas[b], correction.factor(original_area(load, b).value)));
            }
        }
        fig.series.push(Series::with_errors(
            format!("S~, a_r = {} at full resolution", load.contact_area),
            Style::Points,
            pts,
        ));
        fig.series.push(Series::xy(
            format!("S(a_r) of eq. (gamma), a_r = {}", load.contact_area),
            Style::Dashed,
            theory,
        ));
    }
    fig
}

/// The account, from the numbers.
pub fn account(scene: &EnergyScene, zetas: &[f64], h: &Headline, criteria: &Criteria) -> String {
    let (head, low) = (&h.head, &h.low);
    let below = criteria.paper(FAILS_BELOW);
    let low_text = if below.is_some_and(|b| low.area.value < b) {
        format!(
            " At the lowest load (a_r = {:.4}, {}) E_exa / E_c = {}.",
            low.area.value,
            realizations(h.low_runs),
            low.corrected.text(1.0, 3, "")
        )
    } else {
        String::new()
    };
    format!(
        "{}, at the load that gives a_r = {:.3} at full resolution (zeta = {}), the \
         measured total elastic energy is {} of the corrected theory's E_c (eq. gamma) and \
         {} of the original theory's E_P: the corrected theory's energy exceeds the \
         measurement by {:+.1}% ({}), the original theory's by {:+.0}%.{} Each theory uses \
         its own a_r(p0, zeta).",
        scene.base().over(),
        head.area.value,
        round_sig(zetas[zetas.len() - 1], 4),
        head.corrected.text(1.0, 3, ""),
        head.original.text(1.0, 3, ""),
        100.0 * (1.0 / head.corrected.value - 1.0),
        head.corrected.z_text(1.0, "Persson's 1"),
        100.0 * (1.0 / head.original.value - 1.0),
        low_text,
    )
}
