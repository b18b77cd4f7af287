//! The layers of `src/` depend on one another in one direction only, and no two modules
//! depend on each other.
//!
//! Layers, from the bottom: `error`; `io`, `stats`, `provenance`; `plot`; `engine`;
//! `persson`; `experiments` and `speed`; `validation`; `report`; `tasks`. A module may use modules of
//! its own layer's folder and of lower layers only. Within and across folders, the
//! "uses" relation between modules that are not ancestors of each other has no cycle.
//! References are read from `crate::...` paths and `super::` imports outside comments
//! and `#[cfg(test)]` code.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The rank of each top-level module: a module may use only lower ranks.
const LAYERS: &[(&str, u32)] = &[
    ("error", 0),
    ("io", 1),
    ("stats", 1),
    ("provenance", 1),
    ("plot", 2),
    ("engine", 3),
    ("persson", 4),
    ("experiments", 5),
    ("speed", 5),
    ("validation", 6),
    ("report", 7),
    ("measured", 7),
    ("tasks", 8),
];

/// Every library source file with its module path (`engine::solver::cg`).
fn modules() -> Vec<(Vec<String>, PathBuf)> {
    fn walk(dir: &Path, prefix: &[String], out: &mut Vec<(Vec<String>, PathBuf)>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let stem = path.file_stem().unwrap().to_string_lossy().to_string();
            if path.is_dir() {
                let mut p = prefix.to_vec();
                p.push(stem);
                walk(&path, &p, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let mut p = prefix.to_vec();
                if stem != "mod" {
                    p.push(stem);
                }
                out.push((p, path));
            }
        }
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = Vec::new();
    walk(&src, &[], &mut out);
    // The binary and its commands sit on top of everything.
    out.retain(|(m, _)| !m.is_empty() && m[0] != "main" && m[0] != "lib" && m[0] != "commands");
    out
}

/// The code of a file without comments, strings' contents aside, and without its
/// `#[cfg(test)]` module (which, by convention here, comes last).
fn code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The module paths a file refers to.
fn references(module: &[String], text: &str) -> BTreeSet<Vec<String>> {
    let mut out = BTreeSet::new();
    let bytes = text.as_bytes();
    let ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    // A path that starts here, not in the middle of another one.
    let starts = |i: usize| i == 0 || !(ident(bytes[i - 1]) || bytes[i - 1] == b':');
    let mut i = 0;
    while i < bytes.len() {
        let rest = &bytes[i..];
        let (base, skip) = if rest.starts_with(b"crate::") && starts(i) {
            (Vec::new(), "crate::".len())
        } else if rest.starts_with(b"super::") && starts(i) {
            // `super` is the parent module (of `a` in `a/mod.rs`, `a` in `a/b.rs`).
            let mut b = module.to_vec();
            b.pop();
            (b, "super::".len())
        } else {
            i += 1;
            continue;
        };
        let mut path = base;
        let mut j = i + skip;
        loop {
            let start = j;
            while j < bytes.len() && ident(bytes[j]) {
                j += 1;
            }
            if j == start {
                break;
            }
            path.push(text[start..j].to_string());
            if bytes[j..].starts_with(b"::") {
                j += 2;
            } else {
                break;
            }
        }
        out.insert(path);
        i = j.max(i + 1);
    }
    out
}

/// The longest prefix of `path` that is a module.
fn resolve(path: &[String], known: &BTreeSet<Vec<String>>) -> Option<Vec<String>> {
    (1..=path.len())
        .rev()
        .map(|k| path[..k].to_vec())
        .find(|p| known.contains(p))
}

fn rank(top: &str) -> u32 {
    LAYERS
        .iter()
        .find(|(n, _)| *n == top)
        .unwrap_or_else(|| panic!("src/{top} is in no layer: add it to LAYERS"))
        .1
}

fn graph() -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let mods = modules();
    let known: BTreeSet<Vec<String>> = mods.iter().map(|(m, _)| m.clone()).collect();
    let mut g = BTreeMap::new();
    for (m, path) in &mods {
        let text = code(path);
        let refs: BTreeSet<Vec<String>> = references(m, &text)
            .into_iter()
            .filter_map(|r| resolve(&r, &known))
            .filter(|r| r != m)
            .collect();
        g.insert(m.clone(), refs);
    }
    g
}

#[test]
fn layers_depend_downwards_only() {
    let mut wrong = Vec::new();
    for (m, refs) in graph() {
        for r in refs {
            if r[0] != m[0] && rank(&r[0]) >= rank(&m[0]) {
                wrong.push(format!("{} uses {}", m.join("::"), r.join("::")));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "uses against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn no_two_modules_depend_on_each_other() {
    let g = graph();
    let ancestor = |a: &[String], b: &[String]| b.starts_with(a) || a.starts_with(b);
    // Depth-first search for a cycle among edges between non-ancestors.
    fn visit(
        n: &Vec<String>,
        g: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        ancestor: &dyn Fn(&[String], &[String]) -> bool,
        state: &mut BTreeMap<Vec<String>, u8>,
        stack: &mut Vec<Vec<String>>,
    ) -> Option<Vec<Vec<String>>> {
        state.insert(n.clone(), 1);
        stack.push(n.clone());
        for m in g.get(n).into_iter().flatten() {
            if ancestor(n, m) {
                continue;
            }
            match state.get(m).copied().unwrap_or(0) {
                1 => {
                    let i = stack.iter().position(|x| x == m).unwrap();
                    return Some(stack[i..].to_vec());
                }
                0 => {
                    if let Some(c) = visit(m, g, ancestor, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(n.clone(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in g.keys() {
        if state.get(n).copied().unwrap_or(0) == 0 {
            if let Some(c) = visit(n, &g, &ancestor, &mut state, &mut Vec::new()) {
                let names: Vec<String> = c.iter().map(|m| m.join("::")).collect();
                panic!("a dependency cycle: {} -> back", names.join(" -> "));
            }
        }
    }
}

/// One experiment's internals are its own: no module imports `experiments::<one
/// experiment>` (a folder under src/experiments) but that experiment and the registry,
/// which names every experiment once. What two experiments share lives beside them.
#[test]
fn no_module_imports_one_experiment_but_the_registry() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/experiments");
    let experiments: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert!(experiments.len() >= 7, "{experiments:?}");
    let registry = ["validation".to_string(), "registry".to_string()];
    let mut wrong = Vec::new();
    for (m, refs) in graph() {
        if m.starts_with(&registry) {
            continue;
        }
        for r in refs {
            let into = r.len() >= 2 && r[0] == "experiments" && experiments.contains(&r[1]);
            if into && !m.starts_with(&r[..2]) {
                wrong.push(format!("{} uses {}", m.join("::"), r.join("::")));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports of one experiment's internals:\n{}",
        wrong.join("\n")
    );
}

/// A measured surface is checked with the engine's sweeps and climbs, not with an
/// experiment's: no module under `src/measured` uses `experiments` (what a validation and
/// a measured scan share, the fixed-load climb, the contact history and the contact
/// changes, lives in the engine).
#[test]
fn the_measured_check_imports_no_experiment() {
    let wrong: Vec<String> = graph()
        .into_iter()
        .filter(|(m, _)| m[0] == "measured")
        .flat_map(|(m, refs)| {
            refs.into_iter()
                .filter(|r| r[0] == "experiments")
                .map(move |r| format!("{} uses {}", m.join("::"), r.join("::")))
        })
        .collect();
    assert!(
        wrong.is_empty(),
        "the measured check uses experiments:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_reader_finds_crate_and_super_paths() {
    // In experiments/modes/onset.rs.
    let here = vec![
        "experiments".to_string(),
        "modes".to_string(),
        "onset".to_string(),
    ];
    let refs = references(
        &here,
        "use crate::engine::grid::Grid;\nuse super::{band, Load};\nx::crate::no",
    );
    assert!(refs.contains(&vec!["engine".into(), "grid".into(), "Grid".into()]));
    assert!(refs.contains(&vec!["experiments".into(), "modes".into()]));
    assert_eq!(refs.len(), 2, "{refs:?}");
}

/// Two-dimensional transforms are the engine's ([`persson_check::engine::fft`]): no module
/// above it plans an FFT of its own, so that a scan's spectrum and a solver's see the same
/// convention and the same bits. The one exception transforms profiles, in one dimension,
/// which the engine does not do.
#[test]
fn only_the_engine_plans_fourier_transforms() {
    const ONE_DIMENSIONAL: &[&str] = &["measured::line::spectrum"];
    let mut wrong = Vec::new();
    for (m, path) in modules() {
        let name = m.join("::");
        if m[0] == "engine" || ONE_DIMENSIONAL.contains(&name.as_str()) {
            continue;
        }
        let text = code(&path);
        for planner in ["FftPlanner", "RealFftPlanner", "plan_fft"] {
            if text.contains(planner) {
                wrong.push(format!("{name} uses {planner}"));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "transforms planned outside the engine:\n{}",
        wrong.join("\n")
    );
}

/// The front ends are adapters: the command line's `src/commands/` and the Python
/// package's `python/src/` parse their flags and keywords into the requests of `tasks`
/// and print or return what comes back, so neither names an `engine` item (a type a front
/// end must name is re-exported by `tasks`). A file's own comments are not read.
#[test]
fn the_front_ends_import_no_engine_item() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["src/commands", "python/src"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files.push(root.join("src/main.rs"));
    assert!(files.len() >= 15, "{files:?}");
    let wrong: Vec<String> = files
        .iter()
        .filter(|path| {
            let text = std::fs::read_to_string(path).unwrap();
            text.lines().any(|l| {
                let code = l.find("//").map_or(l, |i| &l[..i]);
                code.contains("engine::")
            })
        })
        .map(|path| path.display().to_string())
        .collect();
    assert!(
        wrong.is_empty(),
        "front-end files that name engine items:\n{}",
        wrong.join("\n")
    );
}

/// `report` only formats what is in its `--from` folder: no file under `src/report/`, its
/// tests included, runs the speed study (`speed::run`, or `run` imported from
/// `crate::speed`); the study is `persson-check speed`'s step. A file's comments are not
/// read.
#[test]
fn the_report_runs_no_speed_study() {
    let files =
        crate::common::rust_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src/report"));
    assert!(files.len() >= 10, "{files:?}");
    let wrong: Vec<String> = files
        .iter()
        .filter(|path| {
            let text = std::fs::read_to_string(path).unwrap();
            let code: String = text
                .lines()
                .map(|l| l.find("//").map_or(l, |i| &l[..i]))
                .collect::<Vec<_>>()
                .join(" ")
                .split_whitespace()
                .collect();
            runs_the_speed_study(&code)
        })
        .map(|path| path.display().to_string())
        .collect();
    assert!(
        wrong.is_empty(),
        "files of the report that run the speed study:\n{}",
        wrong.join("\n")
    );
}

/// Whether `code` (without comments or whitespace) names `speed::run`, or imports `run`
/// (or everything) from a `speed::{...}` group.
fn runs_the_speed_study(code: &str) -> bool {
    if code.contains("speed::run") || code.contains("speed::*") {
        return true;
    }
    code.match_indices("speed::{").any(|(i, m)| {
        let group = &code[i + m.len()..];
        let group = &group[..group.find('}').unwrap_or(group.len())];
        group
            .split(',')
            .any(|item| item == "run" || item.starts_with("runas") || item == "*")
    })
}

#[test]
fn the_speed_study_finder_finds_its_forms() {
    for code in [
        "crate::speed::run(&o,&mut|_|{})",
        "usecrate::speed::{run,SpeedOptions};",
        "usecrate::speed::{SpeedStudy,runasstudy};",
        "usecrate::speed::*;",
    ] {
        assert!(runs_the_speed_study(code), "{code}");
    }
    for code in [
        "usecrate::speed::{SpeedStudy,SOLVERS};",
        "crate::speed::SpeedStudy::read(&p)",
        "fnrun_speed(){}",
    ] {
        assert!(!runs_the_speed_study(code), "{code}");
    }
}

/// Every file under `dir` (relative path) with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                out.insert(path.strip_prefix(root).unwrap().to_path_buf(), bytes);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// Copies every file under `from` into `to`.
fn copy_tree(from: &Path, to: &Path) {
    for (rel, bytes) in snapshot(from) {
        let path = to.join(rel);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
}

/// `report` writes nothing into its `--from` folder: run on a copy of the committed
/// reduced outcomes (with a history, whose trend figure it draws), the copy's files and
/// their bytes are as before, and the scorecard and its figures are beside `--out`.
#[test]
fn report_writes_nothing_into_its_from_folder() {
    let root = tempfile::tempdir().unwrap();
    let (from, review) = (root.path().join("from"), root.path().join("review"));
    copy_tree(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("results/reduced"),
        &from,
    );
    std::fs::create_dir(&review).unwrap();
    let before = snapshot(&from);
    assert!(before.len() > 10, "{} files", before.len());
    let card = review.join("scorecard.md");
    let history = review.join("headlines.jsonl");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_persson-check"))
        .arg("report")
        .arg("--from")
        .arg(&from)
        .arg("--out")
        .arg(&card)
        .arg("--history")
        .arg(&history)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "report failed:\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let after = snapshot(&from);
    let changed: Vec<&PathBuf> = before
        .keys()
        .chain(after.keys())
        .filter(|k| before.get(*k) != after.get(*k))
        .collect();
    assert!(
        changed.is_empty(),
        "report changed its --from folder: {changed:?}"
    );
    let text = std::fs::read_to_string(&card).unwrap();
    assert!(
        text.contains("No speed study in `"),
        "the speed section says how to run it"
    );
    assert!(review.join("trend").is_dir() && history.is_file());
}
