//! One claim's block: its statement, place, reading and rule (with the rule's region in the
//! unit the page prints), the measurement and result, the rival readings, the amendments
//! with the earlier rules, and the other scale's result.

use std::fmt::Write as _;

use super::cells::{anchor, measured_cell, result_text, value};
use crate::report::format::{md, prose};
use crate::stats::Region;
use crate::validation::claims::{ClaimKind, Unit};
use crate::validation::register::{claim_id, Register};
use crate::validation::ClaimOutcome;

/// The rule in words: phrase, unit, the rule as written and, for a unit the page prints
/// scaled (a share in %, a difference of shares in points), its region in the printed
/// unit, so that the rule and the measured value read alike.
fn rule_text(c: &ClaimOutcome) -> String {
    let phrase = c.phrase.map_or("?", |p| p.name());
    let unit = c.unit.map_or("?", Unit::name);
    let written = format!("phrase `{phrase}`, unit `{unit}`: `{}`", c.rule.text());
    match (c.unit.map(Unit::display), c.region()) {
        (Some((factor, suffix)), Some(region)) if factor != 1.0 && c.difference.is_none() => {
            format!("{written}, that is {}", region_in(region, factor, suffix))
        }
        _ => written,
    }
}

/// A region with its bounds scaled by `factor` and followed by `suffix`: "-4 to 4 points",
/// "at most 5%", "outside 0.9 to 1.1%".
fn region_in(region: Region, factor: f64, suffix: &str) -> String {
    let n = |x: f64| {
        let t = format!("{:.4}", x * factor);
        let t = t.trim_end_matches('0').trim_end_matches('.');
        if t == "-0" {
            "0".to_string()
        } else {
            t.to_string()
        }
    };
    match region {
        Region::Interval { lo, hi, .. } if lo.is_finite() && hi.is_finite() => {
            format!("{} to {}{suffix}", n(lo), n(hi))
        }
        Region::Interval { lo, .. } if lo.is_finite() => format!("at least {}{suffix}", n(lo)),
        Region::Interval { hi, .. } => format!("at most {}{suffix}", n(hi)),
        Region::Outside(lo, hi) => format!("outside {} to {}{suffix}", n(lo), n(hi)),
        Region::Except(t) => format!("not {}{suffix}", n(t)),
    }
}

/// One claim's block: the statement, its reading and rule, the result with its reason,
/// the rival readings, the amendments (with the earlier rules and their verdicts from the
/// register) and, where given, the other scale's result.
pub(super) fn block(
    s: &mut String,
    validation: &str,
    c: &ClaimOutcome,
    other: Option<(&str, &ClaimOutcome)>,
    register: Option<&Register>,
) {
    let _ = writeln!(
        s,
        "#### <a id=\"{}\"></a>`{}`\n",
        anchor(validation, &c.key),
        claim_id(validation, &c.key)
    );
    let _ = writeln!(s, "> {}\n", prose(&c.statement));
    let _ = writeln!(s, "- **Where:** {}", prose(&c.place));
    if let Some(scene) = &c.scene {
        let _ = writeln!(s, "- **The paper's scene:** {}", prose(scene));
    }
    let _ = writeln!(s, "- **Paper:** {}", md(&c.paper));
    if let Some(r) = &c.reading {
        let _ = writeln!(s, "- **Reading:** {}", prose(r));
    }
    let _ = writeln!(s, "- **Rule:** {}", rule_text(c));
    if let Some(d) = &c.departs {
        let _ = writeln!(s, "- **Departs from the phrase's rule:** {}", prose(d));
    }
    let kind = match c.kind {
        ClaimKind::Evidence => "",
        ClaimKind::Consistency => " (consistency check, counted apart)",
        ClaimKind::Inconsistent => " (the paper two ways, counted apart)",
    };
    let _ = writeln!(
        s,
        "- **Measured:** {}: {}{kind}",
        measured_cell(c),
        result_text(c.result)
    );
    if let Some(why) = &c.why {
        let _ = writeln!(s, "- **Why:** {}", prose(why));
    }
    if let Some(commit) = &c.planned {
        let _ = writeln!(
            s,
            "- **Realizations planned at `{commit}`** (`docs/power-plan.md`: from the error bar alone, before the planned jobs ran)"
        );
    }
    for r in &c.readings {
        let _ = writeln!(
            s,
            "- **Rival reading:** {}: {} ({})",
            prose(&r.reading),
            value(c, r.measured),
            r.result.text()
        );
    }
    let earlier = register.map_or(&[][..], |reg| reg.rules(&claim_id(validation, &c.key)));
    for (a, r) in c.amendments.iter().zip(earlier) {
        let verdict = |v: &Option<crate::validation::register::Verdicted>| match v {
            Some(v) => format!("{} ({})", v.result.text(), value(c, v.measured)),
            None => "no verdict recorded".into(),
        };
        let _ = writeln!(
            s,
            "- **Amended:** {}. *The earlier rule* (registered {} at `{}`, no longer in force): \
             region `{}`, under which the full scale was {} and the reduced scale {}.",
            prose(a.reason.trim_end_matches('.')),
            r.registered,
            &r.commit[..r.commit.len().min(10)],
            r.rule.get("region").and_then(|g| g.as_str()).unwrap_or("?"),
            verdict(&r.full),
            verdict(&r.reduced),
        );
    }
    if let Some((scale, o)) = other {
        let _ = writeln!(
            s,
            "- **{scale}:** {}: {}",
            measured_cell(o),
            o.result.text()
        );
    }
    s.push('\n');
}
