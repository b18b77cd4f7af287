//! Embeds the project's git commit and whether the working tree had local changes, for the
//! scorecard's provenance (`persson_check::provenance`), and generates the table of
//! built-in validation definitions from `validations/*.toml`
//! (`persson_check::validation::source::DEFINITIONS`).
//!
//! Sets `PERSSON_CHECK_COMMIT` (40 hex digits, or "unknown") and `PERSSON_CHECK_DIRTY`
//! ("yes", "no" or "unknown"). Without git, or outside the project's own repository (a
//! crate unpacked from a tarball, possibly inside some other repository), both are
//! "unknown" and the build goes on.

use std::path::{Path, PathBuf};
use std::process::Command;

fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .arg("-C")
        .arg(dir)
        .args(args)
        .output()
        .ok()?;
    if !out.status.success() {
        return None;
    }
    String::from_utf8(out.stdout).ok()
}

/// Writes `$OUT_DIR/definitions.rs`: `&[(name, include_str!(path)), ...]` for every
/// `validations/*.toml`, sorted by name.
fn definitions(manifest: &Path) {
    let dir = manifest.join("validations");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("the validations/ folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    let mut table = String::from("&[\n");
    for path in &files {
        let name = path
            .file_stem()
            .expect("a file name")
            .to_string_lossy()
            .to_string();
        table.push_str(&format!(
            "    ({name:?}, include_str!({:?})),\n",
            path.display().to_string()
        ));
    }
    table.push(']');
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("set by cargo"));
    std::fs::write(out.join("definitions.rs"), table).expect("OUT_DIR is writable");
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    definitions(&manifest);
    // Re-run when the sources change (the dirty flag) or git's HEAD, branch or index move
    // (a commit); paths are only named when they exist, or cargo would re-run every time.
    for rel in [
        "build.rs",
        "Cargo.toml",
        "Cargo.lock",
        "src",
        "tests",
        "validations",
        "golden",
    ] {
        let path = manifest.join(rel);
        if path.exists() {
            println!("cargo:rerun-if-changed={}", path.display());
        }
    }

    let toplevel = git(&manifest, &["rev-parse", "--show-toplevel"])
        .map(|s| PathBuf::from(s.trim()))
        .and_then(|p| p.canonicalize().ok());
    let ours = toplevel.is_some_and(|t| manifest.canonicalize().is_ok_and(|m| m == t));
    let (commit, dirty) = if ours {
        for what in ["HEAD", "index"] {
            if let Some(p) = git(&manifest, &["rev-parse", "--git-path", what]) {
                let p = manifest.join(p.trim());
                if p.exists() {
                    println!("cargo:rerun-if-changed={}", p.display());
                }
            }
        }
        if let Some(branch) = git(&manifest, &["symbolic-ref", "-q", "HEAD"]) {
            if let Some(p) = git(&manifest, &["rev-parse", "--git-path", branch.trim()]) {
                let p = manifest.join(p.trim());
                if p.exists() {
                    println!("cargo:rerun-if-changed={}", p.display());
                }
            }
        }
        let commit = git(&manifest, &["rev-parse", "HEAD"])
            .map(|s| s.trim().to_string())
            .filter(|s| s.len() == 40 && s.chars().all(|c| c.is_ascii_hexdigit()));
        let dirty = git(
            &manifest,
            &["status", "--porcelain", "--untracked-files=no"],
        )
        .map(|s| if s.trim().is_empty() { "no" } else { "yes" });
        (commit, dirty)
    } else {
        (None, None)
    };
    println!(
        "cargo:rustc-env=PERSSON_CHECK_COMMIT={}",
        commit.as_deref().unwrap_or("unknown")
    );
    println!(
        "cargo:rustc-env=PERSSON_CHECK_DIRTY={}",
        dirty.unwrap_or("unknown")
    );
}
