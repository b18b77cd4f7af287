//! The table and figures of the contact-area law: `a_r` and `a_r / p~0` against the
//! reduced pressure, every Hurst exponent beside Persson's theory and eq. (contactArea).

use super::stats::{log_grid, AreaStats};
use crate::experiments::{figure, Table};
use crate::persson::{persson_contact_area, ContactAreaLaw};
use crate::plot::{Axis, Figure, Series, Style};

/// Points of the theory curves.
const CURVE_POINTS: usize = 60;

/// A law `a_r(p~0)`: its label in the figure of `a_r` and in that of `a_r / p~0`, its
/// style, and the function.
type Law = (&'static str, &'static str, Style, fn(f64) -> f64);

/// `a_r` at every Hurst exponent and pressure, beside both laws.
pub fn area_table(name: &str, pressures: &[f64], s: &AreaStats) -> Table {
    let mut table = Table::new(
        name,
        &[
            "hurst",
            "reduced_pressure",
            "contact_area",
            "std_error",
            "persson",
            "paper_law",
        ],
    );
    for h in &s.hursts {
        for (&p, a) in pressures.iter().zip(&h.areas) {
            table.push(vec![
                h.hurst,
                p,
                a.value,
                a.std_error,
                persson_contact_area(p),
                ContactAreaLaw::PAPER.contact_area(p),
            ]);
        }
    }
    table
}

/// `a_r` against `p~0`, and `a_r / p~0` against `p~0` (`label`: how the grid was
/// treated).
pub fn area_figures(pressures: &[f64], s: &AreaStats, label: &str) -> Vec<Figure> {
    let x = || Axis::log("reduced pressure p0 / (E* g)");
    let mut area = figure(
        "contact_area",
        format!("Relative contact area against reduced pressure ({label})"),
        x(),
        Axis::log("relative contact area a_r"),
    );
    let mut kappa = figure(
        "kappa",
        format!("a_r / p~0 against reduced pressure ({label})"),
        x(),
        Axis::linear("a_r / p~0"),
    );
    for h in &s.hursts {
        // a_r, or a_r / p~0.
        let points = |per_p: bool| {
            pressures
                .iter()
                .zip(&h.areas)
                .map(|(&p, a)| {
                    let d = if per_p { p } else { 1.0 };
                    (p, a.value / d, a.std_error / d)
                })
                .collect::<Vec<_>>()
        };
        area.series.push(Series::with_errors(
            format!("simulation, H = {}", h.hurst),
            Style::Points,
            points(false),
        ));
        kappa.series.push(Series::with_errors(
            format!("H = {}", h.hurst),
            Style::LinePoints,
            points(true),
        ));
    }
    let grid = log_grid(pressures[0], pressures[pressures.len() - 1], CURVE_POINTS);
    let laws: [Law; 2] = [
        (
            "Persson, erf(sqrt2 p~0)",
            "Persson, sqrt(8/pi)",
            Style::Line,
            persson_contact_area,
        ),
        (
            "paper, eq. (contactArea)",
            "paper, eq. (contactArea)",
            Style::Dashed,
            |p| ContactAreaLaw::PAPER.contact_area(p),
        ),
    ];
    for (area_label, kappa_label, style, law) in laws {
        area.series.push(Series::xy(
            area_label,
            style,
            grid.iter().map(|&p| (p, law(p))),
        ));
        kappa.series.push(Series::xy(
            kappa_label,
            style,
            grid.iter().map(|&p| (p, law(p) / p)),
        ));
    }
    vec![area, kappa]
}
