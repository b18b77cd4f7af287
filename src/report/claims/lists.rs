//! The page's tables: the count table (one row per validation) and the lists of claims by
//! result (contradicted with their class, not established with the side they lean to,
//! reproduced grouped by the assumption they test, and the claims counted apart).

use std::fmt::Write as _;

use super::cells::{key_cell, measured_cell, tex};
use super::tally::{every_claim, Class, Counts};
use crate::report::format::{md, push_table};
use crate::validation::claims::ClaimKind;
use crate::validation::{ClaimOutcome, ClaimResult, Outcome};

/// The assumption a validation tests, as the page groups the reproduced claims.
fn assumption(name: &str) -> &'static str {
    match name {
        "a_diffusion" => "(a) pressure-independent diffusion",
        "b_drift" => "(b) no drift",
        "c_flux" | "c_reentry" | "c_source" => "(c) no re-entry",
        "d_onset" => "(d) a mode holds energy only once resolved",
        "e_frozen" | "e_frozen_h03" => "(e) a resolved mode keeps its energy",
        "total_energy" => "the integrated elastic energy",
        "contact_area" => "the contact-area law",
        _ => "other",
    }
}

/// The claims of `outcomes` with their validation's name, in the outcomes' order.
pub(super) fn listed<'a>(outcomes: &[&'a Outcome]) -> Vec<(&'a str, &'a ClaimOutcome)> {
    outcomes
        .iter()
        .flat_map(|o| o.claims.iter().map(move |c| (o.name.as_str(), c)))
        .collect()
}

/// The count table: one row per validation, a total, and the headline line.
pub(super) fn count_table(s: &mut String, outcomes: &[&Outcome]) {
    let header = [
        "validation",
        "headline as the paper's",
        "reproduced",
        "contradicted",
        "not established",
        "not measured",
        "consistency checks",
        "the paper two ways",
        "all",
    ];
    let row = |name: String, headline: String, n: Counts| {
        vec![
            name,
            headline,
            n.reproduced.to_string(),
            n.contradicted.to_string(),
            n.not_established.to_string(),
            (n.not_measured + n.not_judged).to_string(),
            n.consistency.to_string(),
            n.two_ways.to_string(),
            n.all.to_string(),
        ]
    };
    let mut rows: Vec<Vec<String>> = outcomes
        .iter()
        .map(|o| {
            let headline = match o.reproduced {
                Some(true) => "yes",
                Some(false) => "**no**",
                None => "inconclusive",
            };
            row(
                format!("`{}`", o.name),
                headline.into(),
                Counts::of(&o.claims),
            )
        })
        .collect();
    let same = outcomes
        .iter()
        .filter(|o| o.reproduced == Some(true))
        .count();
    rows.push(row(
        "**all**".into(),
        format!("{same} of {}", outcomes.len()),
        Counts::of(every_claim(outcomes)),
    ));
    push_table(s, &header, &rows);
}

/// The lists: contradicted, not established, reproduced by assumption, counted apart.
/// `costs`, a page beside this one that prices each undecided claim, is named under the
/// undecided ones.
pub(super) fn lists(s: &mut String, outcomes: &[&Outcome], costs: Option<&str>) {
    let all = listed(outcomes);
    let pick = |keep: &dyn Fn(&ClaimOutcome) -> bool| -> Vec<(&str, &ClaimOutcome)> {
        all.iter().filter(|(_, c)| keep(c)).copied().collect()
    };
    let evidence = |r: ClaimResult| pick(&|c| c.kind == ClaimKind::Evidence && c.result == r);
    let contradicted = evidence(ClaimResult::Contradicted);
    let _ = writeln!(s, "### Contradicted ({})\n", contradicted.len());
    table(
        s,
        &contradicted,
        &["claim", "where", "paper", "measured (n)", "class"],
        |v, c| with(v, c, [Class::of(c).text().into()]),
    );
    let open = evidence(ClaimResult::NotEstablished);
    let _ = writeln!(s, "### Not established ({})\n", open.len());
    if let Some(page) = costs.filter(|_| !open.is_empty()) {
        let _ = writeln!(
            s,
            "\"Would decide\" assumes the value stays where it is. What each would cost in core-hours, \
             from its error bar alone, and which runs are planned: [{page}]({page}).\n"
        );
    }
    table(
        s,
        &open,
        &[
            "claim",
            "where",
            "paper",
            "measured (n)",
            "leans",
            "would decide",
        ],
        |v, c| {
            with(
                v,
                c,
                [
                    format!("{} the rule's region", c.leans().unwrap_or("—")),
                    md(&c.would_decide().unwrap_or_default()),
                ],
            )
        },
    );
    reproduced_by_assumption(s, &evidence(ClaimResult::Reproduced));
    let unmeasured = pick(&|c| {
        c.kind == ClaimKind::Evidence
            && matches!(
                c.result,
                ClaimResult::NotMeasured | ClaimResult::NotJudgedAtThisScale
            )
    });
    counted_apart(
        s,
        &pick(&|c| c.kind == ClaimKind::Inconsistent),
        &pick(&|c| c.kind == ClaimKind::Consistency),
        &unmeasured,
    );
}

/// A claim's first cells (key, tex lines, the paper's value, the measurement) and `more`.
fn with<const N: usize>(v: &str, c: &ClaimOutcome, more: [String; N]) -> Vec<String> {
    let mut row = vec![
        key_cell(v, c),
        tex(&c.place),
        md(&c.paper),
        measured_cell(c),
    ];
    row.extend(more);
    row
}

/// A table of `claims` under `header`, a row each from `cells`, followed by a blank line;
/// nothing when there are none.
fn table(
    s: &mut String,
    claims: &[(&str, &ClaimOutcome)],
    header: &[&str],
    cells: impl Fn(&str, &ClaimOutcome) -> Vec<String>,
) {
    if claims.is_empty() {
        return;
    }
    let rows: Vec<Vec<String>> = claims.iter().map(|(v, c)| cells(v, c)).collect();
    push_table(s, header, &rows);
    s.push('\n');
}

/// The reproduced claims, a table for each assumption in the order they first appear.
fn reproduced_by_assumption(s: &mut String, reproduced: &[(&str, &ClaimOutcome)]) {
    let _ = writeln!(s, "### Reproduced ({})\n", reproduced.len());
    let mut groups: Vec<&str> = Vec::new();
    for (v, _) in reproduced {
        if !groups.contains(&assumption(v)) {
            groups.push(assumption(v));
        }
    }
    for g in groups {
        let members: Vec<(&str, &ClaimOutcome)> = reproduced
            .iter()
            .filter(|(v, _)| assumption(v) == g)
            .copied()
            .collect();
        let _ = writeln!(s, "{g}:\n");
        table(
            s,
            &members,
            &["claim", "where", "paper", "measured (n)"],
            |v, c| with(v, c, []),
        );
    }
}

/// The claims counted apart: the paper two ways (each reading's result), the consistency
/// checks and the evidence not measured.
fn counted_apart(
    s: &mut String,
    two_ways: &[(&str, &ClaimOutcome)],
    checks: &[(&str, &ClaimOutcome)],
    unmeasured: &[(&str, &ClaimOutcome)],
) {
    let _ = writeln!(s, "### Counted apart\n");
    let _ = writeln!(
        s,
        "**The paper two ways ({}):** the paper states these in ways that cannot all hold; \
         each reading is judged and shown, none is counted as evidence.\n",
        two_ways.len()
    );
    table(
        s,
        two_ways,
        &["claim", "where", "paper", "measured (n)", "readings"],
        |v, c| {
            let readings: Vec<String> = std::iter::once(c.result)
                .chain(c.readings.iter().map(|r| r.result))
                .map(|r| r.text().to_string())
                .collect();
            with(v, c, [readings.join(" / ")])
        },
    );
    let _ = writeln!(
        s,
        "**Consistency checks ({}):** true by construction (an identity, arithmetic on the \
         paper's formula or on a chosen scene): they check the code, not the paper.\n",
        checks.len()
    );
    table(
        s,
        checks,
        &["claim", "where", "measured (n)", "result"],
        |v, c| {
            vec![
                key_cell(v, c),
                tex(&c.place),
                measured_cell(c),
                c.result.text().into(),
            ]
        },
    );
    let _ = writeln!(
        s,
        "**Not measured ({}):** evidence with no measure at this scale; each block says what \
         it would take.\n",
        unmeasured.len()
    );
    table(s, unmeasured, &["claim", "where", "paper"], |v, c| {
        vec![key_cell(v, c), tex(&c.place), md(&c.paper)]
    });
}
