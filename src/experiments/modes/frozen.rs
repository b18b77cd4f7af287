//! Assumption (e): a resolved mode keeps its energy as finer roughness is added.

use super::{curve_figures, curve_table, z_text, ModeEnsemble, ModeResult, ModeScene};
use crate::error::{Error, Result};
use crate::experiments::climb::step_of;
use crate::experiments::ensemble::{by_load, group, load_range, SeedLoad};
use crate::experiments::{
    max_residual, Check, Conclusion, Criteria, Detail, Experiment, Jobs, Table,
};
use crate::plot::{Axis, Figure, Series, Style};
use crate::stats::{round_sig, Estimate, LineFit};

/// The paper's asymptote law `K1 exp(-K2 x)` for `H = 0.8`: `(K1, K2)`.
pub const PAPER_K_H08: (f64, f64) = (0.9, 1.0);
/// The paper's asymptote law `K1 exp(-K2 x)` for `H = 0.3`: `(K1, K2)`.
pub const PAPER_K_H03: (f64, f64) = (0.7, 1.4);

/// Per-realization asymptote `E_inf` (intercept of `E_norm` against `1/zeta`) and
/// `x = -d ln a_r / d ln zeta` over the frozen window of target `t`.
pub fn asymptote(scene: &ModeScene, run: &ModeResult, t: usize) -> Option<(f64, f64)> {
    let zt = scene.targets[t];
    let from = step_of(&run.zetas, scene.frozen_from * zt);
    let e = run.e_norm(t, zt);
    let inv: Vec<f64> = run.zetas[from..].iter().map(|z| 1.0 / z).collect();
    let fit = LineFit::fit(&inv, &e[from..])?;
    let ln_z: Vec<f64> = run.zetas[from..].iter().map(|z| z.ln()).collect();
    let ln_a: Vec<f64> = run.contact_area[from..].iter().map(|a| a.ln()).collect();
    let slope = LineFit::fit(&ln_z, &ln_a)?;
    Some((fit.intercept.value, -slope.slope.value))
}

/// Assumption (e): a resolved mode's energy no longer changes.
pub struct ModeFrozen;

impl Experiment for ModeFrozen {
    type Scene = ModeScene;

    fn validate(scene: &ModeScene) -> Result<()> {
        scene.validate()?;
        for &t in &scene.targets {
            if scene.frozen_from * t * (1.0 + 1e-12) >= scene.zeta_end {
                return Err(Error::invalid(
                    "targets",
                    t,
                    format!(
                        "a magnification with frozen_from * zeta_t < zeta_end = {} (a frozen \
                         window after resolution)",
                        scene.zeta_end
                    ),
                ));
            }
        }
        Ok(())
    }

    fn conclude(
        criteria: &Criteria,
        scene: &ModeScene,
        results: &[(SeedLoad, ModeResult)],
    ) -> Result<Conclusion> {
        let steps = scene.steps();
        let end = steps.len() - 1;
        let loads = by_load(&scene.contact_areas, results);
        let mut c = Conclusion {
            persson: 0.0,
            max_residual: max_residual(results, |r| r.max_residual),
            ..Default::default()
        };
        let from_of = |zt: f64| step_of(&steps, scene.frozen_from * zt);
        // Changes after resolution, asymptotes and contact-area slopes.
        let mut k_points = Vec::new();
        let mut asym_table = Table::new(
            "asymptotes",
            &[
                "contact_area_full",
                "zeta_t",
                "change",
                "change_std_error",
                "asymptote",
                "asymptote_std_error",
                "x",
                "x_std_error",
            ],
        );
        let mut changes = Vec::new();
        for load in &loads {
            for (t, &zt) in scene.targets.iter().enumerate() {
                let k0 = from_of(zt);
                let change = load.change(t, zt, k0, end);
                let fits: Vec<(f64, f64)> = load
                    .runs
                    .iter()
                    .filter_map(|r| asymptote(scene, r, t))
                    .collect();
                let e_inf = Estimate::mean_of(&fits.iter().map(|f| f.0).collect::<Vec<_>>());
                let x = Estimate::mean_of(&fits.iter().map(|f| f.1).collect::<Vec<_>>());
                let s = scene
                    .correction
                    .factor(load.contact_area_at(step_of(&steps, zt)).value);
                asym_table.push(vec![
                    load.contact_area,
                    zt,
                    change.value,
                    change.std_error,
                    e_inf.value,
                    e_inf.std_error,
                    x.value,
                    x.std_error,
                ]);
                c.details.push(Detail {
                    key: format!("change_ar{}_zt{zt}", load.contact_area),
                    name: format!(
                        "change of E_norm from zeta = {:.3} to {:.3} (zeta_t = {zt}, a_r = {} at \
                         full resolution)",
                        steps[k0], steps[end], load.contact_area
                    ),
                    value: change,
                    persson: Some(0.0),
                    paper: None,
                    grid: None,
                });
                c.details.push(Detail {
                    key: format!("asymptote_ar{}_zt{zt}", load.contact_area),
                    name: format!(
                        "asymptote of E_norm, zeta -> infinity (zeta_t = {zt}, a_r = {}), at \
                         x = -dln a_r/dln zeta = {:.3} +- {:.3}",
                        load.contact_area, x.value, x.std_error
                    ),
                    value: e_inf,
                    persson: Some(s),
                    paper: None,
                    grid: None,
                });
                c.golden.insert(
                    format!("change_ar{}_zt{zt}", load.contact_area),
                    round_sig(change.value, 2),
                );
                // Full contact (x ~ 0, a_r ~ 1) is left out of the fit, as in the paper.
                let a_end = load.contact_area_at(end).value;
                if e_inf.value > 0.0 && a_end < 0.99 {
                    k_points.push((x.value, e_inf.value.ln()));
                }
                changes.push((load.contact_area, t, change));
            }
        }
        // Headline: the longest-wavelength target at the lowest load.
        let (lowest, highest) = load_range(&scene.contact_areas);
        let pick = |a: f64, t: usize| {
            changes
                .iter()
                .find(|(ca, tt, _)| *ca == a && *tt == t)
                .expect("every load and target")
                .2
        };
        let measured = pick(lowest, 0);
        c.measured = Some(measured);
        c.golden
            .insert("change_headline".into(), round_sig(measured.value, 2));

        // The paper: the reduction is stronger for long than for short wavelengths.
        if scene.targets.len() > 1 {
            let last = scene.targets.len() - 1;
            let low_load = group(&loads, lowest);
            let diffs: Vec<f64> = low_load
                .runs
                .iter()
                .filter_map(|r| Some(asymptote(scene, r, 0)?.0 - asymptote(scene, r, last)?.0))
                .collect();
            let d = Estimate::mean_of(&diffs);
            c.details.push(Detail {
                key: "asymptote_long_minus_short".into(),
                name: format!(
                    "asymptote of zeta_t = {} minus that of zeta_t = {} at a_r = {lowest} \
                     (paper: negative, long wavelengths lose more)",
                    scene.targets[0], scene.targets[last]
                ),
                value: d,
                persson: Some(0.0),
                paper: None,
                grid: None,
            });
            c.golden
                .insert("asymptote_long_minus_short".into(), round_sig(d.value, 2));
        }

        // The paper's law for the asymptote.
        let paper_k = if (scene.hurst - 0.8).abs() < 0.05 {
            Some(PAPER_K_H08)
        } else if (scene.hurst - 0.3).abs() < 0.05 {
            Some(PAPER_K_H03)
        } else {
            None
        };
        let xs: Vec<f64> = k_points.iter().map(|p| p.0).collect();
        let ys: Vec<f64> = k_points.iter().map(|p| p.1).collect();
        let k_fit = LineFit::fit(&xs, &ys);
        let mut k_text = String::from("too few partial-contact points to fit K1 exp(-K2 x)");
        if let Some(f) = k_fit {
            let k1 = Estimate::new(
                f.intercept.value.exp(),
                f.intercept.std_error * f.intercept.value.exp(),
            );
            let k2 = Estimate::new(-f.slope.value, f.slope.std_error);
            c.details.push(Detail {
                key: "k1".into(),
                name: "K1 of the asymptote law K1 exp(-K2 x)".into(),
                value: k1,
                persson: None,
                paper: paper_k.map(|k| k.0),
                grid: None,
            });
            c.details.push(Detail {
                key: "k2".into(),
                name: "K2 of the asymptote law K1 exp(-K2 x)".into(),
                value: k2,
                persson: None,
                paper: paper_k.map(|k| k.1),
                grid: None,
            });
            c.golden.insert("k1".into(), round_sig(k1.value, 2));
            c.golden.insert("k2".into(), round_sig(k2.value, 2));
            k_text = format!(
                "A fit of the asymptotes to K1 exp(-K2 x) over {} partial-contact points gives \
                 K1 = {:.2} +- {:.2}, K2 = {:.2} +- {:.2}{}.",
                k_points.len(),
                k1.value,
                k1.std_error,
                k2.value,
                k2.std_error,
                match paper_k {
                    Some((a, b)) => format!(" (paper, H = {}: K1 = {a}, K2 = {b})", scene.hurst),
                    None => String::new(),
                }
            );
            c.checks.push(Check {
                decided: true,
                key: "k2_positive".into(),
                name: "the asymptote falls as the contact area shrinks faster (K2 > 0)".into(),
                passed: k2.value > 0.0,
                detail: format!("K2 = {:.3} +- {:.3}", k2.value, k2.std_error),
            });
        }

        // The paper: long wavelengths recede at low load; near full contact the mode is
        // frozen (Persson's assumption nearly holds).
        let low = pick(lowest, 0);
        c.checks.push(Check {
            decided: true,
            key: "long_wavelengths_recede".into(),
            name: "long-wavelength energy recedes after resolution at the lowest load".into(),
            passed: low.value < 0.0 && -low.value > criteria.significance * low.std_error,
            detail: format!(
                "change {:.3} +- {:.3} at a_r = {lowest}, zeta_t = {}",
                low.value, low.std_error, scene.targets[0]
            ),
        });
        if highest > lowest {
            let high = pick(highest, 0);
            c.checks.push(Check {
                decided: true,
                key: "smaller_near_full_contact".into(),
                name: "the change is smaller near full contact than at the lowest load".into(),
                passed: high.value.abs() < low.value.abs(),
                detail: format!(
                    "|change| {:.3} at a_r = {highest} against {:.3} at a_r = {lowest}",
                    high.value.abs(),
                    low.value.abs()
                ),
            });
        }
        c.account = format!(
            "Over {} realizations (H = {}, {}x{} grid, lambda_l = {}, lambda_s = {}), after a \
             band of modes around zeta_t = {} is resolved its normalised energy changes by \
             {:.3} +- {:.3} between zeta = {} zeta_t and zeta = {} at the lowest load \
             (a_r = {lowest} at full resolution), z = {} against Persson's frozen energy. {}",
            scene.seeds.len(),
            scene.hurst,
            scene.n,
            scene.n,
            scene.lambda_l,
            scene.lambda_s,
            scene.targets[0],
            measured.value,
            measured.std_error,
            scene.frozen_from,
            scene.zeta_end,
            z_text(measured, 0.0),
            k_text,
        );
        c.tables.push(curve_table(&criteria.name, scene, &loads));
        c.tables.push(asym_table);
        c.figures = curve_figures("e_norm", scene, &loads);
        let mut fig = Figure {
            name: "asymptote".into(),
            title: format!(
                "Asymptote of E_norm against x = -dln a_r / dln zeta, H = {}",
                scene.hurst
            ),
            x: Axis::linear("x = -d ln a_r / d ln zeta"),
            y: Axis::linear("asymptotic E_norm"),
            y2: None,
            series: vec![Series::xy(
                "simulation (partial contact)",
                Style::Points,
                k_points.iter().map(|&(x, y)| (x, y.exp())),
            )],
        };
        let x_hi = xs.iter().copied().fold(0.5, f64::max) * 1.1;
        let grid: Vec<f64> = (0..=40).map(|i| x_hi * i as f64 / 40.0).collect();
        if let Some(f) = k_fit {
            fig.series.push(Series::xy(
                "fit K1 exp(-K2 x)",
                Style::Line,
                grid.iter().map(|&x| (x, f.at(x).exp())),
            ));
        }
        if let Some((k1, k2)) = paper_k {
            fig.series.push(Series::xy(
                format!("paper, {k1} exp(-{k2} x)"),
                Style::Dashed,
                grid.iter().map(|&x| (x, k1 * (-k2 * x).exp())),
            ));
        }
        c.figures.push(fig);
        Ok(c)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{shipped, synthetic};
    use super::*;

    #[test]
    fn shipped_scenes_are_valid_and_ranges_are_named() {
        let (reduced, full, _) = shipped("e_frozen");
        ModeFrozen::validate(&reduced).unwrap();
        ModeFrozen::validate(&full).unwrap();
        let mut scene = reduced;
        scene.frozen_from = 1.05;
        let e = ModeFrozen::validate(&scene).unwrap_err().to_string();
        assert!(e.contains("frozen_from"), "{e}");
        scene.frozen_from = 5.0;
        let e = ModeFrozen::validate(&scene).unwrap_err().to_string();
        assert!(e.contains("targets") && e.contains("zeta_end"), "{e}");
    }

    #[test]
    fn frozen_statistics_recover_a_known_asymptote_law() {
        let (scene, _, criteria) = shipped("e_frozen");
        let (k, b) = ((0.9, 1.0), 0.8);
        let results = synthetic(&scene, k, b, 0.0);
        let c = ModeFrozen::conclude(&criteria, &scene, &results).unwrap();
        // Headline: first target, lowest load, from frozen_from zeta_t to zeta_end.
        let zt = scene.targets[0];
        let expect = b / scene.zeta_end - b / (scene.frozen_from * zt);
        let m = c.measured.unwrap();
        assert!((m.value - expect).abs() < 1e-12, "{m:?} vs {expect}");
        let k1 = c.detail("k1").unwrap();
        let k2 = c.detail("k2").unwrap();
        assert!((k1.value.value - k.0).abs() < 1e-9, "{k1:?}");
        assert!((k2.value.value - k.1).abs() < 1e-9, "{k2:?}");
        // The asymptote of each run is the intercept against 1/zeta: K1 exp(-K2 x).
        let (e_inf, _) = asymptote(&scene, &results[0].1, 0).unwrap();
        assert!(
            (e_inf - k.0 * (-k.1 * 0.1f64).exp()).abs() < 1e-9,
            "{e_inf}"
        );
        // The figure of each load carries the contact area on the right axis.
        let fig = &c.figures[0];
        assert!(fig.y2.is_some());
        assert!(fig
            .series
            .iter()
            .any(|s| s.side == crate::plot::Side::Right));
    }
}
