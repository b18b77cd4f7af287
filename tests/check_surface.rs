//! `check-surface` on height maps: a periodic scan gives what `solve` gives, a measured
//! (non-periodic) window gives a rising load curve beside Persson's predictions with a
//! page, its figures and no NaN; a rectangular, partly unmeasured window in a named unit
//! runs with `--fill interpolate` and `--modulus`, saying so; a sphere on a rectangular
//! free boundary gives Hertz's contact area; bad scans and flags are refused with a word; a
//! line scan at non-uniform positions (`--line-scan`, an x-y file) is resampled with a
//! warning and checked as its resampled profile is, and positions that do not increase are
//! refused naming the line; maps below the floor on size (7 x 4, 4 x 4) are refused by
//! their size, one at the floor runs, and a scan with few contact points at its load
//! warns of its resolution; the contact area extrapolated to a vanishing pixel from a
//! coarse scan lies closer to a fine scan's answer than the coarse scan's own area, and
//! the page shows both.

use std::path::Path;
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_persson-check"))
}

fn run_ok(cmd: &mut Command) -> String {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{cmd:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).to_string()
}

fn run_err(cmd: &mut Command) -> String {
    let out = cmd.output().unwrap();
    assert!(!out.status.success(), "{cmd:?} succeeded");
    String::from_utf8_lossy(&out.stderr).to_string()
}

/// A generated `n x n` surface written to `dir/name`.
fn surface(dir: &Path, name: &str, n: usize, seed: u64) {
    run_ok(
        bin()
            .args(["surface", "--n", &n.to_string(), "--hurst", "0.8"])
            .args([
                "--lambda-l",
                &(n / 2).to_string(),
                "--lambda-s",
                "4",
                "--seed",
                &seed.to_string(),
                "--out",
                dir.join(name).to_str().unwrap(),
            ]),
    );
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

#[test]
fn a_periodic_scan_gives_what_solve_gives() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    surface(d, "h.npy", 64, 3);
    let p0 = "0.05";
    run_ok(bin().current_dir(d).args([
        "solve",
        "--heights",
        "h.npy",
        "--p0",
        p0,
        "--solver",
        "cg",
        "--tol",
        "1e-8",
        "--out",
        "solved",
    ]));
    run_ok(bin().current_dir(d).args([
        "check-surface",
        "--heights",
        "h.npy",
        "--pixel-size",
        "1",
        "--periodic",
        "--loads",
        p0,
        "--solver",
        "cg",
        "--no-cross-check",
        "--tol",
        "1e-8",
        "--out",
        "checked",
    ]));
    let solved = json(&d.join("solved/summary.json"));
    let checked = json(&d.join("checked/surface.json"));
    let point = &checked["curve"][0];
    // The same solve: the same numbers to the last bit.
    assert_eq!(point["a_r"], solved["contact_area"]);
    assert_eq!(point["energy"], solved["elastic_energy"]);
}

#[test]
fn a_measured_window_gives_a_rising_curve_beside_persson() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    surface(d, "full.npy", 128, 5);
    // Two non-periodic 64 x 64 windows of it, as text (one) and .npy (the other), in a
    // length unit where the pixel is 0.25.
    let full = persson_check::io::npy::read_field(&d.join("full.npy"), 4..=1024).unwrap();
    let window = |i0: usize, j0: usize| -> Vec<f64> {
        (0..64 * 64)
            .map(|k| 0.25 * full.values[(i0 + k / 64) * 128 + j0 + k % 64])
            .collect()
    };
    write_text(&d.join("a.txt"), &window(0, 0), 64);
    persson_check::io::npy::write_field(&d.join("b.npy"), 64, &window(64, 64)).unwrap();
    let stdout = run_ok(bin().current_dir(d).args([
        "check-surface",
        "--heights",
        "a.txt",
        "b.npy",
        "--pixel-size",
        "0.25",
        "--out",
        "checked",
    ]));
    assert!(stdout.contains("contact_area"), "{stdout}");
    let c = json(&d.join("checked/surface.json"));
    let curve = c["curve"].as_array().unwrap();
    assert!(curve.len() >= 5, "{} loads", curve.len());
    let f = |p: &serde_json::Value, k: &str| p[k].as_f64().unwrap();
    for w in curve.windows(2) {
        assert!(f(&w[1], "a_r") > f(&w[0], "a_r"), "the curve does not rise");
    }
    assert!(f(&curve[0], "a_r") > 0.003 && f(&curve[curve.len() - 1], "a_r") < 0.6);
    for p in curve {
        for k in [
            "a_r_persson",
            "a_r_persson_corrected",
            "energy",
            "energy_persson",
        ] {
            assert!(f(p, k) > 0.0, "{k}");
        }
    }
    // CG and its GFMD cross-check on the same windows, at the lowest, middle and highest
    // load.
    let crossed: Vec<f64> = curve
        .iter()
        .filter_map(|p| p["a_r_cross_check"].as_f64().map(|c| c / f(p, "a_r")))
        .collect();
    assert_eq!(crossed.len(), 3, "{crossed:?}");
    assert!(
        crossed.iter().all(|r| (r - 1.0).abs() < 0.01),
        "{crossed:?}"
    );
    assert_eq!(c["solvers_agree"], true);
    assert_eq!(c["comparisons"].as_array().unwrap().len(), 3);
    let md = std::fs::read_to_string(d.join("checked/surface.md")).unwrap();
    let json_text = std::fs::read_to_string(d.join("checked/surface.json")).unwrap();
    for text in [&md, &json_text] {
        assert!(
            !text.contains("NaN") && !text.contains("nan"),
            "a NaN in the output"
        );
    }
    for figure in [
        "psd",
        "contact_area",
        "pressure_distribution",
        "elastic_energy",
    ] {
        for ext in ["svg", "png"] {
            let path = d.join(format!("checked/figures/{figure}.{ext}"));
            assert!(
                std::fs::metadata(&path).unwrap().len() > 1000,
                "{}",
                path.display()
            );
        }
        assert!(md.contains(&format!("figures/{figure}.png")));
    }
}

#[test]
fn bad_scans_and_flags_are_refused_with_a_word() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut rows = vec!["1 2 3 4 5 6".to_string(); 6];
    rows[2] = "1 2 nan 4 NaN 6".into();
    std::fs::write(d.join("holes.txt"), rows.join("\n")).unwrap();
    surface(d, "ok.npy", 32, 1);
    let check = |args: &[&str]| {
        let mut cmd = bin();
        cmd.current_dir(d)
            .arg("check-surface")
            .args(args)
            .args(["--out", "o"]);
        run_err(&mut cmd)
    };
    let e = check(&["--heights", "holes.txt", "--pixel-size", "1"]);
    assert!(
        e.contains("2 of 36 heights") && e.contains("undefined") && e.contains("row 2, column 2"),
        "{e}"
    );
    assert!(
        e.contains("--fill interpolate"),
        "the way to fill them is not named: {e}"
    );
    let e = check(&["--heights", "ok.npy", "--pixel-size", "0"]);
    assert!(e.contains("--pixel-size"), "{e}");
    let e = check(&[
        "--heights",
        "ok.npy",
        "--pixel-size",
        "1",
        "--loads",
        "0.1,-1",
    ]);
    assert!(e.contains("--loads"), "{e}");
    let e = check(&["--heights", "missing.npy", "--pixel-size", "1"]);
    assert!(e.contains("missing.npy"), "{e}");
    // Pixels beyond the tolerance: refused with the way to resample.
    let e = check(&["--heights", "ok.npy", "--pixel-size", "1,1.01"]);
    assert!(e.contains("--pixel-size") && e.contains("resample"), "{e}");
    for (flag, value) in [("--modulus", "-3"), ("--unit", "n m")] {
        let e = check(&["--heights", "ok.npy", "--pixel-size", "1", flag, value]);
        assert!(e.contains(flag), "{flag}: {e}");
    }
    assert!(!d.join("o").exists(), "a refused check wrote output");
}

/// A `rows x cols` window at the corner of the generated 128^2 surface in `dir/full.npy`,
/// heights and pixel scaled by `scale`.
fn window(dir: &Path, rows: usize, cols: usize, scale: f64) -> Vec<f64> {
    let full = persson_check::io::npy::read_field(&dir.join("full.npy"), 4..=1024).unwrap();
    (0..rows * cols)
        .map(|k| scale * full.values[(k / cols) * 128 + k % cols])
        .collect()
}

/// `values` (`rows x cols`) as a text matrix, `nan` where not finite.
fn write_text(path: &Path, values: &[f64], cols: usize) {
    let text: String = values
        .chunks(cols)
        .map(|r| {
            r.iter()
                .map(|v| format!("{v:e}"))
                .collect::<Vec<_>>()
                .join(" ")
                + "\n"
        })
        .collect();
    std::fs::write(path, text).unwrap();
}

#[test]
fn a_rectangular_partly_unmeasured_window_runs_with_fill_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    surface(d, "full.npy", 128, 5);
    // A 48 x 80 window in nm (pixel 2.5 nm), 2% of it unmeasured: a block and scattered
    // points.
    let (rows, cols) = (48, 80);
    let mut h = window(d, rows, cols, 2.5);
    let mut holes = 0;
    for k in (0..rows * cols)
        .filter(|k| k % 97 == 3 || (k / cols == 20 && (30..40).contains(&(k % cols))))
    {
        h[k] = f64::NAN;
        holes += 1;
    }
    write_text(&d.join("scan.txt"), &h, cols);
    let base = [
        "check-surface",
        "--heights",
        "scan.txt",
        "--pixel-size",
        "2.5",
    ];
    let e = run_err(bin().current_dir(d).args(base).args(["--out", "refused"]));
    assert!(
        e.contains(&format!("{holes} of {} heights", rows * cols)),
        "{e}"
    );
    assert!(!d.join("refused").exists());
    let out = bin()
        .current_dir(d)
        .args(base)
        .args(["--fill", "interpolate", "--unit", "nm", "--modulus", "2e9"])
        .args(["--no-cross-check", "--out", "checked"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let c = json(&d.join("checked/surface.json"));
    assert_eq!(
        (c["rows"].as_u64(), c["cols"].as_u64()),
        (Some(48), Some(80))
    );
    assert_eq!(c["filled"][0].as_u64(), Some(holes as u64));
    assert_eq!(c["unit"], "nm");
    let curve = c["curve"].as_array().unwrap();
    assert!(curve.len() >= 5, "{} loads", curve.len());
    let f = |p: &serde_json::Value, k: &str| p[k].as_f64().unwrap();
    for w in curve.windows(2) {
        assert!(f(&w[1], "a_r") > f(&w[0], "a_r"), "the curve does not rise");
    }
    for p in curve {
        assert_eq!(f(p, "p0_pa"), f(p, "p0") * 2e9);
    }
    // One progress line per load on stderr (not a terminal here).
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines = stderr
        .lines()
        .filter(|l| l.starts_with("check-surface: scan 1/1, cg, load"))
        .count();
    assert_eq!(lines, c["loads"].as_array().unwrap().len(), "{stderr}");
    // The page names the filled points, the unit and the pressures in Pa.
    let md = std::fs::read_to_string(d.join("checked/surface.md")).unwrap();
    assert!(
        md.contains(&format!("{holes} of {} points", rows * cols)),
        "{md}"
    );
    assert!(
        md.contains("lengths in nm") && md.contains("rms height (nm)"),
        "{md}"
    );
    assert!(
        md.contains("p0 (Pa)") && md.contains("E_el (J/m^2)"),
        "{md}"
    );
    assert!(
        !md.contains("a_r (—)"),
        "a column for a cross-check not run"
    );
    assert!(
        md.contains("## Re-entry over magnification") && c["reentry"]["share"].as_f64().is_some()
    );
    // Every solve is in solves.jsonl, one line each.
    let solves = std::fs::read_to_string(d.join("checked/solves.jsonl")).unwrap();
    assert_eq!(solves.lines().count(), curve.len());
    for text in [
        &md,
        &std::fs::read_to_string(d.join("checked/surface.json")).unwrap(),
    ] {
        assert!(
            !text.contains("NaN") && !text.contains("nan"),
            "a NaN in the output"
        );
    }
    // A rectangle is not solved periodic: refused with a word.
    let e = run_err(bin().current_dir(d).args(base).args([
        "--fill",
        "interpolate",
        "--periodic",
        "--out",
        "o3",
    ]));
    assert!(e.contains("--periodic") && e.contains("square"), "{e}");
    // More than a tenth unmeasured: refused even with --fill.
    h.iter_mut()
        .take(rows * cols / 9)
        .for_each(|v| *v = f64::NAN);
    write_text(&d.join("scan.txt"), &h, cols);
    let e = run_err(
        bin()
            .current_dir(d)
            .args(base)
            .args(["--fill", "interpolate", "--out", "o2"]),
    );
    assert!(e.contains("more than the 10%"), "{e}");
}

/// The check-surface guide (`docs/check-surface.md`) names every warning the check can give.
#[test]
fn the_check_surface_guide_names_every_warning() {
    let guide = include_str!("../docs/check-surface.md");
    for limit in persson_check::measured::warnings::LIMITS {
        assert!(
            guide.contains(&format!("`{}`", limit.name)),
            "docs/check-surface.md does not name the warning {}",
            limit.name
        );
    }
}

/// Row `row` of a generated `n x n` surface (H = 0.8), heights times `scale`.
fn profile(n: usize, row: usize, scale: f64) -> Vec<f64> {
    use persson_check::engine::fft::Fft2;
    use persson_check::engine::surface::{Surface, SurfaceModel};
    let s = Surface::generate(&SurfaceModel::new(n, 0.8, n as f64 / 2.0, 4.0, 9)).unwrap();
    let h = s.heights_at(f64::INFINITY, &Fft2::new(s.grid()));
    h[row * n..(row + 1) * n]
        .iter()
        .map(|v| v * scale)
        .collect()
}

/// A quick line-scan check, in um: two loads, three synthesized 64^2 surfaces, no
/// re-entry.
const QUICK_LINE: [&str; 9] = [
    "--unit",
    "um",
    "--loads",
    "0.01,0.05",
    "--line-side",
    "64",
    "--line-seeds",
    "3",
    "--no-reentry",
];

#[test]
fn a_line_scan_is_checked_on_synthesized_surfaces_end_to_end() {
    // One stylus profile of 1024 points, one height per line of a text file, in um with a
    // pixel of 0.5 um: a line scan by the rule (one-dimensional), no --line needed.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text: Vec<String> = profile(1024, 3, 0.5)
        .iter()
        .map(|v| format!("{v}"))
        .collect();
    std::fs::write(d.join("trace.txt"), text.join("\n")).unwrap();
    let out = run_ok(
        bin()
            .current_dir(d)
            .args([
                "check-surface",
                "--heights",
                "trace.txt",
                "--pixel-size",
                "0.5",
            ])
            .args(QUICK_LINE)
            .args(["--out", "o"]),
    );
    assert!(
        out.contains("line scans: 1 profile(s) of 1024 points") && out.contains("3 synthesized"),
        "{out}"
    );
    let j = json(&d.join("o/surface.json"));
    let line = &j["line"];
    assert_eq!(line["points"], 1024);
    assert_eq!(line["synthesized_side"], 64);
    assert_eq!(j["scans"].as_array().unwrap().len(), 3);
    let converted = line["converted"].as_array().unwrap();
    assert!(converted.len() > 10);
    assert!(converted.iter().any(|b| b["uncertain"].is_null()));
    assert_eq!(converted.last().unwrap()["uncertain"], "cutoff");
    let curve = j["curve"].as_array().unwrap();
    assert_eq!(curve.len(), 2);
    let a = |i: usize, k: &str| curve[i][k].as_f64().unwrap();
    assert!(a(1, "a_r") > a(0, "a_r") && a(0, "a_r") > 0.0);
    assert!(curve[0]["a_r_std_error"].as_f64().is_some());
    assert_eq!(line["persson"].as_array().unwrap().len(), 2);
    // Under isotropy the surface's rms slope is sqrt 2 times the profile's.
    let (g2, g1) = (
        line["slope_rms_converted"].as_f64().unwrap(),
        line["slope_rms_spectral"].as_f64().unwrap(),
    );
    assert!(
        (g2 / (std::f64::consts::SQRT_2 * g1) - 1.0).abs() < 0.2,
        "{g2} vs {g1}"
    );
    let md = std::fs::read_to_string(d.join("o/surface.md")).unwrap();
    assert!(md.contains("not on the measured profiles"), "{md}");
    assert!(md.contains("near the cutoff"), "{md}");
    assert!(d.join("o/figures/line_psd.png").exists());
    assert!(d.join("o/solves.jsonl").exists());
}

#[test]
fn bad_line_scans_are_refused_with_a_word_about_line_scans() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("short.txt"), "1\n2\n3\n4\n5\n").unwrap();
    let row: Vec<String> = profile(128, 0, 1.0).iter().map(|v| v.to_string()).collect();
    std::fs::write(d.join("a.txt"), row.join(" ")).unwrap();
    std::fs::write(d.join("b.txt"), row[..100].join(" ")).unwrap();
    let check = |args: &[&str]| {
        let mut cmd = bin();
        cmd.current_dir(d)
            .arg("check-surface")
            .args(args)
            .args(["--out", "o"]);
        run_err(&mut cmd)
    };
    let e = check(&["--heights", "short.txt", "--pixel-size", "1"]);
    assert!(
        e.contains("short.txt") && e.contains("line scan of 5 points"),
        "{e}"
    );
    assert!(!e.contains("pixel"), "{e}");
    let e = check(&["--heights", "a.txt", "b.txt", "--pixel-size", "1"]);
    assert!(e.contains("share their length"), "{e}");
    let e = check(&[
        "--heights",
        "a.txt",
        "--pixel-size",
        "1",
        "--line-seeds",
        "1",
    ]);
    assert!(e.contains("--line-seeds"), "{e}");
    assert!(!d.join("o").exists(), "a refused check wrote output");
}

/// A smooth generated window with three single-point spikes of 40 rms heights, written as
/// a text matrix to `dir/spiky.txt`: at the lowest default load the spikes carry the
/// contact.
fn spiky(dir: &Path, n: usize) -> std::path::PathBuf {
    surface(dir, "smooth.npy", n, 5);
    let scan = persson_check::measured::scan::Scan::read(&dir.join("smooth.npy")).unwrap();
    let mut h = scan.heights;
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let rms = (h.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / h.len() as f64).sqrt();
    for k in [
        n * n / 3 + n / 4,
        n * n / 2 + n / 2,
        3 * n * n / 4 + 2 * n / 3,
    ] {
        h[k] += 40.0 * rms;
    }
    let text: String = h
        .chunks(n)
        .map(|row| {
            let cells: Vec<String> = row.iter().map(|x| format!("{x:e}")).collect();
            cells.join(" ") + "\n"
        })
        .collect();
    let path = dir.join("spiky.txt");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_spiky_window_finishes_with_every_load_converged_or_failed_with_its_state() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let path = spiky(d, 48);
    let started = std::time::Instant::now();
    let out = bin()
        .current_dir(d)
        .args(["check-surface", "--heights", path.to_str().unwrap()])
        .args(["--pixel-size", "1", "--no-reentry", "--out", "checked"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        started.elapsed().as_secs_f64() < 120.0,
        "a 48 x 48 spiky window took {:?}",
        started.elapsed()
    );
    // The spikes are reported before the first solve ends.
    let said = stderr.find("beyond 6 rms").expect("the outliers line");
    let first_load = stderr.find("load 1/").expect("a line per load");
    assert!(said < first_load, "{stderr}");
    let c = json(&d.join("checked/surface.json"));
    let o = &c["outliers"][0];
    assert_eq!(o["count"], 3, "three spikes beyond 6 rms: {o}");
    assert!(o["max_rms"].as_f64().unwrap() > 20.0, "{o}");
    let loads = c["loads"].as_array().unwrap().len();
    assert_eq!(o["contact_share"].as_array().unwrap().len(), loads);
    // Every headline load is on the curve (converged) or failed with the solver's state.
    let solved = c["curve"].as_array().unwrap().len();
    let failed: Vec<&serde_json::Value> = c["failures"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["headline"] == true)
        .collect();
    assert_eq!(solved + failed.len(), loads, "{}", c["failures"]);
    for f in &failed {
        let state = &f["state"];
        assert!(
            state["iterations"].as_u64().unwrap() <= 1000
                && state["residual"].as_f64().unwrap() > state["tol"].as_f64().unwrap(),
            "{f}"
        );
    }
    // At the lowest load, if solved, the spikes carry part of the contact, and the page
    // says so.
    if let Some(share) = o["contact_share"][0].as_f64() {
        assert!(share > 0.0, "{o}");
        let page = std::fs::read_to_string(d.join("checked/surface.md")).unwrap();
        assert!(page.contains("## Spikes and outliers"), "{page}");
        assert!(page.contains("of the contact at p0 ="), "{page}");
    }
}

#[test]
fn a_spent_iteration_budget_fails_the_load_with_its_state_and_the_check_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let path = spiky(d, 32);
    run_ok(bin().current_dir(d).args([
        "check-surface",
        "--heights",
        path.to_str().unwrap(),
        "--pixel-size",
        "1",
        "--no-reentry",
        "--no-cross-check",
        "--max-iterations",
        "3",
        "--out",
        "checked",
    ]));
    let c = json(&d.join("checked/surface.json"));
    assert_eq!(c["max_iterations"], 3);
    let failures = c["failures"].as_array().unwrap();
    assert!(!failures.is_empty(), "3 iterations converge nothing cold");
    for f in failures {
        assert_eq!(f["state"]["iterations"], 3, "{f}");
        assert!(f["state"]["contact_points"].as_u64().unwrap() > 0, "{f}");
        assert!(f["message"].as_str().unwrap().contains("(budget 3)"), "{f}");
    }
    let page = std::fs::read_to_string(d.join("checked/surface.md")).unwrap();
    assert!(page.contains("a budget of 3 iterations"), "{page}");
}

#[test]
fn despiking_replaces_the_spikes_and_says_how_many() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let path = spiky(d, 32);
    run_ok(bin().current_dir(d).args([
        "check-surface",
        "--heights",
        path.to_str().unwrap(),
        "--pixel-size",
        "1",
        "--no-reentry",
        "--no-cross-check",
        "--loads",
        "0.05",
        "--despike",
        "8",
        "--out",
        "checked",
    ]));
    let c = json(&d.join("checked/surface.json"));
    let o = &c["outliers"][0];
    assert_eq!(o["despiked"], 3, "{o}");
    assert_eq!(o["count"], 0, "no outlier is left: {o}");
    assert_eq!(c["despike"], 8.0);
    let err = run_err(bin().current_dir(d).args([
        "check-surface",
        "--heights",
        path.to_str().unwrap(),
        "--pixel-size",
        "1",
        "--despike",
        "1",
        "--out",
        "refused",
    ]));
    assert!(err.contains("despike") && err.contains(">= 3"), "{err}");
}

/// A 1024-point profile at positions alternately 0.4 and 0.6 apart, as a stylus file's
/// rounded positions come, written as `x h` lines (with a header comment) to `dir/name`;
/// returns its positions and heights.
fn xy_profile(dir: &Path, name: &str) -> (Vec<f64>, Vec<f64>) {
    let h = profile(1024, 5, 0.5);
    let mut x = vec![0.0];
    for k in 1..h.len() {
        x.push(x[k - 1] + if k % 2 == 1 { 0.4 } else { 0.6 });
    }
    let mut text = vec!["# position (um), height (um)".to_string()];
    text.extend(x.iter().zip(&h).map(|(x, h)| format!("{x} {h}")));
    std::fs::write(dir.join(name), text.join("\n")).unwrap();
    (x, h)
}

#[test]
fn a_line_scan_at_non_uniform_positions_is_resampled_with_a_warning_and_checked() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (x, h) = xy_profile(d, "xy.txt");
    let quick = [&QUICK_LINE[..], &["--no-cross-check"]].concat();
    let out = bin()
        .current_dir(d)
        .args(["check-surface", "--line-scan", "xy.txt"])
        .args(&quick)
        .args(["--out", "o"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let pixel = (x[x.len() - 1] - x[0]) / (x.len() - 1) as f64;
    assert!(
        stderr.contains("warning: xy.txt: a line scan at non-uniform positions (spacings 0.4 to 0.6) resampled onto 1024 evenly spaced points"),
        "{stderr}"
    );
    let j = json(&d.join("o/surface.json"));
    assert!((j["pixel_size"].as_f64().unwrap() / pixel - 1.0).abs() < 1e-12);
    // The same curve as the resampled profile's, handed over as heights.
    let even = persson_check::measured::line::resample::resample(
        Path::new("xy"),
        &x,
        &h,
        persson_check::measured::line::resample::Origin::Indices,
    )
    .unwrap();
    let text: Vec<String> = even.heights.iter().map(|v| format!("{v:?}")).collect();
    std::fs::write(d.join("even.txt"), text.join("\n")).unwrap();
    run_ok(
        bin()
            .current_dir(d)
            .args(["check-surface", "--heights", "even.txt", "--pixel-size"])
            .arg(format!("{pixel:?}"))
            .args(&quick)
            .args(["--out", "e"]),
    );
    let e = json(&d.join("e/surface.json"));
    assert_eq!(j["curve"], e["curve"]);
    assert_eq!(j["curve"].as_array().unwrap().len(), 2);
    // A pixel size that is not the positions' spacing is refused.
    let err = run_err(
        bin()
            .current_dir(d)
            .args([
                "check-surface",
                "--line-scan",
                "xy.txt",
                "--pixel-size",
                "1",
            ])
            .args(["--out", "p"]),
    );
    assert!(
        err.contains("--pixel-size") && err.contains("spacing"),
        "{err}"
    );
}

#[test]
fn a_line_scan_whose_positions_do_not_increase_is_refused_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = "# x h\n0 1.0\n1 2.0\n\n2 1.5\n1.5 0.5\n3 0.0\n";
    std::fs::write(d.join("back.txt"), text).unwrap();
    let e = run_err(bin().current_dir(d).args([
        "check-surface",
        "--line-scan",
        "back.txt",
        "--out",
        "o",
    ]));
    assert!(
        e.contains("back.txt")
            && e.contains("line 6: position 1.5 after 2 (line 5)")
            && e.contains("increase strictly"),
        "{e}"
    );
    std::fs::write(d.join("three.txt"), "0 1 2\n").unwrap();
    let e = run_err(bin().current_dir(d).args([
        "check-surface",
        "--line-scan",
        "three.txt",
        "--out",
        "o",
    ]));
    assert!(e.contains("three.txt") && e.contains("line 1"), "{e}");
    assert!(!d.join("o").exists(), "a refused check wrote output");
}

/// Maps smaller than `MIN_SIDE` (32) on a side are refused naming their size and the
/// minimum; a map exactly at the minimum runs.
#[test]
fn maps_below_the_floor_on_size_are_refused_by_their_size() {
    use persson_check::measured::scan::MIN_SIDE;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, rows, cols) in [("seven.txt", 7, 4), ("four.txt", 4, 4)] {
        let values: Vec<f64> = (0..rows * cols).map(|k| (k as f64 * 0.7).sin()).collect();
        write_text(&d.join(name), &values, cols);
        let e = run_err(
            bin()
                .current_dir(d)
                .args(["check-surface", "--heights", name, "--pixel-size", "1"])
                .args(["--out", "o"]),
        );
        let size = format!("{rows} x {cols}");
        let floor = format!("{MIN_SIDE} x {MIN_SIDE}");
        assert!(
            e.contains("--heights") && e.contains(name) && e.contains(&size) && e.contains(&floor),
            "{e}"
        );
    }
    assert!(!d.join("o").exists(), "a refused check wrote output");
    surface(d, "floor.npy", MIN_SIDE, 1);
    run_ok(bin().current_dir(d).args([
        "check-surface",
        "--heights",
        "floor.npy",
        "--pixel-size",
        "1",
        "--loads",
        "0.05",
        "--no-cross-check",
        "--no-reentry",
        "--out",
        "o",
    ]));
    assert!(d.join("o/surface.json").exists());
}

/// The names of the warnings of a periodic `n x n` generated scan checked at `p0`.
fn warned_at(dir: &Path, n: usize, p0: &str) -> Vec<String> {
    let name = format!("s{n}.npy");
    surface(dir, &name, n, 2);
    let out = format!("o{n}");
    run_ok(bin().current_dir(dir).args([
        "check-surface",
        "--heights",
        &name,
        "--pixel-size",
        "1",
        "--periodic",
        "--loads",
        p0,
        "--no-cross-check",
        "--no-reentry",
        "--out",
        &out,
    ]));
    let j = json(&dir.join(out).join("surface.json"));
    j["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["name"].as_str().unwrap().to_string())
        .collect()
}

/// A 64^2 scan at a low load holds a few dozen contact points: a `resolution` warning;
/// a 256^2 one at a moderate load holds thousands: none.
#[test]
fn too_few_contact_points_give_a_resolution_warning() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let w = warned_at(d, 64, "0.005");
    assert!(w.contains(&"resolution".to_string()), "{w:?}");
    let w = warned_at(d, 256, "0.05");
    assert!(!w.contains(&"resolution".to_string()), "{w:?}");
}

/// A periodic scan of the generated surface (`H = 0.8`, `lambda_l / lambda_s = 6.4`,
/// realization `seed`) with `lambda_s / a = per_pixel`, as the check reads it.
fn sampled(per_pixel: f64, seed: u64) -> persson_check::measured::scan::Scan {
    use persson_check::engine::fft::Fft2;
    use persson_check::engine::surface::{Surface, SurfaceModel};
    use persson_check::measured::psd::Shape;
    let lambda_l = 6.4 * per_pixel;
    let n = (2.0 * lambda_l) as usize;
    let s = Surface::generate(&SurfaceModel::new(n, 0.8, lambda_l, per_pixel, seed)).unwrap();
    persson_check::measured::scan::Scan {
        shape: Shape { rows: n, cols: n },
        heights: s.heights_at(f64::INFINITY, &Fft2::new(s.grid())),
        source: format!("lambda_s_{per_pixel}_px").into(),
        filled: 0,
    }
}

#[test]
fn the_contact_area_extrapolated_from_a_coarse_pixel_lies_closer_to_a_fine_ones() {
    use persson_check::measured::check::{check, CheckOptions};
    use persson_check::measured::psd::Boundary;
    // One realization at two pixels: lambda_s / a = 5 (a 64^2 scan, coarsened by 2 to
    // lambda_s / a = 2.5, which still holds every mode) and lambda_s / a = 20 (256^2).
    let opts = CheckOptions {
        boundary: Boundary::Periodic,
        loads: Some(vec![0.05, 0.145]),
        cross_check: false,
        reentry: false,
        ..CheckOptions::default()
    };
    for seed in [1, 2] {
        let coarse = check(&[sampled(5.0, seed)], &opts, &mut |_| {
            std::ops::ControlFlow::Continue(())
        })
        .unwrap();
        let fine = check(
            &[sampled(20.0, seed)],
            &CheckOptions {
                extrapolate: false,
                ..opts.clone()
            },
            &mut |_| std::ops::ControlFlow::Continue(()),
        )
        .unwrap();
        for (c, f) in coarse.curve.iter().zip(&fine.curve) {
            assert!(f.pixel.is_none());
            let e = c.pixel.as_ref().expect("a 64^2 scan coarsens by 2");
            // 64 / 4 = 16 < 32 points a side: no third level; lambda_s = 5 pixels keeps
            // every mode at twice the pixel.
            assert_eq!(e.coarse.len(), 1);
            assert!(e.folded.is_empty());
            let (raw, extrapolated) = ((c.a_r - f.a_r).abs(), (e.extrapolated - f.a_r).abs());
            assert!(
                extrapolated < raw,
                "seed {seed}, p0 {}: a_r {} at lambda_s/a = 5, {} extrapolated, {} at \
                 lambda_s/a = 20",
                c.p0,
                c.a_r,
                e.extrapolated,
                f.a_r
            );
            // The coarse pixel overstates the area, and the theory is set against the
            // extrapolated one.
            assert!(e.difference < 0.0);
            let ratio = e.extrapolated / c.a_r_persson;
            assert!((c.area_ratio.value - ratio).abs() < 1e-12);
        }
        let page = persson_check::measured::page::markdown(&coarse);
        assert!(page.contains("## The pixel's own error"), "{page}");
        assert!(page.contains("| p0 / E* | a_r at the pixel | at 2 pixels | extrapolated"));
    }
}

#[test]
fn a_noise_floor_is_cut_off_by_default_and_a_tip_radius_cuts_longer_wavelengths() {
    use persson_check::measured::check::{check, CheckOptions};
    use persson_check::measured::cutoff::Reason;
    use persson_check::measured::psd::Boundary;
    let go = &mut |_: persson_check::measured::check::Event| std::ops::ControlFlow::Continue(());
    // A periodic 256^2 scan (lambda_s = 20 pixels) with white noise of 0.15 of its rms
    // height over it.
    let mut scan = sampled(20.0, 3);
    let h_rms = (scan.heights.iter().map(|v| v * v).sum::<f64>() / 65536.0).sqrt();
    let mut x = 5u64;
    for v in &mut scan.heights {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *v += 0.15 * h_rms * 12f64.sqrt() * ((x >> 11) as f64 / 2f64.powi(53) - 0.5);
    }
    let opts = CheckOptions {
        boundary: Boundary::Periodic,
        loads: Some(vec![0.05]),
        cross_check: false,
        reentry: false,
        extrapolate: false,
        ..CheckOptions::default()
    };
    let cut = check(std::slice::from_ref(&scan), &opts, go).unwrap();
    let kept = check(
        std::slice::from_ref(&scan),
        &CheckOptions {
            cutoff: false,
            ..opts.clone()
        },
        go,
    )
    .unwrap();
    let k = cut.cutoff.scans[0].expect("a noise floor");
    assert!(matches!(k.reason, Reason::NoiseFloor { .. }));
    assert!(k.pixels > 2.5, "{k:?}");
    assert!(kept.cutoff.scans[0].is_none() && !kept.cutoff.asked);
    // The floor's steep slopes are gone from the heights solved: a lower g, and with it
    // a larger contact area (a_r ~ p0 / (E* g)); the warning speaks only where the floor
    // was kept.
    let g = |c: &persson_check::measured::check::SurfaceCheck| {
        c.cutoff.slope_rms_spectral.unwrap().value
    };
    assert!(g(&cut) < 0.9 * g(&kept), "{} {}", g(&cut), g(&kept));
    assert!(cut.curve[0].a_r > kept.curve[0].a_r);
    let warned = |c: &persson_check::measured::check::SurfaceCheck| {
        c.warnings.iter().any(|w| w.name == "noise_floor")
    };
    assert!(warned(&kept) && !warned(&cut));
    let page = persson_check::measured::page::markdown(&cut);
    assert!(page.contains("## Reliable scales") && page.contains("noise floor (top octave"));
    // A tip blunter than the surface's rms curvature at its finest scales cuts it,
    // by its radius, at a longer wavelength the blunter it is.
    let mut tip = |r: f64| {
        check(
            std::slice::from_ref(&scan),
            &CheckOptions {
                tip_radius: Some(r),
                ..opts.clone()
            },
            go,
        )
        .unwrap()
        .cutoff
        .scans[0]
            .unwrap()
    };
    let (sharp, blunt) = (tip(5.0), tip(50.0));
    assert_eq!(blunt.reason, Reason::TipRadius { radius: 50.0 });
    assert!(blunt.wavelength > sharp.wavelength, "{sharp:?} {blunt:?}");
    // A radius out of range, or with no cutoff, is refused by its flag.
    let dir = tempfile::tempdir().unwrap();
    surface(dir.path(), "s.npy", 64, 1);
    for bad in [
        &["--tip-radius", "-1"][..],
        &["--tip-radius", "2", "--no-cutoff"],
    ] {
        let err = run_err(
            bin()
                .current_dir(dir.path())
                .args(["check-surface", "--heights", "s.npy", "--pixel-size", "1"])
                .args(bad)
                .args(["--out", "o"]),
        );
        assert!(err.contains("--tip-radius"), "{err}");
    }
}
