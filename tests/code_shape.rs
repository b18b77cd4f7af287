//! Short functions, files of one job: no function in the non-test code of `src/` and
//! `python/src/` runs over [`MAX_FN_LINES`] lines, and no file holds more than
//! [`MAX_FILE_LINES`] lines before its `#[cfg(test)]` module. The limits hold for every
//! file; a failure names each offender with its length, so a contributor sees what to
//! split.
//!
//! The code is rustfmt-formatted, so a function runs from its `fn` line to the first
//! line after it that is a lone `}` at the `fn` line's indentation. Test code is left
//! out: a file's inline `#[cfg(test)] mod ... {` and everything after it, items marked
//! `#[cfg(test)]`, and files declared as `#[cfg(test)] mod name;`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::common::rust_files;

/// The most lines a function may run over, from its `fn` line to its closing brace.
const MAX_FN_LINES: usize = 100;

/// The most lines a file may hold before its `#[cfg(test)]` module.
const MAX_FILE_LINES: usize = 600;

/// The source roots the limits hold for.
const ROOTS: &[&str] = &["src", "python/src"];

/// A `mod` item's name and whether it has an inline body, if `line` declares one.
fn module_item(line: &str) -> Option<(&str, bool)> {
    let mut rest = line.trim_start();
    if let Some(r) = rest.strip_prefix("pub") {
        rest = r.trim_start();
        if rest.starts_with('(') {
            rest = &rest[rest.find(')')? + 1..];
        }
        rest = rest.trim_start();
    }
    let rest = rest.strip_prefix("mod ")?.trim_start();
    let end = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    let (name, after) = rest.split_at(end);
    let after = after.trim();
    if name.is_empty() {
        return None;
    }
    match after {
        ";" => Some((name, false)),
        _ if after.starts_with('{') => Some((name, true)),
        _ => None,
    }
}

/// The files declared as `#[cfg(test)] mod name;` from anywhere in `files`.
fn test_files(files: &[PathBuf]) -> BTreeSet<PathBuf> {
    let mut out = BTreeSet::new();
    for file in files {
        let text = std::fs::read_to_string(file).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let stem = file.file_stem().unwrap().to_string_lossy();
        // `a/mod.rs` declares its children in `a/`, `a.rs` in `a/`.
        let dir = if ["mod", "lib", "main"].contains(&stem.as_ref()) {
            file.parent().unwrap().to_path_buf()
        } else {
            file.with_extension("")
        };
        for pair in lines.windows(2) {
            if pair[0].trim() != "#[cfg(test)]" {
                continue;
            }
            if let Some((name, false)) = module_item(pair[1]) {
                out.insert(dir.join(format!("{name}.rs")));
                out.insert(dir.join(name).join("mod.rs"));
            }
        }
    }
    out
}

/// The lines of a file before its inline `#[cfg(test)]` module.
fn non_test_lines(text: &str) -> Vec<&str> {
    let lines: Vec<&str> = text.lines().collect();
    let end = lines
        .windows(2)
        .position(|p| p[0].trim() == "#[cfg(test)]" && matches!(module_item(p[1]), Some((_, true))))
        .unwrap_or(lines.len());
    lines[..end].to_vec()
}

/// The name and indentation of the function a line opens, if it opens one.
fn fn_item(line: &str) -> Option<(&str, &str)> {
    let body = line.trim_start();
    let indent = &line[..line.len() - body.len()];
    let mut rest = body;
    if let Some(r) = rest.strip_prefix("pub") {
        rest = r.trim_start();
        if rest.starts_with('(') {
            rest = rest[rest.find(')')? + 1..].trim_start();
        }
    }
    for qualifier in ["const ", "async ", "unsafe "] {
        if let Some(r) = rest.strip_prefix(qualifier) {
            rest = r.trim_start();
        }
    }
    if let Some(r) = rest.strip_prefix("extern ") {
        rest = r.trim_start();
        if rest.starts_with('"') {
            rest = rest[1..][rest[1..].find('"')? + 1..].trim_start();
        }
    }
    let rest = rest.strip_prefix("fn ")?;
    let end = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    (end > 0).then(|| (&rest[..end], indent))
}

/// Whether the attributes right above line `i` mark the item as test code.
fn marked_test(lines: &[&str], i: usize) -> bool {
    lines[..i]
        .iter()
        .rev()
        .map(|l| l.trim())
        .take_while(|l| l.starts_with("#[") || l.starts_with("///"))
        .any(|l| l == "#[cfg(test)]")
}

/// Each function of `lines` with a body: its name and its length in lines, from its
/// `fn` line to its closing brace.
fn functions(lines: &[&str]) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some((name, indent)) = fn_item(line) else {
            continue;
        };
        if marked_test(lines, i) {
            continue;
        }
        // The signature ends at a line ending in `{` (a body follows), `;` (none) or
        // `}` (a body on one line).
        let Some(open) = (i..lines.len()).find(|&k| {
            let l = lines[k].trim_end();
            l.ends_with('{') || l.ends_with(';') || l.ends_with('}')
        }) else {
            continue;
        };
        if !lines[open].trim_end().ends_with('{') {
            continue;
        }
        let close = format!("{indent}}}");
        if let Some(end) = (open + 1..lines.len()).find(|&k| lines[k] == close) {
            out.push((name.to_string(), end - i + 1));
        }
    }
    out
}

/// The offenders under the roots: long files and long functions, each with its length.
fn offenders() -> (Vec<String>, Vec<String>) {
    let base = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files: Vec<PathBuf> = ROOTS
        .iter()
        .flat_map(|r| rust_files(&base.join(r)))
        .collect();
    let tests = test_files(&files);
    let (mut long_files, mut long_fns) = (Vec::new(), Vec::new());
    for file in files.iter().filter(|f| !tests.contains(*f)) {
        let text = std::fs::read_to_string(file).unwrap();
        let lines = non_test_lines(&text);
        let shown = file.strip_prefix(base).unwrap().display();
        if lines.len() > MAX_FILE_LINES {
            long_files.push(format!("{shown}: {} lines", lines.len()));
        }
        for (name, n) in functions(&lines) {
            if n > MAX_FN_LINES {
                long_fns.push(format!("{shown}: fn {name}: {n} lines"));
            }
        }
    }
    (long_files, long_fns)
}

#[test]
fn functions_and_files_are_short() {
    let (long_files, long_fns) = offenders();
    let mut msg = String::new();
    if !long_fns.is_empty() {
        msg += &format!(
            "functions over {MAX_FN_LINES} lines (split them along their steps):\n  {}\n",
            long_fns.join("\n  ")
        );
    }
    if !long_files.is_empty() {
        msg += &format!(
            "files over {MAX_FILE_LINES} lines before their #[cfg(test)] module (one job per file):\n  {}\n",
            long_files.join("\n  ")
        );
    }
    assert!(msg.is_empty(), "{msg}");
}

#[test]
fn the_reader_finds_functions_and_their_ends() {
    let code = "\
pub(crate) fn a(
    x: u32,
) -> u32 {
    x
}
fn b() {}
    pub const fn c() -> u32 {
        1
    }
trait T {
    fn d(&self);
}
#[cfg(test)]
fn e() {
}
";
    let lines: Vec<&str> = code.lines().collect();
    assert_eq!(
        functions(&lines),
        vec![("a".to_string(), 5), ("c".to_string(), 3)]
    );
}

#[test]
fn the_reader_cuts_files_at_their_test_module() {
    let code = "fn a() {}\n#[cfg(test)]\nmod shipped;\nfn b() {}\n#[cfg(test)]\nmod tests {\n}\n";
    assert_eq!(non_test_lines(code).len(), 4);
    assert_eq!(module_item("pub(crate) mod x;"), Some(("x", false)));
    assert_eq!(module_item("mod tests {"), Some(("tests", true)));
    assert_eq!(module_item("model {"), None);
}
