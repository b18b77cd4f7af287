//! Command-line flags of every command.

use super::*;

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

/// `check-surface` refuses a load given twice (`--loads 0.01,0.02,0.01`), as a definition
/// refuses a contact area given twice: it would be solved twice and its curve's point
/// counted twice. The message names the flag, the value and "once".
#[test]
fn flag_loads_repeated() {
    let dir = tempdir();
    let heights: String = (0..8)
        .map(|i| {
            (0..8)
                .map(|j| format!("{}", ((i * 8 + j) as f64 * 0.7).sin()))
                .collect::<Vec<_>>()
                .join(" ")
                + "\n"
        })
        .collect();
    std::fs::write(dir.path().join("h.txt"), heights).unwrap();
    rejected(
        dir.path(),
        &[
            "check-surface",
            "--heights",
            "h.txt",
            "--pixel-size",
            "1",
            "--loads",
            "0.01,0.02,0.01",
            "--out",
            "checked",
        ],
        &["--loads", "once", "0.01 appears twice"],
    );
}
