//! The figures of a surface's check page: the radially averaged power spectrum, the
//! contact-area and elastic-energy curves against the load and the pressure distribution
//! at the middle load, each simulation beside Persson's original and corrected
//! predictions. A series keeps its colour in every figure: the headline simulation first,
//! then Persson's original and corrected theory, then the cross-check.

use super::check::{CurvePoint, SurfaceCheck};
use super::units::{eng, metres};
use crate::plot::{Axis, Figure, Series, Style};

/// A load curve's series, in the order that keeps every series' colour across figures:
/// the headline solver's points with their error bars over scans, Persson's two
/// predictions, and the cross-check as a line through its loads where there is one;
/// `pick` reads a point's [value, error, cross-check, Persson, corrected].
fn curve_series(
    c: &SurfaceCheck,
    pick: fn(&CurvePoint) -> [Option<f64>; 5],
    factor: f64,
) -> Vec<Series> {
    let line = |k: usize| -> Vec<(f64, f64)> {
        c.curve
            .iter()
            .filter_map(|p| Some((p.p0, factor * pick(p)[k]?)))
            .collect()
    };
    let mut series = vec![
        Series::with_errors(
            format!("simulation ({})", c.solver.name()),
            Style::Points,
            c.curve.iter().map(|p| {
                let v = pick(p);
                (
                    p.p0,
                    factor * v[0].unwrap_or(f64::NAN),
                    factor * v[1].unwrap_or(f64::NAN),
                )
            }),
        ),
        Series::xy("Persson", Style::Line, line(3)),
        Series::xy("Persson, corrected", Style::Dashed, line(4)),
    ];
    let cross = line(2);
    if let (Some(k), false) = (c.cross_check, cross.is_empty()) {
        series.push(Series::xy(
            format!("cross-check ({})", k.name()),
            Style::Line,
            cross,
        ));
    }
    series
}

/// The page's figures.
pub fn figures(c: &SurfaceCheck) -> Vec<Figure> {
    let u = unit(c);
    let (energy_unit, energy_factor) = energy_unit(c);
    let mut figures = vec![
        Figure {
            name: "psd".into(),
            title: "Radially averaged power spectrum".into(),
            x: Axis::log(format!("q (1/{u})")),
            y: Axis::log(format!("C(q) ({u}^4)")),
            y2: None,
            series: vec![Series::xy(
                "C(q)",
                Style::LinePoints,
                c.statistics.psd.iter().map(|b| (b.q, b.c)),
            )],
        },
        Figure {
            name: "contact_area".into(),
            title: "Relative contact area against the load".into(),
            x: Axis::log("p0 / E*"),
            y: Axis::log("a_r"),
            y2: None,
            series: curve_series(c, area_of, 1.0),
        },
        Figure {
            name: "elastic_energy".into(),
            title: "Elastic energy per unit area against the load".into(),
            x: Axis::log("p0 / E*"),
            y: Axis::log(format!("E_el ({energy_unit})")),
            y2: None,
            series: curve_series(c, energy_of, energy_factor),
        },
    ];
    if let Some(d) = &c.pressure_distribution {
        let col = |k: usize| -> Vec<(f64, f64)> { d.bins.iter().map(|b| (b[0], b[k])).collect() };
        figures.push(Figure {
            name: "pressure_distribution".into(),
            title: format!("Pressure distribution at p0 = {} E*", eng(d.p0)),
            x: Axis::linear("p / p0"),
            y: Axis::linear("Pr(p / p0)"),
            y2: None,
            series: vec![
                Series::xy(
                    format!("simulation ({})", c.solver.name()),
                    Style::LinePoints,
                    col(1),
                ),
                Series::xy("Persson", Style::Line, col(2)),
                Series::xy("Persson, corrected", Style::Dashed, col(3)),
            ],
        });
    }
    figures
}

/// The unit of lengths, for text: `nm`, or `length unit`.
pub(super) fn unit(c: &SurfaceCheck) -> &str {
    c.unit.as_deref().unwrap_or("length unit")
}

/// The contact area's [value, error, cross-check, Persson, corrected].
pub(super) fn area_of(p: &CurvePoint) -> [Option<f64>; 5] {
    [
        Some(p.a_r),
        p.a_r_std_error,
        p.a_r_cross_check,
        Some(p.a_r_persson),
        Some(p.a_r_persson_corrected),
    ]
}

/// The elastic energy's [value, error, cross-check, Persson, corrected].
pub(super) fn energy_of(p: &CurvePoint) -> [Option<f64>; 5] {
    [
        Some(p.energy),
        p.energy_std_error,
        p.energy_cross_check,
        Some(p.energy_persson),
        Some(p.energy_persson_corrected),
    ]
}

/// The energy's unit and the factor to it: J/m^2 with a modulus and a known unit, else
/// `E*` (or `Pa`) times the length unit.
pub(super) fn energy_unit(c: &SurfaceCheck) -> (String, f64) {
    let u = unit(c);
    match (c.modulus, c.unit.as_deref().and_then(metres)) {
        (Some(e), Some(m)) => ("J/m^2".to_string(), e * m),
        (Some(e), None) => (format!("Pa {u}"), e),
        (None, _) => (format!("E* {u}"), 1.0),
    }
}
