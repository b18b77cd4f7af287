//! Running the check: each scan's load curve solved by the headline solver, then by the
//! other one ([`super::options::CheckOptions`]) at the cross-checked loads
//! ([`CROSS_CHECKED_LOADS`] of them, or all), and the re-entry share at the middle load
//! the headline reached ([`super::reentry`]); the scans' measurements then go to
//! [`super::findings`].
//!
//! Unless asked not to, each scan is first cut at its shortest reliable wavelength (the
//! noise floor's onset, or a tip's radius: [`super::cutoff`]), and each load is also solved on the scan coarsened by 2 (and by 4),
//! for the pixel's own error on the contact area ([`super::pixel`]).
//!
//! Before any solve, each scan's spikes and outliers are found ([`super::spikes`]),
//! replaced first when despiking is asked, and reported ([`Event::Outliers`]).
//!
//! A solve that fails is a finding, not the end of the check: the curve goes on with the
//! next load. Every solve has the iteration budget of the options
//! ([`super::options::MAX_ITERATIONS`] by default), and a cross-check solve also a time
//! budget of [`CROSS_CHECK_TIME`] times the headline's time at its load (at least
//! [`CROSS_CHECK_MIN_S`]; only the headline's time where the headline failed), beyond
//! which it is stopped and recorded as failed.

use std::ops::ControlFlow;
use std::time::Duration;

use super::body::{solve_curve, Body, Curve, Outcome};
use super::conclude::{conclude, Measured};
use super::findings::SurfaceCheck;
use super::options::{other, validate, CheckOptions};
use super::psd::ScanSpectrum;
use super::reentry::reentry_share;
use super::scan::Scan;
use super::spikes::{despike, Outliers};
use super::theory::{loads, Theory};
use crate::engine::solver::{Progress, SolveOptions, SolverKind};
use crate::error::{Result, StopReason};

/// The cross-check's time budget at a load, in multiples of the headline solve's time
/// there: a cross-check that would take longer is stopped and recorded as failed.
pub const CROSS_CHECK_TIME: f64 = 20.0;

/// The least time budget of a cross-check solve, seconds (a headline solve of a few
/// milliseconds says little about what the other solver needs).
pub const CROSS_CHECK_MIN_S: f64 = 2.0;

/// The loads cross-checked unless every load is asked for: the lowest, the middle and
/// the highest (GFMD, the cross-check of the default, takes some three times CG's time
/// per load on measured scans: `docs/check-surface.md`, where the time goes).
pub const CROSS_CHECKED_LOADS: usize = 3;

/// What the check reports while it runs.
#[derive(Debug, Clone, Copy)]
pub enum Event<'a> {
    /// A scan's spikes and outliers, found before its solves.
    Outliers {
        /// The scan (index).
        scan: usize,
        /// What was found.
        outliers: &'a Outliers,
    },
    /// An iteration of a solve.
    Iteration {
        /// The scan (index).
        scan: usize,
        /// The solver.
        solver: SolverKind,
        /// The load (index).
        load: usize,
        /// The solve's progress.
        progress: Progress,
    },
    /// A load's solve ended.
    Load {
        /// The scan (index).
        scan: usize,
        /// The solver.
        solver: SolverKind,
        /// Whether it is the headline solver.
        headline: bool,
        /// The load (index) and the number of loads.
        load: usize,
        loads: usize,
        /// How it ended.
        outcome: &'a Outcome,
    },
}

/// Checks the surface of `scans` (one surface, several scans of it; every point
/// measured or filled, see [`super::fill`]). `events` sees every iteration and every
/// load's end; its answer to an iteration may stop that solve
/// ([`StopReason::OutOfTime`]: the load fails over time; [`StopReason::Cancelled`]: the
/// check ends in [`crate::Error::Stopped`]), its answers to other events are not read.
pub fn check(
    scans: &[Scan],
    opts: &CheckOptions,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<SurfaceCheck> {
    let timer = std::time::Instant::now();
    let pixel = validate(scans, opts)?;
    let (outliers, spectra) = spectra(scans, opts, pixel, events)?;
    // The loads come from the first scan's spectrum: common to every scan.
    let loads = loads(
        &Theory::new(&spectra[0].spectrum.shells)?,
        opts.loads.as_deref(),
    )?;
    let mut measured = Vec::with_capacity(scans.len());
    // One body for every scan: its half-space depends on the shape alone.
    let mut body: Option<Body> = None;
    for (k, (Spectra { spectrum, cut }, mut outliers)) in
        spectra.into_iter().zip(outliers).enumerate()
    {
        let theory = Theory::new(&spectrum.shells)?;
        let predicted = loads.iter().map(|&p| theory.at(p)).collect::<Result<_>>()?;
        let body = match body.as_mut() {
            Some(b) => {
                b.set_heights(&spectrum)?;
                b
            }
            None => body.insert(Body::new(&spectrum)?),
        };
        let every: Vec<usize> = (0..loads.len()).collect();
        let head = run_curve(
            body,
            &loads,
            (&every, loads.len()),
            opts.solver,
            opts,
            &[],
            k,
            events,
        )?;
        let pixel = if opts.extrapolate {
            coarse_curves(&spectrum, &loads, opts, k, events)?
        } else {
            Vec::new()
        };
        let mut curves = vec![head];
        if opts.cross_check {
            let index = if opts.cross_check_all {
                every
            } else {
                sample(loads.len(), CROSS_CHECKED_LOADS)
            };
            let budget = cross_check_budget(&curves[0], &index);
            let at: Vec<f64> = index.iter().map(|&i| loads[i]).collect();
            let other = other(opts.solver);
            let of = (&index[..], loads.len());
            let mut cross = run_curve(body, &at, of, other, opts, &budget, k, events)?;
            cross.index = index;
            curves.push(cross);
        }
        outliers.contact_share = (0..loads.len())
            .map(|i| {
                curves[0].pressures[i]
                    .as_deref()
                    .and_then(|p| super::spikes::spike_contact_share(&outliers.points, p))
            })
            .collect();
        let reentry = if opts.reentry {
            middle_solved(&curves[0])
                .map(|i| reentry_share(&spectrum, loads[i], SolverKind::Cg, opts.tol))
                .transpose()?
        } else {
            None
        };
        measured.push(Measured {
            outliers,
            spectrum,
            predicted,
            curves,
            pixel,
            cut,
            reentry,
        });
    }
    Ok(conclude(
        scans,
        opts,
        pixel,
        &loads,
        &measured,
        timer.elapsed().as_secs_f64(),
    ))
}

/// Each scan's spikes and outliers (reported as found) and its spectrum, despiked where
/// asked and cut at its shortest reliable wavelength unless asked not to.
fn spectra(
    scans: &[Scan],
    opts: &CheckOptions,
    pixel: f64,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<(Vec<Outliers>, Vec<Spectra>)> {
    let shape = scans[0].shape;
    let mut outliers = Vec::with_capacity(scans.len());
    let mut spectra = Vec::with_capacity(scans.len());
    for (k, s) in scans.iter().enumerate() {
        let (heights, despiked) = match opts.despike {
            Some(threshold) => despike(&s.heights, shape, threshold),
            None => (s.heights.clone(), 0),
        };
        let as_measured = ScanSpectrum::new(&heights, shape, pixel, opts.boundary)?;
        let mut found = Outliers::of(&as_measured.heights);
        found.despiked = despiked;
        // Only an iteration's answer is read (see above).
        let _ = events(Event::Outliers {
            scan: k,
            outliers: &found,
        });
        outliers.push(found);
        let cut = if opts.cutoff {
            super::cutoff::apply(&as_measured, pixel, opts.tip_radius)?
        } else {
            None
        };
        spectra.push(match cut {
            Some((cutoff, filtered)) => Spectra {
                spectrum: filtered,
                cut: Some((cutoff, as_measured)),
            },
            None => Spectra {
                spectrum: as_measured,
                cut: None,
            },
        });
    }
    Ok((outliers, spectra))
}

/// The scan's load curve on the grids coarsened by each factor of
/// [`super::pixel::factors`], by the headline solver with the check's tolerance and
/// iteration budget, for the pixel's own error ([`super::pixel`]). Its iterations reach
/// `events` (whose answer may stop a solve); its loads' ends do not.
fn coarse_curves(
    spectrum: &ScanSpectrum,
    loads: &[f64],
    opts: &CheckOptions,
    scan: usize,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<Vec<(usize, Curve)>> {
    let solver = opts.solver;
    let mut levels = Vec::new();
    for factor in super::pixel::factors(spectrum.shape, spectrum.boundary) {
        let (heights, shape) = super::pixel::coarsen(&spectrum.heights, spectrum.shape, factor);
        let coarse = ScanSpectrum::new(&heights, shape, factor as f64, spectrum.boundary)?;
        let body = Body::new(&coarse)?;
        let curve = solve_curve(
            &body,
            loads,
            solver,
            SolveOptions {
                tol: opts.tol,
                max_iter: opts.max_iterations,
            },
            &[],
            &mut |_, _| {},
            &mut |load, progress| {
                events(Event::Iteration {
                    scan,
                    solver,
                    load,
                    progress,
                })
            },
        )?;
        levels.push((factor, curve));
    }
    Ok(levels)
}

/// A scan's spectrum as solved, and where a cutoff filtered it, the cutoff and the
/// spectrum as measured.
struct Spectra {
    spectrum: ScanSpectrum,
    cut: Option<(super::cutoff::Cutoff, ScanSpectrum)>,
}

/// `count` of `n` load indices, evenly spread from the first to the last.
fn sample(n: usize, count: usize) -> Vec<usize> {
    let mut index: Vec<usize> = (0..count.min(n))
        .map(|k| {
            if count > 1 {
                (k * (n - 1) + (count - 1) / 2) / (count - 1)
            } else {
                n / 2
            }
        })
        .collect();
    index.dedup();
    index
}

/// One scan's curve by one solver at `loads`, the check's loads `index` of `of`, with its
/// events (the headline solver's when `budget` is empty).
#[allow(clippy::too_many_arguments)]
fn run_curve(
    body: &Body,
    loads: &[f64],
    (index, of): (&[usize], usize),
    solver: SolverKind,
    opts: &CheckOptions,
    budget: &[Option<Duration>],
    scan: usize,
    events: &mut dyn FnMut(Event) -> ControlFlow<StopReason>,
) -> Result<Curve> {
    let headline = budget.is_empty();
    let events = std::cell::RefCell::new(events);
    solve_curve(
        body,
        loads,
        solver,
        SolveOptions {
            tol: opts.tol,
            max_iter: opts.max_iterations,
        },
        budget,
        &mut |load, outcome| {
            let _ = (events.borrow_mut())(Event::Load {
                scan,
                solver,
                headline,
                load: index[load],
                loads: of,
                outcome,
            });
        },
        &mut |load, progress| {
            (events.borrow_mut())(Event::Iteration {
                scan,
                solver,
                load: index[load],
                progress,
            })
        },
    )
}

/// The cross-check's time at each of the loads `index`: [`CROSS_CHECK_TIME`] times the
/// headline's time there, at least [`CROSS_CHECK_MIN_S`]; where the headline failed, its
/// own time (a failed headline has already spent its budget).
fn cross_check_budget(head: &Curve, index: &[usize]) -> Vec<Option<Duration>> {
    index
        .iter()
        .map(|&i| {
            let allowed = match &head.points[i] {
                Ok(s) => CROSS_CHECK_TIME * s.wall_s,
                Err(f) => f.wall_s,
            };
            Some(Duration::from_secs_f64(allowed.max(CROSS_CHECK_MIN_S)))
        })
        .collect()
}

/// The middle one of the loads a curve solved.
fn middle_solved(curve: &Curve) -> Option<usize> {
    let solved: Vec<usize> = (0..curve.points.len())
        .filter(|&i| curve.solved(i).is_some())
        .collect();
    solved.get(solved.len() / 2).copied()
}
