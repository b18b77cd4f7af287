//! Persson checked on the user's own surface: read the scans, refuse or fill their
//! missing points, solve their load curves, compare with Persson's predictions and write
//! `surface.json`, `surface.md` and the figures ([`crate::measured`]), with every solve's
//! outcome appended to `solves.jsonl` as it ends.
//!
//! One request: the command line's `check-surface` builds a [`CheckRequest`] from its
//! flags and Python's `check_surface` from its keywords; [`CheckRequest::task`] checks
//! every value once (an error names the flag or keyword and the allowed range) and gives
//! the [`SurfaceTask`] both run ([`SurfaceTask::run`]: [`check_surface`] on height maps,
//! [`check_line`] on line scans). Which inputs are line scans:
//! [`crate::measured::line::profiles`], [`read_input`]; a line scan at non-uniform
//! positions (an x-y file) is resampled onto even spacing first
//! ([`crate::measured::line::resample`], [`read_line_scan`], [`resample_profile`]).

use std::io::Write as _;
use std::ops::ControlFlow;
use std::path::Path;

use serde::Serialize;

use super::Spelling;
use crate::error::{Error, Result, StopReason};
use crate::measured::check::{check, CheckOptions, Event, SurfaceCheck};
use crate::measured::fill::{fill, Fill};
use crate::measured::line::check::{LineCheck, LineOptions};
use crate::measured::line::profiles::{is_one_dimensional, Profiles};
use crate::measured::line::resample::{read_xy, resample, Origin, Resampled};
use crate::measured::page;
use crate::measured::psd::Boundary;
use crate::measured::scan::{read_matrix, Scan};
use crate::measured::units::eng;

/// The file of every solve's outcome, one JSON line each, written as it ends.
pub const SOLVES_FILE: &str = "solves.jsonl";

/// What the inputs of a check are: height maps of one surface, or line scans of one.
#[derive(Debug, Clone)]
pub enum Input {
    /// Height maps (scans) of one surface.
    Surface(Vec<Scan>),
    /// Line scans of one surface.
    Line(Profiles),
}

/// What `check-surface` is asked, as a front end was given it (flags or keywords), before
/// any check: the command line and Python both build one and call
/// [`CheckRequest::task`].
#[derive(Debug, Clone, PartialEq)]
pub struct CheckRequest {
    /// Pixel sides as given: one value, or two (between rows, between columns) within
    /// 0.1% of each other; `None` where the input brings its own (a resampled line scan).
    pub pixel_size: Option<Vec<f64>>,
    /// Periodic scans (else measured windows, solved with a free boundary).
    pub periodic: bool,
    /// The other options as given (their pixel sides and boundary are set from the two
    /// fields above).
    pub options: CheckOptions,
    /// How line scans are checked (read for line scans only).
    pub line: LineOptions,
}

/// A checked request: what to check and how; both front ends run it.
#[derive(Debug, Clone)]
pub struct SurfaceTask {
    /// The scans or the line scans.
    pub input: Input,
    /// How the surface is checked.
    pub opts: CheckOptions,
    /// How line scans are checked (read for line scans only).
    pub line: LineOptions,
}

impl CheckRequest {
    /// The task of `input` (`input_pixel`: the spacing a resampled line scan brings),
    /// every value checked before any work, named as `s` spells it.
    ///
    /// # Errors
    ///
    /// If the pixel size is missing, not one or two values, or differs from the input's
    /// own; for line scans, if the synthesized surfaces or the options are out of range
    /// ([`crate::measured::line::check::validate`]). The scans themselves are checked by
    /// [`SurfaceTask::run`].
    pub fn task(
        self,
        input: Input,
        input_pixel: Option<f64>,
        s: &dyn Spelling,
    ) -> Result<SurfaceTask> {
        let opts = CheckOptions {
            pixel_size: pixel_sides(self.pixel_size.as_deref(), input_pixel, s)?,
            boundary: if self.periodic {
                Boundary::Periodic
            } else {
                Boundary::Free
            },
            ..self.options
        };
        let line = self.line;
        if let Input::Line(_) = input {
            crate::measured::line::check::validate(&opts, &line).map_err(|e| s.rename(e))?;
        }
        Ok(SurfaceTask { input, opts, line })
    }
}

/// The pixel sides of a request: `given` (one value or two), or the input's own spacing;
/// both must agree to 1e-9 when both are there.
fn pixel_sides(given: Option<&[f64]>, own: Option<f64>, s: &dyn Spelling) -> Result<[f64; 2]> {
    let sides = match (given, own) {
        (Some(&[p]), _) => [p, p],
        (Some(&[a, b]), _) => [a, b],
        (Some(other), _) => {
            return Err(Error::invalid(
                &s.name("pixel_size"),
                format!("{other:?}"),
                "one value, or two (between rows, between columns)",
            ))
        }
        (None, Some(p)) => return Ok([p, p]),
        (None, None) => {
            return Err(Error::invalid(
                &s.name("pixel_size"),
                "none",
                "a positive length in the heights' unit, or two (between rows, between \
                 columns)",
            ))
        }
    };
    if let Some(p) = own {
        if sides
            .iter()
            .any(|&g| g.is_nan() || (g - p).abs() > 1e-9 * p.abs())
        {
            return Err(Error::invalid(
                &s.name("pixel_size"),
                format!("{} x {}", sides[0], sides[1]),
                format!(
                    "the line scan's own spacing, {p} (its positions' span over its points \
                     less one), or left out"
                ),
            ));
        }
    }
    Ok(sides)
}

/// What a check found: on height maps, or on line scans (`surface.json`'s fields).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Checked {
    /// The check of height maps.
    Surface(Box<SurfaceCheck>),
    /// The check of line scans.
    Line(Box<LineCheck>),
}

impl Checked {
    /// The surface's check (for line scans, that of the synthesized surfaces).
    pub fn surface(&self) -> &SurfaceCheck {
        match self {
            Checked::Surface(c) => c,
            Checked::Line(c) => &c.surface,
        }
    }
}

impl SurfaceTask {
    /// The load curves the check solves per solver: one per scan, or one per synthesized
    /// surface.
    pub fn curves(&self) -> usize {
        match &self.input {
            Input::Surface(scans) => scans.len(),
            Input::Line(_) => usize::try_from(self.line.seeds).unwrap_or(usize::MAX),
        }
    }

    /// Runs the check ([`check_surface`] or [`check_line`]), writing into `out` when
    /// given.
    ///
    /// # Errors
    ///
    /// As [`check_surface`] and [`check_line`].
    pub fn run(
        &self,
        out: Option<&Path>,
        s: &dyn Spelling,
        events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
    ) -> Result<Checked> {
        match &self.input {
            Input::Surface(scans) => check_surface(scans, &self.opts, out, s, events)
                .map(|c| Checked::Surface(Box::new(c))),
            Input::Line(profiles) => check_line(profiles, &self.opts, &self.line, out, s, events)
                .map(|c| Checked::Line(Box::new(c))),
        }
    }
}

/// Reads the line scan of the two-column (position, height) text file `path` and
/// resamples it onto even spacing ([`crate::measured::line::resample`]); returns it with
/// its spacing and the warning that says what was done.
///
/// # Errors
///
/// If the file cannot be read or is not two columns of numbers, its positions do not
/// increase strictly (the error names the line and the values), or the profile is
/// refused as a line scan (too few points, undefined heights).
pub fn read_line_scan(path: &Path) -> Result<(Input, f64, String)> {
    let (x, h, lines) = read_xy(path)?;
    let Resampled {
        heights,
        pixel,
        warning,
    } = resample(path, &x, &h, Origin::Lines(&lines))?;
    let n = heights.len();
    let profiles = Profiles::from_values(path, &[1, n], heights, true)?;
    Ok((Input::Line(Profiles::pool(vec![profiles])?), pixel, warning))
}

/// The profile of heights `h` at positions `x` (an array named `name` in messages)
/// resampled onto even spacing ([`crate::measured::line::resample`]), as Python hands it
/// over.
///
/// # Errors
///
/// As [`resample`]: lengths, or positions that do not increase strictly (the point named
/// by its index).
pub fn resample_profile(name: &str, x: &[f64], h: &[f64]) -> Result<Resampled> {
    resample(Path::new(name), x, h, Origin::Indices)
}

/// Reads `paths`: line scans when `line` (2D inputs read as rows of profiles) or when any
/// input is one-dimensional, else height maps.
///
/// # Errors
///
/// If `paths` is empty, or a file cannot be read or holds neither a height map nor line
/// scans, or the line scans cannot be pooled.
pub fn read_input(paths: &[impl AsRef<Path>], line: bool, s: &dyn Spelling) -> Result<Input> {
    if paths.is_empty() {
        return Err(s.rename(Error::invalid(
            "heights",
            "no file",
            "at least one height map or line scan (.npy or text)",
        )));
    }
    let read = paths
        .iter()
        .map(|p| read_matrix(p.as_ref()).map(|m| (p.as_ref(), m)))
        .collect::<Result<Vec<_>>>()?;
    let line = line || read.iter().any(|(_, m)| is_one_dimensional(m.0, m.1));
    if line {
        let parts = read
            .into_iter()
            .map(|(p, (rows, cols, values))| Profiles::from_values(p, &[rows, cols], values, true))
            .collect::<Result<Vec<_>>>()?;
        Ok(Input::Line(Profiles::pool(parts)?))
    } else {
        read.into_iter()
            .map(|(p, (rows, cols, values))| Scan::from_values(p, &[rows, cols], values))
            .collect::<Result<Vec<_>>>()
            .map(Input::Surface)
    }
}

/// `scans` with their missing points filled as `how` says, or the refusal that names
/// the first scan with gaps, their count and first position, and how to fill them.
///
/// # Errors
///
/// If a scan has gaps that `how` does not fill ([`Error::BadFile`], naming the scan).
pub fn fill_scans(scans: &[Scan], how: Fill, s: &dyn Spelling) -> Result<Vec<Scan>> {
    scans
        .iter()
        .map(|scan| {
            fill(scan, how).map(|(filled, _)| filled).map_err(|gaps| {
                Error::bad_file(
                    &scan.source,
                    gaps.message(&s.given("fill", Fill::Interpolate.name())),
                )
            })
        })
        .collect()
}

/// Checks the surface of `scans` with `opts`; writes the page and its files into `out`
/// when given (and `solves.jsonl` there as the solves end). `events` sees every
/// iteration and every load's end; its answer to an iteration may stop the solve
/// ([`crate::measured::check::check`]).
///
/// # Errors
///
/// If `out` is not a folder, the scans or the options are out of range (checked before
/// any solve), the check itself fails (a failed solve is recorded, not an error), a solve
/// is cancelled ([`Error::Stopped`]), or the page cannot be written.
pub fn check_surface(
    scans: &[Scan],
    opts: &CheckOptions,
    out: Option<&Path>,
    s: &dyn Spelling,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<SurfaceCheck> {
    if let Some(dir) = out {
        super::check_out_dir(dir, s)?;
    }
    let scans = fill_scans(scans, opts.fill, s)?;
    crate::measured::check::validate(&scans, opts).map_err(|e| s.rename(e))?;
    let names: Vec<String> = scans
        .iter()
        .map(|s| s.source.display().to_string())
        .collect();
    let result = logged(&names, out, events, &mut |events| {
        check(&scans, opts, events).map_err(|e| s.rename(e))
    })?;
    if let Some(dir) = out {
        page::write(&result, dir)?;
    }
    Ok(result)
}

/// Checks the surface of line scans `profiles` with `opts` and `line`
/// ([`crate::measured::line::check`]): the contact simulated on surfaces synthesized with
/// the spectrum the profiles imply. Writes the page into `out` when given, as
/// [`check_surface`] does.
///
/// # Errors
///
/// As [`check_surface`], for the profiles and the line options.
pub fn check_line(
    profiles: &Profiles,
    opts: &CheckOptions,
    line: &LineOptions,
    out: Option<&Path>,
    s: &dyn Spelling,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<LineCheck> {
    if let Some(dir) = out {
        super::check_out_dir(dir, s)?;
    }
    crate::measured::line::check::validate(opts, line).map_err(|e| s.rename(e))?;
    let names: Vec<String> = (1..=line.seeds)
        .map(|k| format!("synthesized, seed {k}"))
        .collect();
    let result = logged(&names, out, events, &mut |events| {
        crate::measured::line::check::check_line(profiles, opts, line, events)
            .map_err(|e| s.rename(e))
    })?;
    if let Some(dir) = out {
        crate::measured::line::page::write(&result, dir)?;
    }
    Ok(result)
}

/// A check run with the events it reports.
type Run<'a, T> = &'a mut dyn FnMut(&mut dyn FnMut(Event) -> ControlFlow<StopReason>) -> Result<T>;

/// `run` with every load's end appended to `solves.jsonl` in `out` (the scans named
/// `names`) and passed on to `events`.
fn logged<T>(
    names: &[String],
    out: Option<&Path>,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
    run: Run<'_, T>,
) -> Result<T> {
    let mut log = match out {
        Some(dir) => Some(SolveLog::create(dir)?),
        None => None,
    };
    let mut appended = Ok(());
    let result = run(&mut |e| {
        if let (Some(log), Event::Load { .. }) = (log.as_mut(), &e) {
            if appended.is_ok() {
                appended = log.append(names, &e);
            }
        }
        events(e)
    })?;
    appended?;
    Ok(result)
}

/// `solves.jsonl`: one line per solve, flushed as it ends, so that a check stopped
/// midway leaves what it found.
struct SolveLog {
    path: std::path::PathBuf,
    file: std::fs::File,
}

impl SolveLog {
    fn create(dir: &Path) -> Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let path = dir.join(SOLVES_FILE);
        let file = std::fs::File::create(&path).map_err(|e| Error::io(&path, e))?;
        Ok(Self { path, file })
    }

    fn append(&mut self, scans: &[String], e: &Event) -> Result<()> {
        let Event::Load {
            scan,
            solver,
            headline,
            load,
            outcome,
            ..
        } = *e
        else {
            return Ok(());
        };
        let line = serde_json::json!({
            "scan": scans[scan],
            "solver": solver,
            "headline": headline,
            "load": load,
            "p0": outcome.as_ref().map_or_else(|f| f.p0, |s| s.p0),
            "solved": outcome.as_ref().ok(),
            "failed": outcome.as_ref().err(),
        });
        writeln!(self.file, "{line}")
            .and_then(|()| self.file.flush())
            .map_err(|err| Error::io(&self.path, err))
    }
}

/// One line for a load's end, or a scan's outliers found before its solves (`None` for
/// iterations), for logs and progress where no progress bar is drawn: `scan 1/2, gfmd,
/// load 3/8, p0 = 1.23e-3 E*: a_r = 45.6e-3, 123 iterations, 456e-3 s`.
pub fn load_line(scans: usize, e: &Event) -> Option<String> {
    let (scan, solver, load, loads, outcome) = match *e {
        Event::Load {
            scan,
            solver,
            load,
            loads,
            outcome,
            ..
        } => (scan, solver, load, loads, outcome),
        Event::Outliers { scan, outliers } => {
            return Some(format!("scan {}/{scans}: {}", scan + 1, outliers.summary()));
        }
        Event::Iteration { .. } => return None,
    };
    let at = format!(
        "scan {}/{scans}, {}, load {}/{loads}",
        scan + 1,
        solver.name(),
        load + 1
    );
    Some(match outcome {
        Ok(s) => format!(
            "{at}, p0 = {} E*: a_r = {}, {} iterations, {} s",
            eng(s.p0),
            eng(s.contact_area),
            s.iterations,
            eng(s.wall_s)
        ),
        Err(f) => format!("{at}: FAILED: {}", f.message),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::{Flags, Keywords};

    fn request(pixel_size: Option<Vec<f64>>, seeds: u64) -> CheckRequest {
        CheckRequest {
            pixel_size,
            periodic: false,
            options: CheckOptions::default(),
            line: LineOptions { side: 64, seeds },
        }
    }

    fn line_input() -> Input {
        let h: Vec<f64> = (0..128).map(|k| (k as f64 * 0.3).sin()).collect();
        let p = Profiles::from_values(Path::new("p"), &[1, 128], h, true).unwrap();
        Input::Line(Profiles::pool(vec![p]).unwrap())
    }

    #[test]
    fn a_request_names_the_field_and_its_range_as_each_front_end_spells_it() {
        let flags = Flags::default();
        let e = request(Some(vec![1.0, 1.0, 1.0]), 4)
            .task(Input::Surface(Vec::new()), None, &flags)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--pixel-size") && e.contains("one value, or two"),
            "{e}"
        );
        let e = request(None, 4)
            .task(Input::Surface(Vec::new()), None, &Keywords)
            .unwrap_err()
            .to_string();
        assert!(e.contains("invalid pixel_size"), "{e}");
        let e = request(Some(vec![1.0]), 1)
            .task(line_input(), None, &flags)
            .unwrap_err()
            .to_string();
        assert!(e.contains("--line-seeds") && e.contains("[2, 64]"), "{e}");
        // A resampled line scan brings its spacing; one given must be that one.
        let t = request(None, 4)
            .task(line_input(), Some(0.5), &flags)
            .unwrap();
        assert_eq!(t.opts.pixel_size, [0.5, 0.5]);
        assert_eq!(t.opts.boundary, Boundary::Free);
        let e = request(Some(vec![0.6]), 4)
            .task(line_input(), Some(0.5), &Keywords)
            .unwrap_err()
            .to_string();
        assert!(e.contains("pixel_size") && e.contains("spacing"), "{e}");
    }
}
