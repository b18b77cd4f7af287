//! Assumption (e): a resolved mode keeps its energy as finer roughness is added. The
//! statistics are in [`super::stats`]; here the findings (details, checks, golden
//! values) and the account.

use crate::experiments::keys::{DetailKey, Tag};
use std::collections::BTreeMap;

use super::figures::{asymptote_figure, asymptote_table, curve_figures, curve_table};
use super::stats::{onset_key, AfterResolution, FrozenStats, MODE_WINDOW, PANEL_LOADS};
use super::{reference_sweeps, sweeps, ModeScene};
use crate::engine::tolerance::ZETA_SLACK;
use crate::error::{Error, Result};
use crate::experiments::climb::step_of;
use crate::experiments::declared::{value_at, DetailTable};
use crate::experiments::ensemble::{by_load, load_range};
use crate::experiments::study::{Cell, Study};
use crate::experiments::{Criteria, Experiment, Jobs, Keys, Table};
use crate::plot::Figure;
use crate::stats::{round_sig, Estimate};

/// Assumption (e): a resolved mode's energy no longer changes.
pub struct ModeFrozen;

/// The paper's `(K1, K2)` of the asymptote law, as the definition's claims `k1` and `k2`
/// state them.
fn paper_k(criteria: &Criteria) -> Option<(f64, f64)> {
    Some((criteria.paper("k1")?, criteria.paper("k2")?))
}

/// The key of the change of `E_norm` after resolution at load `load`, target `zeta_t`.
fn change_key(load: f64, zeta_t: f64) -> DetailKey {
    DetailKey::new("change")
        .at(Tag::ContactArea, load)
        .at(Tag::ZetaT, zeta_t)
}

/// The key of the asymptote of `E_norm` at load `load`, target `zeta_t`.
fn asymptote_key(load: f64, zeta_t: f64) -> DetailKey {
    DetailKey::new("asymptote")
        .at(Tag::ContactArea, load)
        .at(Tag::ZetaT, zeta_t)
}

/// The keys of the other details ([`Experiment::detail_table`]).
const ASYMPTOTE_LONG_MINUS_SHORT: &str = "asymptote_long_minus_short";
const K1: &str = "k1";
const K2: &str = "k2";
const CHANGE_FULL_CONTACT_MAX: &str = "change_full_contact_max";
const E_END_LONG_MINUS_SHORT_CD: &str = "e_end_long_minus_short_cd";
const PEAK_SHORT_PARTIAL: &str = "peak_short_partial";
const FALLOFF_MID_CHORD_ZETA: &str = "falloff_mid_chord_zeta";
const R2_X_MINUS_R2_AR: &str = "r2_x_minus_r2_ar";
/// The details of a scene with a reference surface.
const K1_MINUS_REFERENCE: &str = "k1_minus_reference";
const K2_MINUS_REFERENCE: &str = "k2_minus_reference";

/// The study of the asymptote law's readings: its key and columns, `(key, label)`.
const ASYMPTOTE_LAW: &str = "asymptote_law";
const LAW_COLUMNS: &[(&str, &str)] = &[
    ("k1", "K1"),
    ("k2", "K2"),
    ("points", "partial-contact points"),
    ("x_min", "smallest x"),
    ("x_max", "largest x"),
];

type Run<'a> = crate::experiments::Run<'a, ModeFrozen>;

impl Experiment for ModeFrozen {
    const PAPER_CLAIMS: &'static [&'static str] = &["k1", "k2"];
    type Scene = ModeScene;
    type Stats = FrozenStats;

    fn validate(scene: &ModeScene) -> Result<()> {
        scene.validate()?;
        for &t in &scene.targets {
            if scene.frozen_from * t * (1.0 + ZETA_SLACK) >= scene.zeta_end {
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

    fn stats(run: &Run) -> Result<FrozenStats> {
        let sweeps = sweeps(run.results);
        let loads = by_load(&run.scene.contact_areas, &sweeps);
        let stats = FrozenStats::of(run.scene, &loads);
        Ok(match run.scene.reference_scene() {
            Some(reference) => {
                let sweeps = reference_sweeps(run.results);
                let loads = by_load(&reference.contact_areas, &sweeps);
                stats.with_reference(&FrozenStats::of(&reference, &loads))
            }
            None => stats,
        })
    }

    fn headline(s: &FrozenStats) -> (Estimate, f64) {
        (s.headline(), 0.0)
    }

    /// The change and the asymptote of every load and target (the asymptote's label names
    /// the measured `x`, and Persson's value is the correction factor of the measured
    /// contact area), the long-minus-short difference of the asymptotes, the fitted law,
    /// the sweeps' shape, the law against the reference surface's and the onset of every
    /// load.
    fn detail_table<'s>(
        scene: &'s ModeScene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, FrozenStats> {
        let mut t = DetailTable::default();
        after_rows(&mut t, scene);
        let last = scene.targets.len() - 1;
        let (lowest, _) = load_range(&scene.contact_areas);
        t.row(
            ASYMPTOTE_LONG_MINUS_SHORT,
            format!(
                "asymptote of zeta_t = {} minus that of zeta_t = {} at a_r = {lowest} \
                 (paper: negative, long wavelengths lose more)",
                scene.targets[0], scene.targets[last]
            ),
            |s: &FrozenStats| s.long_minus_short,
        )
        .persson(0.0);
        t.row(K1, k_label("K1"), |s: &FrozenStats| s.k().map(|k| k.0));
        t.row(K2, k_label("K2"), |s: &FrozenStats| s.k().map(|k| k.1));
        sweep_rows(&mut t, scene);
        asymptote_rows(&mut t, scene);
        for &load in &scene.contact_areas {
            t.row(
                onset_key(load),
                format!(
                    "E_norm at zeta = {} zeta_t, mean over targets, then over realizations, \
                     a_r = {load} at full resolution",
                    scene.onset_ratio
                ),
                move |s: &FrozenStats| value_at(&s.onsets, load),
            )
            .persson(0.0);
        }
        t
    }

    /// The readings of the asymptote law.
    fn declare_studies(_scene: &ModeScene, keys: &mut Keys) {
        keys.study(ASYMPTOTE_LAW, LAW_COLUMNS);
    }

    /// The golden values: every change, the headline, the long-minus-short difference and the
    /// fitted law.
    fn golden(run: &Run, s: &FrozenStats) -> BTreeMap<String, f64> {
        let scene = run.scene;
        let mut golden = BTreeMap::new();
        for a in &s.after {
            let key = change_key(a.load, scene.targets[a.target]);
            golden.insert(key.to_string(), round_sig(a.change.value, 2));
        }
        golden.insert("change_headline".into(), round_sig(s.headline().value, 2));
        if let Some(d) = s.long_minus_short {
            golden.insert("asymptote_long_minus_short".into(), round_sig(d.value, 2));
        }
        if let Some((k1, k2)) = s.k() {
            golden.insert("k1".into(), round_sig(k1.value, 2));
            golden.insert("k2".into(), round_sig(k2.value, 2));
        }
        golden
    }

    /// The readings of the asymptote law: `x` over the frozen window and at the mode's
    /// own magnification, each with its fitted `(K1, K2)`.
    fn studies(run: &Run, s: &FrozenStats) -> Vec<Study> {
        let scene = run.scene;
        let mut study = Study::new(
            ASYMPTOTE_LAW,
            "Readings of the asymptote law K1 exp(-K2 x): where x = -d ln a_r / d ln zeta is taken",
            LAW_COLUMNS,
        )
        .about(
            "The same asymptotes E_inf of every partial-contact load and target, fitted \
             against x taken over two windows of the sweep; the paper does not state its \
             window",
        );
        let readings = [
            (
                "frozen_window",
                format!(
                    "x over the frozen window, zeta = {} zeta_t to {}",
                    scene.frozen_from, scene.zeta_end
                ),
                s.k(),
                &s.k_points,
            ),
            (
                "mode",
                format!(
                    "x at the mode's own magnification, zeta_t / {MODE_WINDOW} to \
                     {MODE_WINDOW} zeta_t"
                ),
                s.k_mode(),
                &s.k_mode_points,
            ),
        ];
        for (key, label, k, points) in readings {
            let xs = points.iter().map(|p| p.0);
            let (lo, hi) = (
                xs.clone().fold(f64::NAN, f64::min),
                xs.fold(f64::NAN, f64::max),
            );
            study.push(
                key,
                label,
                vec![
                    k.map(|k| k.0).into(),
                    k.map(|k| k.1).into(),
                    Cell::from(points.len() as f64),
                    Cell::from(lo),
                    Cell::from(hi),
                ],
            );
        }
        if let (Some((k1, k2)), Some(paper)) = (s.k_mode(), paper_k(run.criteria)) {
            study.notes.push(format!(
                "At the mode's own magnification K1 = {}, K2 = {} (paper {} and {}); over the \
                 frozen window the fit gives {}.",
                k1.text(1.0, 2, ""),
                k2.text(1.0, 2, ""),
                paper.0,
                paper.1,
                s.k().map_or("no fit".into(), |(a, b)| format!(
                    "K1 = {}, K2 = {}",
                    a.text(1.0, 2, ""),
                    b.text(1.0, 2, "")
                ))
            ));
        }
        vec![study]
    }

    /// The account, from the numbers.
    fn account(run: &Run, s: &FrozenStats) -> String {
        let scene = run.scene;
        let measured = s.headline();
        let fit = |k: Option<(Estimate, Estimate)>, points: usize, reading: &str| {
            k.map(|(k1, k2)| {
                format!(
                    "with x {reading}, K1 = {}, K2 = {} ({points} points)",
                    k1.text(1.0, 2, ""),
                    k2.text(1.0, 2, "")
                )
            })
        };
        let k_text = match (
            fit(s.k(), s.k_points.len(), "over the frozen window"),
            fit(
                s.k_mode(),
                s.k_mode_points.len(),
                "at the mode's own magnification (the claims' reading)",
            ),
        ) {
            (Some(window), Some(mode)) => format!(
                "A fit of the asymptotes of the partial-contact points to K1 exp(-K2 x) gives, \
                 {window}; {mode}{}.",
                match paper_k(run.criteria) {
                    Some((a, b)) => format!(" (paper, H = {}: K1 = {a}, K2 = {b})", scene.hurst),
                    None => String::new(),
                }
            ),
            _ => "too few partial-contact points to fit K1 exp(-K2 x)".to_string(),
        };
        format!(
            "{}, after a band of modes around zeta_t = {} is resolved its normalised energy \
             changes by {} between zeta = {} zeta_t and zeta = {} at the lowest load (a_r = \
             {} at full resolution), {}. {}",
            scene.base().over(),
            scene.targets[0],
            measured.text(1.0, 3, ""),
            scene.frozen_from,
            scene.zeta_end,
            s.lowest,
            measured.z_text(0.0, "Persson's frozen energy"),
            k_text,
        )
    }

    fn tables(run: &Run, s: &FrozenStats) -> Vec<Table> {
        let sweeps = sweeps(run.results);
        let loads = by_load(&run.scene.contact_areas, &sweeps);
        vec![
            curve_table(&run.criteria.name, run.scene, &loads),
            asymptote_table(run.scene, s),
        ]
    }

    fn figures(run: &Run, s: &FrozenStats) -> Vec<Figure> {
        let sweeps = sweeps(run.results);
        let loads = by_load(&run.scene.contact_areas, &sweeps);
        let mut figures = curve_figures("e_norm", run.scene, &loads);
        figures.push(asymptote_figure(run.scene, s, paper_k(run.criteria)));
        figures
    }
}

/// The label of the fitted law's constant `name` (`K1` or `K2`).
fn k_label(name: &str) -> String {
    format!(
        "{name} of the asymptote law K1 exp(-K2 x), x over the frozen window (the claims \
         read x at the mode's own magnification: study asymptote_law, row mode)"
    )
}

/// Target `t` at load `load`, if the run has it.
fn after(s: &FrozenStats, load: f64, t: usize) -> Option<&AfterResolution> {
    s.after.iter().find(|a| a.load == load && a.target == t)
}

/// The change of `E_norm` after resolution and its asymptote, of every load and target:
/// the asymptote's label names the measured `x`, Persson's value is the correction factor
/// `S` of the measured contact area at `zeta_t`.
fn after_rows(t: &mut DetailTable<'_, FrozenStats>, scene: &ModeScene) {
    let steps = scene.steps();
    let end = steps.len() - 1;
    for &load in &scene.contact_areas {
        for (target, &zt) in scene.targets.iter().enumerate() {
            let from = step_of(&steps, scene.frozen_from * zt);
            t.row(
                change_key(load, zt),
                format!(
                    "change of E_norm from zeta = {:.3} to {:.3} (zeta_t = {zt}, a_r = {load} \
                     at full resolution)",
                    steps[from], steps[end]
                ),
                move |s: &FrozenStats| after(s, load, target).map(|a| a.change),
            )
            .persson(0.0);
            t.row_labelled(asymptote_key(load, zt), move |s: &FrozenStats| {
                let a = after(s, load, target)?;
                let name = format!(
                    "asymptote of E_norm, zeta -> infinity (zeta_t = {zt}, a_r = {load}), at \
                     x = -dln a_r/dln zeta = {}",
                    a.x.text(1.0, 3, "")
                );
                Some((name, a.asymptote))
            })
            .persson_from(move |s: &FrozenStats| after(s, load, target).map(|a| a.s));
        }
    }
}

/// The sweeps' shape: the largest change near full contact, the end-of-sweep
/// long-minus-short difference of panels c and d, the peak of the shortest target and the
/// curvature of the fall-off.
fn sweep_rows(t: &mut DetailTable<'_, FrozenStats>, scene: &ModeScene) {
    let last = scene.targets.len() - 1;
    let (_, highest) = load_range(&scene.contact_areas);
    t.row(
        CHANGE_FULL_CONTACT_MAX,
        format!(
            "the change of E_norm after resolution of largest magnitude over the \
             targets at the highest load, a_r = {highest}"
        ),
        |s: &FrozenStats| s.change_full_contact_max,
    )
    .persson(0.0);
    t.row(
        E_END_LONG_MINUS_SHORT_CD,
        format!(
            "E_norm at zeta = {} of zeta_t = {} minus that of zeta_t = {}, per \
             realization, mean of the loads nearest a_r = {} and {}",
            scene.zeta_end, scene.targets[0], scene.targets[last], PANEL_LOADS[0], PANEL_LOADS[1]
        ),
        |s: &FrozenStats| s.end_long_minus_short,
    )
    .persson(0.0);
    t.row(
        PEAK_SHORT_PARTIAL,
        format!(
            "largest ensemble E_norm over the sweep of zeta_t = {}, mean over the loads in \
             partial contact at zeta_t (jackknife error)",
            scene.targets[last]
        ),
        |s: &FrozenStats| s.peak_short_partial,
    );
    t.row(
        FALLOFF_MID_CHORD_ZETA,
        format!(
            "E_norm of zeta_t = {} at the middle of zeta = {} zeta_t .. {} minus the \
             chord linear in zeta, over realizations and partial-contact loads",
            scene.targets[0], scene.frozen_from, scene.zeta_end
        ),
        |s: &FrozenStats| s.falloff_mid_chord,
    )
    .persson(0.0);
}

/// The asymptote law: which variable explains `ln E_inf` better, and its coefficients
/// against the reference surface's.
fn asymptote_rows(t: &mut DetailTable<'_, FrozenStats>, scene: &ModeScene) {
    t.row(
        R2_X_MINUS_R2_AR,
        "over the partial-contact points of the asymptote law (x at the mode's own \
         magnification): r^2 of ln E_inf with x minus r^2 of ln E_inf with ln a_r(zeta_t), \
         the shares of its variance a line in each explains (jackknife error over \
         realizations)",
        |s: &FrozenStats| s.r2_x_minus_r2_ar,
    );
    if let Some(reference) = &scene.reference {
        let label = |name: &str| {
            format!(
                "{name} of the asymptote law (x at the mode's own magnification) at \
                     H = {} minus {name} of the reference surface's law, H = {} ({} \
                     realizations at a_r = {:?}), fitted on the same grid and sweep; \
                     errors of independent surfaces combined",
                scene.hurst,
                reference.hurst,
                reference.seeds.len(),
                reference.contact_areas
            )
        };
        t.row(K1_MINUS_REFERENCE, label("K1"), |s: &FrozenStats| {
            s.k_mode_minus_reference().map(|d| d.0)
        });
        t.row(K2_MINUS_REFERENCE, label("K2"), |s: &FrozenStats| {
            s.k_mode_minus_reference().map(|d| d.1)
        });
    }
}

#[cfg(test)]
mod tests {
    use super::super::stats::asymptote;
    use super::super::tests::{shipped, synthetic};
    use super::super::ModeJob;
    use super::*;
    use crate::experiments::Jobs;

    #[test]
    fn shipped_scenes_are_valid_and_ranges_are_named() {
        let (mut scene, _) = crate::experiments::shipped_valid::<ModeFrozen>("e_frozen");
        scene.frozen_from = 1.05;
        crate::experiments::assert_refused::<ModeFrozen>(&scene, "frozen_from");
        scene.frozen_from = 5.0;
        let e = ModeFrozen::validate(&scene).unwrap_err().to_string();
        assert!(e.contains("targets") && e.contains("zeta_end"), "{e}");
    }

    #[test]
    fn new_details_follow_their_formulas() {
        use super::super::stats::{mid_chord, onset_key};
        use crate::experiments::climb::step_of;
        let (scene, _, criteria) = shipped("e_frozen");
        let (k, b, onset) = ((0.9, 1.0), 0.8, 0.05);
        let results = synthetic(&scene, k, b, onset);
        let c = ModeFrozen::conclude(&criteria, &scene, &results).unwrap();
        let value = |key: DetailKey| c.detail(key).unwrap().value.value;
        // Every band holds `onset` before resolution.
        for &a in &scene.contact_areas {
            assert!((value(onset_key(a)) - onset).abs() < 1e-12);
        }
        // The largest |change| at the highest load, among its change details.
        let highest = scene.contact_areas.iter().copied().fold(0.0, f64::max);
        let changes: Vec<f64> = scene
            .targets
            .iter()
            .map(|zt| value(change_key(highest, *zt)))
            .collect();
        let max = changes
            .iter()
            .copied()
            .fold(0.0, |m: f64, x| if x.abs() > m.abs() { x } else { m });
        assert_eq!(value("change_full_contact_max".into()), max);
        // At the end of the sweep every target holds K1 exp(-K2 x) + b / zeta_end.
        assert!(value("e_end_long_minus_short_cd".into()).abs() < 1e-12);
        // Against 1/zeta the fall-off is E + b / zeta: the chord in zeta lies above it.
        let steps = scene.steps();
        let zt = scene.targets[0];
        let (za, zb) = (scene.frozen_from * zt, scene.zeta_end);
        let zm = steps
            .iter()
            .copied()
            .min_by(|x, y| {
                (x - (za + zb) / 2.0)
                    .abs()
                    .total_cmp(&(y - (za + zb) / 2.0).abs())
            })
            .unwrap();
        let f = |z: f64| b / z;
        let expect = f(zm) - (f(za) + (f(zb) - f(za)) * (zm - za) / (zb - za));
        assert!((mid_chord(&scene, &sweeps(&results)[0].1, 0) - expect).abs() < 1e-12);
        assert!(expect < 0.0);
        // The shortest target peaks on resolution, K1 exp(-K2 x_l) + b / zeta_t, at the
        // loads in partial contact there (synthetic a_r = a_l (zeta / zeta_end)^-x_l).
        let t = scene.targets.len() - 1;
        let zt = scene.targets[t];
        let peaks: Vec<f64> = scene
            .contact_areas
            .iter()
            .enumerate()
            .map(|(l, &a)| (0.1 * (l + 1) as f64, a))
            .filter(|&(x, a)| a * (zt / scene.zeta_end).powf(-x) < 0.99)
            .map(|(x, _)| k.0 * (-k.1 * x).exp() + b / zt)
            .collect();
        assert!(!peaks.is_empty());
        let p = c.detail("peak_short_partial").unwrap().value;
        let mean = peaks.iter().sum::<f64>() / peaks.len() as f64;
        assert!((p.value - mean).abs() < 1e-12, "{p:?} vs {mean}");
        assert!(p.std_error.abs() < 1e-12);
        assert!(step_of(&steps, zt) < steps.len());
    }

    #[test]
    fn the_reference_sweeps_are_e_frozens_own_jobs() {
        // e_frozen_h03's reference surface is e_frozen's full scene: its sweeps are keyed
        // as e_frozen's, so the committed results serve both and none runs twice.
        let (_, h03, _) = shipped("e_frozen_h03");
        let (_, h08, _) = shipped("e_frozen");
        let reference = h03.reference_scene().expect("a reference at full scale");
        use crate::experiments::scene::without_planned;
        assert_eq!(
            without_planned(reference.key_scene()),
            without_planned(h08.key_scene())
        );
        // The reference shares e_frozen's committed realizations, not its planned ones.
        let mut committed = h08.clone();
        committed.more_seeds.clear();
        let own = committed.jobs();
        let shared: Vec<ModeJob> = h03
            .jobs()
            .iter()
            .filter_map(|j| {
                let (scene, job) = h03.shared_job(j)?;
                assert_eq!(without_planned(scene), without_planned(h08.key_scene()));
                Some(job)
            })
            .collect();
        assert_eq!(shared, own);
        // The H = 0.3 sweeps keep the keys they had before the reference existed.
        let mut without = h03.clone();
        without.reference = None;
        assert_eq!(h03.key_scene(), without.key_scene());
        // A reference surface out of range is named by its field.
        let mut bad = h03;
        bad.reference.as_mut().unwrap().hurst = 1.2;
        let e = ModeFrozen::validate(&bad).unwrap_err().to_string();
        assert!(e.contains("reference.hurst"), "{e}");
    }

    #[test]
    fn the_reference_law_and_the_variance_shares_follow_their_formulas() {
        let (mut scene, _, criteria) = shipped("e_frozen");
        scene.reference = Some(super::super::ReferenceSurface {
            hurst: 0.5,
            seeds: scene.seeds.clone(),
            contact_areas: scene.contact_areas.clone(),
            headline_contact_area: scene.headline_contact_area,
        });
        let (k, k_ref) = ((0.9, 1.0), (0.7, 1.4));
        let mut results = synthetic(&scene, k, 0.8, 0.0);
        let reference = synthetic(&scene.reference_scene().unwrap(), k_ref, 0.8, 0.0);
        results.extend(reference.into_iter().map(|(j, r)| match j {
            ModeJob::Sweep(j) => (ModeJob::Reference(j), r),
            j => (j, r),
        }));
        let c = ModeFrozen::conclude(&criteria, &scene, &results).unwrap();
        let d1 = c.detail("k1_minus_reference").unwrap().value;
        let d2 = c.detail("k2_minus_reference").unwrap().value;
        assert!((d1.value - (k.0 - k_ref.0)).abs() < 1e-9, "{d1:?}");
        assert!((d2.value - (k.1 - k_ref.1)).abs() < 1e-9, "{d2:?}");
        // ln E_inf is a line in x (each load's area falls as a power of zeta, so x is the
        // same at every magnification): x explains all of its variance, ln a_r(zeta_t),
        // which also varies with the target at one load, less. Identical realizations
        // leave no jackknife spread.
        let r = c.detail("r2_x_minus_r2_ar").unwrap().value;
        assert!(r.value > 0.0 && r.value < 1.0, "{r:?}");
        assert!(r.std_error.abs() < 1e-9, "{r:?}");
        let stats = ModeFrozen::stats(&crate::experiments::Run {
            criteria: &criteria,
            scene: &scene,
            results: &results,
        })
        .unwrap();
        let points: Vec<&super::super::stats::AfterResolution> = stats
            .after
            .iter()
            .filter(|a| a.asymptote.value > 0.0 && a.a_end < super::super::stats::FULL_CONTACT)
            .collect();
        let ln_e: Vec<f64> = points.iter().map(|a| a.asymptote.value.ln()).collect();
        let ln_a: Vec<f64> = points.iter().map(|a| a.a_t.ln()).collect();
        let expect = 1.0 - crate::stats::pearson(&ln_e, &ln_a).powi(2);
        assert!((r.value - expect).abs() < 1e-9, "{r:?} against {expect}");
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
        let (e_inf, _) = asymptote(&scene, &sweeps(&results)[0].1, 0).unwrap();
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
