//! `check-surface --scales`: two generated scans of one surface at pixel sizes ten times
//! apart (a coarse 128^2 window at pixel 10 nm of one realization, a fine 256^2 window at
//! pixel 1 nm, given in µm, of a finer realization of the same spectrum) are stitched
//! without a gap into the generating spectrum, and the page sets each scan's simulated
//! contact against Persson on its band and on the whole surface; a scan list with a bad
//! field, or `--scales` with `--pixel-size`, is refused with a word.

use std::path::Path;
use std::process::Command;

use persson_check::engine::fft::Fft2;
use persson_check::engine::surface::{Amplitudes, Surface};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_persson-check"))
}

/// The generating spectrum, `C(q) = q^-3.6` (nm^4, q in 1/nm): `H = 0.8`.
fn generating(q: f64) -> f64 {
    q.powf(-3.6)
}

/// A `side^2` window of an `n^2` realization of [`generating`] at pixel `pixel` nm,
/// heights in nm times `scale`.
fn window(n: usize, side: usize, pixel: f64, seed: u64, scale: f64) -> Vec<f64> {
    let dq = 2.0 * std::f64::consts::PI / n as f64;
    let power = |q_grid: f64| generating(q_grid / pixel) / pixel.powi(4) * dq * dq;
    let s = Surface::generate_tabulated(n, &power, seed, Amplitudes::Gaussian).unwrap();
    let h = s.heights_at(f64::INFINITY, &Fft2::new(s.grid()));
    (0..side * side)
        .map(|k| h[(k / side) * n + k % side] * pixel * scale)
        .collect()
}

const LIST: &str = "# one surface at two scales\n\
    [[scan]]\nfile = \"coarse.npy\"\npixel_size = 10\nunit = \"nm\"\n\n\
    [[scan]]\nfile = \"fine.npy\"\npixel_size = 0.001\nunit = \"µm\"\n";

/// The two scans and their list in `dir`.
fn two_scans(dir: &Path) {
    let coarse = window(512, 128, 10.0, 1, 1.0);
    persson_check::io::npy::write_field(&dir.join("coarse.npy"), 128, &coarse).unwrap();
    let fine = window(512, 256, 1.0, 2, 1e-3);
    persson_check::io::npy::write_field(&dir.join("fine.npy"), 256, &fine).unwrap();
    std::fs::write(dir.join("scales.toml"), LIST).unwrap();
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

#[test]
fn two_scans_ten_times_apart_are_stitched_and_each_set_against_the_whole_surface() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    two_scans(d);
    let out = bin()
        .current_dir(d)
        .args([
            "check-surface",
            "--scales",
            "scales.toml",
            "--loads",
            "0.005,0.02",
        ])
        .args(["--no-cross-check", "--no-reentry", "--out", "checked"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("stitched spectrum:") && stdout.contains("whole surface"),
        "{stdout}"
    );
    let c = json(&d.join("checked/scales.json"));
    // The fine scan in µm is converted into the first scan's nm.
    assert_eq!(c["unit"], "nm");
    assert!((f(&c["scans"][1]["pixel_size"]) - 1.0).abs() < 1e-12);
    // Bands ten times apart overlap: no gap, and the stitched spectrum is the generating
    // one where the two are joined (within 10%), and everywhere within 10% plus three of
    // its standard errors (the coarse scan's lowest bins rest on a few modes).
    let stitched = &c["stitched"];
    assert_eq!(stitched["gaps"].as_array().unwrap().len(), 0);
    let (fine_lo, coarse_hi) = (
        f(&c["scans"][1]["band"]["lo"]),
        f(&c["scans"][0]["band"]["hi"]),
    );
    let mut joined = 0;
    for b in stitched["bins"].as_array().unwrap() {
        let (q, cq, e) = (f(&b["q"]), f(&b["c"]), f(&b["std_error"]));
        let d = cq / generating(q) - 1.0;
        assert!(d.abs() < 0.1 + 3.0 * e / cq, "q {q}: {d:+.3}");
        if q > fine_lo && q < coarse_hi {
            joined += 1;
            assert!(d.abs() < 0.1, "q {q}: {d:+.3} where the scans are joined");
        }
    }
    assert!(joined >= 2, "{joined} bins where the scans are joined");
    // Each areal scan simulated, beside Persson on its band and on the whole surface:
    // the fine scales remove about half the coarse scan's predicted contact (its band's
    // rms slope is about half the surface's), the coarse ones a tenth of the fine scan's.
    let ratio = |k: usize| f(&c["scans"][k]["comparison"][0]["whole_over_band"]);
    assert!(
        ratio(0) < 0.7 && ratio(1) > 0.8 && ratio(1) < 1.0,
        "{} {}",
        ratio(0),
        ratio(1)
    );
    for k in 0..2 {
        let row = &c["scans"][k]["comparison"][1];
        assert!(f(&row["a_r"]) > 0.0 && f(&row["a_r_persson_whole"]) < f(&row["a_r_persson_band"]));
        assert!(d.join(format!("checked/scan-{k}/surface.md")).exists());
    }
    let page = std::fs::read_to_string(d.join("checked/scales.md")).unwrap();
    for words in [
        "The stitched spectrum",
        "no gap",
        "Persson, whole surface",
        "scan[1]: simulated, against Persson on its band and on the whole surface",
        "figures/scales_psd.svg",
    ] {
        assert!(page.contains(words), "{words}:\n{page}");
    }
    assert!(d.join("checked/figures/scales_psd.svg").exists());
    assert!(d.join("checked/figures/scales_contact_area.svg").exists());
}

#[test]
fn a_scan_list_with_a_bad_field_is_refused_with_a_word() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("bad.toml"),
        LIST.replace("pixel_size = 10", "pixel = 10"),
    )
    .unwrap();
    std::fs::write(
        d.join("neg.toml"),
        LIST.replace("pixel_size = 10", "pixel_size = -10"),
    )
    .unwrap();
    let err = |args: &[&str]| {
        let out = bin().current_dir(d).args(args).output().unwrap();
        assert!(!out.status.success(), "{args:?} succeeded");
        String::from_utf8_lossy(&out.stderr).to_string()
    };
    let e = err(&["check-surface", "--scales", "bad.toml", "--out", "o"]);
    assert!(
        e.contains("bad.toml") && e.contains("pixel") && e.contains("pixel_size"),
        "{e}"
    );
    let e = err(&["check-surface", "--scales", "neg.toml", "--out", "o"]);
    assert!(
        e.contains("invalid --scales scan[0].pixel_size = -10"),
        "{e}"
    );
    let e = err(&[
        "check-surface",
        "--scales",
        "neg.toml",
        "--pixel-size",
        "1",
        "--out",
        "o",
    ]);
    assert!(e.contains("--pixel-size") && e.contains("--scales"), "{e}");
}
