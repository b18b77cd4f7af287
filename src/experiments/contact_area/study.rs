//! The studies of the contact-area law: every reading of the law's largest deviation
//! (denominator, grid), the order of the grid error on three grids, and the fall of
//! `a_r / p~0` at low load on every grid.

use super::stats::{AreaStats, CORRECTION_LOADS};
use super::{grid_label, AreaScene, Run};
use crate::experiments::study::{Cell, Study};
use crate::experiments::Keys;

/// The studies' keys and columns, `(key, label)`.
const LAW_READINGS: &str = "law_readings";
const READINGS_COLUMNS: &[(&str, &str)] = &[
    ("deviation", "largest deviation, %"),
    ("hurst", "H"),
    ("reduced_pressure", "p~0"),
    ("contact_area", "a_r there"),
];
const GRID_ORDER: &str = "grid_order";
const ORDER_COLUMNS: &[(&str, &str)] = &[
    ("a_r_1", "a_r, coarse"),
    ("a_r_2", "a_r, middle"),
    ("a_r_3", "a_r, fine"),
    ("ratio", "(a1 - a2) / (a2 - a3)"),
    ("first_order", "first order"),
    ("extrapolated_coarse", "extrapolated, coarse pair"),
    ("extrapolated_fine", "extrapolated, fine pair"),
];
const KAPPA_FALL: &str = "kappa_fall";
const FALL_COLUMNS: &[(&str, &str)] = &[
    ("kappa_lowest", "a_r / p~0 at the lowest load"),
    ("kappa_at", "a_r / p~0 at the correction's first load"),
    ("fall", "fall, %"),
    ("contact_points", "contact points at the lowest load"),
    ("l_over_lambda_l", "L / lambda_l"),
];

/// Declares the studies a run of `scene` can have: the readings and the fall always, the
/// order of the grid error with a finer grid.
pub(super) fn keys(scene: &AreaScene, keys: &mut Keys) {
    keys.study(LAW_READINGS, READINGS_COLUMNS);
    if scene.finer_grid.is_some() {
        keys.study(GRID_ORDER, ORDER_COLUMNS);
    }
    keys.study(KAPPA_FALL, FALL_COLUMNS);
}

/// The readings of the law's deviation (denominator, grid) and the finer grid's
/// order of the grid error.
pub(super) fn studies(run: &Run, s: &AreaStats) -> Vec<Study> {
    let label = grid_label(run.scene);
    let mut readings = Study::new(
        LAW_READINGS,
        "Readings of the contact-area law's largest deviation",
        READINGS_COLUMNS,
    )
    .percent(&["deviation"])
    .about(
        "The paper says 'within O(10%)' and names no denominator or grid; every \
         defensible reading of the same runs, over the loads with a_r in the law's range",
    );
    let headline = (
        "extrapolated_over_a_r".to_string(),
        format!("{label}, |a_r - law| / a_r (the claim's reading)"),
        s.law,
    );
    for (key, row_label, d) in std::iter::once(&headline).chain(&s.readings) {
        readings.push(
            key.clone(),
            row_label.clone(),
            vec![
                d.estimate().into(),
                Cell::from(d.at.0),
                Cell::from(d.at.1),
                Cell::from(d.at.2),
            ],
        );
    }
    let mut studies = vec![readings];
    if let Some(g) = s.grid_order.first() {
        let n = |k: usize| run.scene.n * g.refinements[k];
        let mut order = Study::new(
            GRID_ORDER,
            format!(
                "The grid error on three grids ({}^2, {}^2, {}^2): is it first order in eps_c?",
                n(0),
                n(1),
                n(2)
            ),
            ORDER_COLUMNS,
        )
        .about(
            "The same realizations on three grids; the ratio of successive differences is \
             the first-order value for an error proportional to eps_c and twice as large per \
             order above it",
        );
        for g in &s.grid_order {
            order.push(
                format!("H{}_p{}", g.hurst, g.pressure),
                format!("H = {}, p~0 = {}", g.hurst, g.pressure),
                vec![
                    g.areas[0].into(),
                    g.areas[1].into(),
                    g.areas[2].into(),
                    g.ratio.into(),
                    Cell::from(g.first_order),
                    g.extrapolated[0].into(),
                    g.extrapolated[1].into(),
                ],
            );
        }
        studies.push(order);
    }
    if let Some(fall) = kappa_fall(run, s) {
        studies.push(fall);
    }
    studies
}

/// The fall of `a_r / p~0` between the lowest load and the first load of the correction's
/// exponent, per Hurst exponent on every grid and extrapolated: a discretisation cause
/// would shrink it on the finer grid, a finite-size one would grow as the contact spots get
/// fewer (the contact points at the lowest load).
fn kappa_fall(run: &Run, s: &AreaStats) -> Option<Study> {
    let scene = run.scene;
    if s.fall.is_empty() {
        return None;
    }
    let (lowest, at) = (scene.reduced_pressures[0], CORRECTION_LOADS[0]);
    let mut study = Study::new(
        KAPPA_FALL,
        format!(
            "The fall of a_r / p~0 from p~0 = {lowest} to {at}, per grid: a finite-size cause?"
        ),
        FALL_COLUMNS,
    )
    .percent(&["fall"])
    .about(format!(
        "Eq. (contactArea) makes a_r / p~0 flat to third order at low load; a fall that \
         shrinks from grid to grid would be the grid's; one that persists from grid to grid, \
         with few contact points at the lowest load, could be the finite number of contact \
         spots. Every job has L / lambda_l = {}: a system-size cause (tex 161-163) cannot be \
         read from them",
        scene.n as f64 / scene.lambda_l
    ));
    for f in &s.fall {
        let (key, label) = match f.grid {
            Some(n) => (
                format!("H{}_grid{n}", f.hurst),
                format!("H = {}, {n}^2", f.hurst),
            ),
            None => (
                format!("H{}_extrapolated", f.hurst),
                format!("H = {}, {}", f.hurst, grid_label(scene)),
            ),
        };
        study.push(
            key,
            label,
            vec![
                f.kappa_lowest.into(),
                f.kappa_at.into(),
                f.fall.into(),
                f.contact_points.into(),
                Cell::from(scene.n as f64 / scene.lambda_l),
            ],
        );
    }
    Some(study)
}
