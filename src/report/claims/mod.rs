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

use self::blocks::block;
use self::lists::{count_table, listed, lists};
use self::tally::every_claim;
use crate::error::{Error, Result};
use crate::validation::register::Register;
use crate::validation::Outcome;

mod blocks;
mod cells;
mod figure;
mod lists;
mod tally;

pub use self::figure::{chart, position};
pub use self::tally::{counts, headlines, Class, Counts};

/// The marker lines of the page in `docs/claims.md`.
pub const MARKERS: (&str, &str) = ("<!-- paper-claims -->", "<!-- /paper-claims -->");

/// The file stem of the chart of the claims ([`chart`]).
pub const CHART: &str = "claims";

/// The page beside the claims page that prices each undecided claim
/// (`scripts/power_plan.py --remaining`).
pub const COSTS: &str = "undecided.md";

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
    lists(s, outcomes, None);
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
    lists(&mut s, &full, Some(COSTS));
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
