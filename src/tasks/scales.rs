//! One surface measured at several scales ([`crate::measured::scales`]): the scan list
//! the command line reads (`check-surface --scales FILE.toml`), and the check both front
//! ends run on it ([`check_scales`]).
//!
//! The scan list is a TOML file of `[[scan]]` tables, one per scan, each with its
//! `file` (a height map or line scans, `.npy` or text, relative to the list's folder),
//! its `pixel_size` (the spacing of its points, in its unit), its `unit` (optional; scans
//! in different units are converted) and `line` (optional: read a 2D file as rows of
//! profiles; a 1D file always is one):
//!
//! ```toml
//! [[scan]]
//! file = "stylus.txt"
//! pixel_size = 0.5
//! unit = "µm"
//!
//! [[scan]]
//! file = "afm.npy"
//! pixel_size = 2.0
//! unit = "nm"
//! ```
//!
//! A field not in this list, a value of the wrong type, a pixel that is not positive or
//! a unit that is not one are refused naming the scan (`scan[1]`, counted from 0) and
//! the field.

use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::check::fill_scans;
use super::Spelling;
use crate::error::{Error, Result, StopReason};
use crate::measured::check::{CheckOptions, Event};
use crate::measured::line::profiles::{is_one_dimensional, Profiles};
use crate::measured::scales::{check_scales as check, page, Measured, ScaleScan, ScalesCheck};
use crate::measured::scan::{read_matrix, Scan};

/// One `[[scan]]` of the list, as written.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScanEntry {
    /// The file, relative to the list's folder.
    pub file: PathBuf,
    /// The spacing of its points, in its unit.
    pub pixel_size: f64,
    /// Its length unit.
    #[serde(default)]
    pub unit: Option<String>,
    /// Read a 2D file as rows of profiles.
    #[serde(default)]
    pub line: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScanList {
    scan: Vec<ScanEntry>,
}

/// The entries of the scan list `text` (read from `path`, named `s.name("scales")`).
///
/// # Errors
///
/// If the text is not a list of `[[scan]]` tables with the fields above (the error names
/// the file, the line and the field), or a scan's pixel is not positive or its unit
/// malformed (naming `scan[i].pixel_size`, `scan[i].unit`).
pub fn parse_list(path: &Path, text: &str, s: &dyn Spelling) -> Result<Vec<ScanEntry>> {
    let list: ScanList = toml::from_str(text).map_err(|e| {
        Error::bad_file(
            path,
            format!(
                "not a scan list ({}): each [[scan]] takes file, pixel_size (a positive \
                 length), unit (optional) and line (optional, true or false)",
                e.to_string().trim_end()
            ),
        )
    })?;
    let name = s.name("scales");
    for (i, e) in list.scan.iter().enumerate() {
        crate::error::check_positive(&format!("{name} scan[{i}].pixel_size"), e.pixel_size)
            .map_err(|e| {
                with_allowed(
                    e,
                    "a positive length, the spacing of the scan's points in its unit",
                )
            })?;
        if let Some(u) = &e.unit {
            crate::measured::units::check_unit(u)
                .map_err(|err| err.with_field(&format!("{name} scan[{i}].unit")))?;
        }
    }
    Ok(list.scan)
}

/// `e` with its allowed range said in `allowed`.
fn with_allowed(e: Error, allowed: &str) -> Error {
    match e {
        Error::InvalidInput { field, value, .. } => Error::invalid(&field, value, allowed),
        other => other,
    }
}

/// Reads the scan list `path` and its scans, each named `scan[i]` (its file is its
/// source).
///
/// # Errors
///
/// As [`parse_list`], and if a scan's file cannot be read or holds neither a height map
/// nor line scans.
pub fn read_list(path: &Path, s: &dyn Spelling) -> Result<Vec<ScaleScan>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let entries = parse_list(path, &text, s)?;
    let dir = path.parent().unwrap_or(Path::new("."));
    entries
        .into_iter()
        .enumerate()
        .map(|(i, e)| {
            let file = dir.join(&e.file);
            let (rows, cols, values) = read_matrix(&file)?;
            let measured = if e.line || is_one_dimensional(rows, cols) {
                Measured::Line(Profiles::pool(vec![Profiles::from_values(
                    &file,
                    &[rows, cols],
                    values,
                    true,
                )?])?)
            } else {
                Measured::Map(Scan::from_values(&file, &[rows, cols], values)?)
            };
            Ok(ScaleScan {
                label: format!("scan[{i}]"),
                measured,
                pixel: e.pixel_size,
                unit: e.unit,
            })
        })
        .collect()
}

/// Checks the surface of `scans` at several scales with `opts` (their pixel sides and
/// unit are each scan's own): every areal scan's missing points filled or refused as
/// `opts.fill` says, then [`crate::measured::scales::check_scales`]; writes `scales.md`
/// and its files into `out` when given.
///
/// # Errors
///
/// If `out` is not a folder, a scan is refused, the check fails, or the page cannot be
/// written.
pub fn check_scales(
    scans: Vec<ScaleScan>,
    opts: &CheckOptions,
    out: Option<&Path>,
    s: &dyn Spelling,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<ScalesCheck> {
    if let Some(dir) = out {
        super::check_out_dir(dir, s)?;
    }
    let scans = scans
        .into_iter()
        .map(|mut scan| {
            if let Measured::Map(m) = &scan.measured {
                let filled = fill_scans(std::slice::from_ref(m), opts.fill, s)?;
                scan.measured = Measured::Map(filled.into_iter().next().expect("one scan"));
            }
            Ok(scan)
        })
        .collect::<Result<Vec<_>>>()?;
    let result = check(&scans, opts, events).map_err(|e| renamed(e, s))?;
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        page::write(&result, dir)?;
    }
    Ok(result)
}

/// `e` with the field it names as the front end spells it: a scan list's field
/// (`scan[1].unit`) inside the flag or keyword of the list, a plain option (`loads`) as
/// [`Spelling::rename`] names it, any other (`heights[1].unit`) as it is.
fn renamed(e: Error, s: &dyn Spelling) -> Error {
    let Error::InvalidInput { field, .. } = &e else {
        return e;
    };
    if field.starts_with("scan[") {
        let f = format!("{} {field}", s.name("scales"));
        e.with_field(&f)
    } else if field.chars().all(|c| c.is_ascii_lowercase() || c == '_') {
        s.rename(e)
    } else {
        e
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::{Flags, Keywords};

    const LIST: &str = "[[scan]]\nfile = \"coarse.npy\"\npixel_size = 10.0\nunit = \"nm\"\n\n\
                        [[scan]]\nfile = \"fine.txt\"\npixel_size = 1e-3\nunit = \"µm\"\n";

    #[test]
    fn a_scan_list_is_read_and_a_bad_field_refused_by_name() {
        let flags = Flags::default();
        let p = Path::new("scales.toml");
        let list = parse_list(p, LIST, &flags).unwrap();
        assert_eq!(list.len(), 2);
        assert_eq!(list[1].unit.as_deref(), Some("µm"));
        assert_eq!(list[1].pixel_size, 1e-3);
        assert!(!list[0].line);
        // A field not in the list.
        let e = parse_list(p, &LIST.replace("unit = \"nm\"", "units = \"nm\""), &flags)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("scales.toml") && e.contains("units") && e.contains("pixel_size"),
            "{e}"
        );
        // A pixel that is not positive, named as each front end spells it.
        let bad = LIST.replace("10.0", "-10.0");
        let e = parse_list(p, &bad, &flags).unwrap_err().to_string();
        assert!(
            e.contains("invalid --scales scan[0].pixel_size = -10")
                && e.contains("positive length"),
            "{e}"
        );
        let e = parse_list(p, &bad, &Keywords).unwrap_err().to_string();
        assert!(e.contains("invalid scales scan[0].pixel_size"), "{e}");
        // A unit that is not one; a pixel of the wrong type.
        let e = parse_list(p, &LIST.replace("\"µm\"", "\"micro metres\""), &flags)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("scan[1].unit") && e.contains("without spaces"),
            "{e}"
        );
        let e = parse_list(p, &LIST.replace("10.0", "\"ten\""), &flags)
            .unwrap_err()
            .to_string();
        assert!(e.contains("pixel_size"), "{e}");
        // No scan at all.
        let e = parse_list(p, "", &flags).unwrap_err().to_string();
        assert!(e.contains("scan"), "{e}");
    }
}
