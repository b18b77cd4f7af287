//! Units of a measured surface: its length unit (the heights' and the pixel's), the
//! contact modulus that turns pressures from units of `E*` into pascals, the pixel's two
//! sides and when they count as square, and numbers written with three significant
//! digits in engineering notation (`12.3e-6`: the exponent a multiple of three).

use crate::error::{Error, Result};

/// Two pixel sides that differ by at most this share of the larger one are taken as
/// square (their geometric mean is used): instruments round their calibrations.
pub const SQUARE_PIXEL_TOLERANCE: f64 = 1e-3;

/// `v` rounded to three significant digits, with the decimal exponent of the result
/// (rounding first, so that a carry, 9.996 -> 10.0, moves the exponent); `None` for zero
/// or a value that is not finite.
fn three_digits(v: f64) -> Option<(f64, i32)> {
    if !v.is_finite() || v == 0.0 {
        return None;
    }
    let rounded: f64 = format!("{v:.2e}")
        .parse()
        .expect("a formatted float parses");
    Some((rounded, rounded.abs().log10().floor() as i32))
}

/// `v` with three significant digits in engineering notation: `123e-9`, `1.50`, `12.3e3`,
/// `0`; `—` for a value that is not finite.
pub fn eng(v: f64) -> String {
    let Some((rounded, exponent)) = three_digits(v) else {
        return if v == 0.0 { "0" } else { "—" }.to_string();
    };
    let e3 = exponent.div_euclid(3) * 3;
    let mantissa = rounded / 10f64.powi(e3);
    let decimals = (2 - (exponent - e3)).max(0) as usize;
    let m = format!("{mantissa:.decimals$}");
    if e3 == 0 {
        m
    } else {
        format!("{m}e{e3}")
    }
}

/// A share as a percentage with three significant digits in plain decimals: `0.878%`,
/// `12.3%`, `0%`.
pub fn percent(share: f64) -> String {
    let v = 100.0 * share;
    let Some((rounded, exponent)) = three_digits(v) else {
        return if v == 0.0 { "0%" } else { "—" }.to_string();
    };
    let decimals = (2 - exponent).max(0) as usize;
    format!("{rounded:.decimals$}%")
}

/// A length with its unit: `12.3 nm`, or `12.3 (length unit)` without one.
pub fn length(v: f64, unit: Option<&str>) -> String {
    format!("{} {}", eng(v), unit.unwrap_or("(length unit)"))
}

/// Metres per unit for the units instruments write (SurfaceTopography's among them).
const METRES: [(&str, f64); 9] = [
    ("m", 1.0),
    ("mm", 1e-3),
    ("µm", 1e-6),
    ("μm", 1e-6),
    ("um", 1e-6),
    ("nm", 1e-9),
    ("pm", 1e-12),
    ("Å", 1e-10),
    ("A", 1e-10),
];

/// Metres per `unit`, when it is one of the units known here.
pub fn metres(unit: &str) -> Option<f64> {
    METRES.iter().find(|(u, _)| *u == unit).map(|&(_, m)| m)
}

/// Checks a length unit's name: a short word without spaces.
pub fn check_unit(unit: &str) -> Result<()> {
    if unit.is_empty() || unit.len() > 16 || unit.chars().any(char::is_whitespace) {
        return Err(Error::invalid(
            "unit",
            format!("{unit:?}"),
            "a length unit's name without spaces (m, mm, µm, nm, ...)",
        ));
    }
    Ok(())
}

/// The square pixel of sides `sides` (along axis 0, between rows, and axis 1, between
/// columns): their geometric mean when they differ by at most
/// [`SQUARE_PIXEL_TOLERANCE`]; otherwise an error that says how to resample.
pub fn square_pixel(sides: [f64; 2]) -> Result<f64> {
    for side in sides {
        crate::error::check_positive("pixel_size", side)?;
    }
    let [a, b] = sides;
    let differ = (a - b).abs() / a.max(b);
    if differ > SQUARE_PIXEL_TOLERANCE {
        let fine = a.min(b);
        return Err(Error::invalid(
            "pixel_size",
            format!(
                "{} x {} (sides differ by {})",
                eng(a),
                eng(b),
                percent(differ)
            ),
            format!(
                "square pixels, sides within {}% of each other: resample the scan onto \
                 square pixels first, e.g. with scipy.ndimage.zoom(h, ({}, {})) onto \
                 pixels of {} (SurfaceTopography: interpolate the topography onto a grid \
                 of equal spacings)",
                100.0 * SQUARE_PIXEL_TOLERANCE,
                eng(a / fine),
                eng(b / fine),
                eng(fine)
            ),
        ));
    }
    Ok((a * b).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_three_significant_digits_and_exponents_of_three() {
        let cases = [
            (1.234e-7, "123e-9"),
            (0.0015, "1.50e-3"),
            (1.5, "1.50"),
            (12.34, "12.3"),
            (123.4, "123"),
            (12345.0, "12.3e3"),
            (9.996, "10.0"),
            (999.7, "1.00e3"),
            (-0.00065432, "-654e-6"),
            (0.0, "0"),
            (f64::NAN, "—"),
        ];
        for (v, text) in cases {
            assert_eq!(eng(v), text, "{v}");
        }
        assert_eq!(length(2.5e-9, Some("m")), "2.50e-9 m");
        let shares = [
            (0.00878, "0.878%"),
            (0.0013, "0.130%"),
            (0.123, "12.3%"),
            (0.99996, "100%"),
            (0.0, "0%"),
        ];
        for (share, text) in shares {
            assert_eq!(percent(share), text, "{share}");
        }
        assert_eq!(length(3.0, None), "3.00 (length unit)");
    }

    #[test]
    fn pixels_within_the_tolerance_are_square_and_others_are_refused_with_a_recipe() {
        // 1.8534 x 1.8546 µm: 0.065% apart.
        let p = square_pixel([1.8534, 1.8546]).unwrap();
        assert!((p - (1.8534f64 * 1.8546).sqrt()).abs() < 1e-15);
        assert_eq!(square_pixel([0.5, 0.5]).unwrap(), 0.5);
        let e = square_pixel([0.1277, 0.3146]).unwrap_err().to_string();
        assert!(e.contains("pixel_size") && e.contains("resample"), "{e}");
        assert!(e.contains("zoom(h, (1.00, 2.46))"), "{e}");
        assert!(square_pixel([0.0, 1.0]).is_err() && square_pixel([1.0, f64::NAN]).is_err());
        assert_eq!(metres("nm"), Some(1e-9));
        assert_eq!(metres("furlong"), None);
        assert!(check_unit("µm").is_ok() && check_unit("").is_err() && check_unit("n m").is_err());
    }
}
