//! Validation definitions (`validate --dir`).

use super::*;
use persson_check::validation::source::DEFINITIONS;

/// A folder holding `files` (name, text) is rejected by `validate --dir`, naming `words`;
/// the output folder, created beforehand, stays empty.
fn bad_definitions(files: &[(&str, &str)], words: &[&str]) {
    let dir = tempdir();
    std::fs::create_dir(dir.path().join("defs")).unwrap();
    std::fs::create_dir(dir.path().join("out")).unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join("defs").join(name), text).unwrap();
    }
    rejected(
        dir.path(),
        &["validate", "--dir", "defs", "--out", "out"],
        words,
    );
    assert!(listing(&dir.path().join("out")).is_empty(), "wrote output");
    // Without an output folder beforehand, none is created.
    std::fs::remove_dir(dir.path().join("out")).unwrap();
    rejected(
        dir.path(),
        &["validate", "--dir", "defs", "--out", "out"],
        words,
    );
}

/// `bad_definitions` for one `contact_area.toml`.
fn bad_definition(text: &str, words: &[&str]) {
    let words: Vec<&str> = words.iter().copied().chain(["contact_area.toml"]).collect();
    bad_definitions(&[("contact_area.toml", text)], &words);
}

#[test]
fn definition_empty_seeds() {
    bad_definition(
        &edit(DEFINITION, "seeds = [1, 2, 3, 4]", "seeds = []"),
        &["[reduced]", "seeds", "at least one seed"],
    );
}

#[test]
fn definition_empty_seeds_in_full_scene() {
    // Checked even when only the reduced scene would run.
    bad_definition(
        &edit_full(DEFINITION, "seeds = [1, 2, 3, 4, 5, 6, 7, 8]", "seeds = []"),
        &["[full]", "seeds", "at least one seed"],
    );
}

#[test]
fn definition_zero_seeds_wrong_type() {
    bad_definition(
        &edit(DEFINITION, "seeds = [1, 2, 3, 4]", "seeds = 0"),
        &["seeds = 0", "invalid type", "sequence"],
    );
}

#[test]
fn definition_unknown_key() {
    bad_definition(
        &edit(DEFINITION, "low_load = 0.03", "lo_load = 0.03"),
        &["lo_load", "unknown field"],
    );
}

#[test]
fn definition_unknown_top_level_key() {
    bad_definition(
        &edit(DEFINITION, "title =", "owner = \"me\"\ntitle ="),
        &["owner", "unknown field"],
    );
}

#[test]
fn definition_missing_field() {
    bad_definition(
        &edit(DEFINITION, "low_load = 0.03\n", ""),
        &["missing field `low_load`", "[reduced]"],
    );
}

#[test]
fn definition_missing_header_field() {
    bad_definition(
        &edit(DEFINITION, "experiment = \"contact_area\"\n", ""),
        &["missing field `experiment`"],
    );
}

#[test]
fn definition_wrong_type_in_header() {
    bad_definition(
        &edit(
            DEFINITION,
            "experiment = \"contact_area\"",
            "experiment = 3",
        ),
        &["experiment", "string"],
    );
}

#[test]
fn definition_unknown_experiment() {
    bad_definition(
        &edit(
            DEFINITION,
            "experiment = \"contact_area\"",
            "experiment = \"nope\"",
        ),
        &["nope", "unknown", "contact_area"],
    );
}

#[test]
fn definition_name_differs_from_file() {
    bad_definition(
        &edit(DEFINITION, "name = \"contact_area\"", "name = \"other\""),
        &["other", "file name"],
    );
}

#[test]
fn definition_hurst_out_of_range() {
    bad_definition(
        &edit(
            DEFINITION,
            "hursts = [0.3, 0.5, 0.8]",
            "hursts = [0.3, 1.5]",
        ),
        &["[reduced]", "hurst = 1.5", "(0, 1)"],
    );
}

#[test]
fn definition_lambda_s_out_of_range() {
    bad_definition(
        &edit(DEFINITION, "lambda_s = 4", "lambda_s = 1"),
        &["[reduced]", "lambda_s = 1", ">= 2 grid spacings"],
    );
}

#[test]
fn definition_lambda_l_out_of_range() {
    bad_definition(
        &edit_full(DEFINITION, "lambda_l = 256", "lambda_l = 1024"),
        &["[full]", "lambda_l = 1024", "L = 512"],
    );
}

#[test]
fn definition_significance_zero() {
    bad_definition(
        &edit(DEFINITION, "significance = 3.0", "significance = 0"),
        &["verdict.significance = 0", "> 0"],
    );
}

#[test]
fn definition_resolution_negative() {
    bad_definition(
        &edit(DEFINITION, "resolution = 0.1", "resolution = -0.1"),
        &["verdict.resolution = -0.1", "> 0"],
    );
}

#[test]
fn definition_not_toml() {
    bad_definitions(
        &[("contact_area.toml", "name = \"contact_area\n")],
        &["contact_area.toml", "line 1", "string"],
    );
    // A control character is not echoed raw.
    let stderr_nul = {
        let dir = tempdir();
        std::fs::create_dir(dir.path().join("defs")).unwrap();
        std::fs::write(dir.path().join("defs/x.toml"), "\u{0}").unwrap();
        rejected(
            dir.path(),
            &["validate", "--dir", "defs", "--out", "out"],
            &["x.toml", "line 1"],
        )
    };
    assert!(!stderr_nul.contains('\u{0}'), "{stderr_nul:?}");
}

#[test]
fn definition_not_utf8() {
    let dir = tempdir();
    std::fs::create_dir(dir.path().join("defs")).unwrap();
    std::fs::write(dir.path().join("defs/x.toml"), [0xff, 0xfe, b'\n']).unwrap();
    rejected(
        dir.path(),
        &["validate", "--dir", "defs", "--out", "out"],
        &["x.toml", "UTF-8"],
    );
}

/// Every built-in definition with its reduced scene's seeds replaced by `seeds` is
/// rejected with a message holding `words` (and the file, the table and the field).
fn every_definition_rejects_seeds(seeds: &str, words: &[&str]) {
    for (name, text) in DEFINITIONS {
        let line = text
            .lines()
            .find(|l| l.starts_with("seeds = ["))
            .unwrap_or_else(|| panic!("{name}: no seeds"));
        let file = format!("{name}.toml");
        let text = edit(text, line, seeds);
        let expected: Vec<&str> = [file.as_str(), "[reduced]", "seeds"]
            .into_iter()
            .chain(words.iter().copied())
            .collect();
        bad_definitions(&[(&file, &text)], &expected);
    }
}

#[test]
fn every_definition_rejects_empty_seeds() {
    every_definition_rejects_seeds("seeds = []", &["at least one seed"]);
}

#[test]
fn every_definition_rejects_a_repeated_seed() {
    every_definition_rejects_seeds("seeds = [3, 5, 3]", &["distinct", "3 appears twice"]);
}

/// Every built-in definition whose reduced scene lists its loads (`contact_areas`) is
/// rejected when one load appears twice, with the file, the table, the field and "once".
#[test]
fn every_definition_with_loads_rejects_a_repeated_load() {
    let mut checked = 0;
    for (name, text) in DEFINITIONS {
        let mut table = "";
        let Some(line) = text.lines().find(|l| {
            if l.starts_with('[') {
                table = l;
            }
            l.starts_with("contact_areas = [")
        }) else {
            continue;
        };
        if table != "[reduced]" {
            continue;
        }
        let first = line["contact_areas = [".len()..]
            .split([',', ']'])
            .next()
            .unwrap();
        let repeated = format!("{}, {first}]", line.trim_end().trim_end_matches(']'));
        let file = format!("{name}.toml");
        let text = edit(text, line, &repeated);
        bad_definitions(
            &[(&file, &text)],
            &[file.as_str(), "[reduced]", "contact_areas", "once"],
        );
        checked += 1;
    }
    assert!(checked >= 4, "only {checked} definitions list their loads");
}

#[test]
fn one_bad_definition_stops_all_before_any_runs() {
    // contact_area sorts first and is valid: it must not run (nor write) either.
    let frozen = DEFINITIONS
        .iter()
        .find(|(name, _)| *name == "e_frozen")
        .unwrap()
        .1;
    let bad = edit(frozen, "hurst = 0.8", "hurst = 1.5");
    bad_definitions(
        &[("contact_area.toml", DEFINITION), ("e_frozen.toml", &bad)],
        &["e_frozen.toml", "hurst = 1.5", "(0, 1)"],
    );
}

#[test]
fn definition_folder_empty() {
    bad_definitions(&[], &["--dir", "*.toml"]);
}

#[test]
fn definition_folder_missing() {
    let dir = tempdir();
    rejected(
        dir.path(),
        &["validate", "--dir", "nowhere", "--out", "out"],
        &["--dir", "nowhere", "folder"],
    );
}

#[test]
fn validate_unknown_name() {
    let dir = tempdir();
    rejected(
        dir.path(),
        &["validate", "no_such_validation", "--out", "out"],
        &["no_such_validation", "one of", "contact_area"],
    );
}

#[test]
fn validate_out_is_a_file() {
    let dir = tempdir();
    std::fs::write(dir.path().join("out"), "keep").unwrap();
    rejected(
        dir.path(),
        &["validate", "contact_area", "--out", "out"],
        &["--out", "not"],
    );
    assert_eq!(std::fs::read(dir.path().join("out")).unwrap(), b"keep");
}

#[test]
fn validate_missing_out() {
    let dir = tempdir();
    rejected(dir.path(), &["validate", "contact_area"], &["--out"]);
}

#[test]
fn definition_without_a_claim_its_experiment_reads() {
    // c_flux's experiment reads the paper's fluxes from the claims flux_in and flux_out,
    // total_energy's the contact area below which the correction fails: a definition
    // that renames one is refused when it loads, naming the claim.
    for (name, from, to, key) in [
        (
            "c_flux",
            "key = \"flux_in\"",
            "key = \"flux_into\"",
            "`flux_in`",
        ),
        (
            "total_energy",
            "key = \"correction_fails_below\"",
            "key = \"fails_below\"",
            "`correction_fails_below`",
        ),
    ] {
        let text = DEFINITIONS
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, t)| *t)
            .unwrap();
        let file = format!("{name}.toml");
        bad_definitions(
            &[(file.as_str(), &edit(text, from, to))],
            &[key, "[[claims]]", file.as_str()],
        );
    }
}
