//! Scene files (`--scene`) given to `surface` and `solve`.

use super::*;

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
