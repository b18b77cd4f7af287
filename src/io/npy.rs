//! `.npy` field files (the command-line contract, [`crate::conventions`]): float64, shape `(N, N)`, row-major.
//!
//! Reading checks everything a field must satisfy and names what is wrong: a file that is
//! not `.npy`, truncated data, another dtype, another rank, a non-square or empty array,
//! NaN or infinite entries (with their row and column), and bytes left over after the
//! data. Fortran-ordered arrays are accepted and transposed. Writing is atomic
//! ([`crate::io`]).

use std::ops::RangeInclusive;
use std::path::Path;

use crate::error::{Error, Result};

/// A square float64 field read from a `.npy` file.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Points per side.
    pub n: usize,
    /// Values, row-major.
    pub values: Vec<f64>,
}

/// Reads a square float64 field from `path`, with `N` in `sizes` (the grid sizes the
/// caller accepts: nothing outside them is allocated).
pub fn read_field(path: &Path, sizes: RangeInclusive<usize>) -> Result<Field> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse_field(&bytes, sizes).map_err(|m| Error::bad_file(path, m))
}

/// Parses a square float64 field with `N` in `sizes` from the bytes of a `.npy` file; the
/// error says what is wrong.
pub fn parse_field(
    bytes: &[u8],
    sizes: RangeInclusive<usize>,
) -> std::result::Result<Field, String> {
    let mut rest = bytes;
    let npy = npyz::NpyFile::new(&mut rest).map_err(|e| header_error(&e))?;
    let dtype = npy.dtype();
    let is_f64 = matches!(&dtype, npyz::DType::Plain(t)
        if t.type_char() == npyz::TypeChar::Float && t.size_field() == 8);
    if !is_f64 {
        return Err(format!(
            "dtype is {}, expected float64 ('<f8')",
            dtype.descr()
        ));
    }
    let n = check_shape(npy.shape(), sizes)?;
    let fortran = npy.order() == npyz::Order::Fortran;
    let mut values: Vec<f64> = npy.into_vec().map_err(|e| {
        format!(
            "data is truncated or unreadable ({e}); expected {} float64 values",
            n * n
        )
    })?;
    if !rest.is_empty() {
        return Err(format!(
            "{} bytes follow the {n} x {n} float64 values (the header's shape is wrong or \
             the file is damaged)",
            rest.len()
        ));
    }
    if values.len() != n * n {
        return Err(format!(
            "data holds {} values, expected {}",
            values.len(),
            n * n
        ));
    }
    if fortran {
        let mut t = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                t[i * n + j] = values[j * n + i];
            }
        }
        values = t;
    }
    check_finite(&values, n)?;
    Ok(Field { n, values })
}

/// Checks the shape of a field: two dimensions, square, not empty, with `N` in `sizes`.
/// Returns `N`, or says what is wrong in the reader's words (also used for arrays handed
/// over in memory, so that both name a bad shape alike).
pub fn check_shape(
    shape: &[u64],
    sizes: RangeInclusive<usize>,
) -> std::result::Result<usize, String> {
    if shape.len() != 2 {
        return Err(format!(
            "array has {} dimensions (shape {:?}), expected 2 (N, N)",
            shape.len(),
            shape
        ));
    }
    if shape[0] == 0 || shape[1] == 0 {
        return Err(format!("array is empty (shape {shape:?})"));
    }
    if shape[0] != shape[1] {
        return Err(format!(
            "array is not square (shape {shape:?}), expected (N, N)"
        ));
    }
    let n = shape[0] as usize;
    if !sizes.contains(&n) {
        return Err(format!(
            "N = {n} is outside [{}, {}]",
            sizes.start(),
            sizes.end()
        ));
    }
    Ok(n)
}

/// Checks that every entry of a row-major `n x n` field is finite; names the first that is
/// not, by row and column, in the reader's words.
pub fn check_finite(values: &[f64], n: usize) -> std::result::Result<(), String> {
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        return Err(format!(
            "entry at row {}, column {} is {} (fields must be finite)",
            k / n,
            k % n,
            values[k]
        ));
    }
    Ok(())
}

/// The reader's complaint about a header, on one short line.
fn header_error(e: &std::io::Error) -> String {
    if e.kind() == std::io::ErrorKind::UnexpectedEof {
        return "not a valid .npy file (the header is truncated)".to_string();
    }
    let text = e.to_string();
    let first: String = text
        .lines()
        .next()
        .unwrap_or("")
        .chars()
        .take(160)
        .collect();
    format!("not a valid .npy file ({})", first.trim_end())
}

/// Writes a square float64 field to `path` atomically.
pub fn write_field(path: &Path, n: usize, values: &[f64]) -> Result<()> {
    assert_eq!(values.len(), n * n, "field length");
    crate::io::write_atomic_with(path, |w| {
        use npyz::WriterBuilder;
        let mut writer = npyz::WriteOptions::<f64>::new()
            .default_dtype()
            .shape(&[n as u64, n as u64])
            .writer(w)
            .begin_nd()?;
        writer.extend(values.iter().copied())?;
        writer.finish()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.npy");
        let values: Vec<f64> = (0..25).map(|i| i as f64 * 0.5 - 3.0).collect();
        write_field(&path, 5, &values).unwrap();
        let f = read_field(&path, 4..=32768).unwrap();
        assert_eq!(f.n, 5);
        assert_eq!(f.values, values);
    }

    #[test]
    fn names_the_problem() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.npy");
        let mut values = vec![1.0; 16];
        values[6] = f64::INFINITY;
        write_field(&path, 4, &values).unwrap();
        let e = read_field(&path, 4..=32768).unwrap_err().to_string();
        assert!(e.contains("row 1, column 2"), "{e}");
        let bytes = std::fs::read(&path).unwrap();
        let e = parse_field(&bytes[..bytes.len() - 9], 4..=32768).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
        let e = parse_field(b"hello", 4..=32768).unwrap_err();
        assert!(e.contains("not a valid .npy"), "{e}");
    }
}
