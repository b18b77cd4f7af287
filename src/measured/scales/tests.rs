use std::path::{Path, PathBuf};

use super::*;
use crate::engine::fft::Fft2;
use crate::engine::surface::{Amplitudes, Surface};
use crate::measured::psd::Shape;

const HURST: f64 = 0.8;

/// The generating spectrum, `C(q) = q^(-2 - 2H)` (length^4, the length unit of the fine
/// scan's pixel), for every `q`.
fn generating(q: f64) -> f64 {
    q.powf(-2.0 - 2.0 * HURST)
}

/// A `side x side` window (top left) of an `n x n` realization of [`generating`] with
/// pixel `pixel`, heights in the same unit, times `scale`.
fn window(n: usize, side: usize, pixel: f64, seed: u64, scale: f64) -> Scan {
    let dq = 2.0 * std::f64::consts::PI / n as f64;
    let power = |q_grid: f64| generating(q_grid / pixel) / pixel.powi(4) * dq * dq;
    let s = Surface::generate_tabulated(n, &power, seed, Amplitudes::Gaussian).unwrap();
    let h = s.heights_at(f64::INFINITY, &Fft2::new(s.grid()));
    let heights = (0..side * side)
        .map(|k| h[(k / side) * n + k % side] * pixel * scale)
        .collect();
    Scan {
        shape: Shape {
            rows: side,
            cols: side,
        },
        heights,
        source: PathBuf::from(format!("window {side} of {n}, pixel {pixel}")),
        filled: 0,
    }
}

fn map(label: &str, scan: Scan, pixel: f64, unit: Option<&str>) -> ScaleScan {
    ScaleScan {
        label: label.to_string(),
        measured: Measured::Map(scan),
        pixel,
        unit: unit.map(str::to_string),
    }
}

/// A coarse 256^2 window (pixel 10) of a 1024^2 realization and a fine 512^2 window
/// (pixel 1) of another 1024^2 realization of the same spectrum: 2560 and 512 wide.
fn two_scales(seed: u64) -> Vec<ScaleScan> {
    vec![
        map(
            "coarse",
            window(1024, 256, 10.0, seed, 1.0),
            10.0,
            Some("nm"),
        ),
        map(
            "fine",
            window(1024, 512, 1.0, seed + 100, 1.0),
            1.0,
            Some("nm"),
        ),
    ]
}

/// The stitched bins' relative deviations from the generating spectrum at their `q`,
/// with their stated relative errors.
fn deviations(s: &Stitched) -> Vec<(f64, f64, f64)> {
    s.bins
        .iter()
        .map(|b| (b.q, b.c / generating(b.q) - 1.0, b.std_error / b.c))
        .collect()
}

#[test]
fn two_scans_ten_times_apart_stitch_to_the_generating_spectrum() {
    let sp = spectra(&two_scales(1), Boundary::Free, None).unwrap();
    let [coarse, fine] = [sp.bands[0], sp.bands[1]];
    // Bands: 4 lowest modes up to wavelengths of 4 pixels.
    let two_pi = 2.0 * std::f64::consts::PI;
    assert!((coarse.lo - 4.0 * two_pi / 2560.0).abs() < 1e-12);
    assert!((fine.hi - two_pi / 4.0).abs() < 1e-12);
    assert!(sp.stitched.gaps.is_empty(), "{:?}", sp.stitched.gaps);
    let dev = deviations(&sp.stitched);
    for (q, d, e) in &dev {
        eprintln!("q {q:.4e}: {:+.3} (stated {:.3})", d, e);
    }
    // Where the stated error allows a 10% test at three standard errors, the stitched
    // spectrum is within 10%; everywhere within 10% plus three standard errors.
    for &(q, d, e) in &dev {
        assert!(
            d.abs() < 0.10 + 3.0 * e,
            "q {q}: {d:+.3}, stated error {e:.3}"
        );
        if e < 0.1 / 3.0 {
            assert!(d.abs() < 0.10, "q {q}: {d:+.3}, stated error {e:.3}");
        }
    }
    // In the overlap, where the two scans are joined, within 10%.
    let overlap: Vec<_> = dev
        .iter()
        .filter(|(q, ..)| *q > fine.lo && *q < coarse.hi)
        .collect();
    assert!(overlap.len() >= 3, "{overlap:?}");
    assert!(
        overlap.iter().all(|(_, d, _)| d.abs() < 0.10),
        "{overlap:?}"
    );
}

#[test]
fn scans_in_different_units_are_converted() {
    let nm = spectra(&two_scales(2), Boundary::Free, None).unwrap();
    // The fine scan in micrometres: heights and pixel a thousandth.
    let mut mixed = two_scales(2);
    if let Measured::Map(s) = &mut mixed[1].measured {
        s.heights.iter_mut().for_each(|h| *h *= 1e-3);
    }
    mixed[1].pixel = 1e-3;
    mixed[1].unit = Some("µm".into());
    let converted = spectra(&mixed, Boundary::Free, None).unwrap();
    assert_eq!(converted.unit.as_deref(), Some("nm"));
    assert_eq!(nm.stitched.bins.len(), converted.stitched.bins.len());
    for (a, b) in nm.stitched.bins.iter().zip(&converted.stitched.bins) {
        assert!((a.q / b.q - 1.0).abs() < 1e-9 && (a.c / b.c - 1.0).abs() < 1e-9);
    }
    // One scan without a unit among scans with different units: refused by name.
    mixed[0].unit = None;
    let e = spectra(&mixed, Boundary::Free, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("invalid coarse.unit = none") && e.contains("nm"),
        "{e}"
    );
    mixed[0].unit = Some("furlong".into());
    let e = spectra(&mixed, Boundary::Free, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("coarse.unit = furlong"), "{e}");
    mixed[0].pixel = -1.0;
    let e = validate(&mixed).unwrap_err().to_string();
    assert!(e.contains("coarse.pixel_size = -1"), "{e}");
}

#[test]
fn scans_whose_bands_do_not_meet_leave_a_gap() {
    // Pixels 100 times apart: the coarse scan reaches wavelengths of 400 (fine pixels),
    // the fine 128^2 window starts at 128 / 4 = 32.
    let scans = vec![
        map("coarse", window(256, 128, 100.0, 3, 1.0), 100.0, None),
        map("fine", window(256, 128, 1.0, 4, 1.0), 1.0, None),
    ];
    let sp = spectra(&scans, Boundary::Free, None).unwrap();
    let two_pi = 2.0 * std::f64::consts::PI;
    assert_eq!(sp.stitched.gaps.len(), 1, "{:?}", sp.stitched.gaps);
    let g = sp.stitched.gaps[0];
    assert!((g.from - two_pi / 400.0).abs() < 1e-12, "{g:?}");
    assert!((g.to - 4.0 * two_pi / 128.0).abs() < 1e-12, "{g:?}");
    assert!(sp.stitched.bins.iter().all(|b| b.q < g.from || b.q > g.to));
    // The page says so.
    let check = ScalesCheck {
        unit: None,
        scans: Vec::new(),
        stitched: sp.stitched,
        h_rms: 1.0,
        slope_rms: 1.0,
        whole: Vec::new(),
        method: METHOD.into(),
        wall_s: 0.0,
    };
    let md = page::markdown(&check);
    assert!(
        md.contains("**A gap**") && md.contains("interpolated"),
        "{md}"
    );
}

#[test]
fn persson_on_the_whole_surface_sees_more_slope_than_on_the_coarse_band() {
    let sp = spectra(&two_scales(5), Boundary::Free, None).unwrap();
    let lo = sp.stitched.band.lo;
    // The generating spectrum on the shells' lattice q_k = k lo: each shell adds
    // 2 pi k^3 lo^4 C(k lo) to g^2.
    let lattice = |b: Band| -> f64 {
        (1..=(b.hi / lo) as usize)
            .map(|k| k as f64 * lo)
            .filter(|&q| b.holds(q))
            .map(|q| 2.0 * std::f64::consts::PI * q.powi(3) * lo * generating(q))
            .sum()
    };
    let g2 = |b: Band| {
        sp.stitched
            .shells(b, 1.0)
            .rms_gradient(f64::INFINITY)
            .powi(2)
    };
    // From the fine scan's lowest wavevector up, where every bin rests on some hundreds
    // of modes, g^2 is the generating spectrum's within 10% (bins' own bias 3%); below,
    // the coarse scan's lowest bins rest on a few modes each (stated errors of 20-35%).
    let upper = Band {
        lo: sp.bands[1].lo,
        hi: sp.stitched.band.hi,
    };
    let ratio = g2(upper) / lattice(upper);
    assert!((ratio - 1.0).abs() < 0.1, "{ratio}");
    // Persson on the whole surface: more slope, less contact than on the coarse band.
    let whole = Theory::new(&sp.stitched.shells(sp.stitched.band, 1.0)).unwrap();
    let coarse = Theory::new(&sp.stitched.shells(sp.bands[0], 1.0)).unwrap();
    assert!(g2(sp.stitched.band) > 2.0 * g2(sp.bands[0]));
    let p0 = 0.01;
    assert!(whole.at(p0).unwrap().contact_area < coarse.at(p0).unwrap().contact_area);
}

#[test]
fn line_scans_at_the_coarse_scale_give_the_spectrum_by_their_conversion() {
    // The coarse scale measured as 64 profiles of 1024 points (pixel 10: 10.24e3 long),
    // eight rows 128 apart of each of eight realizations, each its own input, beside the
    // fine 512^2 window (pixel 1).
    let n = 1024;
    let dq = 2.0 * std::f64::consts::PI / n as f64;
    let power = |q_grid: f64| generating(q_grid / 10.0) / 10f64.powi(4) * dq * dq;
    let mut parts = Vec::new();
    for seed in 0..8 {
        let s = Surface::generate_tabulated(n, &power, 20 + seed, Amplitudes::Gaussian).unwrap();
        let h = s.heights_at(f64::INFINITY, &Fft2::new(s.grid()));
        for r in 0..8 {
            let row: Vec<f64> = h[r * 128 * n..(r * 128 + 1) * n]
                .iter()
                .map(|v| v * 10.0)
                .collect();
            parts.push(Profiles::from_values(Path::new("row"), &[n], row, true).unwrap());
        }
    }
    let scans = vec![
        ScaleScan {
            label: "stylus".into(),
            measured: Measured::Line(Profiles::pool(parts).unwrap()),
            pixel: 10.0,
            unit: None,
        },
        map("fine", window(1024, 512, 1.0, 8, 1.0), 1.0, None),
    ];
    let sp = spectra(&scans, Boundary::Free, None).unwrap();
    // The profiles' band is that of their certain converted bins, inside the reliable
    // band of 4 x 2 pi / L to wavelengths of 4 pixels.
    let band = sp.bands[0];
    let reliable = reliable_band(10240.0, 10.0, Boundary::Free, None);
    assert!(band.lo >= reliable.lo && band.hi <= reliable.hi, "{band:?}");
    let line = &sp.stitched.scans[0];
    assert!(line.len() >= 8, "{line:?}");
    for b in line {
        let d = b.c / generating(b.q) - 1.0;
        eprintln!(
            "line q {:.3e}: {d:+.3} (stated {:.3})",
            b.q,
            b.std_error / b.c
        );
    }
    let gap = sp.stitched.gaps.first().map_or(0.0, |g| g.to / g.from);
    eprintln!("band {band:?}, gap {:?}", sp.stitched.gaps);
    assert!(gap < 2.0, "{:?}", sp.stitched.gaps);
    for b in &sp.stitched.bins {
        let d = b.c / generating(b.q) - 1.0;
        assert!(
            d.abs() < 0.1 + 3.0 * b.std_error / b.c,
            "q {}: {d:+.3}",
            b.q
        );
    }
}
