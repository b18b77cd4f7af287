//! Bad input never turns into a plausible number: every command (`surface`, `solve`,
//! `validate`, `report`) run on a bad scene file, validation definition, `.npy` field or
//! command-line argument exits non-zero, names on stderr what is wrong, where (file and
//! field, or flag) and the allowed range, and writes no output.
//!
//! Each case runs the real binary in a fresh temporary folder. Messages are matched on a
//! few key words, not whole sentences. Run with `--nocapture` to see every case's exit
//! code and first line of stderr.

use std::path::Path;
use std::process::Command;

use persson_check::validation::builtin::DEFINITIONS;

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
const DEFINITION: &str = include_str!("../validations/contact_area.toml");

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

// ---------------------------------------------------------------------------------------
// Harness
// ---------------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------------
// Scene files (`--scene`)
// ---------------------------------------------------------------------------------------

/// A scene file `bad.toml` holding `text` is rejected by `surface` and by `solve`, with the
/// file and `words` named.
fn bad_scene(text: &str, words: &[&str]) {
    let dir = tempdir();
    std::fs::write(dir.path().join("bad.toml"), text).unwrap();
    let words: Vec<&str> = words.iter().copied().chain(["bad.toml"]).collect();
    rejected(
        dir.path(),
        &["surface", "--scene", "bad.toml", "--out", "h.npy"],
        &words,
    );
    rejected(
        dir.path(),
        &["solve", "--scene", "bad.toml", "--out", "solved"],
        &words,
    );
}

#[test]
fn a_valid_scene_is_accepted() {
    // The harness itself: the same commands succeed on the valid scene.
    let dir = tempdir();
    std::fs::write(dir.path().join("ok.toml"), SCENE).unwrap();
    let (code, stderr) = run(
        dir.path(),
        &["surface", "--scene", "ok.toml", "--out", "h.npy"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    let (code, stderr) = run(
        dir.path(),
        &["solve", "--scene", "ok.toml", "--out", "solved"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(dir.path().join("solved/summary.json").is_file());
    let (code, stderr) = run(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--p0",
            "0.1",
            "--out",
            "solved2",
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn scene_unknown_key() {
    bad_scene(
        &edit(SCENE, "seed = 1", "sead = 1"),
        &["sead", "unknown field", "line 6", "expected one of"],
    );
}

#[test]
fn scene_unknown_key_in_solve() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = 0.1\nload = 3"),
        &["load", "unknown field", "line 10"],
    );
}

#[test]
fn scene_unknown_table() {
    bad_scene(
        &format!("{SCENE}\n[solver]\ntol = 1e-8\n"),
        &["solver", "unknown field"],
    );
}

#[test]
fn scene_missing_field() {
    bad_scene(
        &edit(SCENE, "hurst = 0.8\n", ""),
        &["missing field `hurst`", "[surface]"],
    );
}

#[test]
fn scene_missing_surface_table() {
    bad_scene("[solve]\np0 = 0.1\n", &["missing field `surface`"]);
}

#[test]
fn scene_empty_file() {
    bad_scene("", &["missing field `surface`"]);
}

#[test]
fn scene_not_toml() {
    bad_scene("[surface\nn = 32\n", &["line 1"]);
}

#[test]
fn scene_wrong_type_string() {
    bad_scene(
        &edit(SCENE, "n = 32", "n = \"big\""),
        &["n = \"big\"", "invalid type", "expected usize"],
    );
}

#[test]
fn scene_wrong_type_float_for_integer() {
    bad_scene(
        &edit(SCENE, "n = 32", "n = 32.5"),
        &["n = 32.5", "invalid type"],
    );
}

#[test]
fn scene_wrong_type_negative_seed() {
    bad_scene(&edit(SCENE, "seed = 1", "seed = -1"), &["seed = -1", "u64"]);
}

#[test]
fn scene_wrong_type_solver() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = 0.1\nsolver = \"newton\""),
        &["newton", "unknown variant", "cg"],
    );
}

#[test]
fn scene_hurst_zero() {
    bad_scene(
        &edit(SCENE, "hurst = 0.8", "hurst = 0"),
        &["hurst", "(0, 1)"],
    );
}

#[test]
fn scene_hurst_one() {
    bad_scene(
        &edit(SCENE, "hurst = 0.8", "hurst = 1"),
        &["hurst", "(0, 1)"],
    );
}

#[test]
fn scene_hurst_above_one() {
    bad_scene(
        &edit(SCENE, "hurst = 0.8", "hurst = 1.5"),
        &["hurst = 1.5", "(0, 1)"],
    );
}

#[test]
fn scene_hurst_nan() {
    bad_scene(
        &edit(SCENE, "hurst = 0.8", "hurst = nan"),
        &["hurst = NaN", "(0, 1)"],
    );
}

#[test]
fn scene_lambda_s_below_two_spacings() {
    bad_scene(
        &edit(SCENE, "lambda_s = 4", "lambda_s = 1.5"),
        &["lambda_s = 1.5", ">= 2 grid spacings"],
    );
}

#[test]
fn scene_lambda_l_beyond_box() {
    bad_scene(
        &edit(SCENE, "lambda_l = 16", "lambda_l = 64"),
        &["lambda_l = 64", "L = 32"],
    );
}

#[test]
fn scene_lambda_l_below_lambda_s() {
    bad_scene(
        &edit(SCENE, "lambda_l = 16", "lambda_l = 3"),
        &["lambda_l = 3", "lambda_s = 4"],
    );
}

#[test]
fn scene_lambda_r_below_lambda_l() {
    bad_scene(
        &edit(SCENE, "seed = 1", "seed = 1\nlambda_r = 8"),
        &["lambda_r = 8", "lambda_l = 16", "L = 32"],
    );
}

#[test]
fn scene_grid_too_small() {
    bad_scene(&edit(SCENE, "n = 32", "n = 2"), &["n = 2", "[4, 32768]"]);
}

#[test]
fn scene_rms_gradient_zero() {
    bad_scene(
        &edit(SCENE, "seed = 1", "seed = 1\nrms_gradient = 0"),
        &["rms_gradient = 0", "> 0"],
    );
}

#[test]
fn scene_zeta_below_one() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = 0.1\nzeta = 0.5"),
        &["solve.zeta = 0.5", "[1, zeta_max = 4]"],
    );
}

#[test]
fn scene_zeta_above_zeta_max() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = 0.1\nzeta = 5"),
        &["solve.zeta = 5", "[1, zeta_max = 4]"],
    );
}

#[test]
fn scene_p0_zero() {
    bad_scene(&edit(SCENE, "p0 = 0.1", "p0 = 0"), &["solve.p0 = 0", "> 0"]);
}

#[test]
fn scene_p0_negative() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = -1"),
        &["solve.p0 = -1", "> 0"],
    );
}

#[test]
fn scene_p0_infinite() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = inf"),
        &["solve.p0 = inf", "finite"],
    );
}

#[test]
fn scene_contact_area_above_one() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "contact_area = 1.5"),
        &["solve.contact_area = 1.5", "(0, 1)"],
    );
}

#[test]
fn scene_contact_area_zero() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "contact_area = 0"),
        &["solve.contact_area = 0", "(0, 1)"],
    );
}

#[test]
fn scene_both_loads() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = 0.1\ncontact_area = 0.2"),
        &["p0", "contact_area", "one of"],
    );
}

#[test]
fn scene_tol_zero() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = 0.1\ntol = 0"),
        &["solve.tol = 0", "[1e-14, 1)"],
    );
}

#[test]
fn scene_e_star_negative() {
    bad_scene(
        &edit(SCENE, "p0 = 0.1", "p0 = 0.1\ne_star = -1"),
        &["solve.e_star = -1", "> 0"],
    );
}

#[test]
fn scene_file_missing() {
    let dir = tempdir();
    rejected(
        dir.path(),
        &["surface", "--scene", "nowhere.toml", "--out", "h.npy"],
        &["nowhere.toml", "No such file"],
    );
}

// ---------------------------------------------------------------------------------------
// Validation definitions (`validate --dir`)
// ---------------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------------
// `.npy` fields (`solve --heights`)
// ---------------------------------------------------------------------------------------

/// A version-1 `.npy` file with header fields `descr` and `shape` (Python literals) and
/// raw `data`.
fn npy(descr: &str, shape: &str, data: &[u8]) -> Vec<u8> {
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let used = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - used % 64) % 64));
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((header.len() as u16).to_le_bytes());
    bytes.extend(header.as_bytes());
    bytes.extend(data);
    bytes
}

/// Little-endian float64 bytes.
fn f64s(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A smooth periodic 8 x 8 field.
fn field8() -> Vec<f64> {
    let tau = std::f64::consts::TAU;
    (0..64)
        .map(|k| ((k / 8) as f64 * tau / 8.0).sin() + ((k % 8) as f64 * tau / 8.0).cos())
        .collect()
}

/// A heights file holding `bytes` is rejected by `solve --heights`, naming the file and
/// `words`.
fn bad_heights(bytes: &[u8], words: &[&str]) {
    let dir = tempdir();
    std::fs::write(dir.path().join("h.npy"), bytes).unwrap();
    let words: Vec<&str> = words.iter().copied().chain(["h.npy"]).collect();
    rejected(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--p0",
            "0.1",
            "--out",
            "solved",
        ],
        &words,
    );
}

#[test]
fn heights_valid_file_is_accepted() {
    let dir = tempdir();
    std::fs::write(
        dir.path().join("h.npy"),
        npy("<f8", "(8, 8)", &f64s(&field8())),
    )
    .unwrap();
    let (code, stderr) = run(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--p0",
            "0.1",
            "--out",
            "solved",
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn heights_truncated_data() {
    let bytes = npy("<f8", "(8, 8)", &f64s(&field8()));
    bad_heights(
        &bytes[..bytes.len() - 9],
        &["truncated", "64 float64 values"],
    );
}

#[test]
fn heights_truncated_header() {
    let bytes = npy("<f8", "(8, 8)", &f64s(&field8()));
    bad_heights(&bytes[..30], &["not a valid .npy", "truncated"]);
}

#[test]
fn heights_empty_file() {
    bad_heights(b"", &["not a valid .npy"]);
}

#[test]
fn heights_not_npy() {
    bad_heights(b"1.0 2.0\n3.0 4.0\n", &["not a valid .npy"]);
}

#[test]
fn heights_trailing_bytes() {
    let mut data = f64s(&field8());
    data.extend(f64s(&[1.0, 2.0]));
    bad_heights(&npy("<f8", "(8, 8)", &data), &["16 bytes follow", "8 x 8"]);
}

#[test]
fn heights_float32() {
    let data: Vec<u8> = field8()
        .iter()
        .flat_map(|&v| (v as f32).to_le_bytes())
        .collect();
    bad_heights(&npy("<f4", "(8, 8)", &data), &["dtype", "<f4", "float64"]);
}

#[test]
fn heights_int64() {
    let data: Vec<u8> = (0..64i64).flat_map(|v| v.to_le_bytes()).collect();
    bad_heights(&npy("<i8", "(8, 8)", &data), &["dtype", "<i8", "float64"]);
}

#[test]
fn heights_complex128() {
    bad_heights(
        &npy("<c16", "(8, 8)", &[0; 1024]),
        &["dtype", "<c16", "float64"],
    );
}

#[test]
fn heights_one_dimensional() {
    bad_heights(
        &npy("<f8", "(64,)", &f64s(&field8())),
        &["1 dimensions", "expected 2 (N, N)"],
    );
}

#[test]
fn heights_three_dimensional() {
    bad_heights(
        &npy("<f8", "(4, 4, 4)", &f64s(&field8())),
        &["3 dimensions", "expected 2 (N, N)"],
    );
}

#[test]
fn heights_scalar() {
    bad_heights(
        &npy("<f8", "()", &f64s(&[1.0])),
        &["0 dimensions", "expected 2 (N, N)"],
    );
}

#[test]
fn heights_non_square() {
    bad_heights(
        &npy("<f8", "(8, 4)", &f64s(&field8()[..32])),
        &["not square", "[8, 4]", "(N, N)"],
    );
}

#[test]
fn heights_empty_array() {
    bad_heights(&npy("<f8", "(0, 0)", &[]), &["empty"]);
}

#[test]
fn heights_grid_too_small() {
    bad_heights(
        &npy("<f8", "(2, 2)", &f64s(&[0.0, 1.0, 2.0, 3.0])),
        &["N = 2", "[4, 32768]"],
    );
}

#[test]
fn heights_shape_overflowing_u64() {
    // The dimensions' product overflows: rejected, not a panic.
    bad_heights(
        &npy("<f8", "(0x100000000, 0x100000000, 2)", &[0; 64]),
        &["3 dimensions"],
    );
}

#[test]
fn heights_shape_larger_than_data() {
    bad_heights(
        &npy("<f8", "(40000, 40000)", &f64s(&field8())),
        &["N = 40000", "[4, 32768]"],
    );
    // Within range but far more than the file holds: read as far as the data goes.
    bad_heights(
        &npy("<f8", "(20000, 20000)", &f64s(&field8())),
        &["truncated", "400000000 float64 values"],
    );
    bad_heights(
        &npy("<f8", "(16, 16)", &f64s(&field8())),
        &["truncated", "256 float64 values"],
    );
}

#[test]
fn heights_nan() {
    let mut values = field8();
    values[10] = f64::NAN;
    bad_heights(
        &npy("<f8", "(8, 8)", &f64s(&values)),
        &["row 1, column 2", "NaN", "finite"],
    );
}

#[test]
fn heights_infinite() {
    let mut values = field8();
    values[63] = f64::INFINITY;
    bad_heights(
        &npy("<f8", "(8, 8)", &f64s(&values)),
        &["row 7, column 7", "inf", "finite"],
    );
    values[63] = f64::NEG_INFINITY;
    bad_heights(
        &npy("<f8", "(8, 8)", &f64s(&values)),
        &["row 7, column 7", "-inf", "finite"],
    );
}

#[test]
fn heights_flat_with_a_target_contact_area() {
    // A flat surface is in full contact at any load: no contact area in (0, 1) is reachable.
    let dir = tempdir();
    std::fs::write(
        dir.path().join("h.npy"),
        npy("<f8", "(8, 8)", &f64s(&[0.5; 64])),
    )
    .unwrap();
    rejected(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--contact-area",
            "0.3",
            "--out",
            "solved",
        ],
        &["contact_area = 0.3", "flat", "--p0"],
    );
}

#[test]
fn heights_file_missing() {
    let dir = tempdir();
    rejected(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--p0",
            "0.1",
            "--out",
            "solved",
        ],
        &["h.npy", "No such file"],
    );
}

#[test]
fn heights_file_lambda_l_out_of_range() {
    for value in ["64", "0", "-1"] {
        let dir = tempdir();
        std::fs::write(
            dir.path().join("h.npy"),
            npy("<f8", "(8, 8)", &f64s(&field8())),
        )
        .unwrap();
        let args = [
            "solve",
            "--heights",
            "h.npy",
            "--file-lambda-l",
            value,
            "--p0",
            "0.1",
            "--out",
            "solved",
        ];
        let stderr = rejected(dir.path(), &args, &["--file-lambda-l"]);
        assert!(
            stderr.contains("L = 8") || stderr.contains("> 0"),
            "{stderr}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Command-line arguments
// ---------------------------------------------------------------------------------------

/// `surface` with the valid flags, `flag` set to `value` (or removed when `value` is
/// None), plus `extra`, is rejected naming `words`.
fn bad_surface_flag(flag: &str, value: Option<&str>, extra: &[&str], words: &[&str]) {
    let mut args = vec!["surface"];
    let mut k = 0;
    while k < SURFACE_FLAGS.len() {
        let (name, v) = (SURFACE_FLAGS[k], SURFACE_FLAGS[k + 1]);
        if name != flag {
            args.extend([name, v]);
        } else if let Some(value) = value {
            args.extend([name, value]);
        }
        k += 2;
    }
    args.extend(extra);
    args.extend(["--out", "h.npy"]);
    rejected(tempdir().path(), &args, words);
}

/// `solve` on the valid scene with `args` added is rejected naming `words`.
fn bad_solve_flags(args: &[&str], words: &[&str]) {
    let dir = tempdir();
    std::fs::write(dir.path().join("ok.toml"), edit(SCENE, "p0 = 0.1\n", "")).unwrap();
    let mut all = vec!["solve", "--scene", "ok.toml", "--out", "solved"];
    all.extend(args);
    rejected(dir.path(), &all, words);
}

#[test]
fn flag_n_one() {
    bad_surface_flag("--n", Some("1"), &[], &["--n = 1", "[4, 32768]"]);
}

#[test]
fn flag_n_negative() {
    bad_surface_flag("--n", Some("-3"), &[], &["--n", "-3", "invalid digit"]);
}

#[test]
fn flag_n_not_a_number() {
    bad_surface_flag("--n", Some("many"), &[], &["--n", "many", "invalid"]);
}

#[test]
fn flag_hurst_out_of_range() {
    bad_surface_flag("--hurst", Some("1.5"), &[], &["--hurst = 1.5", "(0, 1)"]);
    bad_surface_flag("--hurst", Some("NaN"), &[], &["--hurst = NaN", "(0, 1)"]);
}

#[test]
fn flag_lambda_s_below_two_spacings() {
    bad_surface_flag(
        "--lambda-s",
        Some("1"),
        &[],
        &["--lambda-s = 1", ">= 2 grid spacings"],
    );
}

#[test]
fn flag_lambda_l_beyond_box() {
    bad_surface_flag(
        "--lambda-l",
        Some("64"),
        &[],
        &["--lambda-l = 64", "L = 32"],
    );
}

#[test]
fn flag_missing_hurst() {
    bad_surface_flag("--hurst", None, &[], &["--hurst", "missing"]);
}

#[test]
fn flag_missing_seed() {
    bad_surface_flag("--seed", None, &[], &["seed", "missing", "--seed"]);
}

#[test]
fn flag_surface_zeta_out_of_range() {
    bad_surface_flag(
        "--seed",
        Some("1"),
        &["--zeta", "0.5"],
        &["--zeta = 0.5", "[1, zeta_max = 4]"],
    );
    bad_surface_flag(
        "--seed",
        Some("1"),
        &["--zeta", "8"],
        &["--zeta = 8", "[1, zeta_max = 4]"],
    );
}

#[test]
fn flag_scene_with_surface_flags() {
    bad_surface_flag(
        "--seed",
        Some("1"),
        &["--scene", "s.toml"],
        &["--scene", "cannot be used with"],
    );
}

#[test]
fn flag_surface_missing_out() {
    let mut args = vec!["surface"];
    args.extend(SURFACE_FLAGS);
    rejected(tempdir().path(), &args, &["--out", "required"]);
}

#[test]
fn flag_surface_out_is_a_folder() {
    let dir = tempdir();
    std::fs::create_dir(dir.path().join("h.npy")).unwrap();
    let mut args = vec!["surface"];
    args.extend(SURFACE_FLAGS);
    args.extend(["--out", "h.npy"]);
    rejected(dir.path(), &args, &["--out", "folder"]);
}

#[test]
fn flag_threads_zero() {
    bad_surface_flag(
        "--seed",
        Some("1"),
        &["--threads", "0"],
        &["--threads", "1..=1024"],
    );
}

#[test]
fn flag_threads_negative() {
    bad_surface_flag(
        "--seed",
        Some("1"),
        &["--threads", "-1"],
        &["--threads", "-1", "1..=1024"],
    );
}

#[test]
fn flag_p0_zero() {
    bad_solve_flags(&["--p0", "0"], &["--p0 = 0", "> 0"]);
}

#[test]
fn flag_p0_negative() {
    bad_solve_flags(&["--p0", "-1"], &["--p0 = -1", "> 0"]);
}

#[test]
fn flag_p0_not_finite() {
    bad_solve_flags(&["--p0", "inf"], &["--p0 = inf", "finite"]);
    bad_solve_flags(&["--p0", "NaN"], &["--p0 = NaN", "finite"]);
}

#[test]
fn flag_contact_area_out_of_range() {
    bad_solve_flags(
        &["--contact-area", "1.5"],
        &["--contact-area = 1.5", "(0, 1)"],
    );
    bad_solve_flags(&["--contact-area", "0"], &["--contact-area = 0", "(0, 1)"]);
    bad_solve_flags(&["--contact-area", "1"], &["--contact-area = 1", "(0, 1)"]);
}

#[test]
fn flag_both_loads() {
    bad_solve_flags(
        &["--p0", "0.1", "--contact-area", "0.1"],
        &["--p0", "--contact-area", "cannot be used with"],
    );
}

#[test]
fn flag_no_load() {
    bad_solve_flags(&[], &["load", "missing", "--p0", "--contact-area"]);
}

#[test]
fn flag_tol_out_of_range() {
    bad_solve_flags(&["--p0", "0.1", "--tol", "0"], &["--tol = 0", "[1e-14, 1)"]);
    bad_solve_flags(&["--p0", "0.1", "--tol", "1"], &["--tol = 1", "[1e-14, 1)"]);
    bad_solve_flags(
        &["--p0", "0.1", "--tol", "1e-20"],
        &["--tol = 0.00000000000000000001", "[1e-14, 1)"],
    );
}

#[test]
fn flag_max_iter_zero() {
    bad_solve_flags(
        &["--p0", "0.1", "--max-iter", "0"],
        &["--max-iter = 0", ">= 1"],
    );
}

#[test]
fn flag_solve_zeta_out_of_range() {
    bad_solve_flags(
        &["--p0", "0.1", "--zeta", "0.5"],
        &["--zeta = 0.5", "[1, zeta_max"],
    );
    bad_solve_flags(
        &["--p0", "0.1", "--zeta", "100"],
        &["--zeta = 100", "[1, zeta_max = 4"],
    );
}

#[test]
fn flag_unknown_solver() {
    bad_solve_flags(
        &["--p0", "0.1", "--solver", "newton"],
        &["--solver", "newton", "possible values"],
    );
}

#[test]
fn flag_solve_missing_out() {
    let dir = tempdir();
    std::fs::write(dir.path().join("ok.toml"), SCENE).unwrap();
    rejected(
        dir.path(),
        &["solve", "--scene", "ok.toml"],
        &["--out", "required"],
    );
}

#[test]
fn flag_solve_out_is_a_file() {
    let dir = tempdir();
    std::fs::write(dir.path().join("ok.toml"), SCENE).unwrap();
    std::fs::write(dir.path().join("solved"), "keep").unwrap();
    rejected(
        dir.path(),
        &["solve", "--scene", "ok.toml", "--out", "solved"],
        &["--out", "solved", "folder"],
    );
    assert_eq!(std::fs::read(dir.path().join("solved")).unwrap(), b"keep");
}

#[test]
fn flag_solve_scene_and_heights() {
    bad_solve_flags(
        &["--heights", "h.npy", "--p0", "0.1"],
        &["--heights", "cannot be used with"],
    );
}

// ---------------------------------------------------------------------------------------
// `report`
// ---------------------------------------------------------------------------------------

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
        &[
            "report",
            "--from",
            "nowhere",
            "--out",
            "card.md",
            "--no-speed",
        ],
        &["--from", "nowhere", "existing folder"],
    );
}

#[test]
fn report_from_empty() {
    let dir = tempdir();
    outcomes(dir.path(), &[]);
    rejected(
        dir.path(),
        &["report", "--from", "from", "--out", "card.md", "--no-speed"],
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
        &["report", "--from", "from", "--out", "card.md", "--no-speed"],
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
        &["report", "--from", "from", "--out", "card.md", "--no-speed"],
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
        &["report", "--from", "from", "--out", "card.md", "--no-speed"],
        &["x.json", "not valid JSON"],
    );
    assert_eq!(listing(&dir.path().join("from")), ["x.json"]);
}

#[test]
fn report_speed_n_out_of_range() {
    // Below the smallest grid, or too small for the study's scene (lambda_s = 8 <
    // lambda_l = N/2).
    for (n, range) in [
        ("0", "[4, 32768]"),
        ("1", "[4, 32768]"),
        ("16", "fits the scene"),
    ] {
        let dir = tempdir();
        outcomes(dir.path(), &[]);
        rejected(
            dir.path(),
            &[
                "report",
                "--from",
                "from",
                "--out",
                "card.md",
                "--speed-n",
                n,
            ],
            &[&format!("--speed-n = {n}"), range],
        );
        assert!(listing(&dir.path().join("from")).is_empty());
    }
}

#[test]
fn report_golden_missing() {
    let dir = tempdir();
    outcomes(dir.path(), &[]);
    rejected(
        dir.path(),
        &[
            "report",
            "--from",
            "from",
            "--out",
            "card.md",
            "--golden",
            "nowhere",
            "--no-speed",
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
        &["report", "--from", "from", "--out", "card.md", "--no-speed"],
        &["--out", "card.md", "folder"],
    );
}

#[test]
fn report_missing_out() {
    let dir = tempdir();
    rejected(
        dir.path(),
        &["report", "--no-speed"],
        &["--out", "required"],
    );
}
