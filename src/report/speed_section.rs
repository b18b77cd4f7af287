//! The speed-against-error study as the scorecard shows it: a function per table.

use std::fmt::Write as _;

use super::format::{duration, failed, md, num, or_dash, pm, push_rows, push_table, sig};
use super::{Scorecard, SpeedSection};
use crate::engine::solver::SolverKind;
use crate::speed::{SizeRow, SpeedStudy, ThreadRow, SOLVERS};

impl Scorecard<'_> {
    pub(super) fn speed_section(&self, s: &mut String) {
        let _ = writeln!(s, "## Speed against error\n");
        let Some(study) = self.speed_study(s) else {
            return;
        };
        scene(s, study);
        tolerance_table(s, study);
        size_table(s, study);
        thread_table(s, study);
        floor_table(s, study);
        warm_table(s, study);
        self.speed_files(s);
    }

    /// The study in the outcomes' folder, after saying where it is from; `None`, with how to
    /// produce one, when there is none.
    fn speed_study(&self, s: &mut String) -> Option<&SpeedStudy> {
        let from = &self.opts.from;
        match self.speed {
            SpeedSection::Found(study) => {
                let _ = writeln!(
                    s,
                    "From `{}`, run started {}.\n",
                    from.join(SpeedStudy::JSON).display(),
                    study.started_at
                );
                Some(study)
            }
            SpeedSection::Absent => {
                let _ = writeln!(
                    s,
                    "No speed study in `{dir}`. `persson-check speed --out {dir}` runs it \
                     (`--n N` sets its grid) and writes `speed.json` there; then run \
                     `report` again.\n",
                    dir = from.display()
                );
                None
            }
            SpeedSection::Unreadable(e) => {
                let _ = writeln!(
                    s,
                    "**The speed study in `{}` could not be read:** {}\n",
                    from.join(SpeedStudy::JSON).display(),
                    md(e)
                );
                None
            }
        }
    }

    /// The study's figures, shown, and its tables, linked.
    fn speed_files(&self, s: &mut String) {
        let dir = self.opts.from.join(SpeedStudy::FIGURES);
        for name in ["speed_error", "speed_iterations"] {
            let png = dir.join(format!("{name}.png"));
            if png.exists() {
                let _ = writeln!(s, "![{name}]({})\n", self.link_to(&png));
            }
        }
        let tables: Vec<String> = SpeedStudy::TABLES
            .iter()
            .map(|name| (name, SpeedStudy::table_path(&self.opts.from, name)))
            .filter(|(_, path)| path.exists())
            .map(|(name, path)| format!("[{name}]({})", self.link_to(&path)))
            .collect();
        if !tables.is_empty() {
            let _ = writeln!(s, "All rows, one table per study: {}.\n", tables.join(", "));
        }
    }
}

/// The scene, the reference solution, and the run's machine and time.
fn scene(s: &mut String, study: &SpeedStudy) {
    let o = &study.options;
    let r = &study.reference;
    let _ = writeln!(
        s,
        "One scene: H = {}, N = {}, lambda\\_l = N/2 = {}, lambda\\_s = {}, p0 = {}, \
         seed {}; cold solves, the fastest of {} per row. Reference: {} at tol {} \
         (residual {}, {} iterations, {}): a\\_r = {}, E = {}.\n",
        sig(o.hurst, 3),
        o.n,
        o.n / 2,
        sig(o.lambda_s, 3),
        sig(o.p0, 3),
        o.seed,
        o.repeats,
        r.solver.name(),
        sig(r.tol, 2),
        num(r.residual),
        r.iterations,
        duration(r.wall_s),
        sig(r.contact_area, 6),
        sig(r.elastic_energy, 6)
    );
    let _ = writeln!(
        s,
        "**Times are from one run on a shared machine**: {}, a pool of {} threads, \
         started {}, commit `{}`, {} in all. Ratios between rows mean more than the \
         absolute times.\n",
        md(&study.machine.summary()),
        study.threads,
        study.started_at,
        study.commit,
        duration(study.wall_s)
    );
}

/// Cold solves at each tolerance: time, iterations and the errors against the reference.
fn tolerance_table(s: &mut String, study: &SpeedStudy) {
    let header = [
        "solver",
        "tol",
        "wall time",
        "iterations",
        "residual reached",
        "tamaas error",
        "abs. a\\_r error",
        "rel. energy error",
    ];
    push_rows(s, &header, &study.tolerance, |t| {
        vec![
            t.solver.name().to_string(),
            sig(t.tol, 2),
            t.error.as_deref().map_or_else(|| time(t.wall_s), failed),
            count(t.iterations),
            or_dash(t.residual, num),
            or_dash(t.tamaas, num),
            or_dash(t.area_error, num),
            or_dash(t.energy_error, num),
        ]
    });
}

/// Iterations against the grid size, with the fitted exponent.
fn size_table(s: &mut String, study: &SpeedStudy) {
    let o = &study.options;
    let _ = writeln!(
        s,
        "**Iterations against grid size** (tol {}, lambda\\_l = N/2, lambda\\_s = {}). The \
         paper's argument for GFMD in reciprocal space: mass weighting lowers critical \
         slowing-down from O(L^2) (plain damped dynamics) to O(L^(1/2)), i.e. an exponent \
         of 1/2.\n",
        sig(o.size_tol, 2),
        sig(o.lambda_s, 3)
    );
    let grids = distinct(study.sizes.iter().map(|r| r.n));
    let mut header = solver_header(&grids, |n| format!("N = {n}"));
    header.push("exponent k (iterations ~ N^k)".into());
    let mut rows = solver_rows(&grids, |kind, n| {
        let row = study.sizes.iter().find(|r| r.solver == kind && r.n == n);
        row.map(size_cell)
    });
    for (row, kind) in rows.iter_mut().zip(SOLVERS) {
        row.push(exponent_cell(study, kind));
    }
    push_table(s, &header, &rows);
}

fn size_cell(r: &SizeRow) -> String {
    match (&r.iterations, &r.error) {
        (Some(i), _) => format!("{i} ({})", time(r.wall_s)),
        (None, Some(e)) => failed(e),
        _ => "—".into(),
    }
}

fn exponent_cell(study: &SpeedStudy, kind: SolverKind) -> String {
    match study.fits.iter().find(|f| f.solver == kind) {
        Some(f) => match (f.exponent, f.std_error) {
            (Some(k), Some(e)) => format!("{} ({} grids)", pm(k, e), f.points),
            (Some(k), None) => format!("{} ({} grids, no error bar)", sig(k, 3), f.points),
            _ => "n/a (fewer than two grids converged)".into(),
        },
        None => "—".into(),
    }
}

/// Wall time and speed-up against pools of threads.
fn thread_table(s: &mut String, study: &SpeedStudy) {
    let o = &study.options;
    let _ = writeln!(
        s,
        "**Thread scaling** (N = {}, tol {}; wall time and speed-up against one thread).\n",
        o.n,
        sig(o.size_tol, 2)
    );
    let pools = distinct(study.threads_study.iter().map(|t| t.threads));
    let header = solver_header(&pools, |k| {
        format!("{k} thread{}", if k == 1 { "" } else { "s" })
    });
    let rows = solver_rows(&pools, |kind, k| {
        let row = study
            .threads_study
            .iter()
            .find(|t| t.solver == kind && t.threads == k);
        row.map(thread_cell)
    });
    push_table(s, &header, &rows);
}

fn thread_cell(t: &ThreadRow) -> String {
    match (t.wall_s, &t.error) {
        (Some(w), _) => match t.speedup {
            Some(x) => format!("{} (× {})", duration(w), sig(x, 3)),
            None => duration(w),
        },
        (None, Some(e)) => failed(e),
        _ => "—".into(),
    }
}

/// The cost of a cold solve in FFT pairs, grid by grid.
fn floor_table(s: &mut String, study: &SpeedStudy) {
    if study.floor.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "**The floor** (tol {}): one forward + inverse 2D FFT pair bounds the cost of an \
         iteration from below. \"Pairs / iteration\" counts the transforms each solve \
         made (set-up and the final residual included); \"iteration in pairs\" is the \
         solve's wall time over (iterations × pair); \"each pair\" is its wall time over \
         (pairs used × pair), 1 meaning nothing but transforms.\n",
        sig(study.options.size_tol, 2)
    );
    let header = [
        "solver",
        "N",
        "FFT pair",
        "iterations",
        "cold solve",
        "pairs / iteration",
        "iteration in pairs",
        "each pair",
    ];
    push_rows(s, &header, &study.floor, |r| {
        vec![
            r.solver.name().to_string(),
            r.n.to_string(),
            duration(r.fft_pair_s),
            count(r.iterations),
            r.error.as_deref().map_or_else(|| time(r.wall_s), failed),
            ratio(r.pairs_per_iteration),
            ratio(r.iteration_in_pairs),
            ratio(r.overhead),
        ]
    });
}

/// Warm re-solves against cold solves of the same problem.
fn warm_table(s: &mut String, study: &SpeedStudy) {
    if study.warm.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "**Warm starts** (tol {}): a re-solve from a converged solution after a 1% load \
         change, and after adding one magnification shell (from the solution one shell \
         lower), against a cold solve of the same problem.\n",
        sig(study.options.size_tol, 2)
    );
    let header = [
        "solver",
        "N",
        "change",
        "cold (iterations)",
        "warm (iterations)",
        "warm / cold",
    ];
    push_rows(s, &header, &study.warm, |r| {
        let warm = format!("{} ({})", time(r.warm_wall_s), count(r.warm_iterations));
        vec![
            r.solver.name().to_string(),
            r.n.to_string(),
            md(&r.change),
            format!("{} ({})", time(r.cold_wall_s), count(r.cold_iterations)),
            r.error.as_deref().map_or(warm, failed),
            ratio(r.ratio),
        ]
    });
}

/// A wall time, or an em dash.
fn time(seconds: Option<f64>) -> String {
    or_dash(seconds, duration)
}

/// A count, or an em dash.
fn count(n: Option<usize>) -> String {
    or_dash(n, |i| i.to_string())
}

/// A ratio to three significant digits, or an em dash.
fn ratio(x: Option<f64>) -> String {
    or_dash(x, |x| sig(x, 3))
}

/// The distinct values, ascending.
fn distinct(values: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut v: Vec<usize> = values.collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// The header of a table with one row per solver and one column per key.
fn solver_header(keys: &[usize], label: impl Fn(usize) -> String) -> Vec<String> {
    let mut header = vec!["solver".to_string()];
    header.extend(keys.iter().map(|&k| label(k)));
    header
}

/// One row per solver: its name, then `cell(solver, key)` for each key, an em dash where
/// there is none.
fn solver_rows(
    keys: &[usize],
    cell: impl Fn(SolverKind, usize) -> Option<String>,
) -> Vec<Vec<String>> {
    SOLVERS
        .iter()
        .map(|&kind| {
            let mut row = vec![kind.name().to_string()];
            row.extend(
                keys.iter()
                    .map(|&k| cell(kind, k).unwrap_or_else(|| "—".into())),
            );
            row
        })
        .collect()
}
