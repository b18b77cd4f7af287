//! Every claim of the shipped definitions, walked: its rule is its phrase's (or it says
//! why not), and every measure it names (its own, an ordering's, each other reading's) is
//! one that the committed outcomes hold, at full scale and on the reduced scenes, or one
//! that a part of the scene a merge left pending gives, so a mistyped key cannot read as
//! "not measured". Every detail and study of the committed
//! outcomes is one its experiment declares for that scene, so the declarations that the
//! claims are checked against when a definition loads cannot fall behind the code.

use std::path::Path;

use persson_check::stats::Estimate;
use persson_check::validation::claims::{validate_claims, Measure, Measures, Rule};
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
fn measures_of(c: &ClaimSpec) -> Vec<Measure> {
    let mut m: Vec<Measure> = c.measure.iter().cloned().collect();
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
                scene: &o.scene,
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

/// Every claim's rule is the last one registered for it in `validations/register.json`,
/// and every earlier one has its amendment, with its reason, in the claim: a rule changed
/// after its verdict was seen without saying so fails here.
#[test]
fn every_rule_is_registered_and_every_change_is_an_amendment() {
    use persson_check::validation::register::{Register, REGISTER_FILE};
    use persson_check::validation::source::claims_of;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let register = Register::read(&root.join(REGISTER_FILE)).unwrap();
    let claims = claims_of(&builtin_sources()).unwrap();
    let problems = register.problems(&claims);
    assert!(
        problems.is_empty(),
        "the register of rules (validations/register.json) against the definitions:\n{}",
        problems.join("\n")
    );
    // Every registered rule of an amended claim records the verdicts it gave.
    for (id, rules) in &register.claims {
        for r in &rules[..rules.len() - 1] {
            assert!(
                r.full.is_some() || r.reduced.is_some(),
                "{id}: {}",
                r.sha256
            );
        }
    }
}

/// Every claim that counts as evidence can be reproduced and can be contradicted: an
/// estimate well inside its rule's region (away from its alternative) with a small error
/// bar reproduces it, one well outside contradicts it. A claim whose rule cannot give both
/// (a region of every value, a rule that holds its alternative everywhere) fails here.
#[test]
fn every_evidence_claim_can_pass_and_can_fail() {
    use persson_check::stats::Region;
    use persson_check::validation::claims::{ClaimKind, ClaimResult};
    let mut wrong = Vec::new();
    let mut walked = 0;
    for d in definitions() {
        for c in d.claims.iter().filter(|c| c.kind() == ClaimKind::Evidence) {
            walked += 1;
            let region = match &c.rule {
                Rule::Exceeds(_) => Region::above(0.0),
                r => r.region(c.value).expect("a region"),
            };
            let alt = c.alternative.as_ref().map(|a| a.value);
            let (inside, outside) = points(region, alt);
            let tiny = |x: f64| Estimate::new(x, 1e-9 * (1.0 + x.abs()));
            let got = (
                c.judge_estimate(tiny(inside), 3.0),
                c.judge_estimate(tiny(outside), 3.0),
            );
            if got != (ClaimResult::Reproduced, ClaimResult::Contradicted) {
                wrong.push(format!(
                    "{}.{}: {inside} -> {:?}, {outside} -> {:?}",
                    d.name, c.key, got.0, got.1
                ));
            }
        }
    }
    assert!(walked > 80, "{walked} evidence claims walked");
    assert!(
        wrong.is_empty(),
        "claims that cannot pass or fail:\n{}",
        wrong.join("\n")
    );
}

/// A point inside `region` away from `alternative`, and one outside it.
fn points(region: persson_check::stats::Region, alternative: Option<f64>) -> (f64, f64) {
    use persson_check::stats::Region;
    match region {
        Region::Interval { lo, hi, .. } if lo.is_finite() && hi.is_finite() => {
            let w = hi - lo;
            let inside = match alternative {
                // The middle of the larger part beside the alternative.
                Some(a) if a > lo && a < hi => {
                    if a - lo > hi - a {
                        0.5 * (lo + a)
                    } else {
                        0.5 * (a + hi)
                    }
                }
                _ => 0.5 * (lo + hi),
            };
            (inside, hi + w.max(1e-6))
        }
        Region::Interval { lo, .. } if lo.is_finite() => {
            let step = lo.abs().max(1.0);
            let inside = match alternative {
                Some(a) if a > lo => a + step,
                _ => lo + step,
            };
            (inside, lo - step)
        }
        Region::Interval { hi, .. } => {
            let step = hi.abs().max(1.0);
            let inside = match alternative {
                Some(a) if a < hi => a - step,
                _ => hi - step,
            };
            (inside, hi + step)
        }
        Region::Outside(lo, hi) => (hi + (hi - lo).max(1e-6), 0.5 * (lo + hi)),
        Region::Except(t) => (t + 1.0, t),
    }
}

/// `docs/claims.md` holds the table that the committed outcomes give, as
/// `persson-check claims --write docs/claims.md` writes it: an outcome changed without
/// writing the table again fails here.
#[test]
fn the_committed_claims_table_is_the_committed_outcomes_table() {
    use persson_check::report::claims::{page, MARKERS};
    use persson_check::report::read_outcomes;
    use persson_check::validation::register::{Register, REGISTER_FILE};
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
    let register = Register::read(&root.join(REGISTER_FILE)).unwrap();
    assert!(
        doc[start..end] == page(&full, &reduced, Some(&register), Some("figures/claims.svg")),
        "docs/claims.md is not the page of results/full and results/reduced: write it again \
         with `persson-check claims --write docs/claims.md`"
    );
}

/// `docs/undecided.md` prices exactly the evidence claims that the committed full-scale
/// outcomes leave not established: a merge that decides or undecides a claim without
/// writing the page again (`scripts/power_plan.py --remaining`) fails here.
#[test]
fn the_priced_undecided_claims_are_the_committed_undecided_claims() {
    use persson_check::report::read_outcomes;
    use persson_check::validation::claims::{ClaimKind, ClaimResult};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut undecided: Vec<String> = read_outcomes(&root.join("results/full"))
        .unwrap()
        .into_iter()
        .flat_map(|l| {
            let name = l.outcome.name.clone();
            l.outcome
                .claims
                .into_iter()
                .filter(|c| {
                    c.kind == ClaimKind::Evidence && c.result == ClaimResult::NotEstablished
                })
                .map(move |c| format!("{name}.{}", c.key))
        })
        .collect();
    let page = include_str!("../docs/undecided.md");
    let mut priced: Vec<String> = page
        .lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .filter_map(|l| l.split_once('`').map(|(id, _)| id.to_string()))
        .collect();
    undecided.sort();
    priced.sort();
    assert!(!priced.is_empty());
    assert_eq!(
        priced, undecided,
        "docs/undecided.md is not priced on results/full: write it again with \
         `scripts/power_plan.py --remaining --write docs/undecided.md`"
    );
    let count = format!("**{} not established.**", undecided.len());
    assert!(
        page.contains(&count),
        "docs/undecided.md does not open with {count}"
    );
}
