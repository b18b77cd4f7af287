//! Bad input never turns into a plausible number: every command (`surface`, `solve`,
//! `validate`, `report`) run on a bad scene file, validation definition, `.npy` field or
//! command-line argument exits non-zero, names on stderr what is wrong, where (file and
//! field, or flag) and the allowed range, and writes no output.
//!
//! The cases are grouped by what they feed: [`scene`] files, validation [`definition`]s,
//! [`npy`] height fields, [`command_line`] flags, and the [`report`] command's inputs.
//!
//! Each case runs the real binary in a fresh temporary folder. Messages are matched on a
//! few key words, not whole sentences. Run with `--nocapture` to see every case's exit
//! code and first line of stderr.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_persson-check");

/// A valid scene: 32^2, zeta_max = 16 / 4 = 4, with a load.
const SCENE: &str = "\
[surface]
n = 32
hurst = 0.8
lambda_l = 16
lambda_s = 4
seed = 1

[solve]
p0 = 0.1
";

/// A valid validation definition.
const DEFINITION: &str = include_str!("../../validations/contact_area.toml");

/// Flags of a valid generated surface (32^2, zeta_max = 4).
const SURFACE_FLAGS: &[&str] = &[
    "--n",
    "32",
    "--hurst",
    "0.8",
    "--lambda-l",
    "16",
    "--lambda-s",
    "4",
    "--seed",
    "1",
];

mod command_line;
mod definition;
mod npy;
mod report;
mod scene;

/// Runs the binary in `dir`: exit code and stderr.
fn run(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The names of the entries in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Asserts that `args`, run in `dir`, fail without a panic, with a message holding every
/// one of `words`, and leave `dir` as it was (no output, no temporary file). Returns
/// stderr.
fn rejected(dir: &Path, args: &[&str], words: &[&str]) -> String {
    let before = listing(dir);
    let (code, stderr) = run(dir, args);
    eprintln!(
        "{} -> exit {code:?}: {}",
        args.join(" "),
        stderr.lines().next().unwrap_or("")
    );
    assert!(
        code.is_some_and(|c| c != 0),
        "{args:?}: exit {code:?}, stderr:\n{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{args:?} panicked:\n{stderr}");
    for w in words {
        assert!(
            stderr.contains(w),
            "{args:?}: stderr lacks {w:?}:\n{stderr}"
        );
    }
    assert_eq!(listing(dir), before, "{args:?}: the folder changed");
    stderr
}

/// `text` with `from` replaced by `to` (once), checking that `from` is there.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} not in the text");
    text.replacen(from, to, 1)
}

/// A definition with `from` replaced by `to` in its `[full]` scene only.
fn edit_full(text: &str, from: &str, to: &str) -> String {
    let (head, full) = text.split_once("[full]").expect("a [full] table");
    format!("{head}[full]{}", edit(full, from, to))
}

fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}
