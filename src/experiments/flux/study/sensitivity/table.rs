//! The sensitivity study's rows as a generic table of [`crate::experiments::study`]: its
//! key, its columns and one row per setting and value.

use super::SensitivityRow;
use crate::experiments::study::{Cell, Study};

/// The study's key.
pub const KEY: &str = "sensitivity";

/// The study's columns, `(key, label)`.
pub const COLUMNS: &[(&str, &str)] = &[
    ("n", "grid (points per side)"),
    ("zeta", "zeta"),
    ("dzeta", "dzeta"),
    ("realizations", "realizations"),
    ("flux_in", "into contact, % of A0"),
    ("flux_out", "out of contact, % of A0"),
    ("flux_in_of_contact", "into contact, % of the contact area"),
    (
        "flux_out_of_contact",
        "out of contact, % of the contact area",
    ),
    ("net_over_gross", "net / mean one-way flux"),
    ("net_flow", "net flow to non-contact, out - in, % of A0"),
    (
        "net_flow_residual",
        "net flow + change of a_r in the step, % of A0 (fixed load; empty: n/a)",
    ),
    // The column of `flux_in_of_noncontact`: the stored name is kept for the
    // committed results.
    ("zero_bin", "non-contact entering contact, %"),
    ("contact_area", "a_r at zeta"),
    ("variance_added", "height variance added, % of that at zeta"),
    ("modes_added", "modes added"),
];

/// The rows as a generic table (one row per setting and value, keyed
/// `PARAMETER=VALUE`, the transition scene's row `transition`), in % where the column
/// says so.
pub fn study(rows: &[SensitivityRow]) -> Study {
    let mut study = Study::new(
        KEY,
        "What sets the one-step flux: one setting at a time",
        COLUMNS,
    )
    .percent(&[
        "flux_in",
        "flux_out",
        "net_flow",
        "net_flow_residual",
        "flux_in_of_contact",
        "flux_out_of_contact",
        "zero_bin",
        "variance_added",
    ])
    .about(
        "Each row moves one setting away from the base configuration (the first row of each \
         setting shares it) and repeats the step over the realizations: mean and standard \
         error over realizations. At fixed load the net flow to non-contact is the fall of \
         a_r over the step (the points in contact after it are those before, plus those \
         that entered, less those that left, a counting identity of any two sets): the \
         residual of that identity is its own column. At fixed area the control holds a_r \
         to 1e-5 of it (or 1.5 points), so the net flow there is near zero.",
    );
    for r in rows {
        let key = if r.parameter == "transition" {
            "transition".to_string()
        } else {
            format!("{}={}", r.parameter, r.value)
        };
        let label = format!("{} = {} ({})", r.parameter, r.label, r.config.solver.name());
        study.push(
            key,
            label,
            vec![
                Cell::from(r.config.n as f64),
                Cell::from(r.config.zeta),
                Cell::from(r.config.dzeta),
                Cell::from(r.realizations as f64),
                r.flux_in.into(),
                r.flux_out.into(),
                r.flux_in_of_contact.into(),
                r.flux_out_of_contact.into(),
                r.net_over_gross.into(),
                r.net_flow.into(),
                r.net_flow_residual.into(),
                r.flux_in_of_noncontact.into(),
                r.contact_area.into(),
                r.variance_added.into(),
                r.modes_added.map_or(Cell::Empty, Cell::from),
            ],
        );
    }
    study
}
