//! Every claim of the shipped definitions, walked: its rule is its phrase's (or it says
//! why not), and every measure it names (its own, an ordering's, each other reading's) is
//! one that the committed outcomes hold, at full scale and on the reduced scenes, or one
//! that a part of the scene a merge left pending gives, so a mistyped key cannot read as
//! "not measured". Every detail and study of the committed
//! outcomes is one its experiment declares for that scene, so the declarations that the
//! claims are checked against when a definition loads cannot fall behind the code.

use std::path::Path;

use persson_check::stats::Estimate;
use persson_check::validation::claims::{validate_claims, Measures, Rule};
use persson_check::validation::registry::Registry;
use persson_check::validation::source::builtin_sources;
use persson_check::validation::Scale;
use persson_check::validation::{ClaimSpec, Outcome};
use serde::Deserialize;

#[derive(Deserialize)]
struct Verdict {
    resolution: f64,
}

#[derive(Deserialize)]
struct Claims {
    name: String,
    verdict: Verdict,
    #[serde(default)]
    claims: Vec<ClaimSpec>,
}

fn definitions() -> Vec<Claims> {
    builtin_sources()
        .iter()
        .map(|s| toml::from_str(&s.text).unwrap())
        .collect()
}

#[test]
fn every_claim_has_its_phrases_rule_and_a_place() {
    let defs = definitions();
    let mut n = 0;
    for d in &defs {
        validate_claims(&d.claims, d.verdict.resolution)
            .unwrap_or_else(|e| panic!("{}: {e}", d.name));
        for c in &d.claims {
            assert!(
                c.place.contains("tex "),
                "{}/{}: no line of the paper",
                d.name,
                c.key
            );
            n += 1;
        }
    }
    assert!(n > 0);
}

/// The committed outcome of validation `name` at `scale` ("full" or "reduced").
fn committed_outcome(root: &Path, scale: &str, name: &str) -> Outcome {
    let path = root.join(scale).join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The measures a claim names.
fn measures_of(c: &ClaimSpec) -> Vec<String> {
    let mut m: Vec<String> = c.measure.iter().cloned().collect();
    if let (Some(_), Rule::Exceeds(other)) = (&c.measure, &c.rule) {
        m.push(other.clone());
    }
    m.extend(c.other_readings.iter().map(|r| r.measure.clone()));
    m
}

#[test]
fn every_measure_a_claim_names_is_in_the_committed_outcomes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
    let mut missing = Vec::new();
    let mut read = 0;
    for d in definitions() {
        for scale in ["full", "reduced"] {
            let o = committed_outcome(&root, scale, &d.name);
            read += 1;
            let measures = Measures {
                headline: Estimate::new(o.value, o.std_error),
                details: &o.details,
                studies: &o.studies,
                cross_checks: o
                    .cross_checks
                    .iter()
                    .map(|c| (c.solver.clone(), Estimate::new(c.value, c.std_error)))
                    .collect(),
                pending: o.merge.as_ref().map_or(&[][..], |m| &m.pending[..]),
            };
            for c in &d.claims {
                // A magnitude of the paper's own scene (`reduced = false`) may name a load
                // or grid of it that the reduced scene does not have; the full outcome must.
                if scale == "reduced" && !c.reduced {
                    continue;
                }
                for m in measures_of(c) {
                    let pending = measures.pending.iter().any(|p| p.gives(&m));
                    if measures.get(&m).is_none() && !pending {
                        missing.push(format!("{scale}/{}: {} names {m}", d.name, c.key));
                    }
                }
            }
        }
    }
    assert!(read >= 20, "{read} outcomes read");
    assert!(
        missing.is_empty(),
        "measures not in the outcomes:\n{}",
        missing.join("\n")
    );
}

#[test]
fn every_key_in_the_committed_outcomes_is_declared_by_its_experiment() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
    let registry = Registry::builtin();
    let mut undeclared = Vec::new();
    let mut read = 0;
    for source in builtin_sources() {
        let (name, _) = source.header().unwrap();
        for scale in [Scale::Full, Scale::Reduced] {
            let keys = registry
                .keys(&source, scale)
                .unwrap_or_else(|e| panic!("{name} [{scale}]: {e}"));
            let o = committed_outcome(&root, &scale.to_string(), &name);
            read += 1;
            for d in &o.details {
                if !keys.has_detail(&d.key, d.grid) {
                    let grid = d.grid.map(|n| format!("@{n}")).unwrap_or_default();
                    undeclared.push(format!("{scale}/{name}: detail {}{grid}", d.key));
                }
            }
            for s in &o.studies {
                match keys.study_columns(&s.key) {
                    None => undeclared.push(format!("{scale}/{name}: study {}", s.key)),
                    Some(columns) => {
                        for c in s.columns.iter().filter(|c| !columns.contains(&c.key)) {
                            undeclared.push(format!(
                                "{scale}/{name}: column {} of study {}",
                                c.key, s.key
                            ));
                        }
                    }
                }
            }
        }
    }
    assert!(read >= 20, "{read} outcomes read");
    assert!(
        undeclared.is_empty(),
        "written but not declared by the experiment:\n{}",
        undeclared.join("\n")
    );
}

#[test]
fn the_reviewers_guide_states_each_phrases_rule() {
    use persson_check::validation::claims::PHRASES;
    let guide = include_str!("../docs/reviewing.md");
    for p in PHRASES {
        let row = guide
            .lines()
            .find(|l| l.starts_with(&format!("| `{}` |", p.name())))
            .unwrap_or_else(|| panic!("docs/reviewing.md: no row for phrase `{}`", p.name()));
        assert!(row.contains(p.wordings()), "{row}");
        assert!(row.ends_with(&format!("| {} |", p.rule_text())), "{row}");
    }
}

/// Every committed outcome was concluded from the definition shipped beside it: its
/// recorded definition hash is the file's. An edit of a definition (a claim, a rule, a
/// reading) that is not followed by concluding its outcomes again fails here, so the claims
/// in results/ and docs/claims.md cannot fall behind the definitions.
#[test]
fn every_committed_outcome_was_concluded_from_its_shipped_definition() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
    let mut stale = Vec::new();
    for source in builtin_sources() {
        let (name, _) = source.header().unwrap();
        for scale in ["full", "reduced"] {
            let o = committed_outcome(&root, scale, &name);
            if o.definition_sha256 != source.sha256() {
                stale.push(format!("results/{scale}/{name}.json"));
            }
        }
    }
    assert!(
        stale.is_empty(),
        "outcomes concluded from another version of their definition (conclude them again: \
         `validate NAME --resume` on a copy of results/reduced, `validate NAME --full --merge \
         --accept-other-commit [--partial]` for results/full):\n{}",
        stale.join("\n")
    );
}

/// `docs/claims.md` holds the table that the committed outcomes give, as
/// `persson-check claims --write docs/claims.md` writes it: an outcome changed without
/// writing the table again fails here.
#[test]
fn the_committed_claims_table_is_the_committed_outcomes_table() {
    use persson_check::report::claims::{table, MARKERS};
    use persson_check::report::read_outcomes;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let read = |scale: &str| -> Vec<Outcome> {
        read_outcomes(&root.join("results").join(scale))
            .unwrap_or_else(|e| panic!("results/{scale}: {e}"))
            .into_iter()
            .map(|l| l.outcome)
            .collect()
    };
    let (full, reduced) = (read("full"), read("reduced"));
    assert!(!full.is_empty() && !reduced.is_empty());
    let doc = include_str!("../docs/claims.md");
    let (open, close) = MARKERS;
    let start = doc.find(open).expect("docs/claims.md: no opening marker") + open.len() + 1;
    let end = doc.find(close).expect("docs/claims.md: no closing marker");
    assert!(
        doc[start..end] == table(&full, &reduced),
        "docs/claims.md is not the table of results/full and results/reduced: write it again \
         with `persson-check claims --write docs/claims.md`"
    );
}
