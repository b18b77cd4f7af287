//! Points a scan lacks (NaN or infinite: the instrument measured nothing there) are never
//! passed on silently: by default the scan is refused with their count and the first
//! one's row and column; on request they are filled by harmonic interpolation, up to
//! [`MAX_FILLED_SHARE`] of the scan.
//!
//! Harmonic interpolation (the usual choice for undefined data of a height map, e.g.
//! SurfaceTopography's `interpolate_undefined_data("harmonic")`): the filled heights solve
//! the discrete Laplace equation on the missing points with the measured points held
//! fixed, `sum_{j ~ i} (h_j - h_i) = 0` over the four neighbours `j` of every missing point
//! `i` that lie inside the scan (at its edges the equation has fewer terms: no flux across
//! the edge). Each filled height is the mean of its neighbours: the smoothest surface that
//! meets the measured points, with no new extremum. The linear system is symmetric
//! positive definite whenever some point is measured, and is solved by conjugate gradients
//! with the diagonal as preconditioner, to a residual of [`FILL_TOL`] relative to the
//! right-hand side.

use serde::{Deserialize, Serialize};

use super::scan::{Missing, Scan};

/// Whether the points a scan lacks are filled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum Fill {
    /// Refuse a scan with missing points.
    #[default]
    None,
    /// Fill them by harmonic interpolation from their neighbours.
    Interpolate,
}

impl Fill {
    /// Every choice, in the order messages list them.
    pub const ALL: [Fill; 2] = [Fill::None, Fill::Interpolate];

    /// The choice's name, as the command line and Python write it.
    pub fn name(self) -> &'static str {
        match self {
            Fill::None => "none",
            Fill::Interpolate => "interpolate",
        }
    }
}

/// The largest share of a scan that is filled: beyond it the scan is refused even when
/// filling is asked for (a surface a tenth of which is made up says more about the
/// interpolation than about the sample).
pub const MAX_FILLED_SHARE: f64 = 0.10;

/// The residual, relative to the right-hand side, at which the interpolation stops.
pub const FILL_TOL: f64 = 1e-12;

/// Why a scan with missing points was not filled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gaps {
    /// The missing points.
    pub missing: Missing,
    /// The scan's points.
    pub points: usize,
    /// Whether filling was asked for (then there are too many).
    pub asked: bool,
}

impl Gaps {
    /// The share of the scan that is missing.
    pub fn share(&self) -> f64 {
        self.missing.count as f64 / self.points as f64
    }

    /// The refusal in words; `ask` is how the user asks for filling (`--fill
    /// interpolate`, `fill=interpolate`).
    pub fn message(&self, ask: &str) -> String {
        let (row, col) = self.missing.first.unwrap_or((0, 0));
        let what = format!(
            "{} of {} heights ({}) are undefined (NaN, infinite or masked: points the \
             instrument did not measure), the first at row {row}, column {col}",
            self.missing.count,
            self.points,
            super::units::percent(self.share())
        );
        let limit = 100.0 * MAX_FILLED_SHARE;
        if self.asked {
            format!(
                "{what}: more than the {limit}% that are filled by interpolation; crop the \
                 scan to its measured part"
            )
        } else {
            format!(
                "{what}: {ask} fills them by harmonic interpolation from their neighbours \
                 (up to {limit}% of the points), or crop them"
            )
        }
    }
}

/// `scan` with its missing points filled as `fill` says, and how many were filled; the
/// scan unchanged when none is missing.
pub fn fill(scan: &Scan, fill: Fill) -> Result<(Scan, usize), Gaps> {
    let missing = scan.missing();
    if missing.count == 0 {
        return Ok((scan.clone(), 0));
    }
    let gaps = Gaps {
        missing,
        points: scan.heights.len(),
        asked: fill == Fill::Interpolate,
    };
    if !gaps.asked || gaps.share() > MAX_FILLED_SHARE {
        return Err(gaps);
    }
    let mut filled = scan.clone();
    harmonic(&mut filled.heights, scan.shape.rows, scan.shape.cols);
    filled.filled = missing.count;
    Ok((filled, missing.count))
}

/// Fills the non-finite values of the `rows x cols` field `h` by harmonic interpolation
/// (see the module docs). At least one value must be finite.
pub fn harmonic(h: &mut [f64], rows: usize, cols: usize) {
    let unknown: Vec<usize> = (0..h.len()).filter(|&k| !h[k].is_finite()).collect();
    if unknown.is_empty() {
        return;
    }
    // The index of every unknown among the unknowns (usize::MAX for a measured point).
    let mut index = vec![usize::MAX; h.len()];
    for (i, &k) in unknown.iter().enumerate() {
        index[k] = i;
    }
    let neighbours = |k: usize| {
        let (r, c) = (k / cols, k % cols);
        [
            (r > 0).then(|| k - cols),
            (r + 1 < rows).then(|| k + cols),
            (c > 0).then(|| k - 1),
            (c + 1 < cols).then(|| k + 1),
        ]
        .into_iter()
        .flatten()
    };
    // A x = b: A_ii = neighbours of i, A_ij = -1 for unknown neighbours j, b_i = sum of
    // the measured neighbours.
    let degree: Vec<f64> = unknown
        .iter()
        .map(|&k| neighbours(k).count() as f64)
        .collect();
    let b: Vec<f64> = unknown
        .iter()
        .map(|&k| {
            neighbours(k)
                .filter(|&j| index[j] == usize::MAX)
                .map(|j| h[j])
                .sum()
        })
        .collect();
    let apply = |x: &[f64], out: &mut [f64]| {
        for (i, &k) in unknown.iter().enumerate() {
            let off: f64 = neighbours(k)
                .filter(|&j| index[j] != usize::MAX)
                .map(|j| x[index[j]])
                .sum();
            out[i] = degree[i] * x[i] - off;
        }
    };
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let m = unknown.len();
    // Start from the mean of the measured heights.
    let measured: Vec<f64> = h.iter().copied().filter(|v| v.is_finite()).collect();
    let start = measured.iter().sum::<f64>() / measured.len() as f64;
    let mut x = vec![start; m];
    let mut ax = vec![0.0; m];
    apply(&x, &mut ax);
    let mut r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
    let mut z: Vec<f64> = r.iter().zip(&degree).map(|(r, d)| r / d).collect();
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let target = FILL_TOL * dot(&b, &b).sqrt().max(f64::MIN_POSITIVE);
    let mut ap = vec![0.0; m];
    // CG ends in at most m steps in exact arithmetic; the bound guards rounding.
    for _ in 0..10 * m + 100 {
        if dot(&r, &r).sqrt() <= target {
            break;
        }
        apply(&p, &mut ap);
        let alpha = rz / dot(&p, &ap);
        for i in 0..m {
            x[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        z.iter_mut()
            .zip(&r)
            .zip(&degree)
            .for_each(|((z, r), d)| *z = r / d);
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        p.iter_mut().zip(&z).for_each(|(p, z)| *p = z + beta * *p);
    }
    for (i, &k) in unknown.iter().enumerate() {
        h[k] = x[i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measured::psd::Shape;
    use std::path::PathBuf;

    fn scan(rows: usize, cols: usize, f: impl Fn(usize, usize) -> f64) -> Scan {
        Scan {
            shape: Shape { rows, cols },
            heights: (0..rows * cols).map(|k| f(k / cols, k % cols)).collect(),
            source: PathBuf::from("s"),
            filled: 0,
        }
    }

    #[test]
    fn a_plane_is_filled_exactly_and_each_filled_point_is_its_neighbours_mean() {
        // A plane is harmonic: gaps inside the scan (single points and a block) come back
        // to rounding. (At an edge the equation has no term across it, so a plane's
        // slope across the edge is not kept there.)
        let plane = |r: usize, c: usize| 0.3 * r as f64 - 0.2 * c as f64 + 1.0;
        let mut holed = scan(20, 30, plane);
        let holes = [31, 250, 251, 252, 280, 281, 282, 310, 311, 312, 568];
        for &k in &holes {
            holed.heights[k] = f64::NAN;
        }
        holed.heights[400] = f64::INFINITY;
        let (filled, count) = fill(&holed, Fill::Interpolate).unwrap();
        assert_eq!(count, holes.len() + 1);
        for (k, (a, b)) in filled
            .heights
            .iter()
            .zip(&scan(20, 30, plane).heights)
            .enumerate()
        {
            assert!((a - b).abs() < 1e-9, "point {k}: {a} vs {b}");
        }
        // On a rough field: every filled point is the mean of its neighbours.
        let rough = |r: usize, c: usize| ((r * 7 + c * 13) % 11) as f64;
        let mut holed = scan(16, 12, rough);
        for k in [0, 5, 6, 17, 18, 100, 101, 113, 191] {
            holed.heights[k] = f64::NAN;
        }
        let (filled, _) = fill(&holed, Fill::Interpolate).unwrap();
        for k in [0usize, 5, 6, 17, 18, 100, 101, 113, 191] {
            let (r, c) = (k / 12, k % 12);
            let mut nb = Vec::new();
            if r > 0 {
                nb.push(filled.heights[k - 12]);
            }
            if r + 1 < 16 {
                nb.push(filled.heights[k + 12]);
            }
            if c > 0 {
                nb.push(filled.heights[k - 1]);
            }
            if c + 1 < 12 {
                nb.push(filled.heights[k + 1]);
            }
            let mean = nb.iter().sum::<f64>() / nb.len() as f64;
            assert!((filled.heights[k] - mean).abs() < 1e-9, "point {k}");
        }
    }

    #[test]
    fn missing_points_are_refused_unless_filled_and_beyond_the_share_always() {
        let mut holed = scan(10, 10, |r, c| (r + c) as f64);
        holed.heights[23] = f64::NAN;
        holed.heights[57] = f64::NAN;
        let gaps = fill(&holed, Fill::None).unwrap_err();
        let text = gaps.message("--fill interpolate");
        assert!(text.contains("2 of 100 heights"), "{text}");
        assert!(text.contains("row 2, column 3"), "{text}");
        assert!(text.contains("--fill interpolate"), "{text}");
        // 11 of 100: beyond the share, refused even when asked.
        for k in 60..69 {
            holed.heights[k] = f64::NAN;
        }
        let gaps = fill(&holed, Fill::Interpolate).unwrap_err();
        let text = gaps.message("--fill interpolate");
        assert!(text.contains("11 of 100") && text.contains("10%"), "{text}");
        // A whole scan without a gap comes back as it is.
        let whole = scan(6, 7, |r, c| (r * c) as f64);
        assert_eq!(fill(&whole, Fill::None).unwrap(), (whole.clone(), 0));
    }
}
