//! Persson checked on the user's own surface: read the scans, refuse or fill their
//! missing points, solve their load curves, compare with Persson's predictions and write
//! `surface.json`, `surface.md` and the figures ([`crate::measured`]), with every solve's
//! outcome appended to `solves.jsonl` as it ends. The command line's `check-surface` and
//! Python's `check_surface` both call [`check_surface`], or [`check_line`] for line scans
//! (which inputs are line scans: [`crate::measured::line::profiles`]; [`read_input`]).

use std::io::Write as _;
use std::ops::ControlFlow;
use std::path::Path;

use super::Spelling;
use crate::error::{Error, Result, StopReason};
use crate::measured::check::{check, CheckOptions, Event, SurfaceCheck};
use crate::measured::fill::{fill, Fill};
use crate::measured::line::check::{LineCheck, LineOptions};
use crate::measured::line::profiles::{is_one_dimensional, Profiles};
use crate::measured::page;
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
