//! Speed against error for a re-entry history: the same climbs at several solver
//! tolerances, so that a scene can be run at the loosest tolerance that leaves what the
//! claims read unchanged.
//!
//! A history adds every shell of modes one at a time at fixed load and records, for every
//! point, whether it was ever out of contact ([`crate::experiments::history`]). A looser residual
//! tolerance stops each of the ~10^3 warm-started solves earlier; the question is whether
//! the re-entry share (the headline of assumption (c), paper section 3.3) and the contact
//! set at `zeta_max` move. Each row of the study is one grid, one load and one tolerance,
//! over the grid's realizations:
//!
//! * `share`: the re-entry share, mean over realizations with its standard error;
//! * `shift_se`: the mean, over realizations, of the share's change against the same
//!   realization at the tightest tolerance, in units of the standard error of the share at
//!   the tightest tolerance (of the scene's headline where the grid has one realization);
//! * `contact_differs`: the share of the grid's points whose contact at `zeta_max` differs
//!   from the tightest run's, mean over realizations;
//! * `iterations_per_shell` and `seconds_per_shell`: the cost (wall time of a job run on
//!   one thread of a shared machine: compare rows of one run, not runs).
//!
//! A tolerance is accepted when every row at it, on every grid and load, lies within
//! [`SHIFT_SE`] standard errors of the tightest and differs from it at fewer than
//! [`DIFFERS`] of the points; the study names the loosest accepted tolerance.
//!
//! A row at the scene's own grid, tolerance, load and seeds is not run again: it reads the
//! headline's histories.

use serde::{Deserialize, Serialize};

use super::stats::{ratio, ReentryStats};
use super::{ReentryJob, ReentryOutput, ReentryResult, ReentryScene};
use crate::engine::sweep::shell_steps;
use crate::error::{check_positive, Error, Result};
use crate::experiments::climb::climb_job;
use crate::experiments::contact_change::unpack_categories;
use crate::experiments::ensemble::{check_contact_areas, SeedLoad};
use crate::experiments::history::{self, History};
use crate::experiments::other_grid::other_grid;
use crate::experiments::study::{with_settings, Cell, Study};
use crate::experiments::{JobContext, Work};
use crate::stats::Estimate;

/// A tolerance is accepted when its shares lie within this many standard errors of the
/// tightest tolerance's.
pub const SHIFT_SE: f64 = 0.1;
/// ... and its contact sets at `zeta_max` differ from the tightest's at fewer than this
/// share of the points.
pub const DIFFERS: f64 = 0.001;

/// The study as a scene states it (`[full.tolerance]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TolerancePlan {
    /// Tolerances, each run on every grid.
    pub tols: Vec<f64>,
    /// The grids (the scene's Hurst exponent on each).
    pub grids: Vec<ToleranceGrid>,
}

other_grid! {
    /// One grid of the study with its realizations and loads.
    pub struct ToleranceGrid {
        /// Realizations.
        pub seeds: Vec<u64>,
        /// Contact areas at `zeta_max` (the loads).
        pub contact_areas: Vec<f64>,
    }
}

other_grid! {
    /// One history of the study: everything it depends on besides the Hurst exponent.
    pub struct ToleranceJob {
        /// Realization.
        pub seed: u64,
        /// Contact area at `zeta_max`.
        pub contact_area: f64,
        /// Residual tolerance.
        pub tol: f64,
    }
}

/// What one history of the study measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ToleranceResult {
    /// Points in contact at `zeta_max`.
    pub contact_points: u64,
    /// Of those, points that were out of contact at some step.
    pub reentered: u64,
    /// Shells added.
    pub shells: usize,
    /// Solver iterations over the climb (the load search excluded).
    pub iterations: u64,
    /// Wall time of the climb, seconds.
    pub wall_s: f64,
    /// Largest residual.
    pub max_residual: f64,
    /// The contact at `zeta_max`, one bit a point (least significant first), as hex.
    pub contact: String,
}

impl ToleranceResult {
    /// The re-entry share.
    pub fn share(&self) -> f64 {
        ratio(self.reentered, self.contact_points)
    }
}

/// A history of the study's, or one of the headline's read in its place: what a row needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// The re-entry share.
    pub share: f64,
    /// Contact at `zeta_max`, one byte (0 or 1) a point.
    pub contact: Vec<u8>,
    /// Solver iterations.
    pub iterations: u64,
    /// Wall time, seconds.
    pub wall_s: f64,
    /// Shells added.
    pub shells: usize,
}

impl ToleranceGrid {
    /// The job of `seed` at `contact_area` and `tol` on this grid.
    pub fn job(&self, seed: u64, contact_area: f64, tol: f64) -> ToleranceJob {
        ToleranceJob {
            n: self.n,
            lambda_l: self.lambda_l,
            lambda_s: self.lambda_s,
            seed,
            contact_area,
            tol,
        }
    }
}

impl TolerancePlan {
    /// Checks the plan: tolerances in (0, 1), distinct; every grid a valid scene at
    /// `hurst`; errors name the field.
    pub fn validate(&self, hurst: f64) -> Result<()> {
        if self.tols.is_empty() {
            return Err(Error::invalid(
                "tolerance.tols",
                "[]",
                "at least one tolerance",
            ));
        }
        for (k, &t) in self.tols.iter().enumerate() {
            crate::error::check_open("tolerance.tols", t, 0.0, 1.0)?;
            if self.tols[..k].contains(&t) {
                return Err(Error::invalid("tolerance.tols", t, "each tolerance once"));
            }
        }
        if self.grids.is_empty() {
            return Err(Error::invalid("tolerance.grids", "[]", "at least one grid"));
        }
        for g in &self.grids {
            g.base(hurst, &g.seeds, self.tols[0]).validate()?;
            check_contact_areas(&g.contact_areas)?;
        }
        Ok(())
    }

    /// Every history of the plan, grids outermost, then loads, tolerances and seeds.
    pub fn jobs(&self) -> Vec<ToleranceJob> {
        let mut jobs = Vec::new();
        for g in &self.grids {
            for &a in &g.contact_areas {
                for &t in &self.tols {
                    for &s in &g.seeds {
                        jobs.push(g.job(s, a, t));
                    }
                }
            }
        }
        jobs
    }
}

/// What a job costs: a load search and every shell.
pub fn work(job: &ToleranceJob, hurst: f64) -> Work {
    let b = job.base(hurst, &[], job.tol);
    Work::search_then(job.n, 0, b.shells(0.0, b.zeta_max()))
}

/// Runs (or resumes) one history of the study.
pub fn run(
    job: &ToleranceJob,
    hurst: f64,
    ctx: &JobContext,
    seconds: f64,
) -> Result<ToleranceResult> {
    check_positive("tolerance.tol", job.tol)?;
    let seeds = [job.seed];
    let b = job.base(hurst, &seeds, job.tol);
    let r = b.realization(job.seed)?;
    let steps = shell_steps(&r.surface, 0.0, r.surface.zeta_max());
    // No flux interval: the study reads the contact at zeta_max only.
    let mut history = History::new(r.model.grid.points(), (f64::INFINITY, f64::INFINITY));
    let climbed = climb_job(&b, ctx, &r, job.contact_area, &steps, &mut history, seconds)?;
    let (contact_points, reentered, _) = history.counts();
    Ok(ToleranceResult {
        contact_points,
        reentered,
        shells: steps.len(),
        iterations: climbed.iterations,
        wall_s: climbed.wall_s,
        max_residual: climbed.max_residual,
        contact: pack_bits(&history.in_contact),
    })
}

/// Packs 0/1 values, eight to a byte (least significant first), as hex.
pub fn pack_bits(bits: &[u8]) -> String {
    bits.chunks(8)
        .map(|q| {
            let b = q
                .iter()
                .enumerate()
                .fold(0u8, |acc, (k, &v)| acc | ((v & 1) << k));
            format!("{b:02x}")
        })
        .collect()
}

/// Unpacks [`pack_bits`] into `len` values.
pub fn unpack_bits(hex: &str, len: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(len);
    for k in (0..hex.len()).step_by(2) {
        let b = u8::from_str_radix(hex.get(k..k + 2).unwrap_or("00"), 16).unwrap_or(0);
        for j in 0..8 {
            if out.len() < len {
                out.push((b >> j) & 1);
            }
        }
    }
    out.resize(len, 0);
    out
}

/// One row: a grid, a load and a tolerance, with its realizations' samples (in the
/// grid's seed order; a missing sample is `None`).
pub struct RowSamples<'a> {
    /// The grid.
    pub grid: &'a ToleranceGrid,
    /// The load.
    pub contact_area: f64,
    /// The tolerance.
    pub tol: f64,
    /// One sample per seed.
    pub samples: Vec<Option<&'a Sample>>,
}

/// The verdict of the study: the loosest tolerance accepted on every row, with every
/// tighter one, if any.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Choice {
    /// The loosest accepted tolerance (none when no row could be compared).
    pub tol: Option<f64>,
    /// The tightest tolerance, the reference.
    pub tightest: f64,
}

/// The tolerance study: its key and columns, `(key, label)`.
pub const STUDY: &str = "tolerance";

/// The columns of [`STUDY`].
pub fn columns() -> Vec<(&'static str, &'static str)> {
    with_settings(
        &["n", "contact_area", "tol", "realizations"],
        &[
            ("share", "re-entry share"),
            (
                "shift_se",
                "share minus the tightest's (same realization), in standard errors",
            ),
            (
                "contact_differs",
                "points whose contact at zeta_max differs from the tightest's",
            ),
            ("iterations_per_shell", "solver iterations a shell"),
            ("seconds_per_shell", "wall seconds a shell"),
            ("accepted", "accepted (1) or not (0)"),
        ],
    )
}

/// The study's table from its rows (every grid, load and tolerance, tolerances in the
/// plan's order), with the standard error of the headline's share at each load of the
/// scene's grid for grids of one realization (`headline_se(grid, load)`).
pub fn study(
    tols: &[f64],
    rows: &[RowSamples],
    headline_se: impl Fn(&ToleranceGrid, f64) -> Option<f64>,
) -> Study {
    let mut study = Study::new(
        STUDY,
        "Speed against error of a history: the same climbs at several solver tolerances",
        &columns(),
    )
    .about(format!(
        "Each row: one grid, one load, one tolerance, the climbs of every realization \
         through every shell at fixed load (as the headline's). The shift and the differing \
         points are against the same realization at the tightest tolerance of the grid; the \
         standard error is the tightest row's over realizations, or the headline's at that \
         load where the grid has one realization. A tolerance is accepted when every row at \
         it shifts by at most {SHIFT_SE} standard errors and differs at fewer than {}% of \
         the points. Wall seconds are of jobs run side by side on one machine.",
        100.0 * DIFFERS
    ))
    .percent(&["share", "contact_differs"]);
    let mut accepted_at: Vec<(f64, Option<bool>)> = tols.iter().map(|&t| (t, None)).collect();
    for row in rows {
        let tightest = tightest_of(tols, rows, row.grid, row.contact_area);
        let present: Vec<&Sample> = row.samples.iter().flatten().copied().collect();
        let share = Estimate::mean_of(&present.iter().map(|s| s.share).collect::<Vec<_>>());
        let (shift, differs) = against_tightest(row, tightest, present.len(), &headline_se);
        let accepted = match (shift, differs) {
            (Some(s), Some(d)) => Some(s.abs() <= SHIFT_SE && d < DIFFERS),
            _ => None,
        };
        if let Some(slot) = accepted_at.iter_mut().find(|(t, _)| *t == row.tol) {
            slot.1 = match (slot.1, accepted) {
                (Some(false), _) | (_, Some(false)) => Some(false),
                (_, Some(true)) => Some(true),
                (s, None) => s,
            };
        }
        let per_shell = |f: &dyn Fn(&Sample) -> f64| {
            let v: Vec<f64> = present
                .iter()
                .map(|s| f(s) / s.shells.max(1) as f64)
                .collect();
            Cell::from(Estimate::mean_of(&v).value)
        };
        study.push(
            format!("n{}_ar{}_tol{:e}", row.grid.n, row.contact_area, row.tol),
            format!(
                "{}, a_r {}, tol {:e}",
                row.grid.grid_label(),
                row.contact_area,
                row.tol
            ),
            vec![
                (row.grid.n as f64).into(),
                row.contact_area.into(),
                row.tol.into(),
                (present.len() as f64).into(),
                if present.is_empty() {
                    Cell::Empty
                } else {
                    share.into()
                },
                shift.unwrap_or(f64::NAN).into(),
                differs.unwrap_or(f64::NAN).into(),
                per_shell(&|s| s.iterations as f64),
                per_shell(&|s| s.wall_s),
                accepted.map_or(f64::NAN, |a| f64::from(u8::from(a))).into(),
            ],
        );
    }
    study.notes = notes(&choice(tols, &accepted_at), &accepted_at);
    study
}

/// A row against the tightest row of its grid and load: the mean shift of the share in
/// standard errors (the tightest row's over realizations, or `headline_se` where that has
/// none) and the mean share of the points whose contact differs; none unless every
/// realization of the row has a sample (`present` of them) and a tightest one.
fn against_tightest(
    row: &RowSamples,
    tightest: Option<&RowSamples>,
    present: usize,
    headline_se: &dyn Fn(&ToleranceGrid, f64) -> Option<f64>,
) -> (Option<f64>, Option<f64>) {
    match tightest {
        Some(t) if present > 0 && present == row.samples.len() => {
            let pairs: Vec<(&Sample, &Sample)> = row
                .samples
                .iter()
                .zip(&t.samples)
                .filter_map(|(a, b)| Some(((*a)?, (*b)?)))
                .collect();
            let t_shares: Vec<f64> = t.samples.iter().flatten().map(|s| s.share).collect();
            let se = Estimate::mean_of(&t_shares).std_error;
            let se = if se.is_finite() && se > 0.0 {
                Some(se)
            } else {
                headline_se(row.grid, row.contact_area)
            };
            if pairs.len() == row.samples.len() {
                let n = pairs.len() as f64;
                let d = pairs.iter().map(|(a, b)| a.share - b.share).sum::<f64>() / n;
                let differs = pairs
                    .iter()
                    .map(|(a, b)| {
                        a.contact
                            .iter()
                            .zip(&b.contact)
                            .filter(|(x, y)| x != y)
                            .count() as f64
                            / a.contact.len().max(1) as f64
                    })
                    .sum::<f64>()
                    / n;
                (se.map(|se| d / se), Some(differs))
            } else {
                (None, None)
            }
        }
        _ => (None, None),
    }
}

/// The row of the tightest tolerance of `grid` at `contact_area`.
fn tightest_of<'a>(
    tols: &[f64],
    rows: &'a [RowSamples<'a>],
    grid: &ToleranceGrid,
    contact_area: f64,
) -> Option<&'a RowSamples<'a>> {
    let t = tols.iter().copied().fold(f64::INFINITY, f64::min);
    rows.iter()
        .find(|r| r.grid == grid && r.contact_area == contact_area && r.tol == t)
}

/// The loosest tolerance accepted with every tighter one, with the tightest.
fn choice(tols: &[f64], accepted_at: &[(f64, Option<bool>)]) -> Choice {
    let mut sorted: Vec<(f64, Option<bool>)> = accepted_at.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let tightest = tols.iter().copied().fold(f64::INFINITY, f64::min);
    let tol = sorted
        .iter()
        .take_while(|(_, a)| *a == Some(true))
        .map(|&(t, _)| t)
        .last();
    Choice { tol, tightest }
}

/// The study's statements, from its verdicts.
fn notes(choice: &Choice, accepted_at: &[(f64, Option<bool>)]) -> Vec<String> {
    let verdicts = accepted_at
        .iter()
        .map(|(t, a)| {
            let v = match a {
                Some(true) => "accepted",
                Some(false) => "not accepted",
                None => "not compared (rows missing)",
            };
            format!("tol {t:e}: {v}")
        })
        .collect::<Vec<_>>()
        .join("; ");
    let chosen = match choice.tol {
        Some(t) if t > choice.tightest => format!(
            "The loosest tolerance whose shares lie within {SHIFT_SE} standard errors of tol \
             {:e} and whose contact sets differ at fewer than {}% of the points, on every \
             grid and load: {t:e}.",
            choice.tightest,
            100.0 * DIFFERS
        ),
        _ => format!(
            "No tolerance looser than the tightest ({:e}) keeps the shares within {SHIFT_SE} \
             standard errors and the contact sets within {}% of the points on every grid \
             and load.",
            choice.tightest,
            100.0 * DIFFERS
        ),
    };
    vec![chosen, verdicts]
}

/// The tolerance study's table: its own histories and, where a row repeats the headline's
/// grid, tolerance and loads, the headline's.
pub(super) fn of_results(
    scene: &ReentryScene,
    plan: &TolerancePlan,
    results: &[(ReentryJob, ReentryOutput)],
    histories: &[(SeedLoad, ReentryResult)],
    stats: &ReentryStats,
) -> Study {
    let own: Vec<(ToleranceJob, Sample)> = results
        .iter()
        .filter_map(|(j, r)| match (j, r) {
            (ReentryJob::Tolerance(j), ReentryOutput::Tolerance(r)) => Some((
                j.clone(),
                Sample {
                    share: r.share(),
                    contact: unpack_bits(&r.contact, j.n * j.n),
                    iterations: r.iterations,
                    wall_s: r.wall_s,
                    shells: r.shells,
                },
            )),
            _ => None,
        })
        .collect();
    let n2 = scene.n * scene.n;
    let headline: Vec<(SeedLoad, Sample)> = histories
        .iter()
        .filter_map(|(j, r)| {
            let map = r.map.as_deref()?;
            let contact = unpack_categories(map, n2)
                .into_iter()
                .map(|c| u8::from(c == history::IN_THROUGHOUT || c == history::REENTERED))
                .collect();
            Some((
                j.clone(),
                Sample {
                    share: r.share(),
                    contact,
                    iterations: r.iterations,
                    wall_s: r.wall_s,
                    shells: r.shells,
                },
            ))
        })
        .collect();
    let mut rows = Vec::new();
    for grid in &plan.grids {
        for &a in &grid.contact_areas {
            for &t in &plan.tols {
                let samples = grid
                    .seeds
                    .iter()
                    .map(|&seed| {
                        let job = grid.job(seed, a, t);
                        match scene.headline_job(&job) {
                            Some(h) => headline.iter().find(|(j, _)| *j == h).map(|(_, s)| s),
                            None => own.iter().find(|(j, _)| *j == job).map(|(_, s)| s),
                        }
                    })
                    .collect();
                rows.push(RowSamples {
                    grid,
                    contact_area: a,
                    tol: t,
                    samples,
                });
            }
        }
    }
    study(&plan.tols, &rows, |grid, a| {
        let on_scene =
            (grid.n, grid.lambda_l, grid.lambda_s) == (scene.n, scene.lambda_l, scene.lambda_s);
        on_scene
            .then(|| {
                stats
                    .shares
                    .iter()
                    .find(|s| s.load == a)
                    .map(|s| s.share.std_error)
            })
            .flatten()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits_round_trip() {
        let bits: Vec<u8> = (0..37).map(|i| u8::from(i % 3 == 0)).collect();
        assert_eq!(unpack_bits(&pack_bits(&bits), bits.len()), bits);
    }

    fn sample(share: f64, contact: &[u8]) -> Sample {
        Sample {
            share,
            contact: contact.to_vec(),
            iterations: 100,
            wall_s: 1.0,
            shells: 10,
        }
    }

    #[test]
    fn the_loosest_tolerance_that_moves_nothing_is_chosen() {
        let grid = ToleranceGrid {
            n: 4,
            lambda_l: 4.0,
            lambda_s: 2.0,
            seeds: vec![1, 2],
            contact_areas: vec![0.5],
        };
        let contact = vec![1u8; 2000];
        let mut moved = contact.clone();
        moved[0] = 0;
        moved[1] = 0;
        moved[2] = 0;
        // Tightest: shares 0.5 and 0.6 (standard error 0.05).
        let t7 = [sample(0.5, &contact), sample(0.6, &contact)];
        // 1e-6: the same shares, one point in 2000 differs (0.05%): accepted.
        let mut one = contact.clone();
        one[0] = 0;
        let t6 = [sample(0.5, &one), sample(0.6, &contact)];
        // 1e-5: shifted by 0.01 (0.2 standard errors): not accepted.
        let t5 = [sample(0.51, &contact), sample(0.61, &contact)];
        // 1e-4: the same shares, but 3 points in 2000 (0.15%) differ: not accepted.
        let t4 = [sample(0.5, &moved), sample(0.6, &moved)];
        let tols = [1e-4, 1e-5, 1e-6, 1e-7];
        let rows: Vec<RowSamples> = [(1e-4, &t4), (1e-5, &t5), (1e-6, &t6), (1e-7, &t7)]
            .into_iter()
            .map(|(tol, s)| RowSamples {
                grid: &grid,
                contact_area: 0.5,
                tol,
                samples: s.iter().map(Some).collect(),
            })
            .collect();
        let s = study(&tols, &rows, |_, _| None);
        let col = |row: usize, c: &str| s.rows[row].cells[s.column(c).unwrap()];
        assert_eq!(col(0, "accepted"), Cell::Number(0.0));
        assert_eq!(col(1, "accepted"), Cell::Number(0.0));
        assert_eq!(col(2, "accepted"), Cell::Number(1.0));
        assert_eq!(col(3, "accepted"), Cell::Number(1.0));
        let Cell::Number(shift) = col(1, "shift_se") else {
            panic!("a shift")
        };
        assert!((shift - 0.2).abs() < 1e-9, "{shift}");
        assert!(s.notes[0].contains("1e-6"), "{}", s.notes[0]);
    }
}
