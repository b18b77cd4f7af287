//! Line scans: the profiles of a stylus profilometer (or any one-dimensional trace of a
//! surface), read and checked before anything is computed from them.
//!
//! The rule: a one-dimensional input (a 1D array, a `1 x n` or `n x 1` matrix, one value
//! per line of a text file) is one profile; a 2D input read as line scans (`--line`,
//! `line=True`) is several profiles of one surface, one per row, each along axis 1 (the
//! spacing between columns); its columns are then the profiles across, used only to test
//! isotropy. Several inputs pool their profiles, which must share their length. Heights
//! keep the file's length unit; the spacing of the points is the pixel size, in the same
//! unit. Undefined points (NaN, infinite) are refused: a profile is cropped to its
//! measured part before it is checked.

use std::path::Path;

use crate::error::{Error, Result};

/// The fewest points of a profile: below this the spectrum has too few bins to be
/// converted, and the synthesized surfaces too few modes.
pub const MIN_POINTS: usize = 64;

/// The most points of a profile (a stylus trace of 4 million points is already beyond
/// any instrument's).
pub const MAX_POINTS: usize = 1 << 22;

/// The profiles of one surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Profiles {
    /// Points per profile.
    pub points: usize,
    /// Heights, one profile after another, in the input's length unit.
    pub heights: Vec<f64>,
    /// Where each input came from, and how many profiles it gave.
    pub sources: Vec<(String, usize)>,
    /// The profiles across (the columns of 2D inputs of at least [`MIN_POINTS`] rows),
    /// when every input has them, of one length.
    pub across: Option<Across>,
    /// Whether the profiles are neighbouring rows of 2D maps (their long wavelengths then
    /// are not independent; [`super::spectrum`] counts them so).
    pub rows_of_a_map: bool,
}

/// Profiles across the rows of 2D inputs: the columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Across {
    /// Points per profile.
    pub points: usize,
    /// Heights, one column after another.
    pub heights: Vec<f64>,
}

impl Profiles {
    /// The profiles of one input of `shape` (row-major `values`), named `source` in
    /// messages; `line` reads a 2D input as rows of profiles (else a 2D input is refused:
    /// it is a height map).
    pub fn from_values(
        source: &Path,
        shape: &[usize],
        values: Vec<f64>,
        line: bool,
    ) -> Result<Self> {
        let (rows, cols) = match *shape {
            [n] => (1, n),
            [rows, cols] => (rows, cols),
            _ => {
                return Err(Error::bad_file(
                    source,
                    format!(
                        "array of shape {shape:?}: a line scan is a 1D profile, or a 2D array \
                         of profiles (one per row)"
                    ),
                ))
            }
        };
        if values.len() != rows * cols || values.is_empty() {
            return Err(Error::bad_file(source, "the line scan is empty"));
        }
        // One column of a text file is one profile too.
        let (rows, cols, values) = if cols == 1 {
            (1, rows, values)
        } else {
            (rows, cols, values)
        };
        if rows > 1 && !line {
            return Err(Error::bad_file(
                source,
                format!(
                    "a {rows} x {cols} height map, not a line scan: check it as a surface, or \
                     read its rows as profiles of one surface (--line, line=True)"
                ),
            ));
        }
        check_length(source, cols, "points")?;
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            let count = values.iter().filter(|v| !v.is_finite()).count();
            return Err(Error::bad_file(
                source,
                format!(
                    "{count} of {} heights of the line scan are undefined, the first in \
                     profile {} at point {}: crop the profiles to their measured part \
                     (missing points are not filled along a line)",
                    values.len(),
                    k / cols,
                    k % cols
                ),
            ));
        }
        let across = (rows >= MIN_POINTS).then(|| Across {
            points: rows,
            heights: (0..rows * cols)
                .map(|k| values[(k % rows) * cols + k / rows])
                .collect(),
        });
        Ok(Self {
            points: cols,
            heights: values,
            sources: vec![(source.display().to_string(), rows)],
            across,
            rows_of_a_map: rows > 1,
        })
    }

    /// The profiles of several inputs, pooled; every profile of one length.
    pub fn pool(parts: Vec<Self>) -> Result<Self> {
        let mut parts = parts.into_iter();
        let Some(mut all) = parts.next() else {
            return Err(Error::invalid(
                "heights",
                "no line scan",
                "at least one profile",
            ));
        };
        for p in parts {
            if p.points != all.points {
                return Err(Error::bad_file(
                    Path::new(&p.sources[0].0),
                    format!(
                        "profiles of {} points, the first input's ({}) have {}: profiles of one \
                         surface share their length (crop them to one)",
                        p.points, all.sources[0].0, all.points
                    ),
                ));
            }
            all.across = match (all.across, p.across) {
                (Some(mut a), Some(b)) if a.points == b.points => {
                    a.heights.extend(b.heights);
                    Some(a)
                }
                _ => None,
            };
            all.heights.extend(p.heights);
            all.sources.extend(p.sources);
            all.rows_of_a_map |= p.rows_of_a_map;
        }
        Ok(all)
    }

    /// Reads the profiles of `path` (`.npy` or text; see the module docs for the rule).
    pub fn read(path: &Path, line: bool) -> Result<Self> {
        let (rows, cols, values) = crate::measured::scan::read_matrix(path)?;
        Self::from_values(path, &[rows, cols], values, line)
    }

    /// Number of profiles.
    pub fn count(&self) -> usize {
        self.heights.len() / self.points
    }

    /// Profile `k`.
    pub fn profile(&self, k: usize) -> &[f64] {
        &self.heights[k * self.points..(k + 1) * self.points]
    }
}

/// Whether `path`'s contents are one-dimensional (a line scan by the module's rule).
pub fn is_one_dimensional(rows: usize, cols: usize) -> bool {
    rows == 1 || cols == 1
}

fn check_length(source: &Path, points: usize, what: &str) -> Result<()> {
    if !(MIN_POINTS..=MAX_POINTS).contains(&points) {
        return Err(Error::bad_file(
            source,
            format!(
                "a line scan of {points} {what}: a profile must hold {MIN_POINTS} to \
                 {MAX_POINTS} points (its spectrum is converted to a surface's over the \
                 decades it spans)"
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rule_one_dimensional_is_a_profile_and_rows_are_profiles_with_line() {
        let p = Path::new("p.npy");
        let one = Profiles::from_values(p, &[100], vec![0.5; 100], false).unwrap();
        assert_eq!(
            (one.count(), one.points, one.across.is_none()),
            (1, 100, true)
        );
        let column = Profiles::from_values(p, &[100, 1], vec![0.5; 100], false).unwrap();
        assert_eq!((column.count(), column.points), (1, 100));
        let values: Vec<f64> = (0..64 * 80).map(|k| k as f64).collect();
        let rows = Profiles::from_values(p, &[64, 80], values.clone(), true).unwrap();
        assert_eq!((rows.count(), rows.points), (64, 80));
        assert_eq!(rows.profile(1)[0], 80.0);
        let across = rows.across.as_ref().unwrap();
        assert_eq!(
            (across.points, across.heights[1], across.heights[64]),
            (64, 80.0, 1.0)
        );
        // A 2D map without --line is a surface, named so.
        let e = Profiles::from_values(p, &[64, 80], values, false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("height map") && e.contains("--line"), "{e}");
    }

    #[test]
    fn bad_line_scans_are_refused_with_a_word_about_line_scans() {
        let p = Path::new("trace.csv");
        let cases: [(&[usize], Vec<f64>, &str); 4] = [
            (&[10], vec![1.0; 10], "a profile must hold 64"),
            (&[2, 2, 2], vec![1.0; 8], "a line scan is a 1D profile"),
            (&[0], vec![], "empty"),
            (
                &[100],
                (0..100)
                    .map(|k| if k == 7 { f64::NAN } else { 1.0 })
                    .collect(),
                "undefined, the first in profile 0 at point 7",
            ),
        ];
        for (shape, values, expected) in cases {
            let e = Profiles::from_values(p, shape, values, true)
                .unwrap_err()
                .to_string();
            assert!(e.contains(expected) && e.contains("trace.csv"), "{e}");
            assert!(!e.contains("pixel"), "{e}");
        }
        let a = Profiles::from_values(p, &[100], vec![1.0; 100], false).unwrap();
        let b = Profiles::from_values(Path::new("b"), &[90], vec![1.0; 90], false).unwrap();
        let e = Profiles::pool(vec![a, b]).unwrap_err().to_string();
        assert!(e.contains("share their length"), "{e}");
    }
}
