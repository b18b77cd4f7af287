//! The paper's claims as a reviewer reads them: a count table (validation by result), the
//! contradicted claims first, one line each with the class of the contradiction (the data
//! disagree, or a reading decides), then the claims not established (the side they lean to
//! and what would decide them), the reproduced ones grouped by assumption, then what is
//! counted apart (consistency checks, statements the paper makes two ways, claims not
//! measured), and one block per claim below with its reading, rule, rival readings,
//! amendments and the reduced scene's value. The same page is the scorecard's claims
//! section (one scale) and `docs/claims.md` (the full scale, with the reduced scenes'
//! values in the blocks), written between two markers of a Markdown file (`persson-check
//! claims --write`); [`chart`] is the figure beside it: every evidence claim's measurement
//! against its rule's region, in units of the rule's tolerance.
//!
//! Every cell comes from the outcomes' `claims` ([`crate::validation::claims`]) and the
//! register of rules ([`crate::validation::register`]): the statement, the rule and the
//! paper's value are the definitions' data, the result is the one rule's.

use std::fmt::Write as _;
use std::path::Path;

use super::format::{md, num, pm, prose, push_table};
use crate::error::{Error, Result};
use crate::plot::{IntervalChart, IntervalRow};
use crate::stats::{Estimate, Region};
use crate::validation::claims::{ClaimKind, ErrorKind, Unit};
use crate::validation::register::{claim_id, Register};
use crate::validation::{ClaimOutcome, ClaimResult, Outcome, Verdict};

/// The marker lines of the page in `docs/claims.md`.
pub const MARKERS: (&str, &str) = ("<!-- paper-claims -->", "<!-- /paper-claims -->");

/// The file stem of the chart of the claims ([`chart`]).
pub const CHART: &str = "claims";

/// Why an evidence claim is contradicted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// Every reading the claim states is contradicted too (or it states none).
    DisagreesWithData,
    /// A rival reading of the paper's words gives another result.
    DecidedByAReading,
}

impl Class {
    /// The class in words.
    pub fn text(self) -> &'static str {
        match self {
            Class::DisagreesWithData => "disagrees with the data",
            Class::DecidedByAReading => "decided by a reading",
        }
    }

    /// The class of a contradicted claim: decided by a reading when a rival reading is
    /// measured and not contradicted.
    pub fn of(c: &ClaimOutcome) -> Self {
        let rival_differs = c.readings.iter().any(|r| {
            matches!(
                r.result,
                ClaimResult::Reproduced | ClaimResult::NotEstablished
            )
        });
        if rival_differs {
            Class::DecidedByAReading
        } else {
            Class::DisagreesWithData
        }
    }
}

/// The claims of a set of outcomes counted by result.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    /// Every claim.
    pub all: usize,
    /// Evidence claims reproduced.
    pub reproduced: usize,
    /// Evidence claims contradicted.
    pub contradicted: usize,
    /// Of those, decided by a reading.
    pub by_reading: usize,
    /// Evidence claims not established.
    pub not_established: usize,
    /// Evidence claims not measured.
    pub not_measured: usize,
    /// Evidence claims not judged at this scale.
    pub not_judged: usize,
    /// Consistency checks.
    pub consistency: usize,
    /// Statements the paper makes two ways.
    pub two_ways: usize,
}

impl Counts {
    /// The counts of `claims`.
    pub fn of<'a>(claims: impl IntoIterator<Item = &'a ClaimOutcome>) -> Self {
        let mut n = Counts::default();
        for c in claims {
            n.all += 1;
            match c.kind {
                ClaimKind::Consistency => n.consistency += 1,
                ClaimKind::Inconsistent => n.two_ways += 1,
                ClaimKind::Evidence => match c.result {
                    ClaimResult::Reproduced => n.reproduced += 1,
                    ClaimResult::Contradicted => {
                        n.contradicted += 1;
                        if Class::of(c) == Class::DecidedByAReading {
                            n.by_reading += 1;
                        }
                    }
                    ClaimResult::NotEstablished => n.not_established += 1,
                    ClaimResult::NotMeasured => n.not_measured += 1,
                    ClaimResult::NotJudgedAtThisScale => n.not_judged += 1,
                },
            }
        }
        n
    }

    /// Evidence claims.
    pub fn evidence(&self) -> usize {
        self.all - self.consistency - self.two_ways
    }

    /// The counts in words.
    pub fn text(&self) -> String {
        let judged = if self.not_judged > 0 {
            format!(", {} not judged at this scale", self.not_judged)
        } else {
            String::new()
        };
        format!(
            "{} claims; {} evidence: {} reproduced, {} contradicted ({} disagree with the \
             data, {} decided by a reading), {} not established, {} not measured{judged}; \
             counted apart: {} consistency checks, {} statements the paper makes two ways",
            self.all,
            self.evidence(),
            self.reproduced,
            self.contradicted,
            self.contradicted - self.by_reading,
            self.by_reading,
            self.not_established,
            self.not_measured,
            self.consistency,
            self.two_ways,
        )
    }
}

/// The claims of every outcome, in order.
fn every_claim<'a>(outcomes: &[&'a Outcome]) -> Vec<&'a ClaimOutcome> {
    outcomes.iter().flat_map(|o| &o.claims).collect()
}

/// The claim counts of `outcomes` in words (the scorecard's and the main job's summary).
pub fn counts(outcomes: &[&Outcome]) -> String {
    Counts::of(every_claim(outcomes)).text()
}

/// The headline verdicts of `outcomes` against the paper's, in words: "10 of 10 headline
/// verdicts as the paper's (0 hold, 10 violated, 0 inconclusive)".
pub fn headlines(outcomes: &[&Outcome]) -> String {
    let count = |v: Verdict| outcomes.iter().filter(|o| o.verdict == v).count();
    let same = outcomes
        .iter()
        .filter(|o| o.reproduced == Some(true))
        .count();
    let differ: Vec<String> = outcomes
        .iter()
        .filter(|o| o.reproduced == Some(false))
        .map(|o| format!("`{}`", o.name))
        .collect();
    format!(
        "{same} of {} headline verdicts as the paper's ({} hold, {} violated, {} \
         inconclusive){}",
        outcomes.len(),
        count(Verdict::Holds),
        count(Verdict::Violated),
        count(Verdict::Inconclusive),
        if differ.is_empty() {
            String::new()
        } else {
            format!("; not as the paper: {}", differ.join(", "))
        }
    )
}

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

/// The lines of the paper's source a place names: "tex 612-617, 660-661".
fn tex(place: &str) -> String {
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
fn anchor(validation: &str, key: &str) -> String {
    format!(
        "c-{}",
        claim_id(validation, key)
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
            .collect::<String>()
    )
}

/// The claim's key, linked to its block.
fn key_cell(validation: &str, c: &ClaimOutcome) -> String {
    format!(
        "[`{}`](#{})",
        claim_id(validation, &c.key),
        anchor(validation, &c.key)
    )
}

/// A value in the claim's unit (in % where it is a share or a relative change).
fn value(c: &ClaimOutcome, e: Option<Estimate>) -> String {
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
fn measured_cell(c: &ClaimOutcome) -> String {
    let v = value(c, c.measured);
    match (c.measured, c.realizations) {
        (Some(_), Some(n)) if c.error == ErrorKind::Fit => format!("{v} (fit, n = {n})"),
        (Some(_), Some(n)) => format!("{v} (n = {n})"),
        _ => v,
    }
}

/// A result in words, marked where it needs attention.
fn result_text(r: ClaimResult) -> String {
    match r {
        ClaimResult::Contradicted => "**contradicted**".into(),
        ClaimResult::NotEstablished => "*not established*".into(),
        r => r.text().into(),
    }
}

/// The claims of `outcomes` with their validation's name, in the outcomes' order.
fn listed<'a>(outcomes: &[&'a Outcome]) -> Vec<(&'a str, &'a ClaimOutcome)> {
    outcomes
        .iter()
        .flat_map(|o| o.claims.iter().map(move |c| (o.name.as_str(), c)))
        .collect()
}

/// The count table: one row per validation, a total, and the headline line.
fn count_table(s: &mut String, outcomes: &[&Outcome]) {
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
fn lists(s: &mut String, outcomes: &[&Outcome]) {
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
fn block(
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

/// The scorecard's section: the page for one scale.
pub fn section(s: &mut String, outcomes: &[&Outcome]) {
    if every_claim(outcomes).is_empty() {
        return;
    }
    let _ = writeln!(s, "## The paper's claims\n");
    let _ = writeln!(
        s,
        "{}. {}.\n",
        headlines(outcomes),
        Counts::of(every_claim(outcomes)).text()
    );
    count_table(s, outcomes);
    s.push('\n');
    lists(s, outcomes);
    let _ = writeln!(s, "### Each claim\n");
    for (v, c) in listed(outcomes) {
        block(s, v, c, None, None);
    }
}

/// The page of `docs/claims.md`: the full outcomes' claims, with the reduced scenes'
/// result in each block, the earlier rules of amended claims from `register`, and the
/// chart (`chart_file`, relative to the page) beside the count table.
pub fn page(
    full: &[Outcome],
    reduced: &[Outcome],
    register: Option<&Register>,
    chart_file: Option<&str>,
) -> String {
    let full: Vec<&Outcome> = full.iter().collect();
    let reduced: Vec<&Outcome> = reduced.iter().collect();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "**Full scale** (the paper's scenes, [`results/full`](../results/full/)): {}. {}.\n",
        headlines(&full),
        Counts::of(every_claim(&full)).text()
    );
    let _ = writeln!(
        s,
        "**Reduced scenes** (the main job, [`results/reduced`](../results/reduced/)): {}. \
         {}.\n",
        headlines(&reduced),
        Counts::of(every_claim(&reduced)).text()
    );
    let _ = writeln!(s, "### Counts (full scale)\n");
    count_table(&mut s, &full);
    s.push('\n');
    if let Some(file) = chart_file {
        let _ = writeln!(
            s,
            "![Each evidence claim's measurement against its rule, in units of the rule's \
             tolerance]({file})\n\nThe figure: one row per evidence claim measured at full \
             scale, grouped by validation; the dot is the measurement's distance into the \
             rule's region in units of the rule's tolerance (0 is the rule's edge, right of \
             it inside; 1 is the centre of a two-sided region), the bar its interval (+-3 \
             standard errors, wider for fewer than four realizations); a bar across 0 is \
             not established, an arrow lies beyond the axis (a dot beyond it is not drawn). \
             A claim measured without an error bar (one realization) has no row.\n"
        );
    }
    lists(&mut s, &full);
    let _ = writeln!(s, "### Each claim\n");
    for (v, c) in listed(&full) {
        let other = reduced
            .iter()
            .find(|o| o.name == v)
            .and_then(|o| o.claims.iter().find(|r| r.key == c.key))
            .map(|r| ("Reduced scene", r));
        block(&mut s, v, c, other, register);
    }
    s
}

/// A claim's position for the chart: its measurement's distance into the rule's region in
/// units of the tolerance (the rule's edge at 0, inside positive; a two-sided region's
/// centre at 1) and its interval's half width in those units.
pub fn position(c: &ClaimOutcome, resolution: f64) -> Option<(f64, f64)> {
    let (e, region) = (c.judged()?, c.region()?);
    if !(e.value.is_finite() && e.has_error()) {
        return None;
    }
    let half = c.interval_z.unwrap_or(3.0) * e.std_error;
    let band = c.unit.map_or(resolution, |u| u.band_width(resolution));
    Some(match region {
        Region::Interval { lo, hi, .. } if lo.is_finite() && hi.is_finite() => {
            let w = 0.5 * (hi - lo);
            let centre = 0.5 * (hi + lo);
            ((w - (e.value - centre).abs()) / w, half / w)
        }
        Region::Interval { lo, .. } if lo.is_finite() => ((e.value - lo) / band, half / band),
        Region::Interval { hi, .. } => ((hi - e.value) / band, half / band),
        Region::Outside(lo, hi) => {
            let w = 0.5 * (hi - lo);
            (((e.value - 0.5 * (hi + lo)).abs() - w) / w, half / w)
        }
        Region::Except(t) => ((e.value - t).abs() / band, half / band),
    })
}

/// The chart of the evidence claims of `outcomes` measured with an error bar: each
/// claim's position against its rule ([`position`], a number of a measure's own unit in
/// units of its validation's resolution), grouped by validation, coloured by result.
pub fn chart(outcomes: &[&Outcome]) -> IntervalChart {
    let kinds = ["reproduced", "contradicted", "not established"];
    let rows = outcomes
        .iter()
        .flat_map(|o| {
            o.claims
                .iter()
                .filter(|c| c.kind == ClaimKind::Evidence)
                .filter_map(move |c| {
                    let kind = match c.result {
                        ClaimResult::Reproduced => 0,
                        ClaimResult::Contradicted => 1,
                        ClaimResult::NotEstablished => 2,
                        _ => return None,
                    };
                    let (value, half) = position(c, o.rule.resolution)?;
                    Some(IntervalRow {
                        group: o.name.clone(),
                        label: c.key.clone(),
                        value,
                        half,
                        kind,
                    })
                })
        })
        .collect();
    IntervalChart {
        name: CHART.into(),
        title: "The paper's claims against their rules".into(),
        x_label: "distance into the rule's region, in units of its tolerance (0: the edge)".into(),
        range: (-6.0, 2.0),
        kinds: kinds.iter().map(|k| k.to_string()).collect(),
        rows,
    }
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
