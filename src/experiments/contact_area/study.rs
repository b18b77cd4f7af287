//! The studies of the contact-area law: every reading of the law's largest deviation
//! (denominator, grid), and the order of the grid error on three grids.

use super::stats::AreaStats;
use super::{grid_label, Run};
use crate::experiments::study::{Cell, Study};

/// The readings of the law's deviation (denominator, grid) and the finer grid's
/// order of the grid error.
pub(super) fn studies(run: &Run, s: &AreaStats) -> Vec<Study> {
    let label = grid_label(run.scene);
    let mut readings = Study::new(
        "law_readings",
        "Readings of the contact-area law's largest deviation",
        &[
            ("deviation", "largest deviation, %"),
            ("hurst", "H"),
            ("reduced_pressure", "p~0"),
            ("contact_area", "a_r there"),
        ],
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
            "grid_order",
            format!(
                "The grid error on three grids ({}^2, {}^2, {}^2): is it first order in eps_c?",
                n(0),
                n(1),
                n(2)
            ),
            &[
                ("a_r_1", "a_r, coarse"),
                ("a_r_2", "a_r, middle"),
                ("a_r_3", "a_r, fine"),
                ("ratio", "(a1 - a2) / (a2 - a3)"),
                ("first_order", "first order"),
                ("extrapolated_coarse", "extrapolated, coarse pair"),
                ("extrapolated_fine", "extrapolated, fine pair"),
            ],
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
    studies
}
