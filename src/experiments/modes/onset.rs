//! Assumption (d): a mode holds energy only once its roughness is resolved. Statistics,
//! then findings (details, checks, golden values), then the account.

use crate::experiments::keys::{DetailKey, Tag};
use std::collections::BTreeMap;

use super::figures::{curve_figures, curve_table};
use super::stats::{ensemble_peak_shift, golden, mean_onset, Load, ModeEnsemble, PARTIAL};
use super::{narrow_sweeps, sweeps, ModeScene};
use crate::error::Result;
use crate::experiments::climb::step_of;
use crate::experiments::declared::DetailTable;
use crate::experiments::ensemble::{by_load, group, load_range};
use crate::experiments::{Criteria, Experiment, Table};
use crate::plot::Figure;
use crate::stats::{round_sig, Estimate};

/// Assumption (d): a mode holds no energy before it is resolved.
pub struct ModeOnset;

/// A band at its onset point (`onset_ratio zeta_t`) at one load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Onset {
    /// The load, as the contact area at full resolution.
    pub load: f64,
    /// The target's index.
    pub target: usize,
    /// The step of the onset point.
    pub step: usize,
    /// `E_norm` there.
    pub e_norm: Estimate,
    /// The measured contact area there.
    pub contact_area: Estimate,
}

/// Where the narrow bands peak, against the scene's bands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NarrowPeak {
    /// The narrow bands' relative half-width.
    pub band: f64,
    /// Their `zeta_peak / zeta_t`, as [`OnsetStats::peak`].
    pub peak: Estimate,
    /// The scene's bands' ratio minus the narrow bands', band by band: the same
    /// realizations, loads and solves (the band changes what is recorded, not the
    /// climb), so the differences pair up one to one.
    pub shift: Estimate,
    /// The same shift read from the ensemble curves' peaks, interpolated between steps
    /// ([`ensemble_peak_shift`]); `None` when the sweeps do not pair up.
    pub ensemble_shift: Option<Estimate>,
}

/// The statistics of assumption (d).
#[derive(Debug, Clone)]
pub struct OnsetStats {
    /// Per realization the mean over targets at the headline load, over realizations.
    pub headline: Estimate,
    /// Every load and target at its onset point, loads outermost.
    pub onsets: Vec<Onset>,
    /// The lowest load.
    pub lowest: f64,
    /// The highest load.
    pub highest: f64,
    /// Where the bands peak: the magnification of a band's largest `E_norm` over its
    /// `zeta_t`, over bands, realizations and the loads still in partial contact at
    /// `zeta_t` (measured `a_r` below [`PARTIAL`]).
    pub peak: Estimate,
    /// The same with the narrow bands, where the scene runs them.
    pub narrow: Option<NarrowPeak>,
}

/// `zeta_peak / zeta_t` of every band of every realization at the loads in partial contact.
pub fn peak_ratios(scene: &ModeScene, loads: &[Load]) -> Vec<f64> {
    let steps = scene.steps();
    let mut ratios = Vec::new();
    for load in loads {
        for (t, &zt) in scene.targets.iter().enumerate() {
            if load.contact_area_at(step_of(&steps, zt)).value >= PARTIAL {
                continue;
            }
            for r in &load.runs {
                let e = r.e_norm(t, zt);
                let k = (0..e.len())
                    .max_by(|&a, &b| e[a].total_cmp(&e[b]))
                    .expect("a sweep has steps");
                ratios.push(r.zetas[k] / zt);
            }
        }
    }
    ratios
}

impl OnsetStats {
    /// The statistics of the loads' sweeps.
    pub fn of(scene: &ModeScene, loads: &[Load]) -> Self {
        let steps = scene.steps();
        let onset = |load: &Load, t: usize| {
            let zt = scene.targets[t];
            let step = step_of(&steps, scene.onset_ratio * zt);
            Onset {
                load: load.contact_area,
                target: t,
                step,
                e_norm: load.e_norm(t, zt, step),
                contact_area: load.contact_area_at(step),
            }
        };
        let (lowest, highest) = load_range(&scene.contact_areas);
        Self {
            headline: group(loads, scene.headline_contact_area).mean(|r| mean_onset(scene, r)),
            onsets: loads
                .iter()
                .flat_map(|load| (0..scene.targets.len()).map(move |t| onset(load, t)))
                .collect(),
            lowest,
            highest,
            peak: Estimate::mean_of(&peak_ratios(scene, loads)),
            narrow: None,
        }
    }

    /// Target `t` at load `load`.
    pub fn at(&self, load: f64, t: usize) -> &Onset {
        self.onsets
            .iter()
            .find(|o| o.load == load && o.target == t)
            .expect("every load and target")
    }

    /// The onsets of every target at the highest and at the lowest load.
    fn extremes(&self, targets: usize) -> impl Iterator<Item = (&Onset, &Onset)> + '_ {
        (0..targets).map(move |t| (self.at(self.highest, t), self.at(self.lowest, t)))
    }
}

/// The key of the onset detail of load `load` on the band of target `zeta_t`.
fn onset_at_key(load: f64, zeta_t: f64) -> DetailKey {
    super::stats::onset_key(load).at(Tag::ZetaT, zeta_t)
}

/// The key of the detail of where the bands peak.
const PEAK_OVER_ZETA_T: &str = "peak_over_zeta_t";
/// The key of where the narrow bands peak.
const PEAK_NARROW_BAND: &str = "peak_over_zeta_t_narrow";
/// The key of the peak's shift that the band's width makes: the scene's bands' peak
/// minus the narrow bands'.
const PEAK_BAND_SHIFT: &str = "peak_band_shift";
/// The key of that shift read from the peaks of the ensemble curves.
const PEAK_BAND_SHIFT_ENSEMBLE: &str = "peak_band_shift_ensemble";

type Run<'a> = crate::experiments::Run<'a, ModeOnset>;

impl Experiment for ModeOnset {
    type Scene = ModeScene;
    type Stats = OnsetStats;

    fn stats(run: &Run) -> Result<OnsetStats> {
        let sweeps = sweeps(run.results);
        let loads = by_load(&run.scene.contact_areas, &sweeps);
        let mut stats = OnsetStats::of(run.scene, &loads);
        let narrow = narrow_sweeps(run.results);
        if let (Some(band), false) = (run.scene.narrow_band, narrow.is_empty()) {
            let narrow_loads = by_load(&run.scene.contact_areas, &narrow);
            let ratios = peak_ratios(&run.scene.with_band(band), &narrow_loads);
            let wide = peak_ratios(run.scene, &loads);
            let shift = if wide.len() == ratios.len() {
                let d: Vec<f64> = wide.iter().zip(&ratios).map(|(w, n)| w - n).collect();
                Estimate::mean_of(&d)
            } else {
                // Not the same bands (a partial run): compared as independent.
                Estimate::difference(stats.peak, Estimate::mean_of(&ratios))
            };
            stats.narrow = Some(NarrowPeak {
                band,
                peak: Estimate::mean_of(&ratios),
                shift,
                ensemble_shift: ensemble_peak_shift(run.scene, &loads, &narrow_loads),
            });
        }
        Ok(stats)
    }

    fn headline(s: &OnsetStats) -> (Estimate, f64) {
        (s.headline, 0.0)
    }

    /// `E_norm` at the onset point of every load and target (its label names the contact
    /// area measured there), and where the bands peak, with the narrow bands where the
    /// scene runs them.
    fn detail_table<'s>(
        scene: &'s ModeScene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, OnsetStats> {
        let mut t = DetailTable::default();
        let steps = scene.steps();
        for &load in &scene.contact_areas {
            for (target, &zt) in scene.targets.iter().enumerate() {
                let zeta = steps[step_of(&steps, scene.onset_ratio * zt)];
                t.row_labelled(onset_at_key(load, zt), move |s: &OnsetStats| {
                    let o = s
                        .onsets
                        .iter()
                        .find(|o| o.load == load && o.target == target)?;
                    let name = format!(
                        "E_norm at zeta = {zeta:.3} (zeta_t = {zt}), a_r = {load} at full \
                         resolution ({:.3} measured at that zeta)",
                        o.contact_area.value
                    );
                    Some((name, o.e_norm))
                })
                .persson(0.0);
            }
        }
        t.always(
            PEAK_OVER_ZETA_T,
            format!(
                "magnification of a band's largest E_norm over its zeta_t (mean over bands, \
                 realizations and loads with a_r < {PARTIAL} at zeta_t; the sweep ends at \
                 zeta = {})",
                scene.zeta_end
            ),
            |s: &OnsetStats| s.peak,
        )
        .persson(1.0);
        if let Some(band) = scene.narrow_band {
            t.row(
                PEAK_NARROW_BAND,
                format!(
                    "as peak_over_zeta_t with bands of |q/q_t - 1| <= {band} (the same \
                     realizations and loads, swept again)"
                ),
                |s: &OnsetStats| s.narrow.map(|n| n.peak),
            )
            .persson(1.0);
            t.row(
                PEAK_BAND_SHIFT,
                format!(
                    "peak_over_zeta_t with bands of +-{} minus with bands of +-{band}, \
                     band by band (the same solves)",
                    scene.band
                ),
                |s: &OnsetStats| s.narrow.map(|n| n.shift),
            )
            .persson(0.0);
            t.row(
                PEAK_BAND_SHIFT_ENSEMBLE,
                format!(
                    "as peak_band_shift, read from the ensemble E_norm curve of each band and \
                     load (ratio of sums over realizations), its peak interpolated between \
                     steps by a parabola in ln zeta; mean over the bands and loads with \
                     a_r < {PARTIAL} at zeta_t, error by jackknife over realizations"
                ),
                |s: &OnsetStats| s.narrow.and_then(|n| n.ensemble_shift),
            )
            .persson(0.0);
        }
        t
    }

    /// The golden values: the headline and every onset.
    fn golden(run: &Run, s: &OnsetStats) -> BTreeMap<String, f64> {
        let scene = run.scene;
        let mut golden_values =
            BTreeMap::from([("onset_headline".to_string(), round_sig(s.headline.value, 2))]);
        for o in &s.onsets {
            let key = onset_at_key(o.load, scene.targets[o.target]);
            golden_values.insert(key.to_string(), golden(o.e_norm.value));
        }
        golden_values
    }

    /// The account, from the numbers.
    fn account(run: &Run, s: &OnsetStats) -> String {
        let scene = run.scene;
        let (lowest, highest) = (s.lowest, s.highest);
        let (high_text, grow_text) = onset_texts(scene, s);
        let low: Vec<String> = grow_text
            .iter()
            .map(|t| t.split(" against ").next().unwrap_or_default().to_string())
            .collect();
        format!(
            "{}, at the load that gives a_r = {} at full resolution, bands of modes within \
             {:.0}% of q_t = zeta_t q_l (zeta_t = {:?}) hold, at zeta = {} zeta_t (before any \
             mode of the band is resolved), on average E_norm = {} of the energy Persson's \
             theory assigns them once resolved ({}). At the lowest load (a_r = {lowest}) the \
             onset is {}; at the highest (a_r = {highest}) it is {}. A mode's energy is thus \
             populated before its roughness is resolved once contact is partial, as the paper \
             reports (the pressure of a partial contact has Fourier components at every \
             wavevector), while near full contact Persson's step holds.",
            scene.base().over(),
            scene.headline_contact_area,
            100.0 * scene.band,
            scene.targets,
            scene.onset_ratio,
            s.headline.text(1.0, 3, ""),
            s.headline.z_text(0.0, "Persson's 0"),
            low.join(", "),
            high_text.join(", "),
        )
    }

    fn tables(run: &Run, _s: &OnsetStats) -> Vec<Table> {
        let sweeps = sweeps(run.results);
        let loads = by_load(&run.scene.contact_areas, &sweeps);
        vec![curve_table(&run.criteria.name, run.scene, &loads)]
    }

    fn figures(run: &Run, _s: &OnsetStats) -> Vec<Figure> {
        let sweeps = sweeps(run.results);
        let loads = by_load(&run.scene.contact_areas, &sweeps);
        curve_figures("e_norm", run.scene, &loads)
    }
}

/// Per target, in words: the onset at the highest load with the contact area there, and
/// the onset at the lowest load against that at the highest.
fn onset_texts(scene: &ModeScene, s: &OnsetStats) -> (Vec<String>, Vec<String>) {
    s.extremes(scene.targets.len())
        .map(|(high, low)| {
            let zt = scene.targets[high.target];
            let at_high = high.e_norm.text(1.0, 4, "");
            let a_high = high.contact_area.value;
            (
                format!("zeta_t = {zt}: {at_high} (a_r = {a_high:.3} at the onset point)"),
                format!(
                    "zeta_t = {zt}: {} against {at_high}",
                    low.e_norm.text(1.0, 3, "")
                ),
            )
        })
        .unzip()
}

#[cfg(test)]
mod tests {
    use super::super::tests::{shipped, synthetic};
    use super::*;

    #[test]
    fn shipped_scenes_are_valid_at_both_scales() {
        crate::experiments::shipped_valid::<ModeOnset>("d_onset");
    }

    #[test]
    fn narrow_bands_pair_up_with_the_scene_bands() {
        use super::super::{ModeJob, ModeOutput, NarrowJob};
        let (mut scene, _, criteria) = shipped("d_onset");
        scene.narrow_band = Some(0.02);
        let mut results = synthetic(&scene, (0.9, 1.0), 0.8, 0.25);
        // The same sweeps as if recorded with narrow bands: no shift, and paired exactly.
        let narrow: Vec<_> = results
            .iter()
            .map(|(j, r)| match (j, r) {
                (ModeJob::Sweep(j), ModeOutput::Sweep(r)) => (
                    ModeJob::Narrow(NarrowJob {
                        band: 0.02,
                        seed: j.seed,
                        contact_area: j.contact_area,
                    }),
                    ModeOutput::Narrow(r.clone()),
                ),
                _ => unreachable!("synthetic sweeps"),
            })
            .collect();
        results.extend(narrow);
        let c = ModeOnset::conclude(&criteria, &scene, &results).unwrap();
        let shift = c.detail(PEAK_BAND_SHIFT).unwrap().value;
        assert_eq!((shift.value, shift.std_error), (0.0, 0.0));
        let shift = c.detail(PEAK_BAND_SHIFT_ENSEMBLE).unwrap().value;
        assert_eq!((shift.value, shift.std_error), (0.0, 0.0));
        // Narrow curves tilted upwards (E_norm times zeta^0.3) peak later: the shift, the
        // scene's bands' peak minus the narrow ones', is negative in both readings.
        let mut tilted = results.clone();
        for (j, r) in &mut tilted {
            if let (ModeJob::Narrow(_), ModeOutput::Narrow(r)) = (j, r) {
                for band in &mut r.band_energy {
                    for (e, z) in band.iter_mut().zip(&r.zetas) {
                        *e *= z.powf(0.3);
                    }
                }
            }
        }
        let later = ModeOnset::conclude(&criteria, &scene, &tilted).unwrap();
        for key in [PEAK_BAND_SHIFT, PEAK_BAND_SHIFT_ENSEMBLE] {
            let shift = later.detail(key).unwrap().value;
            assert!(shift.value < 0.0, "{key}: {shift:?}");
        }
        let (wide, narrow) = (
            c.detail(PEAK_OVER_ZETA_T).unwrap().value,
            c.detail(PEAK_NARROW_BAND).unwrap().value,
        );
        assert_eq!(wide, narrow);
        // Without narrow results the details are absent, not zero.
        results.retain(|(j, _)| matches!(j, ModeJob::Sweep(_)));
        let c = ModeOnset::conclude(&criteria, &scene, &results).unwrap();
        assert!(c.detail(PEAK_BAND_SHIFT).is_none());
        assert!(c.detail(PEAK_BAND_SHIFT_ENSEMBLE).is_none());
    }

    #[test]
    fn a_peak_between_steps_is_the_parabola_vertex_in_ln_zeta() {
        use super::super::stats::interpolated_peak;
        // Uneven steps around a parabola in ln zeta with its vertex at zeta = 3.
        let zetas = [1.0, 2.0, 2.5, 3.4, 4.0, 8.0];
        let e: Vec<f64> = zetas
            .iter()
            .map(|z: &f64| 1.0 - (z.ln() - 3f64.ln()).powi(2))
            .collect();
        assert!((interpolated_peak(&zetas, &e) - 3.0).abs() < 1e-12);
        // At an end of the sweep: the step itself.
        assert_eq!(
            interpolated_peak(&zetas, &[6.0, 5.0, 4.0, 3.0, 2.0, 1.0]),
            1.0
        );
        // A flat top of two equal steps: midway between them in ln zeta.
        let z = interpolated_peak(&[1.0, 2.0, 4.0, 8.0], &[0.0, 1.0, 1.0, 0.0]);
        assert!((z - 8f64.sqrt()).abs() < 1e-12, "{z}");
    }

    #[test]
    fn onset_statistic_is_the_band_energy_below_resolution() {
        let (scene, _, criteria) = shipped("d_onset");
        let results = synthetic(&scene, (0.9, 1.0), 0.0, 0.25);
        let c = ModeOnset::conclude(&criteria, &scene, &results).unwrap();
        let m = c.measured.unwrap();
        assert!((m.value - 0.25).abs() < 1e-12, "{m:?}");
        // Equal onset at every load: no guards, and every onset detail reads the same.
        assert!(c.guards.is_empty());
        for d in c.details.iter().filter(|d| d.key.stem() == "onset") {
            assert!((d.value.value - 0.25).abs() < 1e-12, "{d:?}");
        }
    }
}
