//! Helpers shared by the test modules: definition folders with a spliced scene, outcomes
//! and tables without what depends on the clock or the machine, and the source files of a
//! folder.

pub mod contact;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

/// Longest a single run may take before a test gives up.
pub const TIMEOUT: Duration = Duration::from_secs(180);

/// The validation definitions shipped in `validations/`.
pub fn validations_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("validations")
}

/// A temporary folder of definitions: copies of the built-in `copies`, and `c_reentry`
/// with its `[reduced]` table replaced by `reduced` (which must end with a blank line) and
/// without its claims, which name the shipped scenes' measures (its variants' among them):
/// the tests that splice a scene compare runs, not claims.
pub fn definitions_with_reentry(reduced: &str, copies: &[&str]) -> tempfile::TempDir {
    let validations = validations_dir();
    let dir = tempfile::tempdir().unwrap();
    for name in copies {
        let file = format!("{name}.toml");
        std::fs::copy(validations.join(&file), dir.path().join(&file)).unwrap();
    }
    let text = std::fs::read_to_string(validations.join("c_reentry.toml")).unwrap();
    let (head, rest) = text.split_at(text.find("[reduced]").expect("a [reduced] table"));
    let head = &head[..head.find("[[claims]]").unwrap_or(head.len())];
    let full = &rest[rest.find("[full]").expect("a [full] table")..];
    std::fs::write(
        dir.path().join("c_reentry.toml"),
        format!("{head}{reduced}{full}"),
    )
    .unwrap();
    dir
}

/// An outcome (`<out>/<name>.json`) without what depends on the clock or the machine: the
/// wall time, the thread count, the provenance of a merge, and the re-entry account's
/// sentence on the mean time of a sweep.
pub fn outcome_numbers(out: &Path, name: &str) -> Value {
    let bytes = std::fs::read(out.join(format!("{name}.json"))).unwrap();
    let mut v: Value = serde_json::from_slice(&bytes).unwrap();
    let o = v.as_object_mut().unwrap();
    o.remove("wall_s");
    o.remove("threads");
    o.remove("merge");
    let account = o["account"].as_str().unwrap();
    let cut = account.find("A sweep took").unwrap_or(account.len());
    o["account"] = account[..cut].to_string().into();
    v
}

/// A CSV table (`<out>/<name>.csv`) without its wall-time columns.
pub fn table_without_wall(out: &Path, name: &str) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(out.join(format!("{name}.csv"))).unwrap();
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let keep: Vec<bool> = rows[0].iter().map(|c| !c.starts_with("wall")).collect();
    rows.iter()
        .map(|r| {
            r.iter()
                .zip(&keep)
                .filter(|(_, &k)| k)
                .map(|(c, _)| c.to_string())
                .collect()
        })
        .collect()
}

/// Runs `cmd` to completion and checks that it succeeded.
pub fn finish(mut cmd: Command) {
    let output = cmd.output().unwrap();
    assert!(
        output.status.success(),
        "{cmd:?} failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Starts `cmd`, waits until `ready()` holds, and kills the process (SIGKILL).
pub fn kill_when(mut cmd: Command, what: &str, ready: impl Fn() -> bool) {
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if ready() {
            child.kill().unwrap();
            child.wait().unwrap();
            return;
        }
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the run ended ({status}) before {what}: make the scene longer");
        }
        assert!(start.elapsed() < TIMEOUT, "no {what} after {TIMEOUT:?}");
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// Asserts that `text` (what `what` prints) has no NaN in it, in any case.
pub fn assert_no_nan(what: &str, text: &str) {
    let nan = text
        .split(|c: char| !c.is_ascii_alphanumeric())
        .any(|word| word.eq_ignore_ascii_case("nan"));
    assert!(!nan, "{what} prints NaN:\n{text}");
}

/// Every `.rs` file under `dir` (its subfolders too), sorted.
pub fn rust_files(dir: &Path) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, &mut out);
    out.sort();
    out
}
