//! Line scans at non-uniform positions (a stylus profilometer's x-y export, a trace whose
//! positions the instrument rounded): read from a two-column text file ([`read_xy`]) and
//! resampled onto even spacing ([`resample`]) before the check.
//!
//! The spectrum of a profile is defined on evenly spaced points (the conversion to the
//! surface's spectrum and the synthesis assume it). A profile of `n` points at strictly
//! increasing positions `x_0 < ... < x_(n-1)` is resampled onto `n` points from its first
//! to its last position, `dx = (x_(n-1) - x_0) / (n - 1)` apart, by linear interpolation
//! (`numpy.interp`'s rule), with a warning that names the spacings it had. Linear
//! interpolation damps the modes near the new spacing's cutoff, which the page marks as
//! uncertain anyway.

use std::path::Path;

use crate::error::{Error, Result};

/// A profile resampled onto even spacing.
#[derive(Debug, Clone, PartialEq)]
pub struct Resampled {
    /// The heights at `x_0 + k dx`, `k = 0..n` (the last exactly at `x_(n-1)`).
    pub heights: Vec<f64>,
    /// The even spacing `dx`, in the positions' unit.
    pub pixel: f64,
    /// What was done, in words: the spacings the profile had and the one it has now.
    pub warning: String,
}

/// Where each point of a profile came from, for messages: a file's lines, or the points'
/// indices.
#[derive(Debug, Clone, Copy)]
pub enum Origin<'a> {
    /// Point `k` is on line `lines[k]` (1-based) of a file.
    Lines(&'a [usize]),
    /// Point `k` is the array's element `k`.
    Indices,
}

impl Origin<'_> {
    fn name(&self, k: usize) -> String {
        match self {
            Origin::Lines(lines) => format!("line {}", lines[k]),
            Origin::Indices => format!("point {k}"),
        }
    }
}

/// The profile of heights `h` at positions `x`, named `source` in messages (points
/// located by `origin`), resampled onto even spacing (see the module docs).
///
/// # Errors
///
/// If `x` and `h` differ in length or hold fewer than 2 points, or a position is not
/// finite or does not increase strictly (the error names the point, its position and the
/// one before it).
pub fn resample(source: &Path, x: &[f64], h: &[f64], origin: Origin<'_>) -> Result<Resampled> {
    if x.len() != h.len() || x.len() < 2 {
        return Err(Error::bad_file(
            source,
            format!(
                "{} positions and {} heights: a non-uniform line scan needs positions and \
                 heights of one length, at least 2",
                x.len(),
                h.len()
            ),
        ));
    }
    if let Some(k) = (1..x.len()).find(|&k| !(x[k].is_finite() && x[k] > x[k - 1])) {
        return Err(Error::bad_file(
            source,
            format!(
                "{}: position {} after {} ({}): a non-uniform line scan's positions must \
                 increase strictly (finite, no repeats); give them sorted",
                origin.name(k),
                x[k],
                x[k - 1],
                origin.name(k - 1)
            ),
        ));
    }
    if !x[0].is_finite() {
        return Err(Error::bad_file(
            source,
            format!("{}: position {} is not finite", origin.name(0), x[0]),
        ));
    }
    let n = x.len();
    let pixel = (x[n - 1] - x[0]) / (n - 1) as f64;
    let mut grid: Vec<f64> = (0..n).map(|k| x[0] + pixel * k as f64).collect();
    grid[n - 1] = x[n - 1];
    let heights = interpolate(&grid, x, h);
    let (lo, hi) = x
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    let warning = format!(
        "a line scan at non-uniform positions (spacings {} to {}) resampled onto {n} evenly \
         spaced points {} apart by linear interpolation",
        general(lo, 4),
        general(hi, 4),
        general(pixel, 6)
    );
    Ok(Resampled {
        heights,
        pixel,
        warning,
    })
}

/// The piecewise linear interpolant of `(x, h)` (`x` increasing) at `at` (within
/// `[x_0, x_(n-1)]`), as `numpy.interp` computes it: `h_j + s (t - x_j)` with
/// `s = (h_(j+1) - h_j) / (x_(j+1) - x_j)` on `x_j <= t < x_(j+1)`, `h_j` at a knot.
fn interpolate(at: &[f64], x: &[f64], h: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mut j = 0;
    at.iter()
        .map(|&t| {
            if t >= x[n - 1] {
                return h[n - 1];
            }
            if t <= x[0] {
                return h[0];
            }
            while x[j + 1] <= t {
                j += 1;
            }
            if x[j] == t {
                return h[j];
            }
            let slope = (h[j + 1] - h[j]) / (x[j + 1] - x[j]);
            slope * (t - x[j]) + h[j]
        })
        .collect()
}

/// `v` to `digits` significant digits as C's `%g` writes it (Python's `:.4g`): trailing
/// zeros dropped, scientific below `1e-4` and from `10^digits`.
pub fn general(v: f64, digits: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = digits.max(1);
    let sci = format!("{:.*e}", digits - 1, v);
    let (mantissa, exp) = sci.split_once('e').expect("the e format has an exponent");
    let exp: i32 = exp.parse().expect("an integer exponent");
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if exp < -4 || exp >= digits as i32 {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", trim(mantissa), exp.abs())
    } else {
        let decimals = usize::try_from(digits as i32 - 1 - exp).unwrap_or(0);
        trim(&format!("{v:.decimals$}"))
    }
}

/// The positions and heights of a two-column text file (`x h` a line, separated by white
/// space, a comma or a semicolon; blank lines and lines starting with `#` or `%`
/// skipped), with the line each point is on (1-based).
///
/// # Errors
///
/// If the file cannot be read, is not text, or a line holds other than two numbers.
pub fn read_xy(path: &Path) -> Result<(Vec<f64>, Vec<f64>, Vec<usize>)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let text = std::str::from_utf8(&bytes)
        .map_err(|_| Error::bad_file(path, "not UTF-8 text (two columns: position, height)"))?;
    let (mut x, mut h, mut lines) = (Vec::new(), Vec::new(), Vec::new());
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with('%') {
            continue;
        }
        let tokens: Vec<&str> = line
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|t| !t.is_empty())
            .collect();
        let values: Option<Vec<f64>> = tokens.iter().map(|t| t.parse().ok()).collect();
        match values.as_deref() {
            Some(&[xi, hi]) => {
                x.push(xi);
                h.push(hi);
                lines.push(k + 1);
            }
            _ => {
                return Err(Error::bad_file(
                    path,
                    format!(
                        "line {}: {line:?} is not two numbers (a line scan's position and \
                         height)",
                        k + 1
                    ),
                ))
            }
        }
    }
    Ok((x, h, lines))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn general_writes_as_c_does() {
        assert_eq!(general(0.4, 4), "0.4");
        assert_eq!(general(0.6000000000000001, 4), "0.6");
        assert_eq!(general(0.500978123, 6), "0.500978");
        assert_eq!(general(12345.0, 4), "1.234e+04");
        assert_eq!(general(1.5e-5, 4), "1.5e-05");
        assert_eq!(general(100.0, 6), "100");
    }

    #[test]
    fn a_profile_is_resampled_as_numpy_interp_does() {
        let x = [0.0, 0.4, 1.0, 1.4, 2.0];
        let h = [0.0, 4.0, 10.0, 14.0, 20.0];
        let r = resample(Path::new("p"), &x, &h, Origin::Indices).unwrap();
        assert_eq!(r.pixel, 0.5);
        // A linear profile stays linear.
        for (k, v) in r.heights.iter().enumerate() {
            assert!((v - 5.0 * k as f64).abs() < 1e-12, "{k}: {v}");
        }
        assert!(
            r.warning
                .contains("(spacings 0.4 to 0.6) resampled onto 5 evenly spaced points 0.5 apart"),
            "{}",
            r.warning
        );
    }

    #[test]
    fn positions_that_do_not_increase_are_refused_naming_the_point() {
        let lines = [3, 4, 6];
        let e = resample(
            Path::new("trace.txt"),
            &[0.0, 1.0, 1.0],
            &[0.0; 3],
            Origin::Lines(&lines),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("trace.txt")
                && e.contains("line 6: position 1 after 1 (line 4)")
                && e.contains("increase strictly"),
            "{e}"
        );
        let e = resample(Path::new("a"), &[0.0], &[0.0], Origin::Indices).unwrap_err();
        assert!(e.to_string().contains("at least 2"), "{e}");
    }
}
