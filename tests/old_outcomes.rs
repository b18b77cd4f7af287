//! Outcomes written by earlier versions still read, to the values they were written with,
//! and render in the scorecard.
//!
//! The fixture is `results/full/b_drift.json` as first committed (2026-11-25), before an
//! outcome had claims, studies or several cross-checks: its one cross-check is the object
//! `cross_check`. The tests read it as written, and with the numbers a writer may leave out
//! (error bars, a cross-check's numbers) left out, which read as NaN and print as words.

use std::path::{Path, PathBuf};

use persson_check::report::{read_outcome, write, ReportOptions};
use persson_check::validation::Outcome;
use serde_json::Value;

use crate::common::assert_no_nan;

/// The fixture: an outcome of 2026-11-25 with one cross-check and no claims.
fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/b_drift_full_outcome_of_2026-11-25_one_cross_check_no_claims.json")
}

fn fixture_json() -> Value {
    serde_json::from_str(&std::fs::read_to_string(fixture()).unwrap()).unwrap()
}

/// A number of the JSON, as an `f64`, NaN for `null`.
fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

/// Writes `json` as `<dir>/b_drift.json`, reads it back and writes the scorecard of the
/// folder (no speed study, no golden values); returns the outcome and the scorecard.
fn read_and_render(dir: &Path, json: &Value) -> (Outcome, String) {
    let path = dir.join("b_drift.json");
    std::fs::write(&path, serde_json::to_string_pretty(json).unwrap()).unwrap();
    let outcome = read_outcome(&path).unwrap();
    let card = dir.join("scorecard.md");
    let opts = ReportOptions {
        from: dir.to_path_buf(),
        out: card.clone(),
        golden: None,
    };
    let summary = write(&opts).unwrap();
    assert_eq!(summary.validations, ["b_drift"]);
    (outcome, std::fs::read_to_string(card).unwrap())
}

#[test]
fn an_outcome_with_one_cross_check_and_no_claims_reads_as_written() {
    let json = fixture_json();
    assert!(json.get("cross_checks").is_none() && json.get("claims").is_none());
    let o = read_outcome(&fixture()).unwrap();
    assert_eq!(o.name, "b_drift");
    assert_eq!(o.value, num(&json["value"]));
    assert_eq!(o.std_error, num(&json["std_error"]));
    assert_eq!(o.persson, num(&json["persson"]));
    assert_eq!(o.paper_value, None);
    assert_eq!(o.paper_range, None);
    assert!(o.claims.is_empty() && o.studies.is_empty());
    // The one cross-check reads as a list of one.
    let written = &json["cross_check"];
    assert_eq!(o.cross_checks.len(), 1);
    let cc = &o.cross_checks[0];
    assert_eq!(cc.solver, written["solver"].as_str().unwrap());
    assert_eq!(cc.value, num(&written["value"]));
    assert_eq!(cc.std_error, num(&written["std_error"]));
    assert_eq!(cc.agrees, written["agrees"].as_bool().unwrap());
    // Every detail to the digit; `null` reads as none.
    let details = json["details"].as_array().unwrap();
    assert_eq!(o.details.len(), details.len());
    assert!(!details.is_empty());
    for (d, w) in o.details.iter().zip(details) {
        assert_eq!(d.key, w["key"].as_str().unwrap());
        assert_eq!(d.value.value, num(&w["value"]["value"]));
        assert_eq!(d.value.std_error, num(&w["value"]["std_error"]));
        assert_eq!(d.persson, w["persson"].as_f64());
        assert_eq!(d.paper, w["paper"].as_f64());
        assert_eq!(d.grid, w["grid"].as_u64().map(|g| g as usize));
    }
    let golden = json["golden"].as_object().unwrap();
    assert_eq!(o.golden.len(), golden.len());
    for (k, v) in golden {
        assert_eq!(o.golden[k], num(v), "{k}");
    }
    let shards = json["merge"]["shards"].as_array().unwrap().len();
    assert_eq!(o.merge.as_ref().unwrap().shards.len(), shards);
}

#[test]
fn an_outcome_with_one_cross_check_and_no_claims_renders() {
    let dir = tempfile::tempdir().unwrap();
    let (o, card) = read_and_render(dir.path(), &fixture_json());
    assert_no_nan("the scorecard", &card);
    // The headline, to four digits as the summary table prints it.
    assert!(card.contains("b\\_drift"), "{card}");
    assert!(card.contains("-0.0160"), "{card}");
    assert!(o.std_error.is_finite() && o.cross_checks[0].std_error.is_finite());
}

#[test]
fn numbers_left_out_of_an_old_outcome_read_as_nan_and_print_as_words() {
    let mut json = fixture_json();
    let top = json.as_object_mut().unwrap();
    top.remove("std_error");
    top.remove("persson");
    let cc = top["cross_check"].as_object_mut().unwrap();
    cc.remove("value");
    cc.remove("std_error");
    for d in top["details"].as_array_mut().unwrap() {
        d["value"].as_object_mut().unwrap().remove("std_error");
        d["value"]["value"] = Value::Null;
    }
    let dir = tempfile::tempdir().unwrap();
    let (o, card) = read_and_render(dir.path(), &json);
    assert!(o.value.is_finite());
    assert!(o.std_error.is_nan() && o.persson.is_nan());
    assert!(o.cross_checks[0].value.is_nan() && o.cross_checks[0].std_error.is_nan());
    assert!(!o.details.is_empty());
    for d in &o.details {
        assert!(
            d.value.value.is_nan() && d.value.std_error.is_nan(),
            "{d:?}"
        );
    }
    assert_no_nan("the scorecard", &card);
    assert!(card.contains("n/a"), "{card}");
    assert!(card.contains("no error bar"), "{card}");
}
