//! The readings of the paper's "about 1%" (the definition's claim [`CLAIM`]): every row,
//! bin width and denominator as one study, with notes on which readings come within the
//! claim's rule.

use super::stats::{Reading, RowStats, SourceStats};
use crate::experiments::study::Study;
use crate::experiments::Criteria;
use crate::stats::{decide, Claim, Estimate};

/// The key of the definition's claim of the paper's "about 1%".
pub const CLAIM: &str = "about_one_percent";

/// The relative tolerance of the rule of [`CLAIM`] (`rule = { near = 0.1 }` in the
/// definition; a test keeps the two equal): the notes judge every reading as the claim
/// judges its own.
pub const NEAR: f64 = 0.1;

/// The study's key.
pub const STUDY: &str = "one_percent_readings";

/// The study's columns: the denominators of a share, as `(key, label)`.
pub(super) const COLUMNS: [(&str, &str); 4] = [
    ("non_contact", "share of the non-contact at zeta"),
    ("contact", "share of the contact at zeta"),
    ("a0", "share of A0"),
    ("bin", "share of the bin's points"),
];

/// A reading's shares, in the order of [`COLUMNS`].
pub(super) fn shares(r: &Reading) -> [Estimate; 4] {
    [r.of_non_contact, r.of_contact, r.of_nominal, r.of_bin]
}

/// The stable key of one row and width: `H0.5_a0.01_z63_w0`.
pub fn row_key(row: &RowStats, r: &Reading) -> String {
    format!("{}_w{}", row.step.key(), r.width)
}

/// One row and width in words.
fn row_label(row: &RowStats, r: &Reading) -> String {
    let bin = if r.width == 0.0 {
        "bin p = 0".to_string()
    } else {
        format!("bin [0, {} p0/a_r)", r.width)
    };
    format!("{}, {bin}", row.step.label())
}

/// A share as a percentage with its error bar.
pub(super) fn percent(e: Estimate) -> String {
    e.text(100.0, 3, "%")
}

/// Whether `e` comes within the rule of [`CLAIM`] of the paper's `paper` at significance
/// `z`: `|e - paper| <= z s + NEAR |paper|`, decided only with an error bar.
pub fn within_claim(e: Estimate, paper: f64, z: f64) -> bool {
    let near = Claim::Near {
        target: paper,
        tolerance: NEAR * paper.abs(),
    };
    decide(e, near, z).passed()
}

/// The study: one row per scene row and bin width, one column per denominator.
pub fn study(criteria: &Criteria, s: &SourceStats) -> Study {
    let mut study = Study::new(
        STUDY,
        "Readings of the paper's 'about 1% of the non-contact re-enters': which scene, which \
         zero bin, which denominator",
        &COLUMNS,
    )
    .percent(&COLUMNS.map(|c| c.0))
    .about(
        "Points in the zero-pressure bin at zeta (p = 0, or p < w p0/a_r) that lie above the \
         bin after the step at fixed load, as a share of the non-contact, of the contact and \
         of the nominal area A0 at zeta, and of the bin itself; means over realizations",
    );
    for row in &s.rows {
        for r in &row.readings {
            study.push(
                row_key(row, r),
                row_label(row, r),
                shares(r).iter().map(|&e| e.into()).collect(),
            );
        }
    }
    study.notes = notes(criteria, s);
    study
}

/// The notes: the claim's own reading against the paper's value, the readings within the
/// claim's rule (if any), and the one nearest to it.
pub fn notes(criteria: &Criteria, s: &SourceStats) -> Vec<String> {
    let Some(paper) = criteria.paper(CLAIM) else {
        return Vec::new();
    };
    let z = criteria.significance;
    let (first, zero) = (&s.rows[0], s.rows[0].readings[0]);
    let own = zero.of_non_contact;
    let mut notes = vec![format!(
        "The claim's reading, the share of the non-contact at {} (bin p = 0), is {}: {:.2} \
         times the paper's {:.3}%.",
        first.step.label(),
        percent(own),
        own.value / paper,
        100.0 * paper
    )];
    let mut hits = Vec::new();
    let mut nearest: Option<(f64, String, Estimate)> = None;
    for row in &s.rows {
        for r in &row.readings {
            for ((_, column), e) in COLUMNS.iter().zip(shares(r)) {
                let what = format!("{}, {column}", row_label(row, r));
                if within_claim(e, paper, z) {
                    hits.push(format!("{what} ({})", percent(e)));
                }
                let distance = (e.value / paper).ln().abs();
                if distance.is_finite() && nearest.as_ref().is_none_or(|n| distance < n.0) {
                    nearest = Some((distance, what, e));
                }
            }
        }
    }
    let rule = format!(
        "the claim's rule ({:.3}% within {:.0}% or {z} standard errors)",
        100.0 * paper,
        100.0 * NEAR
    );
    notes.push(if hits.is_empty() {
        format!("No reading comes within {rule}.")
    } else {
        format!(
            "{} of {} readings come within {rule}: {}.",
            hits.len(),
            s.rows.len() * first.readings.len() * COLUMNS.len(),
            hits.join("; ")
        )
    });
    if let Some((_, what, e)) = nearest {
        notes.push(format!(
            "Nearest to the paper's value: {what}, {} ({:.2} times it).",
            percent(e),
            e.value / paper
        ));
    }
    notes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readings_are_judged_by_the_rule_of_the_definitions_claim() {
        // NEAR is the tolerance of the shipped claim's rule.
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/validations/c_source.toml");
        let def: toml::Table = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let claim = def["claims"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["key"].as_str() == Some(CLAIM))
            .expect("the claim of the paper's 1%");
        assert_eq!(claim["rule"]["near"].as_float(), Some(NEAR));
        // Within 10% of 1%, or 3 standard errors beyond; never without an error bar.
        assert!(within_claim(Estimate::new(0.0105, 1e-4), 0.01, 3.0));
        assert!(!within_claim(Estimate::new(0.012, 1e-4), 0.01, 3.0));
        assert!(within_claim(Estimate::new(0.012, 5e-4), 0.01, 3.0));
        assert!(!within_claim(Estimate::mean_of(&[0.01]), 0.01, 3.0));
    }
}
