//! A measured height map: read from a `.npy` file (2D, float32 or float64) or a plain-text
//! matrix, and checked before anything is computed from it.
//!
//! Instruments write files in many shapes; each problem is refused with a message that
//! names it: a one-dimensional profile, an empty file, a ragged text matrix, and sides
//! outside the grid's range. Rectangular maps are read as they are. Instruments also leave
//! gaps: points not measured are NaN (or infinite) in the map and stay so here, counted by
//! [`Scan::missing`]; [`super::fill`] refuses or fills them before anything is computed.
//! Heights keep the file's length unit; the pixel size is given in the same unit.

use std::path::{Path, PathBuf};

use super::psd::Shape;
use crate::engine::grid::{MAX_N, MIN_N};
use crate::error::{Error, Result};

/// The smallest side of a height map the check takes, in points: at the lowest default
/// load (a contact area of about 1%) a 32 x 32 map holds some ten contact points, and
/// its area moves in steps of 0.1%; a 16 x 16 map holds two or three, in steps of 0.4%
/// (`docs/check-surface.md`, "A floor on size").
pub const MIN_SIDE: usize = 32;

/// One scan: a height map and where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Scan {
    /// Rows and columns.
    pub shape: Shape,
    /// Heights, row-major, in the file's length unit; NaN (or infinite) where the
    /// instrument measured nothing.
    pub heights: Vec<f64>,
    /// The file it was read from (or a name given by the caller).
    pub source: PathBuf,
    /// Points filled by interpolation ([`super::fill`]); 0 as read.
    pub filled: usize,
}

/// The points a scan lacks: how many, and the first (row, column) in row-major order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Missing {
    /// Points that are not finite.
    pub count: usize,
    /// The first of them, `(row, column)`.
    pub first: Option<(usize, usize)>,
}

/// A height map's shape and values, before its checks.
struct Raw {
    rows: usize,
    cols: usize,
    values: Vec<f64>,
}

impl Scan {
    /// A scan from values in memory (row-major, `shape = (rows, cols)`), checked as a file
    /// would be; `source` names it in messages.
    pub fn from_values(source: &Path, shape: &[usize], values: Vec<f64>) -> Result<Self> {
        let (rows, cols) = match *shape {
            [rows, cols] => (rows, cols),
            [len] => {
                return Err(Error::bad_file(
                    source,
                    format!(
                        "a one-dimensional profile ({len} values): a line scan, checked as one \
                         (measured::line), not as a height map"
                    ),
                ))
            }
            _ => {
                return Err(Error::bad_file(
                    source,
                    format!("array of shape {shape:?}: expected a 2D height map (rows, columns)"),
                ))
            }
        };
        Self::check(source, Raw { rows, cols, values })
    }

    /// Reads a scan from `path`: `.npy` by its extension or magic bytes, else a text matrix.
    pub fn read(path: &Path) -> Result<Self> {
        let (rows, cols, values) = read_matrix(path)?;
        Self::check(path, Raw { rows, cols, values })
    }

    fn check(source: &Path, raw: Raw) -> Result<Self> {
        let Raw { rows, cols, values } = raw;
        if rows == 0 || cols == 0 || values.is_empty() {
            return Err(Error::bad_file(source, "the height map is empty"));
        }
        if rows == 1 || cols == 1 {
            return Err(Error::bad_file(
                source,
                format!(
                    "a one-dimensional profile ({rows} x {cols}): a line scan, checked as one \
                     (measured::line), not as a height map"
                ),
            ));
        }
        for (side, what) in [(rows, "rows"), (cols, "columns")] {
            if !(MIN_N..=MAX_N / 2).contains(&side) {
                return Err(Error::bad_file(
                    source,
                    format!(
                        "the height map is {rows} x {cols} (rows x columns): {side} {what}, \
                         each side must be in [{MIN_N}, {}] (a free boundary doubles it)",
                        MAX_N / 2
                    ),
                ));
            }
        }
        Ok(Self {
            shape: Shape { rows, cols },
            heights: values,
            source: source.to_path_buf(),
            filled: 0,
        })
    }

    /// The points that are not finite (not measured).
    pub fn missing(&self) -> Missing {
        let mut missing = Missing {
            count: 0,
            first: None,
        };
        for (k, v) in self.heights.iter().enumerate() {
            if !v.is_finite() {
                missing.count += 1;
                missing
                    .first
                    .get_or_insert((k / self.shape.cols, k % self.shape.cols));
            }
        }
        missing
    }
}

/// The values of `path` (`.npy` by its extension or magic bytes, else a text matrix) as
/// `(rows, columns, row-major values)`, before any check of their shape: a 1D `.npy`
/// array is one row, a text file of one value per line one column.
pub fn read_matrix(path: &Path) -> Result<(usize, usize, Vec<f64>)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let raw = if bytes.starts_with(b"\x93NUMPY") {
        parse_npy(&bytes)
    } else if path.extension().is_some_and(|e| e == "npy") {
        Err("not a valid .npy file (no NUMPY magic bytes)".to_string())
    } else {
        parse_text(&bytes)
    }
    .map_err(|m| Error::bad_file(path, m))?;
    Ok((raw.rows, raw.cols, raw.values))
}

/// A 2D float array from the bytes of a `.npy` file, whatever its shape (checked later).
fn parse_npy(bytes: &[u8]) -> std::result::Result<Raw, String> {
    let mut rest = bytes;
    let npy = npyz::NpyFile::new(&mut rest).map_err(|e| format!("not a valid .npy file ({e})"))?;
    let dtype = npy.dtype();
    let size = match &dtype {
        npyz::DType::Plain(t) if t.type_char() == npyz::TypeChar::Float => t.size_field(),
        _ => 0,
    };
    let shape: Vec<usize> = npy.shape().iter().map(|&d| d as usize).collect();
    let (rows, cols) = match shape[..] {
        [rows, cols] => (rows, cols),
        [len] => (1, len),
        _ => {
            return Err(format!(
                "array of shape {shape:?}: expected a 2D height map (rows, columns)"
            ))
        }
    };
    if rows.saturating_mul(cols) > MAX_N * MAX_N / 4 {
        return Err(format!("array of shape {shape:?} is too large"));
    }
    let fortran = npy.order() == npyz::Order::Fortran;
    let values: Vec<f64> = match size {
        8 => npy.into_vec::<f64>(),
        4 => npy
            .into_vec::<f32>()
            .map(|v| v.into_iter().map(f64::from).collect()),
        _ => {
            return Err(format!(
                "dtype is {}, expected float64 or float32",
                dtype.descr()
            ))
        }
    }
    .map_err(|e| format!("data is truncated or unreadable ({e})"))?;
    if values.len() != rows * cols {
        return Err(format!(
            "data holds {} values, the header says {rows} x {cols}",
            values.len()
        ));
    }
    let values = if fortran {
        (0..rows * cols)
            .map(|k| values[(k % cols) * rows + k / cols])
            .collect()
    } else {
        values
    };
    Ok(Raw { rows, cols, values })
}

/// A matrix from text: one row per line, values separated by white space or commas;
/// blank lines and lines starting with `#` are skipped.
fn parse_text(bytes: &[u8]) -> std::result::Result<Raw, String> {
    let text = std::str::from_utf8(bytes)
        .map_err(|_| "neither a .npy file nor UTF-8 text (a matrix of numbers)".to_string())?;
    let mut values = Vec::new();
    let (mut rows, mut cols) = (0usize, 0usize);
    for (line_no, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let before = values.len();
        for token in line.split(|c: char| c.is_whitespace() || c == ',') {
            if token.is_empty() {
                continue;
            }
            let v: f64 = token.parse().map_err(|_| {
                format!(
                    "line {}: {token:?} is not a number (expected a matrix of heights)",
                    line_no + 1
                )
            })?;
            values.push(v);
        }
        let width = values.len() - before;
        if rows == 0 {
            cols = width;
        } else if width != cols {
            return Err(format!(
                "line {}: {width} values, the first row has {cols} (a ragged matrix)",
                line_no + 1
            ));
        }
        rows += 1;
    }
    Ok(Raw { rows, cols, values })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn a_text_matrix_is_read_row_by_row() {
        let dir = tempfile::tempdir().unwrap();
        let mut text = String::from("# a 4 x 4 scan\n");
        for i in 0..4 {
            let row: Vec<String> = (0..4).map(|j| format!("{}", i * 4 + j)).collect();
            text.push_str(&row.join(if i % 2 == 0 { " " } else { ", " }));
            text.push('\n');
        }
        let s = Scan::read(&write(dir.path(), "h.txt", &text)).unwrap();
        assert_eq!(s.shape, Shape { rows: 4, cols: 4 });
        assert_eq!(s.heights[6], 6.0);
        // A rectangle is read as it is.
        let rect = "1 2 3 4 5\n1 2 3 4 5\n1 2 3 4 5\n1 2 3 4 5\n";
        let s = Scan::read(&write(dir.path(), "rect.txt", rect)).unwrap();
        assert_eq!(s.shape, Shape { rows: 4, cols: 5 });
    }

    #[test]
    fn missing_points_are_counted_and_the_first_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let text = "1 2 3 4 5\n5 6 nan 7 8\n9 10 NaN 12 1\n13 14 15 inf 1\n";
        let s = Scan::read(&write(dir.path(), "h.txt", text)).unwrap();
        assert_eq!(
            s.missing(),
            Missing {
                count: 3,
                first: Some((1, 2))
            }
        );
    }

    #[test]
    fn bad_shapes_are_refused_with_a_word() {
        let dir = tempfile::tempdir().unwrap();
        let cases = [
            ("empty.txt", "", "empty"),
            ("comments.txt", "# nothing\n\n", "empty"),
            ("line.txt", "1 2 3 4 5 6\n", "one-dimensional profile"),
            ("ragged.txt", "1 2 3 4\n1 2 3\n1 2 3 4\n1 2 3 4\n", "ragged"),
            ("words.txt", "1 2 x 4\n", "not a number"),
            ("tiny.txt", "1 2\n3 4\n", "must be in"),
            ("bad.npy", "hello", "not a valid .npy"),
        ];
        for (name, text, expected) in cases {
            let e = Scan::read(&write(dir.path(), name, text))
                .unwrap_err()
                .to_string();
            assert!(e.contains(expected), "{name}: {e}");
            assert!(e.contains(name), "{name}: the file is not named: {e}");
        }
    }

    #[test]
    fn npy_files_of_either_float_width_are_read() {
        use npyz::WriterBuilder;
        let dir = tempfile::tempdir().unwrap();
        let values: Vec<f32> = (0..36).map(|k| k as f32 * 0.5).collect();
        let path = dir.path().join("h32.npy");
        let mut file = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        let mut w = npyz::WriteOptions::<f32>::new()
            .default_dtype()
            .shape(&[6, 6])
            .writer(&mut file)
            .begin_nd()
            .unwrap();
        w.extend(values.iter().copied()).unwrap();
        w.finish().unwrap();
        drop(file);
        let s = Scan::read(&path).unwrap();
        assert_eq!((s.shape.rows, s.heights[7]), (6, 3.5));
        let path64 = dir.path().join("h64.npy");
        let v64: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
        crate::io::npy::write_field(&path64, 6, &v64).unwrap();
        assert_eq!(Scan::read(&path64).unwrap().heights, v64);
        // A 1D profile in a .npy file.
        let e = Scan::from_values(Path::new("p.npy"), &[64], vec![0.0; 64])
            .unwrap_err()
            .to_string();
        assert!(e.contains("one-dimensional"), "{e}");
    }
}
