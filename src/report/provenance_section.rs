//! The provenance section: what is needed to reproduce any row.

use std::fmt::Write as _;

use super::format::{duration, md, table};
use super::outcomes::{scene_seeds, Loaded};
use super::Scorecard;
use crate::provenance;
use crate::validation::Scale;

impl Scorecard<'_> {
    pub(super) fn provenance(&self, s: &mut String) {
        let _ = writeln!(s, "## Provenance\n");
        let golden = self
            .opts
            .golden
            .as_ref()
            .map_or_else(|| "none".into(), |g| format!("`{}`", g.display()));
        let _ = writeln!(
            s,
            "- Scorecard written: {} (UTC)\n\
             - Code: persson-check {}, commit `{}`\n\
             - Machine: {}\n\
             - Threads of this process: {}\n\
             - Outcomes read from: `{}`; golden snapshots: {golden}\n\
             - Outcome files record the definition's SHA-256, the scene, the seeds and the \
             threads, but not the commit that computed them: the commit above is the one \
             that wrote this scorecard. To reproduce a row, check out that commit and run \
             the command in the last column; the definition hash identifies the validation \
             file. An outcome merged from stored job results is dated by the end of its last \
             job, from its merge record; any other by its file's modification time, which a \
             fresh checkout resets.\n",
            self.generated_at,
            provenance::VERSION,
            provenance::commit_label(),
            md(&self.machine.summary()),
            rayon::current_num_threads(),
            self.opts.from.display(),
        );
        let rows: Vec<Vec<String>> = self
            .loaded
            .iter()
            .map(|l| {
                let o = &l.outcome;
                let seeds = scene_seeds(&o.scene).map_or_else(
                    || "—".into(),
                    |v| {
                        v.iter()
                            .map(|x| x.to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    },
                );
                let full = if o.scale == Scale::Full {
                    " --full"
                } else {
                    ""
                };
                vec![
                    md(&o.name),
                    o.scale.to_string(),
                    format!("`{}`", o.definition_sha256),
                    seeds,
                    o.threads.to_string(),
                    duration(o.wall_s),
                    computed(l),
                    format!(
                        "`persson-check validate {}{full} --out {}`",
                        o.name,
                        self.opts.from.display()
                    ),
                ]
            })
            .collect();
        s.push_str(&table(
            &[
                "validation",
                "scale",
                "definition SHA-256",
                "seeds",
                "threads",
                "wall time",
                "computed (UTC)",
                "reproduce with",
            ],
            &rows,
        ));
    }
}

/// When an outcome was computed: the end of its last job for one merged from stored job
/// results (a property of the outcome), else its file's modification time.
pub(super) fn computed(l: &Loaded) -> String {
    l.outcome
        .merge
        .as_ref()
        .and_then(|m| m.shards.iter().map(|s| s.end.as_str()).max())
        .map(str::to_string)
        .or_else(|| l.modified.map(provenance::rfc3339_utc))
        .unwrap_or_else(|| "—".into())
}
