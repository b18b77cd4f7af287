//! `compare BASE NEW`: a folder compared with itself moves nothing; a statistic moved by
//! five combined standard errors is flagged with its z, and a flipped claim is named. The
//! outcome of `tests/fixtures/outcomes/` is made by hand with every part compare reads
//! (details on a grid, a list of cross-checks, claims, a study with text, number, estimate
//! and empty cells).

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_persson-check");

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/outcomes")
}

/// Runs `compare base new --out <tmp>/compare.md`: the exit code and the JSON written.
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

#[test]
fn a_folder_compared_with_itself_moves_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/full");
    for base in [fixtures(), full] {
        let (code, c) = compare(&base, &base, tmp.path());
        assert_eq!(code, 0, "{}", c["summary"]);
        let stats = c["statistics"].as_array().unwrap();
        assert!(stats.len() > 10, "{}", c["summary"]);
        assert!(stats.iter().all(|s| s["identical"] == true));
        assert!(c["flips"].as_array().unwrap().is_empty());
        assert!(c["one_side"].as_array().unwrap().is_empty());
    }
    // The fixture's claims and study cells are statistics.
    let (_, c) = compare(&fixtures(), &fixtures(), tmp.path());
    let keys: Vec<&str> = c["statistics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["key"].as_str().unwrap())
        .collect();
    for key in [
        "headline",
        "detail:share@1024",
        "cross_check:cg",
        "claim:net_over_gross",
        "study:sensitivity/tol=1e-4/ratio",
        "study:sensitivity/hurst=0.3/realizations",
        "study:sensitivity/one_realization/ratio",
    ] {
        assert!(keys.contains(&key), "{key} not in {keys:?}");
    }
    assert!(
        !keys.contains(&"claim:onset"),
        "a claim not measured has no statistic"
    );
}

#[test]
fn a_statistic_moved_by_five_standard_errors_and_a_flipped_claim_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    let new = tmp.path().join("new");
    std::fs::create_dir(&new).unwrap();
    let text = std::fs::read_to_string(fixtures().join("claims_demo.json")).unwrap();
    let mut o: Value = serde_json::from_str(&text).unwrap();
    // The study cell tol=1e-4 / ratio moves by five combined standard errors (both sides
    // keep the error bar 0.004).
    let cell = &mut o["studies"][0]["rows"][0]["cells"][3];
    let (x, s) = (
        cell["value"].as_f64().unwrap(),
        cell["std_error"].as_f64().unwrap(),
    );
    cell["value"] = (x + 5.0 * s * 2f64.sqrt()).into();
    // The claim on net/gross flips.
    o["claims"][1]["result"] = "not reproduced".into();
    std::fs::write(new.join("claims_demo.json"), o.to_string()).unwrap();

    let (code, c) = compare(&fixtures(), &new, tmp.path());
    assert_eq!(code, 1, "{}", c["summary"]);
    let moved: Vec<&Value> = c["statistics"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["beyond"] == true)
        .collect();
    assert_eq!(moved.len(), 1, "{moved:?}");
    assert_eq!(moved[0]["key"], "study:sensitivity/tol=1e-4/ratio");
    let z = moved[0]["z"].as_f64().unwrap();
    assert!((z - 5.0).abs() < 1e-9, "z = {z}");
    let flips = c["flips"].as_array().unwrap();
    assert_eq!(flips.len(), 1, "{flips:?}");
    assert_eq!(flips[0]["key"], "claim:net_over_gross");
    assert_eq!(flips[0]["base"], "reproduced");
    assert_eq!(flips[0]["new"], "not reproduced");
    let md = std::fs::read_to_string(tmp.path().join("compare.md")).unwrap();
    assert!(md.contains("**+5.0**"), "{md}");
    assert!(md.contains("`claim:net_over_gross`"), "{md}");
    // Every other statistic is still identical.
    let identical = c["statistics"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["identical"] == true)
        .count();
    assert_eq!(identical + 1, c["statistics"].as_array().unwrap().len());
}

#[test]
fn a_perturbed_copy_of_the_full_results_is_flagged() {
    let tmp = tempfile::tempdir().unwrap();
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/full");
    let new = tmp.path().join("new");
    std::fs::create_dir(&new).unwrap();
    for entry in std::fs::read_dir(&full).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            std::fs::copy(&path, new.join(path.file_name().unwrap())).unwrap();
        }
    }
    let path = new.join("total_energy.json");
    let mut o: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    let s = o["std_error"].as_f64().unwrap();
    o["value"] = (o["value"].as_f64().unwrap() - 4.0 * s * 2f64.sqrt()).into();
    o["verdict"] = "holds".into();
    std::fs::write(&path, o.to_string()).unwrap();
    let (code, c) = compare(&full, &new, tmp.path());
    assert_eq!(code, 1);
    let moved: Vec<(&str, &str)> = c["statistics"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["beyond"] == true)
        .map(|s| (s["outcome"].as_str().unwrap(), s["key"].as_str().unwrap()))
        .collect();
    assert_eq!(moved, [("total_energy", "headline")]);
    let flips = c["flips"].as_array().unwrap();
    assert_eq!(flips.len(), 1);
    assert_eq!(flips[0]["key"], "verdict");
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
    let fixtures = fixtures();
    let f = fixtures.to_str().unwrap();
    let empty = tmp.path().to_str().unwrap();
    for (args, named) in [
        (vec!["/no/such/folder", f], "BASE"),
        (vec![f, empty], "NEW"),
        (vec![f, f, "--z", "0"], "--z"),
        (vec![f, f, "--z", "-1"], "--z"),
    ] {
        let (code, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
    }
    assert!(!out.exists(), "nothing written on bad input");
}
