//! The speed-against-error study as the scorecard shows it.

use std::fmt::Write as _;

use super::format::{duration, md, num, pm, sig, table};
use super::{Scorecard, SpeedSection};
use crate::speed::{SpeedStudy, SOLVERS};

impl Scorecard<'_> {
    pub(super) fn speed_section(&self, s: &mut String) {
        let _ = writeln!(s, "## Speed against error\n");
        let study = match self.speed {
            SpeedSection::Fresh(study) => study,
            SpeedSection::Earlier(study) => {
                let _ = writeln!(
                    s,
                    "**Not run for this scorecard** (`--no-speed`); shown from an earlier run \
                     started {} (`{}`).\n",
                    study.started_at,
                    self.opts.from.join(SpeedStudy::JSON).display()
                );
                study
            }
            SpeedSection::Skipped => {
                let _ = writeln!(s, "Not run (`--no-speed`), and no earlier study found.\n");
                return;
            }
            SpeedSection::Failed(e) => {
                let _ = writeln!(s, "**The speed study failed:** {}\n", md(e));
                return;
            }
        };
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
        let opt_num = |v: Option<f64>| v.map_or_else(|| "—".into(), num);
        let rows: Vec<Vec<String>> = study
            .tolerance
            .iter()
            .map(|t| {
                let mut row = vec![
                    t.solver.name().to_string(),
                    sig(t.tol, 2),
                    t.wall_s.map_or_else(|| "—".into(), duration),
                    t.iterations.map_or_else(|| "—".into(), |i| i.to_string()),
                    opt_num(t.residual),
                    opt_num(t.tamaas),
                    opt_num(t.area_error),
                    opt_num(t.energy_error),
                ];
                if let Some(e) = &t.error {
                    row[2] = format!("**failed**: {}", md(e));
                }
                row
            })
            .collect();
        s.push_str(&table(
            &[
                "solver",
                "tol",
                "wall time",
                "iterations",
                "residual reached",
                "tamaas error",
                "abs. a\\_r error",
                "rel. energy error",
            ],
            &rows,
        ));
        s.push('\n');

        let grids: Vec<usize> = {
            let mut g: Vec<usize> = study.sizes.iter().map(|r| r.n).collect();
            g.sort_unstable();
            g.dedup();
            g
        };
        let _ = writeln!(
            s,
            "**Iterations against grid size** (tol {}, lambda\\_l = N/2, lambda\\_s = {}). The \
             paper's argument for GFMD in reciprocal space: mass weighting lowers critical \
             slowing-down from O(L^2) (plain damped dynamics) to O(L^(1/2)), i.e. an exponent \
             of 1/2.\n",
            sig(o.size_tol, 2),
            sig(o.lambda_s, 3)
        );
        let mut header: Vec<String> = vec!["solver".into()];
        header.extend(grids.iter().map(|n| format!("N = {n}")));
        header.push("exponent k (iterations ~ N^k)".into());
        let rows: Vec<Vec<String>> = SOLVERS
            .iter()
            .map(|&kind| {
                let mut row = vec![kind.name().to_string()];
                for n in &grids {
                    let cell = study
                        .sizes
                        .iter()
                        .find(|r| r.solver == kind && r.n == *n)
                        .map(|r| match (&r.iterations, &r.error) {
                            (Some(i), _) => {
                                format!("{i} ({})", r.wall_s.map_or_else(|| "—".into(), duration))
                            }
                            (None, Some(e)) => format!("**failed**: {}", md(e)),
                            _ => "—".into(),
                        })
                        .unwrap_or_else(|| "—".into());
                    row.push(cell);
                }
                let fit = study.fits.iter().find(|f| f.solver == kind);
                row.push(match fit {
                    Some(f) => match (f.exponent, f.std_error) {
                        (Some(k), Some(e)) => format!("{} ({} grids)", pm(k, e), f.points),
                        (Some(k), None) => {
                            format!("{} ({} grids, no error bar)", sig(k, 3), f.points)
                        }
                        _ => "n/a (fewer than two grids converged)".into(),
                    },
                    None => "—".into(),
                });
                row
            })
            .collect();
        let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
        s.push_str(&table(&header_refs, &rows));
        s.push('\n');

        let pools: Vec<usize> = {
            let mut p: Vec<usize> = study.threads_study.iter().map(|t| t.threads).collect();
            p.sort_unstable();
            p.dedup();
            p
        };
        let _ = writeln!(
            s,
            "**Thread scaling** (N = {}, tol {}; wall time and speed-up against one thread).\n",
            o.n,
            sig(o.size_tol, 2)
        );
        let mut header: Vec<String> = vec!["solver".into()];
        header.extend(
            pools
                .iter()
                .map(|k| format!("{k} thread{}", if *k == 1 { "" } else { "s" })),
        );
        let rows: Vec<Vec<String>> = SOLVERS
            .iter()
            .map(|&kind| {
                let mut row = vec![kind.name().to_string()];
                for k in &pools {
                    let cell = study
                        .threads_study
                        .iter()
                        .find(|t| t.solver == kind && t.threads == *k)
                        .map(|t| match (t.wall_s, &t.error) {
                            (Some(w), _) => match t.speedup {
                                Some(x) => format!("{} (× {})", duration(w), sig(x, 3)),
                                None => duration(w),
                            },
                            (None, Some(e)) => format!("**failed**: {}", md(e)),
                            _ => "—".into(),
                        })
                        .unwrap_or_else(|| "—".into());
                    row.push(cell);
                }
                row
            })
            .collect();
        let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
        s.push_str(&table(&header_refs, &rows));
        s.push('\n');

        self.floor_table(s, study);
        self.warm_table(s, study);

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

    /// The cost of a cold solve in FFT pairs, grid by grid.
    fn floor_table(&self, s: &mut String, study: &SpeedStudy) {
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
        let rows: Vec<Vec<String>> = study
            .floor
            .iter()
            .map(|r| {
                let opt = |v: Option<f64>| v.map_or_else(|| "—".into(), |x| sig(x, 3));
                let mut row = vec![
                    r.solver.name().to_string(),
                    r.n.to_string(),
                    duration(r.fft_pair_s),
                    r.iterations.map_or_else(|| "—".into(), |i| i.to_string()),
                    r.wall_s.map_or_else(|| "—".into(), duration),
                    opt(r.pairs_per_iteration),
                    opt(r.iteration_in_pairs),
                    opt(r.overhead),
                ];
                if let Some(e) = &r.error {
                    row[4] = format!("**failed**: {}", md(e));
                }
                row
            })
            .collect();
        s.push_str(&table(
            &[
                "solver",
                "N",
                "FFT pair",
                "iterations",
                "cold solve",
                "pairs / iteration",
                "iteration in pairs",
                "each pair",
            ],
            &rows,
        ));
        s.push('\n');
    }

    /// Warm re-solves against cold solves of the same problem.
    fn warm_table(&self, s: &mut String, study: &SpeedStudy) {
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
        let rows: Vec<Vec<String>> = study
            .warm
            .iter()
            .map(|r| {
                let it = |v: Option<usize>| v.map_or_else(|| "—".into(), |i| i.to_string());
                let t = |v: Option<f64>| v.map_or_else(|| "—".into(), duration);
                let mut row = vec![
                    r.solver.name().to_string(),
                    r.n.to_string(),
                    md(&r.change),
                    format!("{} ({})", t(r.cold_wall_s), it(r.cold_iterations)),
                    format!("{} ({})", t(r.warm_wall_s), it(r.warm_iterations)),
                    r.ratio.map_or_else(|| "—".into(), |x| sig(x, 3)),
                ];
                if let Some(e) = &r.error {
                    row[4] = format!("**failed**: {}", md(e));
                }
                row
            })
            .collect();
        s.push_str(&table(
            &[
                "solver",
                "N",
                "change",
                "cold (iterations)",
                "warm (iterations)",
                "warm / cold",
            ],
            &rows,
        ));
        s.push('\n');
    }
}
