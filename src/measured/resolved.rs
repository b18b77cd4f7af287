//! The page's sections on what a scan resolves: where each scan was cut at its shortest
//! reliable wavelength ([`super::cutoff`]) and the pixel's own error on each contact area
//! ([`super::pixel`]).

use std::fmt::Write as _;

use super::check::SurfaceCheck;
use super::cutoff::Reason;
use super::units::{eng, length};

/// The short-wavelength cutoff of each scan ([`super::cutoff`]).
pub(super) fn cutoff(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(s, "## Reliable scales\n");
    let cut = &c.cutoff;
    let u = c.unit.as_deref();
    if !cut.asked {
        let _ = writeln!(
            s,
            "Not cut (asked so): every wavelength down to the pixel is solved and \
             predicted from.\n"
        );
        return;
    }
    let tip = cut.tip_radius.map_or(String::new(), |r| {
        format!(
            ", or where the rms curvature of the surface exceeds that of the tip (radius {})",
            length(r, u)
        )
    });
    let _ = writeln!(
        s,
        "Each scan is cut at its shortest reliable wavelength: where its spectrum flattens \
         into a noise floor (octaves from the top with a log-log slope above -1){tip}. The \
         heights solved and the spectrum of Persson's predictions keep the longer \
         wavelengths only.\n"
    );
    if cut.scans.iter().all(Option::is_none) {
        let _ = writeln!(
            s,
            "No scan has a noise floor{}: every wavelength down to the pixel is kept.\n",
            if cut.tip_radius.is_some() {
                " and the tip follows every wavelength"
            } else {
                ""
            }
        );
        return;
    }
    let _ = writeln!(
        s,
        "| scan | cutoff wavelength | in pixels | why |\n|---|---|---|---|"
    );
    for (scan, cutoff) in c.scans.iter().zip(&cut.scans) {
        let row = match cutoff {
            None => "none | — | no noise floor".to_string(),
            Some(k) => format!(
                "{} | {} | {}",
                length(k.wavelength, u),
                eng(k.pixels),
                match k.reason {
                    Reason::NoiseFloor { slope } =>
                        format!("noise floor (top octave's slope {})", eng(slope)),
                    Reason::TipRadius { radius } =>
                        format!("the tip's radius, {}", length(radius, u)),
                }
            ),
        };
        let _ = writeln!(s, "| `{scan}` | {row} |");
    }
    if let Some(g) = cut.slope_rms_spectral {
        let _ = writeln!(
            s,
            "\nPersson's rms slope g: {} as measured, {} on the heights solved.\n",
            eng(c.statistics.slope_rms_spectral.value),
            eng(g.value)
        );
    }
}

/// The pixel's own error on each contact area ([`super::pixel`]).
pub(super) fn pixel_error(s: &mut String, c: &SurfaceCheck) {
    let _ = writeln!(s, "## The pixel's own error\n");
    if !c.curve.iter().any(|p| p.pixel.is_some()) {
        let _ = writeln!(
            s,
            "Not estimated (not asked for, or the scan is too small to coarsen: each side \
             must keep {} points at twice the pixel).\n",
            super::scan::MIN_SIDE
        );
        return;
    }
    let levels = c
        .curve
        .iter()
        .filter_map(|p| p.pixel.as_ref())
        .map(|e| e.coarse.len())
        .max()
        .unwrap_or(0);
    let _ = writeln!(
        s,
        "Every load solved again on the scan coarsened by {} (every second{} point), and \
         the contact area extrapolated to a vanishing pixel by first-order Richardson, \
         `2 a_r(a) - a_r(2a)`: a pixel misjudges a band along the contact line, an error \
         of first order in the pixel.{}\n",
        if levels > 1 { "2 and by 4" } else { "2" },
        if levels > 1 { ", every fourth" } else { "" },
        if levels > 1 {
            " The third level gives the extrapolation's spread, \
             `|R(a, 2a) - R(2a, 4a)|`, and the order the three levels show."
        } else {
            ""
        }
    );
    let mut head = vec!["p0 / E*", "a_r at the pixel", "at 2 pixels"];
    if levels > 1 {
        head.push("at 4 pixels");
    }
    head.extend(["extrapolated", "difference"]);
    if levels > 1 {
        head.extend(["spread", "order"]);
    }
    let _ = writeln!(
        s,
        "| {} |\n|{}",
        head.join(" | "),
        "---|".repeat(head.len())
    );
    let opt = |v: Option<f64>| v.map_or_else(|| "—".into(), eng);
    for p in &c.curve {
        let Some(e) = &p.pixel else { continue };
        let mut row = vec![eng(p.p0), eng(p.a_r)];
        row.extend((0..levels).map(|k| opt(e.coarse.get(k).map(|l| l.1))));
        row.extend([eng(e.extrapolated), eng(e.difference)]);
        if levels > 1 {
            row.extend([
                opt(e.spread),
                e.order.map_or("—".into(), |o| format!("{o:.2}")),
            ]);
        }
        let _ = writeln!(s, "| {} |", row.join(" | "));
    }
    let folded = |f: usize| {
        c.curve
            .iter()
            .filter_map(|p| p.pixel.as_ref())
            .any(|e| e.folded.contains(&f))
    };
    if folded(2) {
        let _ = writeln!(
            s,
            "\nThe scan holds roughness finer than 4 pixels, which the grid coarsened by 2 \
             folds onto its own wavevectors: the extrapolation mixes the pixel's error with \
             that change of the surface (a short-wavelength cutoff of at least 4 pixels \
             keeps it apart)."
        );
    } else if folded(4) {
        let _ = writeln!(
            s,
            "\nThe scan holds roughness finer than 8 pixels, which the grid coarsened by 4 \
             folds onto its own wavevectors: the spread and the order mix the pixel's error \
             with that change of the surface; the extrapolation, from the pixel and twice \
             the pixel, does not."
        );
    }
    let _ = writeln!(s);
}
