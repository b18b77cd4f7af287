//! `compare BASE NEW` on the committed outcomes: a folder compared with itself moves
//! nothing; a study cell and a claim's measurement moved by five and four combined standard
//! errors are flagged with their z, and a claim whose result flips is named; a perturbed
//! copy of results/full is flagged. The changed outcomes are made with the crate's own
//! types ([`Outcome`], [`ClaimResult`], [`Cell`]) from the committed files.

use std::path::{Path, PathBuf};
use std::process::Command;

use persson_check::experiments::study::Cell;
use persson_check::validation::{ClaimResult, Outcome, Verdict};
use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_persson-check");

fn results(scale: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("results")
        .join(scale)
}

/// Runs `compare base new --out <out>/compare.md`: the exit code and the JSON written.
fn compare(base: &Path, new: &Path, out: &Path) -> (i32, Value) {
    let md = out.join("compare.md");
    let output = Command::new(BIN)
        .args(["compare"])
        .arg(base)
        .arg(new)
        .arg("--out")
        .arg(&md)
        .output()
        .unwrap();
    let code = output.status.code().unwrap();
    assert!(
        code == 0 || code == 1,
        "compare failed ({code}): {}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(md.is_file(), "no Markdown page");
    let json = std::fs::read(out.join("compare.json")).unwrap();
    (code, serde_json::from_slice(&json).unwrap())
}

/// A copy of the outcome files of results/full in `<tmp>/new`.
fn copy_of_full(tmp: &Path) -> PathBuf {
    let new = tmp.join("new");
    std::fs::create_dir(&new).unwrap();
    for entry in std::fs::read_dir(results("full")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            std::fs::copy(&path, new.join(path.file_name().unwrap())).unwrap();
        }
    }
    new
}

fn read(path: &Path) -> Outcome {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

fn write(path: &Path, o: &Outcome) {
    std::fs::write(path, serde_json::to_vec_pretty(o).unwrap()).unwrap();
}

fn statistics(c: &Value) -> &[Value] {
    c["statistics"].as_array().unwrap()
}

fn beyond(c: &Value) -> Vec<(&str, &str, f64)> {
    statistics(c)
        .iter()
        .filter(|s| s["beyond"] == true)
        .map(|s| {
            (
                s["outcome"].as_str().unwrap(),
                s["key"].as_str().unwrap(),
                s["z"].as_f64().unwrap(),
            )
        })
        .collect()
}

#[test]
fn a_folder_compared_with_itself_moves_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    for scale in ["full", "reduced"] {
        let (code, c) = compare(&results(scale), &results(scale), tmp.path());
        assert_eq!(code, 0, "{scale}: {}", c["summary"]);
        assert!(statistics(&c).len() > 100, "{scale}: {}", c["summary"]);
        assert!(statistics(&c).iter().all(|s| s["identical"] == true));
        assert!(c["flips"].as_array().unwrap().is_empty());
        assert!(c["one_side"].as_array().unwrap().is_empty());
    }
    // Every measured claim and every estimate of a study is a statistic of its outcome.
    let (_, c) = compare(&results("full"), &results("full"), tmp.path());
    let keys: Vec<(&str, &str)> = statistics(&c)
        .iter()
        .map(|s| (s["outcome"].as_str().unwrap(), s["key"].as_str().unwrap()))
        .collect();
    let (mut claims, mut cells) = (0, 0);
    for name in ["c_flux", "contact_area", "e_frozen"] {
        let o = read(&results("full").join(format!("{name}.json")));
        for claim in o.claims.iter().filter(|c| c.measured.is_some()) {
            let key = format!("claim:{}", claim.key);
            assert!(keys.contains(&(name, key.as_str())), "{name} {key}");
            claims += 1;
        }
        for study in &o.studies {
            for row in &study.rows {
                for (cell, column) in row.cells.iter().zip(&study.columns) {
                    if let Cell::Estimate(_) = cell {
                        let key = format!("study:{}/{}/{}", study.key, row.key, column.key);
                        assert!(keys.contains(&(name, key.as_str())), "{name} {key}");
                        cells += 1;
                    }
                }
            }
        }
    }
    assert!(claims > 5 && cells > 20, "{claims} claims, {cells} cells");
}

#[test]
fn a_moved_study_cell_a_moved_claim_and_a_flipped_claim_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    let new = copy_of_full(tmp.path());
    let path = new.join("c_flux.json");
    let mut o = read(&path);
    // The first estimate of the flux's sensitivity study with an error bar moves by five
    // combined standard errors (both sides keep the same error bar).
    let (study, row, column) = {
        let s = &mut o.studies[0];
        let (r, k) = s
            .rows
            .iter()
            .enumerate()
            .find_map(|(r, row)| {
                row.cells.iter().position(|c| {
                    matches!(c, Cell::Estimate(e) if e.std_error > 0.0 && e.value.is_finite())
                }).map(|k| (r, k))
            })
            .expect("an estimate with an error bar");
        let Cell::Estimate(e) = &mut s.rows[r].cells[k] else {
            unreachable!()
        };
        e.value += 5.0 * e.std_error * 2f64.sqrt();
        (
            s.key.clone(),
            s.rows[r].key.clone(),
            s.columns[k].key.clone(),
        )
    };
    // The first measured claim moves by four; the first reproduced claim flips.
    let moved = o
        .claims
        .iter_mut()
        .find(|c| c.measured.is_some_and(|m| m.std_error > 0.0))
        .expect("a claim with an error bar");
    let m = moved.measured.as_mut().unwrap();
    m.value -= 4.0 * m.std_error * 2f64.sqrt();
    let moved = moved.key.clone();
    let flipped = o
        .claims
        .iter_mut()
        .find(|c| c.result == ClaimResult::Reproduced)
        .expect("a reproduced claim");
    flipped.result = ClaimResult::Contradicted;
    let flipped = flipped.key.clone();
    write(&path, &o);

    let (code, c) = compare(&results("full"), &new, tmp.path());
    assert_eq!(code, 1, "{}", c["summary"]);
    let cell_key = format!("study:{study}/{row}/{column}");
    let claim_key = format!("claim:{moved}");
    let found = beyond(&c);
    assert_eq!(found.len(), 2, "{found:?}");
    for (key, z) in [(cell_key.as_str(), 5.0), (claim_key.as_str(), -4.0)] {
        let (_, _, got) = *found
            .iter()
            .find(|(o, k, _)| *o == "c_flux" && *k == key)
            .unwrap_or_else(|| panic!("{key} not flagged: {found:?}"));
        assert!((got - z).abs() < 1e-9, "{key}: z = {got}, not {z}");
    }
    let flips = c["flips"].as_array().unwrap();
    assert_eq!(flips.len(), 1, "{flips:?}");
    assert_eq!(flips[0]["key"], format!("claim:{flipped}"));
    assert_eq!(flips[0]["base"], "reproduced");
    assert_eq!(flips[0]["new"], "contradicted");
    let md = std::fs::read_to_string(tmp.path().join("compare.md")).unwrap();
    assert!(md.contains("**+5.0**") && md.contains("**-4.0**"), "{md}");
    assert!(md.contains(&format!("`claim:{flipped}`")), "{md}");
    // Every other statistic is still identical.
    let identical = statistics(&c)
        .iter()
        .filter(|s| s["identical"] == true)
        .count();
    assert_eq!(identical + 2, statistics(&c).len());
}

#[test]
fn a_perturbed_copy_of_the_full_results_is_flagged() {
    let tmp = tempfile::tempdir().unwrap();
    let new = copy_of_full(tmp.path());
    let path = new.join("total_energy.json");
    let mut o = read(&path);
    let before = o.verdict;
    o.value -= 4.0 * o.std_error * 2f64.sqrt();
    o.verdict = if before == Verdict::Holds {
        Verdict::Violated
    } else {
        Verdict::Holds
    };
    write(&path, &o);
    let (code, c) = compare(&results("full"), &new, tmp.path());
    assert_eq!(code, 1);
    let found = beyond(&c);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].0, found[0].1), ("total_energy", "headline"));
    assert!((found[0].2 + 4.0).abs() < 1e-9, "z = {}", found[0].2);
    let flips = c["flips"].as_array().unwrap();
    assert_eq!(flips.len(), 1);
    assert_eq!(flips[0]["key"], "verdict");
    assert_eq!(flips[0]["base"], before.to_string());
}

#[test]
fn bad_input_names_the_argument_and_exits_2() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("c.md");
    let run = |args: &[&str]| {
        let o = Command::new(BIN)
            .arg("compare")
            .args(args)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        (
            o.status.code().unwrap(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let full = results("full");
    let f = full.to_str().unwrap();
    let empty = tempfile::tempdir().unwrap();
    let empty = empty.path().to_str().unwrap();
    // A file that looks like an outcome but is none.
    let broken = tmp.path().join("broken");
    std::fs::create_dir(&broken).unwrap();
    std::fs::write(
        broken.join("x.json"),
        r#"{"name": "x", "statistic": "s", "verdict": "holds"}"#,
    )
    .unwrap();
    let b = broken.to_str().unwrap();
    for (args, named) in [
        (vec!["/no/such/folder", f], "BASE"),
        (vec![f, empty], "NEW"),
        (vec![f, f, "--z", "0"], "--z"),
        (vec![f, f, "--z", "-1"], "--z"),
        (vec![f, b], "x.json"),
    ] {
        let (code, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
    }
    assert!(!out.exists(), "nothing written on bad input");
}

#[test]
fn a_reader_that_closes_the_pipe_ends_compare_quietly() {
    let tmp = tempfile::tempdir().unwrap();
    let full = results("full");
    let mut child = Command::new(BIN)
        .arg("compare")
        .arg(&full)
        .arg(&full)
        .arg("--out")
        .arg(tmp.path().join("compare.md"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // The reader goes before compare has read its outcomes, let alone printed.
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(141), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
    // The files are written before the summary is printed.
    assert!(tmp.path().join("compare.json").exists());
}
