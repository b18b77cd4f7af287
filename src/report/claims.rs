//! The paper's claims as tables: the scorecard's opening section (one row per claim of
//! every outcome, with the statement, its place in the paper, the paper's value, the
//! measured value with its error bar and whether it reproduces), and the table of
//! `docs/claims.md`, full and reduced scenes side by side, written between two markers of
//! a Markdown file (`persson-check claims --write docs/claims.md`).
//!
//! Every cell comes from the outcomes' `claims` ([`crate::validation::claims`]): the
//! statement, the rule and the paper's value are the definitions' data, the result is the
//! one rule's.

use std::fmt::Write as _;
use std::path::Path;

use super::format::{md, pm, prose, push_table};
use crate::error::{Error, Result};
use crate::validation::claims::{ClaimKind, ReadingOutcome};
use crate::validation::{ClaimOutcome, ClaimResult, Outcome};

/// The marker lines of the table in `docs/claims.md`.
pub const MARKERS: (&str, &str) = ("<!-- paper-claims -->", "<!-- /paper-claims -->");

/// A value as the tables print it: in % where the paper prints a percentage.
fn value(c: &ClaimOutcome, e: Option<crate::stats::Estimate>) -> String {
    let Some(e) = e else {
        return "—".into();
    };
    if c.paper.contains('%') {
        format!("{}%", pm(100.0 * e.value, 100.0 * e.std_error))
    } else {
        pm(e.value, e.std_error)
    }
}

/// The measured value, with each other reading's value beside it.
fn measured(c: &ClaimOutcome) -> String {
    let mut s = value(c, c.measured);
    for r in &c.readings {
        let _ = write!(s, "; {}: {}", prose(&r.reading), value(c, r.measured));
    }
    s
}

/// A result in words, marked where it needs attention.
fn result_text(r: ClaimResult) -> String {
    match r {
        ClaimResult::Contradicted => "**contradicted**".into(),
        ClaimResult::NotEstablished => "*not established*".into(),
        r => r.text().into(),
    }
}

/// The result with its reason where it has one, and each other reading's result.
fn result(c: &ClaimOutcome) -> String {
    let mut s = match c.kind {
        ClaimKind::Evidence => result_text(c.result),
        ClaimKind::Consistency => format!("consistency check: {}", c.result.text()),
        ClaimKind::Inconsistent => format!("paper inconsistent; this reading: {}", c.result.text()),
    };
    if let Some(why) = &c.why {
        if c.result != ClaimResult::Reproduced || c.kind != ClaimKind::Evidence {
            let _ = write!(s, " ({})", prose(why));
        }
    }
    for ReadingOutcome {
        reading, result, ..
    } in &c.readings
    {
        let _ = write!(s, "; {}: {}", prose(reading), result.text());
    }
    s
}

/// The statement with the paper's scene and the reading, where given.
fn statement(c: &ClaimOutcome) -> String {
    let mut s = prose(&c.statement);
    if let Some(scene) = &c.scene {
        let _ = write!(s, " (paper's scene: {})", prose(scene));
    }
    if let Some(reading) = &c.reading {
        let _ = write!(s, " [reading: {}]", prose(reading));
    }
    s
}

/// The claims of every outcome, in order.
fn every_claim(outcomes: &[Outcome]) -> Vec<&ClaimOutcome> {
    outcomes.iter().flat_map(|o| &o.claims).collect()
}

/// Counts of the results of `claims`: evidence by result, then consistency checks and
/// statements the paper makes two ways apart.
pub fn counts(claims: &[&ClaimOutcome]) -> String {
    let evidence: Vec<&&ClaimOutcome> = claims
        .iter()
        .filter(|c| c.kind == ClaimKind::Evidence)
        .collect();
    let n = |r: ClaimResult| evidence.iter().filter(|c| c.result == r).count();
    let apart = |k: ClaimKind| claims.iter().filter(|c| c.kind == k).count();
    format!(
        "{} claims: {} reproduced, {} contradicted, {} not established, {} not measured, {} \
         not judged at this scale; apart: {} consistency checks, {} statements the paper \
         makes two ways",
        claims.len(),
        n(ClaimResult::Reproduced),
        n(ClaimResult::Contradicted),
        n(ClaimResult::NotEstablished),
        n(ClaimResult::NotMeasured),
        n(ClaimResult::NotJudgedAtThisScale),
        apart(ClaimKind::Consistency),
        apart(ClaimKind::Inconsistent),
    )
}

/// The scorecard's section: every claim of every outcome, in the outcomes' order.
pub fn section(s: &mut String, outcomes: &[&Outcome]) {
    let all: Vec<&ClaimOutcome> = outcomes.iter().flat_map(|o| &o.claims).collect();
    if all.is_empty() {
        return;
    }
    let _ = writeln!(s, "## The paper's claims\n");
    let _ = writeln!(
        s,
        "Each quantitative statement of the paper, set against its measure by the rule its \
         definition states (`validations/<name>.toml`, `[[claims]]`). {}.\n",
        counts(&all)
    );
    let mut rows = Vec::new();
    for o in outcomes {
        for c in &o.claims {
            rows.push(vec![
                format!("`{}`", o.name),
                statement(c),
                prose(&c.place),
                md(&c.paper),
                measured(c),
                result(c),
            ]);
        }
    }
    push_table(
        s,
        &[
            "validation",
            "claim",
            "where",
            "paper",
            "measured",
            "result",
        ],
        &rows,
    );
}

/// The table of `docs/claims.md`: every claim of the full outcomes and the reduced ones, side by
/// side, in the order of the full outcomes (then any claim only the reduced have).
pub fn table(full: &[Outcome], reduced: &[Outcome]) -> String {
    let key = |o: &Outcome, c: &ClaimOutcome| (o.name.clone(), c.key.clone());
    let mut order: Vec<(String, String, &ClaimOutcome)> = Vec::new();
    for o in full.iter().chain(reduced) {
        for c in &o.claims {
            let k = key(o, c);
            if !order.iter().any(|(n, ck, _)| (n, ck) == (&k.0, &k.1)) {
                order.push((k.0, k.1, c));
            }
        }
    }
    let find = |outcomes: &[Outcome], name: &str, claim: &str| -> Option<ClaimOutcome> {
        outcomes
            .iter()
            .find(|o| o.name == name)?
            .claims
            .iter()
            .find(|c| c.key == claim)
            .cloned()
    };
    let cells = |c: Option<ClaimOutcome>, has_run: bool| match c {
        Some(c) => (measured(&c), result(&c)),
        None if has_run => ("—".into(), "not in this run".into()),
        None => ("not run yet".into(), "—".into()),
    };
    let rows: Vec<Vec<String>> = order
        .iter()
        .map(|(name, claim, c)| {
            let has = |outcomes: &[Outcome]| outcomes.iter().any(|o| &o.name == name);
            let (f, fr) = cells(find(full, name, claim), has(full));
            let (r, rr) = cells(find(reduced, name, claim), has(reduced));
            vec![
                format!("`{name}`"),
                statement(c),
                prose(&c.place),
                md(&c.paper),
                f,
                fr,
                r,
                rr,
            ]
        })
        .collect();
    let mut s = format!(
        "Full scale: {}. Reduced scenes: {}.\n\n",
        counts(&every_claim(full)),
        counts(&every_claim(reduced))
    );
    push_table(
        &mut s,
        &[
            "validation",
            "the paper's claim",
            "where",
            "paper",
            "full scale",
            "result",
            "reduced",
            "result",
        ],
        &rows,
    );
    s
}

/// Replaces the text between the [`MARKERS`] of the Markdown file `path` with `table`
/// (written atomically); an error names the file when it has no markers.
pub fn write_between_markers(path: &Path, table: &str) -> Result<()> {
    let doc = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let (open, close) = MARKERS;
    let (Some(a), Some(b)) = (doc.find(open), doc.find(close)) else {
        return Err(Error::bad_file(
            path,
            format!("no `{open}` and `{close}` lines to write the claims between"),
        ));
    };
    if b < a {
        return Err(Error::bad_file(
            path,
            format!("`{close}` comes before `{open}`"),
        ));
    }
    let start = a + open.len();
    let text = format!("{}\n{}{}", &doc[..start], table, &doc[b..]);
    crate::io::write_atomic(path, text.as_bytes())
}
