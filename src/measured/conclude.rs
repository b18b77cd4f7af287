//! From the scans' measurements to the check's findings ([`SurfaceCheck`], `surface.json`):
//! measurements: the load curve at the loads every scan's headline solve reached,
//! Persson's predictions on each scan's own spectrum beside it, a verdict for each
//! comparison by the scorecard's rule ([`RULE`], [`crate::validation::VerdictRule`]), the
//! surface's statistics and warnings ([`super::warnings`]), the solves that failed with
//! their solver, load and message, and the solvers' work.
//!
//! Several scans are several realizations of one surface: every comparison is made scan
//! by scan, as the ratio of the measurement to Persson's prediction, and the ratios'
//! mean and standard error over the scans ([`Estimate::mean_of`]) decide the verdict
//! (with one scan there is no error bar and every verdict is inconclusive). The
//! comparisons:
//!
//! * **contact area**: `a_r / a_r,P` at each load, against the original theory (the
//!   corrected one is shown beside it);
//! * **elastic energy**: `E_el / E_P` at each load;
//! * **pressure distribution**: at the middle load, the rms pressure over Persson's,
//!   `sqrt(<p^2>) / sqrt(<p^2>_P)`, with the histogram ([`crate::stats::Histogram`])
//!   against `Pr(p)` in the figure.
//!
//! A comparison's verdict over the loads is the conjunction of the loads' verdicts
//! ([`Decision::all`]): violated when any load's is, holds when every load's holds,
//! inconclusive otherwise, and inconclusive with no load at all.

use super::body::{Curve, Solved};
use super::findings::{
    Comparison, CurvePoint, Cutoffs, Distribution, Failure, SolverWork, Statistics, SurfaceCheck,
    RULE, SOLVER_AGREEMENT,
};
use super::options::{other, CheckOptions};
use super::pixel::PixelEstimate;
use super::psd::{Boundary, RadialBin, ScanSpectrum};
use super::reentry::Reentry;
use super::scan::Scan;
use super::theory::Predicted;
use super::warnings::{self, Warning};
use crate::stats::{Bins, Decision, Estimate, Histogram};
use crate::validation::Verdict;

/// What one scan gave.
pub(super) struct Measured {
    pub(super) outliers: super::spikes::Outliers,
    pub(super) spectrum: ScanSpectrum,
    pub(super) predicted: Vec<Predicted>,
    pub(super) curves: Vec<Curve>,
    /// The headline solver's curves on the coarsened scan, `(factor, curve)`, finest
    /// first ([`super::pixel`]; empty when not asked for or the scan is too small).
    pub(super) pixel: Vec<(usize, Curve)>,
    /// The scan's short-wavelength cutoff and its spectrum as measured, where it was cut
    /// ([`super::cutoff`]; `spectrum` is then the filtered heights').
    pub(super) cut: Option<(super::cutoff::Cutoff, ScanSpectrum)>,
    pub(super) reentry: Option<Reentry>,
}

/// From the scans' measurements to the check's findings.
pub(super) fn conclude(
    scans: &[Scan],
    opts: &CheckOptions,
    pixel: f64,
    loads: &[f64],
    measured: &[Measured],
    wall_s: f64,
) -> SurfaceCheck {
    // The loads every scan's headline solve reached.
    let reached: Vec<usize> = (0..loads.len())
        .filter(|&i| measured.iter().all(|m| m.curves[0].solved(i).is_some()))
        .collect();
    let curve: Vec<CurvePoint> = reached
        .iter()
        .map(|&i| curve_point(measured, i, pixel, opts.modulus))
        .collect();
    let distribution = reached
        .get(reached.len() / 2)
        .map(|&i| distribution(measured, loads[i], i));
    let comparisons = comparisons(&curve, distribution.as_ref());
    let solvers_agree = opts
        .cross_check
        .then(|| solvers_agree(measured, loads.len()));
    let solvers = solver_work(measured);
    let failures = failures(scans, measured);
    let statistics = statistics(measured);
    let points = scans[0].shape.rows * scans[0].shape.cols;
    // A floor the cutoff removed from every scan no longer speaks for the contact.
    let floor_cut = measured.iter().all(|m| {
        m.cut
            .as_ref()
            .is_some_and(|c| matches!(c.0.reason, super::cutoff::Reason::NoiseFloor { .. }))
    });
    let warnings = warnings(
        &statistics,
        &curve,
        (opts.loads.is_none(), floor_cut),
        points,
    );
    let reentry = measured[0].reentry.clone();
    SurfaceCheck {
        scans: scans
            .iter()
            .map(|s| s.source.display().to_string())
            .collect(),
        rows: scans[0].shape.rows,
        cols: scans[0].shape.cols,
        pixel_size: pixel,
        pixel_sides: opts.pixel_size,
        unit: opts.unit.clone(),
        modulus: opts.modulus,
        boundary: opts.boundary,
        fill: opts.fill,
        filled: scans.iter().map(|s| s.filled).collect(),
        spectrum_method: spectrum_method(opts.boundary),
        statistics,
        cutoff: Cutoffs {
            asked: opts.cutoff,
            tip_radius: opts.tip_radius,
            scans: measured
                .iter()
                .map(|m| m.cut.as_ref().map(|c| c.0))
                .collect(),
            slope_rms_spectral: Some(mean_over(measured, |m| m.spectrum.slope_rms_spectral)),
        },
        warnings,
        solver: opts.solver,
        cross_check: opts.cross_check.then(|| other(opts.solver)),
        solvers_agree,
        loads: loads.to_vec(),
        curve,
        failures,
        pressure_distribution: distribution,
        reentry,
        comparisons,
        solvers,
        tol: opts.tol,
        max_iterations: opts.max_iterations,
        despike: opts.despike,
        outliers: measured.iter().map(|m| m.outliers.clone()).collect(),
        wall_s,
    }
}

/// The comparisons of the page's verdicts: the contact area and the energy over the
/// loads, and the pressure distribution at the middle load.
fn comparisons(curve: &[CurvePoint], distribution: Option<&Distribution>) -> Vec<Comparison> {
    let over = |f: fn(&CurvePoint) -> Verdict| over_loads(curve.iter().map(f));
    let mut comparisons = vec![
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
    ];
    if let Some(d) = distribution {
        comparisons.push(Comparison {
            name: "pressure_distribution".into(),
            statistic: format!(
                "rms pressure over Persson's at p0 = {} E*",
                super::units::eng(d.p0)
            ),
            verdict: d.verdict,
        });
    }
    comparisons
}

/// Whether the two solvers agree within [`SOLVER_AGREEMENT`] on the contact area and the
/// energy at every load both solved, on every scan.
fn solvers_agree(measured: &[Measured], loads: usize) -> bool {
    measured.iter().all(|m| {
        (0..loads).all(|i| match (m.curves[0].solved(i), m.curves[1].solved(i)) {
            (Some(a), Some(b)) => {
                relative(a.contact_area, b.contact_area) <= SOLVER_AGREEMENT
                    && relative(a.energy, b.energy) <= SOLVER_AGREEMENT
            }
            _ => true,
        })
    })
}

/// Each solver's work over every scan: iterations, largest residual, failed loads and
/// wall time.
fn solver_work(measured: &[Measured]) -> Vec<SolverWork> {
    (0..measured[0].curves.len())
        .map(|k| {
            let solved = || {
                measured
                    .iter()
                    .flat_map(|m| m.curves[k].points.iter().filter_map(|o| o.as_ref().ok()))
            };
            SolverWork {
                solver: measured[0].curves[k].solver,
                iterations: solved().map(|s| s.iterations).sum(),
                max_residual: solved().map(|s| s.residual).fold(0.0, f64::max),
                failed: measured
                    .iter()
                    .map(|m| m.curves[k].points.iter().filter(|o| o.is_err()).count())
                    .sum(),
                wall_s: measured.iter().map(|m| m.curves[k].wall_s).sum(),
            }
        })
        .collect()
}

/// Every failed solve, with its scan and whether it was the headline solver's.
fn failures(scans: &[Scan], measured: &[Measured]) -> Vec<Failure> {
    scans
        .iter()
        .zip(measured)
        .flat_map(|(scan, m)| {
            m.curves.iter().enumerate().flat_map(move |(k, c)| {
                c.points.iter().filter_map(move |o| {
                    o.as_ref().err().map(|f| Failure {
                        scan: scan.source.display().to_string(),
                        solver: f.solver,
                        headline: k == 0,
                        p0: f.p0,
                        message: f.message.clone(),
                        wall_s: f.wall_s,
                        state: f.state,
                    })
                })
            })
        })
        .collect()
}

/// The warnings of [`warnings::LIMITS`] that the surface's statistics and the curve
/// cross (the contact-area range only at the default loads, the noise floor only where
/// no cutoff removed it from every scan); `points` is a scan's number of grid points.
fn warnings(
    st: &Statistics,
    curve: &[CurvePoint],
    (default_loads, floor_cut): (bool, bool),
    points: usize,
) -> Vec<Warning> {
    let areas = || curve.iter().map(|c| c.a_r);
    let mut found = vec![
        warnings::ANISOTROPY.check(st.anisotropy.value),
        st.high_q_slope
            .filter(|_| !floor_cut)
            .and_then(|s| warnings::NOISE_FLOOR.check(s.value)),
        warnings::SKEWNESS.check(st.skewness.value),
        warnings::KURTOSIS.check(st.kurtosis.value),
        warnings::RMS_SLOPE.check(st.slope_rms.value),
    ];
    if default_loads && !curve.is_empty() {
        found.push(warnings::AREA_LOW.check(areas().fold(f64::INFINITY, f64::min)));
        found.push(warnings::AREA_HIGH.check(areas().fold(0.0, f64::max)));
    }
    let pressure = curve.iter().map(|c| c.contact_pressure).fold(0.0, f64::max);
    found.push(warnings::CONTACT_PRESSURE.check(pressure));
    let loads: Vec<(f64, f64)> = curve.iter().map(|c| (c.p0, c.a_r)).collect();
    found.push(resolution(&loads, points));
    found.into_iter().flatten().collect()
}

/// The [`warnings::RESOLUTION`] warning of a curve of `(p0, a_r)` on a scan of `points`
/// grid points: the fewest points in contact, and the loads where they are too few.
fn resolution(curve: &[(f64, f64)], points: usize) -> Option<Warning> {
    let in_contact = |a_r: f64| a_r * points as f64;
    let fewest = curve
        .iter()
        .map(|&(_, a_r)| in_contact(a_r))
        .fold(f64::INFINITY, f64::min);
    let mut w = warnings::RESOLUTION.check(fewest)?;
    let loads: Vec<String> = curve
        .iter()
        .filter(|&&(_, a_r)| warnings::RESOLUTION.crossed(in_contact(a_r)))
        .map(|&(p0, a_r)| {
            let n = in_contact(a_r);
            format!("{} ({n:.0} of {points} points)", super::units::eng(p0))
        })
        .collect();
    w.message = format!("{}; at p0/E* = {}", w.message, loads.join(", "));
    Some(w)
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

/// A comparison's verdict over its loads: the conjunction of theirs by
/// [`Decision::all`] (violated when any is violated, else inconclusive when any is
/// inconclusive, else holds), except that a comparison of no load at all is inconclusive:
/// nothing was measured, where [`Decision::all`] of nothing passes.
fn over_loads(verdicts: impl Iterator<Item = Verdict>) -> Verdict {
    let decisions: Vec<Decision> = verdicts
        .map(|v| match v {
            Verdict::Holds => Decision::Passed,
            Verdict::Violated => Decision::Failed,
            Verdict::Inconclusive => Decision::Undecided,
        })
        .collect();
    if decisions.is_empty() {
        return Verdict::Inconclusive;
    }
    match Decision::all(decisions) {
        Decision::Passed => Verdict::Holds,
        Decision::Failed => Verdict::Violated,
        Decision::Undecided => Verdict::Inconclusive,
    }
}

fn spectrum_method(boundary: Boundary) -> String {
    match boundary {
        Boundary::Periodic => "periodic scan: mean removed, no window".into(),
        Boundary::Free => "non-periodic scan: least-squares plane removed, separable Hann \
                           window (scaled to keep the mean square), physical wavevectors \
                           along each side; contact solved on the detrended heights with a \
                           free boundary"
            .into(),
    }
}

/// The mean over scans of `f`.
fn mean_over(measured: &[Measured], f: impl Fn(&Measured) -> f64) -> Estimate {
    Estimate::mean_of(&measured.iter().map(f).collect::<Vec<_>>())
}

/// The standard error of `e`, `None` without an error bar (one scan).
fn error(e: Estimate) -> Option<f64> {
    e.has_error().then_some(e.std_error)
}

/// Load `i` of the curve, which every scan's headline solve reached; energies converted
/// from pixels to the length unit (`pixel`), the load to pascals with `modulus`.
fn curve_point(measured: &[Measured], i: usize, pixel: f64, modulus: Option<f64>) -> CurvePoint {
    let head = |m: &Measured| -> Solved { m.curves[0].solved(i).expect("reached").clone() };
    let area = mean_over(measured, |m| head(m).contact_area);
    // Each scan's pixel estimate at this load, where every scan has one.
    let estimates: Option<Vec<PixelEstimate>> = measured
        .iter()
        .map(|m| pixel_estimate(m, i, head(m).contact_area))
        .collect();
    // The theory is set against the contact area extrapolated to a vanishing pixel where
    // there is one.
    let area_ratio = Estimate::mean_of(
        &measured
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let a_r = estimates
                    .as_ref()
                    .map_or(head(m).contact_area, |e| e[k].extrapolated);
                a_r / m.predicted[i].contact_area
            })
            .collect::<Vec<_>>(),
    );
    let energy_ratio = mean_over(measured, |m| head(m).energy / m.predicted[i].energy);
    let energy = mean_over(measured, |m| head(m).energy);
    let cross_mean = |f: fn(&Solved) -> f64| -> Option<f64> {
        let v: Option<Vec<f64>> = measured
            .iter()
            .map(|m| m.curves.get(1).and_then(|c| c.solved(i)).map(f))
            .collect();
        v.map(|v| v.iter().sum::<f64>() / v.len() as f64)
    };
    let persson = |f: fn(&Predicted) -> f64| mean_over(measured, |m| f(&m.predicted[i])).value;
    let p0 = measured[0].predicted[i].p0;
    let contact_pressure = if area.value > 0.0 {
        p0 / area.value
    } else {
        f64::INFINITY
    };
    CurvePoint {
        p0,
        p0_pa: modulus.map(|e| p0 * e),
        a_r: area.value,
        a_r_std_error: error(area),
        a_r_cross_check: cross_mean(|s| s.contact_area),
        a_r_persson: persson(|p| p.contact_area),
        a_r_persson_corrected: persson(|p| p.contact_area_corrected),
        pixel: estimates.as_deref().and_then(PixelEstimate::mean),
        area_ratio,
        area_verdict: RULE.judge(area_ratio, 1.0),
        contact_pressure,
        past_yield: warnings::CONTACT_PRESSURE.crossed(contact_pressure),
        energy: pixel * energy.value,
        energy_std_error: error(energy).map(|e| pixel * e),
        energy_cross_check: cross_mean(|s| s.energy).map(|e| pixel * e),
        energy_persson: pixel * persson(|p| p.energy),
        energy_persson_corrected: pixel * persson(|p| p.energy_corrected),
        energy_ratio,
        energy_verdict: RULE.judge(energy_ratio, 1.0),
    }
}

/// One scan's pixel estimate at load `i` from its contact area `fine` there and its
/// coarse curves' (the levels up to the first coarse solve that failed at the load);
/// `None` without a coarse level.
fn pixel_estimate(m: &Measured, i: usize, fine: f64) -> Option<PixelEstimate> {
    let levels: Vec<(usize, f64)> = m
        .pixel
        .iter()
        .map_while(|(f, c)| c.solved(i).map(|s| (*f, s.contact_area)))
        .collect();
    let shortest = super::pixel::shortest_wavelength(&m.spectrum.shells);
    PixelEstimate::of_levels(fine, &levels, shortest)
}

/// Histogram bins of `p / p0` in the distribution figure.
const HISTOGRAM_BINS: usize = 40;

/// The pressure distribution at load `kept` (`p0`), which every scan's headline reached.
fn distribution(measured: &[Measured], p0: f64, kept: usize) -> Distribution {
    let all: Vec<&[f32]> = measured
        .iter()
        .map(|m| m.curves[0].pressures[kept].as_deref().expect("reached"))
        .collect();
    let top = all
        .iter()
        .flat_map(|p| p.iter())
        .map(|&x| f64::from(x))
        .fold(0.0, f64::max)
        .max(1.0);
    let mut histogram = Histogram::new(Bins::linear(
        0.0,
        top / HISTOGRAM_BINS as f64,
        HISTOGRAM_BINS,
    ));
    let total: usize = all.iter().map(|p| p.len()).sum();
    for x in all.iter().flat_map(|p| p.iter()).map(|&x| f64::from(x)) {
        if x > 0.0 {
            histogram.count(x);
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
    let bins = histogram
        .density(total)
        .into_iter()
        .enumerate()
        .map(|(b, density)| {
            let x = histogram.bins().centre(b);
            [x, density, original(x), corrected(x)]
        })
        .collect();
    let rms_ratio = mean_over(measured, |m| {
        let p = m.curves[0].pressures[kept].as_deref().expect("reached");
        let rms = (p.iter().map(|&x| f64::from(x).powi(2)).sum::<f64>() / p.len() as f64).sqrt();
        let persson = m.predicted[kept].distribution.second_moment().sqrt() / p0;
        rms / persson
    });
    Distribution {
        p0,
        bins,
        verdict: RULE.judge(rms_ratio, 1.0),
        rms_ratio,
    }
}

/// The scans' statistics as measured (before any cutoff: the data's own description,
/// whose warnings are about the data).
fn statistics(measured: &[Measured]) -> Statistics {
    fn of(m: &Measured) -> &ScanSpectrum {
        m.cut.as_ref().map_or(&m.spectrum, |c| &c.1)
    }
    let first = of(&measured[0]);
    let bins = first.radial.len();
    let psd = (0..bins)
        .map(|b| {
            let at = |m: &Measured| of(m).radial.get(b).map_or(f64::NAN, |r| r.c);
            RadialBin {
                q: first.radial[b].q,
                c: mean_over(measured, at).value,
                modes: first.radial[b].modes,
            }
        })
        .collect();
    let slopes: Option<Vec<f64>> = measured.iter().map(|m| of(m).high_q_slope).collect();
    Statistics {
        h_rms: mean_over(measured, |m| of(m).h_rms),
        slope_rms: mean_over(measured, |m| of(m).slope_rms),
        slope_rms_spectral: mean_over(measured, |m| of(m).slope_rms_spectral),
        skewness: mean_over(measured, |m| of(m).skewness),
        kurtosis: mean_over(measured, |m| of(m).kurtosis),
        anisotropy: mean_over(measured, |m| of(m).anisotropy),
        high_q_slope: slopes.map(|s| Estimate::mean_of(&s)),
        psd,
    }
}

#[cfg(test)]
mod tests {
    use super::super::body::{solve_curve, Body};
    use super::super::curves::check;
    use super::super::psd::Shape;
    use super::super::theory::Theory;
    use super::*;
    use crate::engine::solver::SolverKind;
    use crate::engine::surface::{Surface, SurfaceModel};
    use std::time::Duration;

    /// A 32^2 window checked by hand: the headline's second load and the cross-check's
    /// first are stopped at once (a time budget of zero), the rest solved.
    #[test]
    fn a_failed_solve_is_listed_by_solver_and_load_and_costs_only_its_own_load() {
        let n = 32;
        let s = Surface::generate(&SurfaceModel::new(n, 0.8, n as f64, 4.0, 3)).unwrap();
        let fft = crate::engine::fft::Fft2::new(s.grid());
        let heights = s.heights_at(f64::INFINITY, &fft);
        let shape = Shape { rows: n, cols: n };
        let scan = Scan {
            shape,
            heights: heights.clone(),
            source: "window.npy".into(),
            filled: 0,
        };
        let spectrum = ScanSpectrum::new(&heights, shape, 1.0, Boundary::Free).unwrap();
        let theory = Theory::new(&spectrum.shells).unwrap();
        let loads = [0.02, 0.05, 0.1];
        let predicted = loads.iter().map(|&p| theory.at(p).unwrap()).collect();
        let body = Body::new(&spectrum).unwrap();
        let zero = Some(Duration::ZERO);
        let curve = |solver, budget: &[Option<Duration>]| {
            solve_curve(
                &body,
                &loads,
                solver,
                crate::engine::solver::SolveOptions::with_tol(1e-6),
                budget,
                &mut |_, _| {},
                &mut |_, _| std::ops::ControlFlow::Continue(()),
            )
            .unwrap()
        };
        let head = curve(SolverKind::Cg, &[None, zero, None]);
        let cross = curve(SolverKind::Gfmd, &[zero, None, None]);
        let measured = [Measured {
            outliers: crate::measured::spikes::Outliers::of(&spectrum.heights),
            spectrum,
            predicted,
            curves: vec![head, cross],
            pixel: Vec::new(),
            cut: None,
            reentry: None,
        }];
        let opts = CheckOptions::default();
        let c = conclude(&[scan], &opts, 1.0, &loads, &measured, 0.0);
        // The curve keeps the loads the headline reached, cross-checked where it was.
        let kept: Vec<f64> = c.curve.iter().map(|p| p.p0).collect();
        assert_eq!(kept, [0.02, 0.1]);
        assert!(c.curve[0].a_r_cross_check.is_none() && c.curve[1].a_r_cross_check.is_some());
        assert_eq!(c.solvers_agree, Some(true));
        let listed: Vec<(SolverKind, bool, f64)> = c
            .failures
            .iter()
            .map(|f| (f.solver, f.headline, f.p0))
            .collect();
        assert_eq!(
            listed,
            [
                (SolverKind::Cg, true, 0.05),
                (SolverKind::Gfmd, false, 0.02)
            ]
        );
        let failed: Vec<usize> = c.solvers.iter().map(|w| w.failed).collect();
        assert_eq!(failed, [1, 1]);
        // Each message names its solver and load, and no flag.
        let text = &c.failures[0].message;
        assert!(
            text.starts_with("cg at p0 = 5.000e-2 E* (load 2 of 3)"),
            "{text}"
        );
        assert!(c.failures.iter().all(|f| !f.message.contains("--")));
        // The page lists both.
        let md = super::super::page::markdown(&c);
        assert!(
            md.contains("## Solves that failed") && md.contains("gfmd (cross-check)"),
            "{md}"
        );
    }

    #[test]
    fn a_comparison_holds_when_every_load_holds_and_is_inconclusive_without_loads() {
        use Verdict::*;
        let over = |v: &[Verdict]| over_loads(v.iter().copied());
        assert_eq!(over(&[Holds, Holds]), Holds);
        assert_eq!(over(&[Holds, Inconclusive]), Inconclusive);
        assert_eq!(over(&[Inconclusive, Violated, Holds]), Violated);
        assert_eq!(over(&[]), Inconclusive);
    }

    /// The `rows x cols` corner of a generated 64^2 surface (H = 0.8), scaled to an rms
    /// slope of about `slope`.
    fn window(rows: usize, cols: usize, slope: f64) -> Vec<f64> {
        let s = Surface::generate(&SurfaceModel::new(64, 0.8, 32.0, 4.0, 5)).unwrap();
        let fft = crate::engine::fft::Fft2::new(s.grid());
        let full = s.heights_at(f64::INFINITY, &fft);
        let h: Vec<f64> = (0..rows * cols)
            .map(|k| full[(k / cols) * 64 + k % cols])
            .collect();
        let g = ScanSpectrum::new(&h, Shape { rows, cols }, 1.0, Boundary::Free)
            .unwrap()
            .slope_rms;
        h.iter().map(|v| v * slope / g).collect()
    }

    fn warned(heights: Vec<f64>, rows: usize, cols: usize) -> Vec<(String, f64, f64)> {
        let scan = Scan {
            shape: Shape { rows, cols },
            heights,
            source: "scan.npy".into(),
            filled: 0,
        };
        // The data's warnings as they are: no cutoff (which removes a noise floor).
        let opts = CheckOptions {
            cross_check: false,
            reentry: false,
            cutoff: false,
            ..CheckOptions::default()
        };
        let c = check(&[scan], &opts, &mut |_| std::ops::ControlFlow::Continue(())).unwrap();
        for w in &c.warnings {
            assert!(
                w.message.contains(&super::super::units::eng(w.value)),
                "{}",
                w.message
            );
        }
        // A 48 x 56 window holds few contact points at the lowest default loads: its
        // resolution warning depends on the slope and is tested apart, below.
        c.warnings
            .iter()
            .filter(|w| w.name != "resolution")
            .map(|w| (w.name.clone(), w.value, w.threshold))
            .collect()
    }

    #[test]
    fn warnings_name_the_statistic_that_crosses_its_threshold() {
        let (rows, cols) = (48, 56);
        let names = |w: &[(String, f64, f64)]| -> Vec<String> {
            w.iter().map(|(n, _, _)| n.clone()).collect()
        };
        // A self-affine window of moderate slope lies inside every threshold.
        assert_eq!(warned(window(rows, cols, 0.1), rows, cols), []);
        // Stripes across the rows: a lay.
        let striped: Vec<f64> = window(rows, cols, 0.02)
            .iter()
            .enumerate()
            .map(|(k, v)| v + 0.5 * (0.9 * (k / cols) as f64).sin())
            .collect();
        let w = warned(striped, rows, cols);
        assert_eq!(names(&w), ["anisotropy"]);
        assert!(
            w[0].1 < 0.2 && w[0].2 == warnings::ANISOTROPY.threshold,
            "{w:?}"
        );
        // White noise over the roughness: the spectrum's high-q end flattens.
        let mut x = 7u64;
        let noisy: Vec<f64> = window(rows, cols, 0.05)
            .iter()
            .map(|v| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                v + 0.3 * ((x >> 11) as f64 / 2f64.powi(53) - 0.5)
            })
            .collect();
        let w = warned(noisy.clone(), rows, cols);
        assert!(names(&w).contains(&"noise_floor".to_string()), "{w:?}");
        // With the cutoff (the default) the floor is cut off, and no longer warned of.
        let scan = Scan {
            shape: Shape { rows, cols },
            heights: noisy,
            source: "noisy.npy".into(),
            filled: 0,
        };
        let opts = CheckOptions {
            cross_check: false,
            reentry: false,
            extrapolate: false,
            ..CheckOptions::default()
        };
        let c = check(&[scan], &opts, &mut |_| std::ops::ControlFlow::Continue(())).unwrap();
        let cut = c.cutoff.scans[0].expect("a noise floor");
        assert!(matches!(
            cut.reason,
            crate::measured::cutoff::Reason::NoiseFloor { .. }
        ));
        assert!(c.warnings.iter().all(|w| w.name != "noise_floor"));
        // Particles on a nearly flat window: far from Gaussian heights, and the load
        // carried by their tips.
        let mut dotted = window(rows, cols, 0.01);
        for k in [300, 1111, 2000] {
            dotted[k] += 3.0;
        }
        let w = names(&warned(dotted, rows, cols));
        for name in ["skewness", "kurtosis", "contact_pressure"] {
            assert!(w.contains(&name.to_string()), "{name}: {w:?}");
        }
        // Steep: beyond small slopes, and past yield at the top default load.
        let w = names(&warned(window(rows, cols, 1.0), rows, cols));
        assert_eq!(w, ["rms_slope", "contact_pressure"]);
    }

    /// A 64^2 scan with 58 points in contact at the lowest load warns, naming that load
    /// and not the higher one; a 256^2 scan at the same areas does not.
    #[test]
    fn too_few_contact_points_warn_of_the_resolution_at_their_loads() {
        let curve = [(4.9e-3, 58.0 / 4096.0), (0.1, 0.2)];
        let w = resolution(&curve, 64 * 64).unwrap();
        assert_eq!((w.name.as_str(), w.value), ("resolution", 58.0));
        assert!(w.message.contains("(58 of 4096 points)"), "{}", w.message);
        assert!(!w.message.contains("819"), "{}", w.message);
        assert_eq!(resolution(&curve, 256 * 256), None);
        assert_eq!(resolution(&[], 64 * 64), None);
    }
}
