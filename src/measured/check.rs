//! The check of one surface: its scans solved along a load curve by the headline solver
//! (and the other as a cross-check), Persson's predictions on each scan's own spectrum,
//! and a verdict for each comparison by the scorecard's rule
//! ([`crate::validation::VerdictRule`]).
//!
//! Several scans are several realizations of one surface: every comparison is made scan
//! by scan, as the ratio of the measurement to Persson's prediction, and the ratios'
//! mean and standard error over the scans decide the verdict (with one scan there is no
//! error bar and every verdict is inconclusive). The comparisons:
//!
//! * **contact area**: `a_r / a_r,P` at each load, against the original theory (the
//!   corrected one is shown beside it);
//! * **elastic energy**: `E_el / E_P` at each load;
//! * **pressure distribution**: at the middle load, the rms pressure over Persson's,
//!   `sqrt(<p^2>) / sqrt(<p^2>_P)`, with the histogram against `Pr(p)` in the figure.
//!
//! A comparison's verdict over the loads: violated when any load's is, holds when every
//! load's holds, inconclusive otherwise.

use serde::{Deserialize, Serialize};

use super::body::{solve_curve, Body, Curve};
use super::psd::{Boundary, RadialBin, ScanSpectrum};
use super::scan::Scan;
use super::theory::{loads, Predicted, Theory};
use crate::engine::solver::{Progress, SolverKind};
use crate::error::{check_positive, Error, Result};
use crate::stats::Estimate;
use crate::validation::{Verdict, VerdictRule};

/// The rule of every comparison: three standard errors, 10% of Persson's value.
pub const RULE: VerdictRule = VerdictRule {
    significance: 3.0,
    resolution: 0.1,
};

/// Solvers agree when their contact areas and energies differ by less than this, relative.
pub const SOLVER_AGREEMENT: f64 = 0.01;

/// How a surface is checked.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckOptions {
    /// Pixel size, in the heights' length unit.
    pub pixel_size: f64,
    /// Periodic scans, or measured windows with a free boundary.
    pub boundary: Boundary,
    /// Loads `p0 / E*` (none: the defaults of [`super::theory::default_areas`]).
    pub loads: Option<Vec<f64>>,
    /// The headline solver.
    pub solver: SolverKind,
    /// Also solve with the other solver.
    pub cross_check: bool,
    /// Residual tolerance of every solve.
    pub tol: f64,
}

impl Default for CheckOptions {
    fn default() -> Self {
        Self {
            pixel_size: 1.0,
            boundary: Boundary::Free,
            loads: None,
            solver: SolverKind::Gfmd,
            cross_check: true,
            tol: 1e-6,
        }
    }
}

/// A value over the scans: mean and standard error (`None` with one scan).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Mean {
    /// Mean over the scans.
    pub value: f64,
    /// Its standard error; absent with one scan.
    pub std_error: Option<f64>,
}

impl Mean {
    fn of(samples: &[f64]) -> Self {
        let e = Estimate::mean_of(samples);
        Self {
            value: e.value,
            std_error: e.has_error().then_some(e.std_error),
        }
    }

    fn estimate(&self) -> Estimate {
        Estimate::new(self.value, self.std_error.unwrap_or(f64::NAN))
    }
}

/// One load of the curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurvePoint {
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// Contact area (headline solver), mean over scans.
    pub a_r: f64,
    /// Its standard error over scans (absent with one scan).
    pub a_r_std_error: Option<f64>,
    /// Contact area by the cross-check solver.
    pub a_r_cross_check: Option<f64>,
    /// Persson's original theory.
    pub a_r_persson: f64,
    /// Persson's corrected theory.
    pub a_r_persson_corrected: f64,
    /// `a_r / a_r,P` over the scans.
    pub area_ratio: Mean,
    /// The contact-area verdict at this load.
    pub area_verdict: Verdict,
    /// Elastic energy per unit area (`E*` times the length unit).
    pub energy: f64,
    /// Its standard error over scans.
    pub energy_std_error: Option<f64>,
    /// Energy by the cross-check solver.
    pub energy_cross_check: Option<f64>,
    /// Persson's energy, original theory.
    pub energy_persson: f64,
    /// Persson's energy, corrected theory.
    pub energy_persson_corrected: f64,
    /// `E_el / E_P` over the scans.
    pub energy_ratio: Mean,
    /// The energy verdict at this load.
    pub energy_verdict: Verdict,
}

/// The pressure distribution at one load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Distribution {
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// Histogram bins: centre in `p / p0`, measured density (per unit `p / p0`, over all
    /// points, so that it integrates to `a_r`), Persson's original and corrected.
    pub bins: Vec<[f64; 4]>,
    /// Rms pressure over Persson's (original), over the scans.
    pub rms_ratio: Mean,
    /// Its verdict.
    pub verdict: Verdict,
}

/// One comparison's summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// Short name: `contact_area`, `elastic_energy`, `pressure_distribution`.
    pub name: String,
    /// What is compared.
    pub statistic: String,
    /// The verdict over its loads.
    pub verdict: Verdict,
}

/// A solver's work on the surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SolverWork {
    /// The solver.
    pub solver: SolverKind,
    /// Iterations over every load and scan.
    pub iterations: usize,
    /// The largest residual.
    pub max_residual: f64,
    /// Wall time of its curves, seconds.
    pub wall_s: f64,
}

/// The surface's statistics, means over the scans.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Statistics {
    /// Rms height (length unit), after detrending.
    pub h_rms: Mean,
    /// Rms slope from finite differences.
    pub slope_rms: Mean,
    /// Rms slope from the spectrum (Persson's `g_bar`).
    pub slope_rms_spectral: Mean,
    /// The radially averaged power spectrum, mean over scans.
    pub psd: Vec<RadialBin>,
}

/// Everything the check found: `surface.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceCheck {
    /// The scans' files.
    pub scans: Vec<String>,
    /// Points per side.
    pub n: usize,
    /// Pixel size.
    pub pixel_size: f64,
    /// The boundary.
    pub boundary: Boundary,
    /// How the spectrum was taken.
    pub spectrum_method: String,
    /// The surface's statistics.
    pub statistics: Statistics,
    /// The headline solver.
    pub solver: SolverKind,
    /// The cross-check solver, if run.
    pub cross_check: Option<SolverKind>,
    /// Whether the two solvers agree at every load (within [`SOLVER_AGREEMENT`]).
    pub solvers_agree: Option<bool>,
    /// The load curve.
    pub curve: Vec<CurvePoint>,
    /// The pressure distribution at the middle load.
    pub pressure_distribution: Distribution,
    /// The comparisons' verdicts.
    pub comparisons: Vec<Comparison>,
    /// The solvers' work.
    pub solvers: Vec<SolverWork>,
    /// Residual tolerance.
    pub tol: f64,
    /// Wall time of the check, seconds.
    pub wall_s: f64,
}

/// What one scan gave.
struct Measured {
    spectrum: ScanSpectrum,
    predicted: Vec<Predicted>,
    curves: Vec<Curve>,
}

/// Checks the surface of `scans` (one surface, several scans of it). `progress` sees the
/// scan, the solver, the load and every iteration.
pub fn check(
    scans: &[Scan],
    opts: &CheckOptions,
    progress: &mut dyn FnMut(usize, SolverKind, usize, Progress),
) -> Result<SurfaceCheck> {
    let timer = std::time::Instant::now();
    validate(scans, opts)?;
    let n = scans[0].n;
    let spectra: Vec<ScanSpectrum> = scans
        .iter()
        .map(|s| ScanSpectrum::new(&s.heights, n, opts.pixel_size, opts.boundary))
        .collect::<Result<_>>()?;
    // The loads come from the first scan's spectrum: common to every scan.
    let loads = loads(&Theory::new(&spectra[0].shells)?, opts.loads.as_deref())?;
    let kept = loads.len() / 2;
    let mut solvers = vec![opts.solver];
    if opts.cross_check {
        solvers.push(other(opts.solver));
    }
    let mut measured = Vec::with_capacity(scans.len());
    // One body for every scan: its half-space depends on the size alone.
    let mut body: Option<Body> = None;
    for (k, spectrum) in spectra.into_iter().enumerate() {
        let theory = Theory::new(&spectrum.shells)?;
        let predicted = loads.iter().map(|&p| theory.at(p)).collect::<Result<_>>()?;
        let body = match body.as_mut() {
            Some(b) => {
                b.set_heights(&spectrum)?;
                b
            }
            None => body.insert(Body::new(&spectrum, n)?),
        };
        let mut curves = Vec::new();
        for &solver in &solvers {
            let mut monitor = |i: usize, p: Progress| progress(k, solver, i, p);
            curves.push(solve_curve(
                body,
                &loads,
                solver,
                opts.tol,
                kept,
                &mut monitor,
            )?);
        }
        measured.push(Measured {
            spectrum,
            predicted,
            curves,
        });
    }
    Ok(conclude(
        scans,
        opts,
        &loads,
        kept,
        &measured,
        timer.elapsed().as_secs_f64(),
    ))
}

/// The other solver: CG for GFMD, GFMD for any other.
fn other(solver: SolverKind) -> SolverKind {
    if solver == SolverKind::Gfmd {
        SolverKind::Cg
    } else {
        SolverKind::Gfmd
    }
}

fn validate(scans: &[Scan], opts: &CheckOptions) -> Result<()> {
    check_positive("pixel_size", opts.pixel_size)?;
    crate::engine::solver::SolveOptions::with_tol(opts.tol).validate()?;
    let Some(first) = scans.first() else {
        return Err(Error::invalid(
            "heights",
            "no scan",
            "at least one height map",
        ));
    };
    for s in scans {
        if s.n != first.n {
            return Err(Error::bad_file(
                &s.source,
                format!(
                    "{} x {} points, the first scan ({}) has {} x {}: scans of one surface share \
                     their size",
                    s.n,
                    s.n,
                    first.source.display(),
                    first.n,
                    first.n
                ),
            ));
        }
    }
    Ok(())
}

/// From the scans' measurements to the check's findings.
fn conclude(
    scans: &[Scan],
    opts: &CheckOptions,
    loads: &[f64],
    kept: usize,
    measured: &[Measured],
    wall_s: f64,
) -> SurfaceCheck {
    let curve: Vec<CurvePoint> = (0..loads.len())
        .map(|i| curve_point(measured, i, opts.pixel_size))
        .collect();
    let distribution = distribution(measured, loads, kept);
    let over = |f: fn(&CurvePoint) -> Verdict| combine(curve.iter().map(f));
    let comparisons = vec![
        Comparison {
            name: "contact_area".into(),
            statistic: "a_r / a_r,Persson at each load (original theory)".into(),
            verdict: over(|c| c.area_verdict),
        },
        Comparison {
            name: "elastic_energy".into(),
            statistic: "E_el / E_Persson at each load (original theory)".into(),
            verdict: over(|c| c.energy_verdict),
        },
        Comparison {
            name: "pressure_distribution".into(),
            statistic: format!(
                "rms pressure over Persson's at p0 = {:.4e} E*",
                distribution.p0
            ),
            verdict: distribution.verdict,
        },
    ];
    let solvers_agree = opts.cross_check.then(|| {
        measured.iter().all(|m| {
            m.curves[0]
                .points
                .iter()
                .zip(&m.curves[1].points)
                .all(|(a, b)| {
                    relative(a.contact_area, b.contact_area) <= SOLVER_AGREEMENT
                        && relative(a.energy, b.energy) <= SOLVER_AGREEMENT
                })
        })
    });
    let solvers = (0..measured[0].curves.len())
        .map(|k| SolverWork {
            solver: measured[0].curves[k].solver,
            iterations: measured
                .iter()
                .flat_map(|m| &m.curves[k].points)
                .map(|s| s.iterations)
                .sum(),
            max_residual: measured
                .iter()
                .flat_map(|m| &m.curves[k].points)
                .map(|s| s.residual)
                .fold(0.0, f64::max),
            wall_s: measured.iter().map(|m| m.curves[k].wall_s).sum(),
        })
        .collect();
    SurfaceCheck {
        scans: scans
            .iter()
            .map(|s| s.source.display().to_string())
            .collect(),
        n: scans[0].n,
        pixel_size: opts.pixel_size,
        boundary: opts.boundary,
        spectrum_method: spectrum_method(opts.boundary),
        statistics: statistics(measured),
        solver: opts.solver,
        cross_check: opts.cross_check.then(|| other(opts.solver)),
        solvers_agree,
        curve,
        pressure_distribution: distribution,
        comparisons,
        solvers,
        tol: opts.tol,
        wall_s,
    }
}

/// `|a - b| / max(|a|, |b|)`, 0 when both are 0.
fn relative(a: f64, b: f64) -> f64 {
    let scale = a.abs().max(b.abs());
    if scale > 0.0 {
        (a - b).abs() / scale
    } else {
        0.0
    }
}

/// Violated when any is, holds when all hold, inconclusive otherwise.
fn combine(verdicts: impl Iterator<Item = Verdict>) -> Verdict {
    let mut all_hold = true;
    for v in verdicts {
        match v {
            Verdict::Violated => return Verdict::Violated,
            Verdict::Inconclusive => all_hold = false,
            Verdict::Holds => {}
        }
    }
    if all_hold {
        Verdict::Holds
    } else {
        Verdict::Inconclusive
    }
}

fn spectrum_method(boundary: Boundary) -> String {
    match boundary {
        Boundary::Periodic => "periodic scan: mean removed, no window".into(),
        Boundary::Free => "non-periodic scan: least-squares plane removed, separable Hann \
                           window (scaled to keep the mean square); contact solved on the \
                           detrended heights with a free boundary"
            .into(),
    }
}

/// The mean over scans of `f`.
fn mean_over(measured: &[Measured], f: impl Fn(&Measured) -> f64) -> Mean {
    Mean::of(&measured.iter().map(f).collect::<Vec<_>>())
}

/// Load `i` of the curve; energies converted from pixels to the length unit (`pixel`).
fn curve_point(measured: &[Measured], i: usize, pixel: f64) -> CurvePoint {
    fn head(m: &Measured, i: usize) -> &super::body::Solved {
        &m.curves[0].points[i]
    }
    fn cross(m: &Measured, i: usize) -> Option<&super::body::Solved> {
        m.curves.get(1).map(|c| &c.points[i])
    }
    let area = mean_over(measured, |m| head(m, i).contact_area);
    let area_ratio = mean_over(measured, |m| {
        head(m, i).contact_area / m.predicted[i].contact_area
    });
    let energy_ratio = mean_over(measured, |m| head(m, i).energy / m.predicted[i].energy);
    let energy = mean_over(measured, |m| head(m, i).energy);
    let cross_mean = |f: fn(&super::body::Solved) -> f64| -> Option<f64> {
        let v: Option<Vec<f64>> = measured.iter().map(|m| cross(m, i).map(f)).collect();
        v.map(|v| v.iter().sum::<f64>() / v.len() as f64)
    };
    let persson = |f: fn(&Predicted) -> f64| mean_over(measured, |m| f(&m.predicted[i])).value;
    CurvePoint {
        p0: measured[0].predicted[i].p0,
        a_r: area.value,
        a_r_std_error: area.std_error,
        a_r_cross_check: cross_mean(|s| s.contact_area),
        a_r_persson: persson(|p| p.contact_area),
        a_r_persson_corrected: persson(|p| p.contact_area_corrected),
        area_ratio,
        area_verdict: RULE.judge(area_ratio.estimate(), 1.0),
        energy: pixel * energy.value,
        energy_std_error: energy.std_error.map(|e| pixel * e),
        energy_cross_check: cross_mean(|s| s.energy).map(|e| pixel * e),
        energy_persson: pixel * persson(|p| p.energy),
        energy_persson_corrected: pixel * persson(|p| p.energy_corrected),
        energy_ratio,
        energy_verdict: RULE.judge(energy_ratio.estimate(), 1.0),
    }
}

/// Histogram bins of `p / p0` in the distribution figure.
const HISTOGRAM_BINS: usize = 40;

fn distribution(measured: &[Measured], loads: &[f64], kept: usize) -> Distribution {
    let p0 = loads[kept];
    let all: Vec<&[f64]> = measured
        .iter()
        .map(|m| &m.curves[0].pressures[..])
        .collect();
    let top = all
        .iter()
        .flat_map(|p| p.iter())
        .copied()
        .fold(0.0, f64::max)
        .max(1.0);
    let width = top / HISTOGRAM_BINS as f64;
    let total: usize = all.iter().map(|p| p.len()).sum();
    let mut counts = vec![0usize; HISTOGRAM_BINS];
    for &x in all.iter().flat_map(|p| p.iter()) {
        if x > 0.0 {
            counts[((x / width) as usize).min(HISTOGRAM_BINS - 1)] += 1;
        }
    }
    let original = |x: f64| {
        mean_over(measured, |m| {
            m.predicted[kept].distribution.density(x * p0) * p0
        })
        .value
    };
    let corrected = |x: f64| {
        mean_over(measured, |m| {
            m.predicted[kept].distribution_corrected.density(x * p0) * p0
        })
        .value
    };
    let bins = counts
        .iter()
        .enumerate()
        .map(|(b, &c)| {
            let x = (b as f64 + 0.5) * width;
            [
                x,
                c as f64 / (total as f64 * width),
                original(x),
                corrected(x),
            ]
        })
        .collect();
    let rms_ratio = mean_over(measured, |m| {
        let p = &m.curves[0].pressures;
        let rms = (p.iter().map(|x| x * x).sum::<f64>() / p.len() as f64).sqrt();
        let persson = m.predicted[kept].distribution.second_moment().sqrt() / p0;
        rms / persson
    });
    Distribution {
        p0,
        bins,
        verdict: RULE.judge(rms_ratio.estimate(), 1.0),
        rms_ratio,
    }
}

fn statistics(measured: &[Measured]) -> Statistics {
    let bins = measured[0].spectrum.radial.len();
    let psd = (0..bins)
        .map(|b| {
            let at = |m: &Measured| m.spectrum.radial.get(b).map_or(f64::NAN, |r| r.c);
            RadialBin {
                q: measured[0].spectrum.radial[b].q,
                c: mean_over(measured, at).value,
                modes: measured[0].spectrum.radial[b].modes,
            }
        })
        .collect();
    Statistics {
        h_rms: mean_over(measured, |m| m.spectrum.h_rms),
        slope_rms: mean_over(measured, |m| m.spectrum.slope_rms),
        slope_rms_spectral: mean_over(measured, |m| m.spectrum.slope_rms_spectral),
        psd,
    }
}
