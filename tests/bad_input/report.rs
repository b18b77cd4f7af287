//! The `report` command's inputs: outcome folders, golden snapshots, its flags; and the
//! `speed` command's grid.

use super::*;

/// A folder `from` with `files` (name, text) in `dir`.
fn outcomes(dir: &Path, files: &[(&str, &str)]) {
    std::fs::create_dir(dir.join("from")).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join("from").join(name), text).unwrap();
    }
}

#[test]
fn report_from_missing() {
    let dir = tempdir();
    rejected(
        dir.path(),
        &["report", "--from", "nowhere", "--out", "card.md"],
        &["--from", "nowhere", "existing folder"],
    );
}

#[test]
fn report_from_empty() {
    let dir = tempdir();
    outcomes(dir.path(), &[]);
    rejected(
        dir.path(),
        &["report", "--from", "from", "--out", "card.md"],
        &["from", "no outcomes"],
    );
    assert!(listing(&dir.path().join("from")).is_empty());
}

#[test]
fn report_outcome_missing_fields() {
    let dir = tempdir();
    let text = r#"{"name": "x", "statistic": "s", "verdict": "holds"}"#;
    outcomes(dir.path(), &[("x.json", text)]);
    rejected(
        dir.path(),
        &["report", "--from", "from", "--out", "card.md"],
        &["x.json", "missing field"],
    );
    assert_eq!(listing(&dir.path().join("from")), ["x.json"]);
}

#[test]
fn report_outcome_wrong_verdict() {
    let dir = tempdir();
    let text = r#"{"name": "x", "statistic": "s", "verdict": "maybe"}"#;
    outcomes(dir.path(), &[("x.json", text)]);
    rejected(
        dir.path(),
        &["report", "--from", "from", "--out", "card.md"],
        &["x.json", "maybe", "holds"],
    );
}

#[test]
fn report_outcome_truncated() {
    let dir = tempdir();
    outcomes(
        dir.path(),
        &[("x.json", r#"{"name": "x", "statistic": "s", "verd"#)],
    );
    rejected(
        dir.path(),
        &["report", "--from", "from", "--out", "card.md"],
        &["x.json", "not valid JSON"],
    );
    assert_eq!(listing(&dir.path().join("from")), ["x.json"]);
}

#[test]
fn speed_n_out_of_range() {
    // Below the smallest grid, or too small for the study's scene (lambda_s = 8 <
    // lambda_l = N/2).
    for (n, range) in [
        ("0", "[4, 32768]"),
        ("1", "[4, 32768]"),
        ("16", "fits the scene"),
    ] {
        let dir = tempdir();
        rejected(
            dir.path(),
            &["speed", "--n", n, "--out", "out"],
            &[&format!("--n = {n}"), range],
        );
        assert!(!dir.path().join("out").exists());
    }
}

#[test]
fn report_golden_missing() {
    let dir = tempdir();
    outcomes(dir.path(), &[]);
    rejected(
        dir.path(),
        &[
            "report", "--from", "from", "--out", "card.md", "--golden", "nowhere",
        ],
        &["--golden", "nowhere", "existing folder"],
    );
}

#[test]
fn report_out_is_a_folder() {
    let dir = tempdir();
    outcomes(dir.path(), &[]);
    std::fs::create_dir(dir.path().join("card.md")).unwrap();
    rejected(
        dir.path(),
        &["report", "--from", "from", "--out", "card.md"],
        &["--out", "card.md", "folder"],
    );
}

#[test]
fn report_missing_out() {
    let dir = tempdir();
    rejected(dir.path(), &["report"], &["--out", "required"]);
}
