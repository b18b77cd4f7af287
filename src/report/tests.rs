//! Tests of the scorecard.

use super::resolution::resolution_studies;
use super::*;
use crate::stats::Estimate;
use crate::validation::outcome::CrossCheck;
use crate::validation::{Detail, Guard, Scale, VerdictRule};
use serde_json::json;
use std::collections::BTreeMap;

fn detail(key: &str, name: &str, value: f64, err: f64, grid: Option<usize>) -> Detail {
    Detail {
        key: key.into(),
        name: name.into(),
        value: Estimate::new(value, err),
        persson: Some(1.0),
        paper: Some(2.0),
        grid,
    }
}

fn outcome(name: &str, verdict: Verdict, reproduced: Option<bool>, scale: Scale) -> Outcome {
    Outcome {
        name: name.into(),
        title: format!("Title of {name}"),
        assumption: format!("assumption of {name}"),
        statistic: "slope kappa = a_r / p~0".into(),
        value: 2.5,
        std_error: if verdict == Verdict::Inconclusive {
            f64::NAN
        } else {
            0.05
        },
        persson: 1.0,
        persson_text: "kappa = 1".into(),
        paper: "kappa ~ 2".into(),
        paper_value: Some(2.0),
        paper_range: None,
        // The paper's verdict as `reproduced` says.
        paper_verdict: match (verdict, reproduced) {
            (v, Some(true)) => v,
            (Verdict::Violated, Some(false)) => Verdict::Holds,
            _ => Verdict::Violated,
        },
        verdict,
        reproduced,
        rule: VerdictRule {
            significance: 3.0,
            resolution: 0.1,
        },
        scale,
        scene: json!({"n": 64, "refinements": [1, 2], "seeds": [1, 2, 3], "tol": 1e-8}),
        definition_sha256: format!("{:0>64}", name.len()),
        wall_s: 12.5,
        max_residual: 3e-9,
        details: vec![
            detail(
                "kappa_on_grid",
                "kappa on the 64x64 grid",
                2.9,
                0.1,
                Some(64),
            ),
            detail(
                "kappa_on_grid",
                "kappa on the 128x128 grid",
                2.7,
                0.1,
                Some(128),
            ),
            detail("deviation", "largest deviation", 0.08, f64::NAN, None),
        ],
        guards: vec![Guard {
            decided: true,
            key: "guard".into(),
            name: format!("guard of {name}"),
            passed: true,
            detail: "numbers behind it".into(),
        }],
        account: format!("Account of {name}: kappa = 2.5 +- 0.05."),
        golden: BTreeMap::from([("kappa".to_string(), 2.5)]),
        claims: Vec::new(),
        studies: Vec::new(),
        files: vec![
            format!("{name}.csv"),
            format!("{name}/fig.svg"),
            format!("{name}/fig.png"),
        ],
        threads: 2,
        solver: "gfmd".into(),
        cross_checks: Vec::new(),
        merge: None,
    }
}

/// Outcomes of every kind in `root/out`, their files, and snapshots in `root/golden`.
fn fixture(root: &Path) -> (PathBuf, PathBuf) {
    let from = root.join("out");
    let golden = root.join("golden");
    std::fs::create_dir_all(&golden).unwrap();
    let outcomes = [
        outcome("a_holds", Verdict::Holds, Some(true), Scale::Reduced),
        outcome("b_violated", Verdict::Violated, Some(false), Scale::Reduced),
        outcome(
            "c_inconclusive",
            Verdict::Inconclusive,
            None,
            Scale::Reduced,
        ),
        outcome("d_full", Verdict::Violated, Some(true), Scale::Full),
    ];
    for o in &outcomes {
        for f in &o.files {
            crate::io::write_atomic(&from.join(f), b"content").unwrap();
        }
        let json = serde_json::to_vec_pretty(o).unwrap();
        crate::io::write_atomic(&from.join(format!("{}.json", o.name)), &json).unwrap();
    }
    // One listed file is missing; a JSON file that is not an outcome is skipped.
    std::fs::remove_file(from.join("d_full.csv")).unwrap();
    std::fs::write(from.join("summary.json"), b"{\"n\": 3}").unwrap();
    let snap = |body: &str| {
        format!("---\nsource: tests/validations.rs\nexpression: outcome.golden\n---\n{body}\n")
    };
    std::fs::write(golden.join("a_holds.snap"), snap("{\n  \"kappa\": 2.5\n}")).unwrap();
    std::fs::write(
        golden.join("b_violated.snap"),
        snap("{\n  \"kappa\": 2.6\n}"),
    )
    .unwrap();
    std::fs::write(golden.join("d_full.snap"), snap("{\n  \"kappa\": 9.9\n}")).unwrap();
    (from, golden)
}

/// The table row of validation `name`, split into cells.
fn row<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let escaped = md(name);
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("| [{escaped}]")))
        .unwrap_or_else(|| panic!("no row for {name}"));
    line.trim_matches('|').split(" | ").map(str::trim).collect()
}

/// Relative link targets in the Markdown (images and files, not anchors).
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(k) = rest.find("](") {
        rest = &rest[k + 2..];
        let end = rest.find(')').unwrap();
        let target = &rest[..end];
        if !target.starts_with('#') {
            out.push(target.replace("%20", " "));
        }
    }
    out
}

#[test]
fn scorecard_states_every_verdict_and_links_existing_files() {
    let root = tempfile::tempdir().unwrap();
    let (from, golden) = fixture(root.path());
    // The scorecard lives in another folder: links must climb out of it.
    let out = root.path().join("review").join("scorecard.md");
    // The speed study as `speed --out` leaves it in the outcomes' folder.
    crate::speed::tiny_study().write(&from).unwrap();
    let opts = ReportOptions {
        from: from.clone(),
        out: out.clone(),
        golden: Some(golden),
    };
    let summary = write(&opts).unwrap();
    assert_eq!(
        summary.validations,
        ["a_holds", "b_violated", "c_inconclusive", "d_full"]
    );
    let text = std::fs::read_to_string(&out).unwrap();
    table_rows_state_verdicts(&text);
    summary_names_what_needs_attention(&text, &summary);
    sections_show_account_details_and_resolution(&text, out.parent().unwrap());
    links_point_at_existing_files(&text, &out);
    speed_and_provenance_are_shown(&text, &from);
    // Written atomically: nothing else in the scorecard's folder than it and its figures.
    let mut beside: Vec<String> = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    beside.sort();
    assert_eq!(beside, ["resolution", "scorecard.md"]);
    assert!(summary
        .files
        .iter()
        .all(|f| f.starts_with(out.parent().unwrap())));
}

/// Columns: validation, assumption, statistic, Persson, measured (solver), cross-check,
/// paper, verdict, reproduced, golden match, grid, seeds, wall time, solver residual.
fn table_rows_state_verdicts(text: &str) {
    let a = row(text, "a_holds");
    assert_eq!(a.len(), 14, "{a:?}");
    assert_eq!(
        &a[3..],
        [
            "1",
            "2.500 ± 0.050 (GFMD)",
            "not run",
            "2 (holds)",
            "holds",
            "as the paper",
            "yes",
            "64, 128",
            "3 (1-3)",
            "12.5 s",
            "3e-9"
        ]
    );
    let b = row(text, "b_violated");
    assert_eq!(b[7], "violated");
    assert_eq!(b[8], "**not as the paper**");
    assert_eq!(b[9], "no (1 differ: kappa = 2.5, snapshot 2.6)");
    let c = row(text, "c_inconclusive");
    assert_eq!(
        c[4], "2.5 (one realization: no error bar) (GFMD)",
        "NaN read back from null"
    );
    assert_eq!(c[7], "**inconclusive**");
    assert_eq!(c[8], "inconclusive");
    assert_eq!(c[9], "not checked");
    let d = row(text, "d_full");
    assert!(d[0].ends_with("(full)"), "{d:?}");
    assert_eq!(d[9], "n/a (full scene)", "full scenes are not compared");
}

/// The summary says plainly what is inconclusive or contradicted.
fn summary_names_what_needs_attention(text: &str, summary: &ReportSummary) {
    assert!(
        text.contains(
            "2 of 4 headline verdicts as the paper's (1 hold, 2 violated, 1 inconclusive)"
        ),
        "{}",
        &text[..600]
    );
    assert!(text.contains("not as the paper: `b_violated`"));
    assert!(text.contains("c\\_inconclusive: the verdict is INCONCLUSIVE"));
    assert!(text.contains(
        "b\\_violated: the headline verdict is NOT THE PAPER'S: this run finds the assumption violated where the paper finds it holds"
    ));
    // The verdict, a golden value that differs, an inconclusive verdict: passing guards and
    // the paper's claims are not in the list.
    assert_eq!(summary.attention.len(), 3, "{:?}", summary.attention);
    assert!(summary
        .attention
        .iter()
        .any(|a| a.starts_with("b_violated: 1 golden value(s) differ")));
    assert!(!summary.attention.iter().any(|a| a.contains("guard")));
}

/// Sections: account, details, resolution study (its figure in the scorecard's folder
/// `dir`), missing files.
fn sections_show_account_details_and_resolution(text: &str, dir: &Path) {
    assert!(text.contains("## a\\_holds: Title of a\\_holds"));
    assert!(text.contains("Account of a\\_holds: kappa = 2.5 +- 0.05."));
    assert!(text.contains("| largest deviation | 0.08 (no error estimate) | 1 | 2 | — |"));
    assert!(text.contains("## Statistic against grid resolution"));
    assert!(
        text.contains(
            "| a\\_holds | kappa on the 128x128 grid | 128 | 2.70 ± 0.10 | -0.2 | 1 | 2 |"
        ),
        "resolution row"
    );
    assert!(dir.join("resolution/resolution_a_holds.png").exists());
    assert!(text.contains("**Missing files**") && text.contains("d\\_full.csv"));
}

/// Every relative link points at an existing file, images included.
fn links_point_at_existing_files(text: &str, out: &Path) {
    let targets = links(text);
    let base = out.parent().unwrap();
    assert!(
        targets.iter().any(|t| t == "../out/a_holds/fig.png"),
        "{targets:?}"
    );
    assert!(targets.iter().any(|t| t.ends_with("speed/speed_error.png")));
    assert!(targets
        .iter()
        .any(|t| t.ends_with("resolution/resolution_b_violated.png")));
    for t in &targets {
        assert!(base.join(t).exists(), "link to missing file {t}");
    }
}

/// The speed section and the provenance block.
fn speed_and_provenance_are_shown(text: &str, from: &Path) {
    assert!(text.contains("## Speed against error"));
    assert!(text.contains(&format!(
        "From `{}`, run started",
        from.join("speed.json").display()
    )));
    assert!(text.contains("**Times are from one run on a shared machine**"));
    assert!(text.contains("exponent k (iterations ~ N^k)"));
    assert!(text.contains("| cg | 1e-4 |") && text.contains("| gfmd | 1e-8 |"));
    assert!(text.contains("**The floor**") && text.contains("| pairs / iteration |"));
    assert!(text.contains("**Warm starts**") && text.contains("| load +1% |"));
    assert!(from.join("speed/tolerance.csv").exists() && from.join("speed.json").exists());
    assert!(text.contains("## Provenance"));
    assert!(text.contains(&format!("commit `{}", provenance::COMMIT)));
    assert!(text.contains("- Machine: "));
    assert!(
        text.contains(&format!("`{:0>64}`", 7)),
        "definition hash of a_holds"
    );
    assert!(text.contains(&format!(
        "`persson-check validate d_full --full --out {}`",
        from.display()
    )));
    assert!(text.contains("| a\\_holds | reduced |") && text.contains("| 1, 2, 3 | 2 | 12.5 s |"));
}

#[test]
fn a_missing_speed_study_is_said_with_how_to_produce_it() {
    let root = tempfile::tempdir().unwrap();
    let (from, _) = fixture(root.path());
    let out = from.join("scorecard.md");
    let opts = ReportOptions {
        from: from.clone(),
        out: out.clone(),
        golden: None,
    };
    write(&opts).unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains(&format!(
        "No speed study in `{dir}`. `persson-check speed --out {dir}` runs it",
        dir = from.display()
    )));
    assert_eq!(row(&text, "a_holds")[9], "not checked", "no golden folder");
    // Links from a scorecard inside the outcomes' folder are plain relative paths.
    assert!(text.contains("](a_holds/fig.png)"));

    // JSON, but not a study (a file that is not JSON at all is refused as a damaged outcome).
    std::fs::write(from.join("speed.json"), r#"{"tolerance": "no rows"}"#).unwrap();
    write(&opts).unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.contains("**The speed study in `"),
        "an unreadable study is said"
    );
}

#[test]
fn unreadable_outcomes_and_empty_folders_are_errors() {
    let root = tempfile::tempdir().unwrap();
    let opts = ReportOptions {
        from: root.path().to_path_buf(),
        out: root.path().join("s.md"),
        golden: None,
    };
    let e = write(&opts).unwrap_err().to_string();
    assert!(e.contains("no outcomes"), "{e}");
    std::fs::write(
        root.path().join("broken.json"),
        br#"{"name": "broken", "statistic": "s", "verdict": "maybe"}"#,
    )
    .unwrap();
    let e = write(&opts).unwrap_err().to_string();
    assert!(e.contains("broken.json") && e.contains("maybe"), "{e}");
    assert!(!root.path().join("s.md").exists());
}

#[test]
fn attention_names_a_headline_verdict_not_the_papers_and_a_failed_guard() {
    let mut o = outcome("e_holds", Verdict::Holds, Some(false), Scale::Reduced);
    let loaded = |o: Outcome| Loaded {
        outcome: o,
        path: PathBuf::from("e_holds.json"),
        modified: None,
    };
    let lines = attention::attention(&[loaded(o.clone())], &[GoldenMatch::FullScene]);
    assert_eq!(lines.len(), 1);
    assert!(
        lines[0].contains("finds the assumption holds where the paper finds it violated"),
        "{lines:?}"
    );
    // A contradicted claim is counted in the claims section, never here.
    o.verdict = Verdict::Violated;
    o.reproduced = Some(true);
    assert!(attention::attention(&[loaded(o.clone())], &[GoldenMatch::FullScene]).is_empty());
    o.guards[0].passed = false;
    let lines = attention::attention(&[loaded(o)], &[GoldenMatch::FullScene]);
    assert!(lines[0].contains("guard FAILED"), "{lines:?}");
}

#[test]
fn statistics_on_several_grids_are_grouped_by_key() {
    let mut o = outcome("a", Verdict::Violated, Some(true), Scale::Reduced);
    o.details.push(detail(
        "other",
        "kappa on the 64x64 grid, other",
        1.0,
        0.1,
        Some(64),
    ));
    let loaded = Loaded {
        outcome: o,
        path: PathBuf::from("a.json"),
        modified: None,
    };
    let studies = resolution_studies(&[loaded]);
    let groups = &studies[0].groups;
    assert_eq!(groups.len(), 2);
    assert_eq!(groups[0].0, "kappa_on_grid");
    assert_eq!(
        groups[0].1.iter().map(|(n, _)| *n).collect::<Vec<_>>(),
        vec![64, 128]
    );
    assert_eq!(groups[1].0, "other");
}

#[test]
fn the_cross_check_is_shown_and_a_disagreement_needs_attention() {
    let mut o = outcome("a", Verdict::Violated, Some(true), Scale::Reduced);
    o.solver = "gfmd".into();
    o.cross_checks = vec![CrossCheck {
        solver: "cg".into(),
        value: 2.51,
        std_error: 0.05,
        agrees: true,
    }];
    assert_eq!(table::cross_check_cell(&o), "CG 2.510 ± 0.050, agrees");
    let mut three = o.clone();
    three.cross_checks.push(CrossCheck {
        solver: "fire".into(),
        value: 2.49,
        std_error: 0.05,
        agrees: true,
    });
    assert_eq!(
        table::cross_check_cell(&three),
        "CG 2.510 ± 0.050, agrees; FIRE 2.490 ± 0.050, agrees"
    );
    assert_eq!(table::measured_cell(&o), "2.500 ± 0.050 (GFMD)");
    let loaded = |o: Outcome| Loaded {
        outcome: o,
        path: PathBuf::from("a.json"),
        modified: None,
    };
    assert!(attention::attention(&[loaded(o.clone())], &[GoldenMatch::FullScene]).is_empty());
    let c = &mut o.cross_checks[0];
    c.value = 3.5;
    c.agrees = false;
    assert!(table::cross_check_cell(&o).contains("DISAGREES"));
    let lines = attention::attention(&[loaded(o)], &[GoldenMatch::FullScene]);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(
        lines[0].starts_with("a: the two solvers DISAGREE"),
        "{lines:?}"
    );
    assert!(
        lines[0].contains("gfmd 2.500 ± 0.050 against cg 3.500 ± 0.050"),
        "{lines:?}"
    );
}

#[test]
fn one_realization_shows_no_error_bar_and_no_nan() {
    assert_eq!(
        table::headline(0.6411, f64::NAN),
        "0.6411 (one realization: no error bar)"
    );
    let root = tempfile::tempdir().unwrap();
    let mut o = outcome("one", Verdict::Inconclusive, None, Scale::Full);
    o.cross_checks = vec![CrossCheck {
        solver: "cg".into(),
        value: 2.5,
        std_error: f64::NAN,
        agrees: true,
    }];
    std::fs::write(
        root.path().join("one.json"),
        serde_json::to_vec(&o).unwrap(),
    )
    .unwrap();
    let opts = ReportOptions {
        from: root.path().to_path_buf(),
        out: root.path().join("s.md"),
        golden: None,
    };
    write(&opts).unwrap();
    let text = std::fs::read_to_string(root.path().join("s.md")).unwrap();
    assert!(!text.contains("NaN"), "NaN in the scorecard");
    assert!(text.contains("one realization: no error bar"));
}

/// An outcome of one realization as written by hand: the error bars `null` (serde_json's
/// NaN) in the headline, a detail, a study's row and the cross-check, one detail's
/// error bar left out, and NaN in the outcome's own text.
const NULL_ERROR_BARS: &str = r#"{
  "name": "one_seed", "title": "One realization", "assumption": "(c) p = 0 absorbs",
  "statistic": "flux_in / flux_out", "value": 0.8585, "std_error": null,
  "persson": 0.0, "persson_text": "ratio 0", "paper": "ratio 1.13", "paper_value": 1.13,
  "paper_verdict": "violated", "verdict": "inconclusive", "reproduced": null,
  "rule": {"significance": 3.0, "resolution": 0.05}, "scale": "reduced",
  "scene": {"n": 512, "seeds": [1]}, "definition_sha256": "00",
  "wall_s": 5.1, "max_residual": 9e-9,
  "details": [
    {"key": "flux_in", "name": "flux in", "value": {"value": 0.0025, "std_error": null},
     "persson": null, "paper": 0.00675, "grid": null},
    {"key": "flux_out", "name": "flux out", "value": {"value": 0.0029}, "paper": 0.00597},
    {"key": "x", "name": "x = 0.35 +- NaN", "value": {"value": null, "std_error": null},
     "persson": 0.42, "paper": null}
  ],
  "checks": [{"key": "enter", "name": "points enter contact", "passed": false,
              "detail": "flux in = 0.0025 +- NaN", "decided": false}],
  "account": "One realization: the ratio is 0.86 +- NaN (z = NaN).",
  "golden": {"ratio": 0.86, "z": null},
  "studies": [{"key": "sensitivity", "title": "Sensitivity", "columns": [
      {"key": "flux_in", "label": "in, %", "percent": true},
      {"key": "flux_out", "label": "out, %", "percent": true}],
    "rows": [{"key": "tol=0.0001", "label": "tol = 1e-4",
      "cells": [{"value": 0.00525, "std_error": null}, {"value": 0.005}]}]}],
  "files": [], "threads": 1, "solver": "gfmd",
  "cross_check": {"solver": "cg", "value": 0.8585, "std_error": null, "agrees": true}
}"#;

#[test]
fn outcomes_with_null_or_absent_error_bars_are_read_and_say_so() {
    let root = tempfile::tempdir().unwrap();
    std::fs::write(root.path().join("one_seed.json"), NULL_ERROR_BARS).unwrap();
    // The same outcome with every error bar left out and no cross-check.
    let mut absent: serde_json::Value = serde_json::from_str(NULL_ERROR_BARS).unwrap();
    fn drop_error_bars(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(map) => {
                map.remove("std_error");
                map.values_mut().for_each(drop_error_bars);
            }
            serde_json::Value::Array(items) => items.iter_mut().for_each(drop_error_bars),
            _ => {}
        }
    }
    drop_error_bars(&mut absent);
    absent["name"] = json!("one_seed_absent");
    absent["cross_check"] = serde_json::Value::Null;
    std::fs::write(
        root.path().join("one_seed_absent.json"),
        serde_json::to_vec(&absent).unwrap(),
    )
    .unwrap();
    let out = root.path().join("s.md");
    let opts = ReportOptions {
        from: root.path().to_path_buf(),
        out: out.clone(),
        golden: None,
    };
    let summary = write(&opts).unwrap();
    assert_eq!(summary.validations, ["one_seed", "one_seed_absent"]);
    let text = std::fs::read_to_string(&out).unwrap();
    let nan = text
        .split(|c: char| !c.is_ascii_alphanumeric())
        .any(|word| word.eq_ignore_ascii_case("nan"));
    assert!(!nan, "NaN in the scorecard:\n{text}");

    let null = row(&text, "one_seed");
    assert_eq!(null[4], "0.8585 (one realization: no error bar) (GFMD)");
    assert_eq!(null[5], "CG 0.8585 (one realization: no error bar), agrees");
    assert_eq!(null[8], "inconclusive");
    let absent = row(&text, "one_seed_absent");
    assert_eq!(absent[4], null[4], "absent reads as null");
    assert_eq!(absent[5], "not run");
    for line in [
        "| flux in | 0.0025 (no error estimate) | — | 0.00675 | — |",
        "| flux out | 0.0029 (no error estimate) | — | 0.00597 | — |",
        "| x = 0.35 (no error bar) | n/a | 0.42 | — | — |",
        "| tol = 1e-4 | 0.525 (no error estimate) | 0.5 (no error estimate) |",
        "| points enter contact | not decided (1 realization) | flux in = 0.0025 (no error bar) |",
        "One realization: the ratio is 0.86 (no error bar) (z = n/a).",
    ] {
        assert!(text.contains(line), "no line {line:?} in\n{text}");
    }
}

#[test]
fn a_merged_outcome_is_dated_by_its_last_job_not_its_file() {
    use crate::validation::outcome::{MergeRecord, ShardRecord};
    let shard = |end: &str| ShardRecord {
        shard: "unsharded".into(),
        host: "vm".into(),
        start: "2026-01-01T00:00:00Z".into(),
        end: end.into(),
        jobs: 1,
        commit: "c".into(),
    };
    let mut o = outcome("a", Verdict::Violated, Some(true), Scale::Full);
    let file_time = std::time::UNIX_EPOCH + std::time::Duration::from_secs(1_900_000_000);
    let loaded = |o: &Outcome| Loaded {
        outcome: o.clone(),
        path: PathBuf::from("a.json"),
        modified: Some(file_time),
    };
    // A plain run: the file's time.
    assert_eq!(
        provenance_section::computed(&loaded(&o)),
        provenance::rfc3339_utc(file_time)
    );
    o.merge = Some(MergeRecord {
        commit: "c".into(),
        other_commits_accepted: false,
        shards: vec![shard("2026-03-02T10:00:00Z"), shard("2026-03-04T08:00:00Z")],
        pending: Vec::new(),
    });
    assert_eq!(
        provenance_section::computed(&loaded(&o)),
        "2026-03-04T08:00:00Z"
    );
}
