//! The cells a claim's row and block share: the tex lines of its place, its key linked to
//! its block, a value in the claim's unit, the measurement with its realizations and the
//! result in words.

use crate::report::format::{num, pm};
use crate::stats::Estimate;
use crate::validation::claims::ErrorKind;
use crate::validation::register::claim_id;
use crate::validation::{ClaimOutcome, ClaimResult};

/// The lines of the paper's source a place names: "tex 612-617, 660-661".
pub(super) fn tex(place: &str) -> String {
    let mut parts = Vec::new();
    for (k, _) in place.match_indices("tex ") {
        let rest = &place[k + 4..];
        let end = rest.find(')').unwrap_or(rest.len());
        for range in rest[..end].split([',', ';']).map(str::trim) {
            if !range.is_empty() && !parts.contains(&range) {
                parts.push(range);
            }
        }
    }
    if parts.is_empty() {
        "—".into()
    } else {
        format!("tex {}", parts.join(", "))
    }
}

/// The anchor of a claim's block.
pub(super) fn anchor(validation: &str, key: &str) -> String {
    format!(
        "c-{}",
        claim_id(validation, key)
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
            .collect::<String>()
    )
}

/// The claim's key, linked to its block.
pub(super) fn key_cell(validation: &str, c: &ClaimOutcome) -> String {
    format!(
        "[`{}`](#{})",
        claim_id(validation, &c.key),
        anchor(validation, &c.key)
    )
}

/// A value in the claim's unit (in % where it is a share or a relative change).
pub(super) fn value(c: &ClaimOutcome, e: Option<Estimate>) -> String {
    let Some(e) = e else {
        return "—".into();
    };
    let (scale, suffix) = match c.unit {
        Some(u) => u.display(),
        None if c.paper.contains('%') => (100.0, "%"),
        None => (1.0, ""),
    };
    if e.std_error.is_finite() {
        format!("{}{suffix}", pm(scale * e.value, scale * e.std_error))
    } else {
        // The unit before the mark: "5.2% (no error estimate)".
        format!("{}{suffix} (no error estimate)", num(scale * e.value))
    }
}

/// The measurement with its realizations: "0.644 ± 0.006 (n = 4)".
pub(super) fn measured_cell(c: &ClaimOutcome) -> String {
    let v = value(c, c.measured);
    match (c.measured, c.realizations) {
        (Some(_), Some(n)) if c.error == ErrorKind::Fit => format!("{v} (fit, n = {n})"),
        (Some(_), Some(n)) => format!("{v} (n = {n})"),
        _ => v,
    }
}

/// A result in words, marked where it needs attention.
pub(super) fn result_text(r: ClaimResult) -> String {
    match r {
        ClaimResult::Contradicted => "**contradicted**".into(),
        ClaimResult::NotEstablished => "*not established*".into(),
        r => r.text().into(),
    }
}
