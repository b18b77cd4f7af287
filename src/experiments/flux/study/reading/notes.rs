//! The scorecard's notes on the sensitivity study: what reproduces the paper's one-step
//! numbers or what was ruled out, how the flux scales with the step, the misprint rows and
//! the paper's transition scene, the net-flow identity and what the paper's net flow says
//! about a misprint.

use super::{matches, percent, reproducing, step_rows, step_scaling, PaperFlux, Reading, MISPRINT};
use crate::experiments::flux::study::sensitivity::{PlannedRow, SensitivityRow};
use crate::plot::significant;
use crate::stats::Estimate;

/// Range of a measure over the rows of one parameter, in percent.
fn range(rows: &[&SensitivityRow], f: fn(&SensitivityRow) -> f64) -> String {
    let lo = rows.iter().map(|r| f(r)).fold(f64::INFINITY, f64::min);
    let hi = rows.iter().map(|r| f(r)).fold(f64::NEG_INFINITY, f64::max);
    format!("{:.3}-{:.3}%", 100.0 * lo, 100.0 * hi)
}

/// The notes of the scorecard: what reproduces the paper's numbers or what was ruled out,
/// the step scaling, the misprint rows (`planned`: every row the plan states, so that a
/// row whose jobs have no results yet reads as not run), the net-flow identity and what
/// the net flow says about a misprint, and the caption's direction against the text's.
pub fn notes(
    rows: &[SensitivityRow],
    planned: &[PlannedRow],
    p: &PaperFlux,
    a_r_before: f64,
    a_r_after: f64,
) -> Vec<String> {
    if rows.is_empty() {
        return Vec::new();
    }
    let mut notes = Vec::new();
    let hits = reproducing(rows, p);
    let n = rows[0].config.n;
    let (paper_in, paper_out) = (percent(p.flux_in), percent(p.flux_out));
    if hits.is_empty() {
        let mut parts = Vec::new();
        let mut seen: Vec<&str> = Vec::new();
        for r in rows {
            if seen.contains(&r.parameter.as_str()) {
                continue;
            }
            seen.push(&r.parameter);
            let group: Vec<&SensitivityRow> =
                rows.iter().filter(|x| x.parameter == r.parameter).collect();
            parts.push(format!(
                "{} ({}): in {} / out {} of the nominal area, {} / {} of the contact area",
                r.parameter,
                group
                    .iter()
                    .map(|x| x.label.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
                range(&group, |x| x.flux_in.value),
                range(&group, |x| x.flux_out.value),
                range(&group, |x| x.flux_in_of_contact.value),
                range(&group, |x| x.flux_out_of_contact.value),
            ));
        }
        notes.push(format!(
            "Flux magnitude, sensitivity study (base {n}x{n}, {} unless the row says): no \
             setting reproduces the paper's {paper_in} and {paper_out} (within 10% plus \
             three standard errors), in either measure, with either number as the inflow. \
             Ruled out as the cause: {}.",
            rows[0].config.solver.name(),
            parts.join("; ")
        ));
    } else {
        notes.push(format!(
            "Flux magnitude, sensitivity study (base {n}x{n}): the paper's {paper_in} and \
             {paper_out} (each within 10% plus three standard errors) are matched by {}; no \
             other setting matches in either measure, with either number as the inflow. \
             Where the matching row changes a printed parameter, the paper's numbers are \
             consistent with a misprint of it (each such row is one reading; the flux alone \
             does not single one out).",
            hits.join("; ")
        ));
    }
    let in_above: Vec<String> = rows
        .iter()
        .filter(|r| !r.config.fixed_area && r.flux_in.value > r.flux_out.value)
        .map(|r| format!("{} = {}", r.parameter, r.label))
        .collect();
    notes.push(if in_above.is_empty() {
        "At fixed load every row has more points leaving contact than entering it: the \
         caption's order (in > out) is reproduced by no setting."
            .to_string()
    } else {
        format!(
            "At fixed load, in > out (the caption's order) in: {}.",
            in_above.join(", ")
        )
    });
    notes.extend(step_notes(rows, p));
    notes.extend(hypothesis_notes(rows, planned, p));
    notes.extend(identity_note(rows));
    notes.extend(net_flow_note(rows, planned, p));
    notes.extend(summary_note(rows, p, &hits));
    notes.push(format!(
        "Direction: the caption's red (entered, {paper_in}) exceeds its blue (left, \
         {paper_out}), which at fixed load would make a_r grow with zeta by {} of the area \
         per step, while the text says the net flux is to non-contact and a_r falls with \
         zeta at fixed load. Here the headline step has a_r going from {a_r_before:.4} to \
         {a_r_after:.4}, the net flux to non-contact, as the text says.",
        percent(p.flux_in - p.flux_out)
    ));
    notes
}

/// What the step rows show: each row's step taken, magnitude and net/gross, and how the
/// flux scales with the added variance (what the paper's magnitude would need).
fn step_notes(rows: &[SensitivityRow], p: &PaperFlux) -> Vec<String> {
    let steps = step_rows(rows);
    let Some((first, _)) = steps.first() else {
        return Vec::new();
    };
    let n = first.config.n;
    let listed: Vec<String> = steps
        .iter()
        .map(|(r, v)| {
            format!(
                "{} (variance +{}%, {} modes): in {}, out {}{}",
                r.label,
                significant(100.0 * v, 3),
                r.modes_added.map_or("?".into(), |m| format!("{m:.0}")),
                r.flux_in.text(100.0, 3, "%"),
                r.flux_out.text(100.0, 3, "%"),
                r.net_over_gross.map_or(String::new(), |e| format!(
                    ", net/gross {}",
                    e.text(1.0, 2, "")
                ))
            )
        })
        .collect();
    let mut notes = vec![format!(
        "Step rows ({n}x{n}; the step taken is the height variance the added modes carry, \
         relative to the variance at zeta): {}.",
        listed.join("; ")
    )];
    if let Some(s) = step_scaling(rows, p) {
        let mut text = format!(
            "Against the added variance, the mean one-way flux grows with exponent {}",
            s.gross_exponent.text(1.0, 2, "")
        );
        if let Some(e) = s.net_exponent {
            text.push_str(&format!(
                " and the net flux with exponent {}",
                e.text(1.0, 2, "")
            ));
        }
        text.push_str(&format!(
            ". The paper's mean one-way flux ({}) would need {:.1} times the variance the \
             stated step adds",
            percent(p.mean()),
            s.variance_factor
        ));
        if let Some(step) = s.step {
            text.push_str(&format!(
                " (dzeta/zeta about {:.3}, {:.1} times the stated {})",
                step,
                step / p.step,
                significant(p.step, 4)
            ));
        }
        if let Some(ng) = s.net_over_gross {
            text.push_str(&format!(
                "; there the net/gross would be about {ng:.2}, against the paper's {:.2}",
                p.net_over_gross()
            ));
        }
        text.push_str(". An extrapolation of these rows, not a measurement.");
        notes.push(text);
    }
    notes
}

/// The study in two sentences: the stated step's magnitude and net/gross against the
/// paper's, and which rows give both of the paper's numbers (none where no step row is the
/// stated step).
fn summary_note(rows: &[SensitivityRow], p: &PaperFlux, hits: &[String]) -> Option<String> {
    let stated = rows.iter().find(|r| p.is_stated_step(r))?;
    let n = stated.config.n;
    let mean = 0.5 * (stated.flux_in.value + stated.flux_out.value);
    let net = stated.net_over_gross.map_or(String::new(), |e| {
        format!(", net/gross {}", e.text(1.0, 2, ""))
    });
    let mut text = format!(
        "In sum ({n}x{n}): at the stated parameters the mean one-way flux is {}, {:.1} \
         times below the paper's {}{net} (the paper's: {:.2}).",
        percent(mean),
        p.mean() / mean,
        percent(p.mean()),
        p.net_over_gross()
    );
    if hits.is_empty() {
        text.push_str(" No row gives both of the paper's numbers.");
    } else {
        text.push_str(
            " The rows that give both of the paper's numbers are listed above; the flux \
             alone does not tell them apart.",
        );
    }
    Some(text)
}

/// The misprint hypotheses (another Hurst exponent or contact area than stated; a planned
/// row without results is not run yet) and the paper's transition scene, row by row
/// against the paper.
fn hypothesis_notes(rows: &[SensitivityRow], planned: &[PlannedRow], p: &PaperFlux) -> Vec<String> {
    let mut notes = Vec::new();
    let described = |r: &SensitivityRow| {
        format!(
            "in {}, out {} of the nominal area{}",
            r.flux_in.text(100.0, 3, "%"),
            r.flux_out.text(100.0, 3, "%"),
            r.net_over_gross.map_or(String::new(), |e| format!(
                ", net/gross {}",
                e.text(1.0, 2, "")
            ))
        )
    };
    let verdict = |r: &SensitivityRow| {
        Reading::BOTH
            .map(|reading| reading.verdict(p, r.flux_in, r.flux_out))
            .join("; ")
    };
    for m in planned.iter().filter(|m| MISPRINT.contains(&m.parameter)) {
        let Some(r) = rows.iter().find(|r| m.is(r)) else {
            notes.push(format!(
                "Misprinted parameter? {}: not run yet (its jobs have no results).",
                m.label
            ));
            continue;
        };
        notes.push(format!(
            "Misprinted parameter? {} at {}x{} (the rest as the base): {}. Against the \
             paper, read with {}. A match is consistent with a misprint of this parameter, \
             not a proof of one.",
            r.label,
            r.config.n,
            r.config.n,
            described(r),
            verdict(r)
        ));
    }
    for r in rows.iter().filter(|r| r.parameter == "transition") {
        if let Some(z) = r.flux_in_of_noncontact {
            notes.push(format!(
                "The paper's transition scene ({}, {}x{}): {} of the non-contact at zeta \
                 enters contact in the step (the paper's 'about 1%' of it is c_source's \
                 claim about_one_percent), {} of the contact area; a_r = {:.4} before the \
                 step.",
                r.label,
                r.config.n,
                r.config.n,
                z.text(100.0, 4, "%"),
                r.flux_in_of_contact.text(100.0, 2, "%"),
                r.contact_area.value
            ));
        }
    }
    notes
}

/// The net-flow identity over every row: out - in is the fall of `a_r` over the step
/// where every residual (its mean and its error bar) lies below half a point of the row's
/// grid, the identity counting points (of any two sets of points in contact, whatever the
/// control). None without a row that checks it.
pub(super) fn identity_note(rows: &[SensitivityRow]) -> Option<String> {
    let checked: Vec<(&SensitivityRow, Estimate)> = rows
        .iter()
        .filter_map(|r| Some((r, r.net_flow_residual?)))
        .collect();
    if checked.is_empty() {
        return None;
    }
    let holds = |r: &SensitivityRow, e: Estimate| {
        let half_point = 0.5 / (r.config.n as f64).powi(2);
        // A missing error bar (one realization) leaves the mean alone to decide.
        e.value.abs() < half_point && (!e.has_error() || e.std_error < half_point)
    };
    let failing: Vec<String> = checked
        .iter()
        .filter(|(r, e)| !holds(r, *e))
        .map(|(r, e)| format!("{} = {} ({:.1e} of A0)", r.parameter, r.label, e.value))
        .collect();
    let largest = checked
        .iter()
        .map(|(_, e)| e.value.abs())
        .fold(0.0, f64::max);
    let count = |k: usize| format!("{k} row{}", if k == 1 { "" } else { "s" });
    let identity = "a counting identity of any two sets of points in contact: those in \
                    contact after the step are those before, plus those that entered, less \
                    those that left, so out - in is the fall of a_r over the step (at fixed \
                    load the fall the added roughness causes; at fixed area near zero)";
    Some(if failing.is_empty() {
        format!(
            "Net-flow identity ({identity}): holds on every row ({}; the largest |residual| \
             {} of A0, below half a point of each grid): a guard of the counting, not a \
             finding.",
            count(checked.len()),
            if largest == 0.0 {
                "0".to_string()
            } else {
                format!("{largest:.1e}")
            }
        )
    } else {
        format!(
            "Net-flow identity ({identity}): does not hold in {} of {}, where the contact \
             area and the fluxes count different points: {}.",
            failing.len(),
            count(checked.len()),
            failing.join("; ")
        )
    })
}

/// The paper's net flow ([`PaperFlux::net_flow`]) against the stated step's row and every
/// misprint row the plan states (a row without results is not run yet): which rows give
/// it, which give the paper's fluxes (either reading), and which give both. None without
/// a misprint row in the plan.
fn net_flow_note(rows: &[SensitivityRow], planned: &[PlannedRow], p: &PaperFlux) -> Option<String> {
    let misprints: Vec<&PlannedRow> = planned
        .iter()
        .filter(|m| MISPRINT.contains(&m.parameter))
        .collect();
    if misprints.is_empty() {
        return None;
    }
    let paper = p.net_flow();
    let net_matches = |r: &SensitivityRow| r.net_flow.is_some_and(|e| matches(e, paper));
    let fluxes_match = |r: &SensitivityRow| {
        Reading::BOTH
            .iter()
            .any(|reading| reading.matches(p, r.flux_in, r.flux_out))
    };
    let said = |r: &SensitivityRow| {
        format!(
            "{}: {}",
            r.net_flow
                .map_or("not measured".into(), |e| e.text(100.0, 3, "%")),
            if net_matches(r) {
                "matches"
            } else {
                "does not match"
            }
        )
    };
    let mut parts = Vec::new();
    let stated = rows.iter().find(|r| p.is_stated_step(r));
    if let Some(r) = stated {
        parts.push(format!("at the stated parameters {}", said(r)));
    }
    let (mut both, mut net_only, mut fluxes_only, mut not_run) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for m in misprints {
        let label = m.label.clone();
        let Some(r) = rows.iter().find(|r| m.is(r)) else {
            parts.push(format!("{label}: not run yet"));
            not_run.push(label);
            continue;
        };
        parts.push(format!("{label}: {}", said(r)));
        match (net_matches(r), fluxes_match(r)) {
            (true, true) => both.push(label),
            (true, false) => net_only.push(label),
            (false, true) => fluxes_only.push(label),
            (false, false) => {}
        }
    }
    let mut text = format!(
        "Net flow and the misprint: the paper's two numbers differ by {} of A0, which at \
         fixed load is the fall of a_r over its step (to non-contact, as the text says). \
         Out - in against it (within 10% plus three standard errors): {}.",
        percent(paper),
        parts.join("; ")
    );
    let none = || "none".to_string();
    text.push_str(&format!(
        " Rows run that give both the paper's fluxes (either reading) and its net flow: {}",
        if both.is_empty() {
            none()
        } else {
            both.join(", ")
        }
    ));
    for (group, what) in [
        (&net_only, "the net flow but not the fluxes"),
        (&fluxes_only, "the fluxes but not the net flow"),
    ] {
        if !group.is_empty() {
            text.push_str(&format!("; {what}: {}", group.join(", ")));
        }
    }
    text.push('.');
    if !both.is_empty() {
        text.push_str(
            " A row that gives both is consistent with a misprint of its parameter alone, \
             not a proof of one.",
        );
    }
    if stated.is_some_and(net_matches) {
        text.push_str(
            " The stated parameters give the paper's net flow too: the net flow alone does \
             not point to a misprint.",
        );
    }
    if !not_run.is_empty() {
        text.push_str(&format!(
            " Not run yet: {}; the note reads it once its jobs have results.",
            not_run.join(", ")
        ));
    }
    Some(text)
}
