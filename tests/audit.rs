//! `audit`: the cheapest committed full job of one validation, recomputed alone with this
//! build, equals its stored result byte for byte; after one byte of a copy of that result
//! is changed, the audit names the number that differs and exits 1. The copy holding that
//! one result, the audit lists every other validation and solver of the crate as without a
//! stored result; results/full has a result for each and none that no job names.

use std::path::Path;
use std::process::Command;

use persson_check::engine::solver::SolverKind;
use persson_check::validation::audit::candidates;
use persson_check::validation::source::builtin_sources;
use persson_check::validation::{Registry, RunOptions};
use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_persson-check");

/// Runs `audit --from from --job key --out from/audit`: the exit code and `audit.json`.
fn audit(from: &Path, key: &str) -> (i32, Value) {
    let out = from.join("audit");
    let output = Command::new(BIN)
        .args(["audit", "--from"])
        .arg(from)
        .args(["--job", key, "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let code = output.status.code().unwrap();
    assert!(
        code == 0 || code == 1,
        "audit failed ({code}): {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains(key), "one line per job: {stdout}");
    assert!(out.join("audit.md").is_file());
    let json = std::fs::read(out.join("audit.json")).unwrap();
    (code, serde_json::from_slice(&json).unwrap())
}

#[test]
fn the_cheapest_committed_job_recomputes_identical_and_a_changed_byte_is_found() {
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/full");
    let found = candidates(&Registry::builtin(), &builtin_sources(), &full).unwrap();
    assert!(found.orphans.is_empty(), "{:?}", found.orphans);
    assert!(found.unstored.is_empty(), "{:?}", found.unstored);
    let cheapest = found
        .candidates
        .iter()
        .filter(|c| c.validations.iter().any(|v| v == "contact_area"))
        .min_by(|a, b| a.estimate_s.total_cmp(&b.estimate_s))
        .unwrap();

    let tmp = tempfile::tempdir().unwrap();
    let copy = tmp.path().join(&cheapest.relative);
    std::fs::create_dir_all(copy.parent().unwrap()).unwrap();
    std::fs::copy(full.join(&cheapest.relative), &copy).unwrap();
    let (code, a) = audit(tmp.path(), &cheapest.key);
    assert_eq!(code, 0, "{}", a["summary"]);
    assert_eq!(a["jobs"][0]["finding"], "identical", "{}", a["jobs"][0]);
    assert_eq!(a["passed"], true);
    // Every other validation and solver of the crate has no stored result in the copy.
    let unstored: Vec<(&str, &str)> = a["unstored"]
        .as_array()
        .unwrap()
        .iter()
        .map(|u| {
            (
                u["validation"].as_str().unwrap(),
                u["solver"].as_str().unwrap(),
            )
        })
        .collect();
    // Solvers outside a default run with no result in the copy are named once.
    let idle: Vec<&str> = a["idle_solvers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap())
        .collect();
    for solver in SolverKind::ALL {
        let pair = ("contact_area", solver.name());
        let default = RunOptions::DEFAULT_SOLVERS.contains(&solver);
        assert_eq!(
            unstored.contains(&pair),
            default && solver != cheapest.solver,
            "{pair:?} in {unstored:?}"
        );
        assert_eq!(
            unstored.contains(&("d_onset", solver.name())),
            default,
            "{unstored:?}"
        );
        assert_eq!(idle.contains(&solver.name()), !default, "{idle:?}");
    }

    // One digit of the result changes: the first digit after the sixth in the result.
    let mut bytes = std::fs::read(&copy).unwrap();
    let result = bytes.windows(9).position(|w| w == b"\"result\":").unwrap();
    let k = (result..bytes.len())
        .filter(|&i| bytes[i].is_ascii_digit())
        .nth(6)
        .unwrap();
    bytes[k] = if bytes[k] == b'9' { b'8' } else { bytes[k] + 1 };
    std::fs::write(&copy, &bytes).unwrap();
    let (code, a) = audit(tmp.path(), &cheapest.key);
    assert_eq!(code, 1, "{}", a["summary"]);
    let job = &a["jobs"][0];
    assert_eq!(job["finding"], "differs", "{job}");
    assert_eq!(job["count"], 1, "{job}");
    let d = &job["differences"][0];
    assert!(d["path"].as_str().unwrap().starts_with("result."), "{d}");
    assert!(d["abs"].as_f64().unwrap() > 0.0, "{d}");
    assert_ne!(d["stored"], d["recomputed"]);
    assert_eq!(a["passed"], false);
}

#[test]
fn bad_input_names_the_flag_and_exits_2() {
    let tmp = tempfile::tempdir().unwrap();
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/full");
    let full = full.to_str().unwrap();
    let out = tmp.path().join("audit");
    let empty = tmp.path().to_str().unwrap();
    for (args, named) in [
        (vec!["--from", full, "--budget", "20"], "--budget"),
        (vec!["--from", full, "--budget", "0m"], "--budget"),
        (vec!["--from", full, "--job", "0123456789abcdef"], "--job"),
        (
            vec!["--from", full, "--validation", "no_such"],
            "--validation",
        ),
        (vec!["--from", empty], "--from"),
    ] {
        let o = Command::new(BIN)
            .arg("audit")
            .args(&args)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
        assert!(
            !out.join("audit.json").exists(),
            "{args:?}: nothing written"
        );
    }
}
