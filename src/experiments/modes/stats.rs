//! The statistics of the single-mode sweeps, as pure functions of the sweeps: the
//! ensemble values of a load that both experiments read, and those of assumption (e): the
//! change of `E_norm` after resolution, the asymptote `E_inf` of each realization (the
//! intercept of `E_norm` against `1/zeta` over the frozen window) with
//! `x = -d ln a_r / d ln zeta` over the same window, and the paper's law
//! `E_inf = K1 exp(-K2 x)` fitted to the partial-contact points.

use super::{ModeResult, ModeScene};
use crate::engine::tolerance::ZETA_SLACK;
use crate::experiments::climb::step_of;
use crate::experiments::ensemble::{group, load_range, LoadGroup};
use crate::experiments::keys::{DetailKey, Tag};
use crate::stats::{pearson, round_sig, Estimate, LineFit};

/// One realization's onset: the mean over targets of `E_norm` at `onset_ratio zeta_t`.
pub fn mean_onset(scene: &ModeScene, run: &ModeResult) -> f64 {
    let steps = &run.zetas;
    scene
        .targets
        .iter()
        .enumerate()
        .map(|(t, &zt)| run.e_norm(t, zt)[step_of(steps, scene.onset_ratio * zt)])
        .sum::<f64>()
        / scene.targets.len() as f64
}

/// Loads whose measured contact area at `zeta_t` reaches this are in full contact there:
/// left out of where the bands peak.
pub const PARTIAL: f64 = 0.99;

/// Ensemble statistics of the single-mode sweeps at one load.
pub(super) type Load<'a> = LoadGroup<'a, ModeResult>;

/// The ensemble values of a load's sweeps.
pub(super) trait ModeEnsemble {
    /// Ensemble `E_norm` of target `t` at step `k`.
    fn e_norm(&self, t: usize, zeta_t: f64, k: usize) -> Estimate;
    /// Ensemble contact area at step `k`.
    fn contact_area_at(&self, k: usize) -> Estimate;
    /// Ensemble change `E_norm(k1) - E_norm(k0)` of target `t`.
    fn change(&self, t: usize, zeta_t: f64, k0: usize, k1: usize) -> Estimate;
}

impl ModeEnsemble for Load<'_> {
    fn e_norm(&self, t: usize, zeta_t: f64, k: usize) -> Estimate {
        self.ratio(|r| (r.band_energy[t][k], r.denominator(t, zeta_t)))
    }

    fn contact_area_at(&self, k: usize) -> Estimate {
        self.mean(|r| r.contact_area[k])
    }

    fn change(&self, t: usize, zeta_t: f64, k0: usize, k1: usize) -> Estimate {
        self.ratio(|r| {
            let e = &r.band_energy[t];
            (e[k1] - e[k0], r.denominator(t, zeta_t))
        })
    }
}

/// A golden value of `E_norm`: two significant digits, and no digits below `1e-4` (an
/// onset of a few `1e-6` near full contact is solver noise, not a result).
pub(super) fn golden(x: f64) -> f64 {
    if x.abs() < 1e-3 {
        (x * 1e4).round() / 1e4
    } else {
        round_sig(x, 2)
    }
}

/// Loads with a measured contact area at the end of the sweep at or above this are full
/// contact (`x ~ 0`) and left out of the fit of the asymptote law, as in the paper.
pub const FULL_CONTACT: f64 = 0.99;

/// The reading of `x` at the mode's own magnification: the slope of `ln a_r` against
/// `ln zeta` over `zeta_t / MODE_WINDOW` to `MODE_WINDOW zeta_t`.
pub const MODE_WINDOW: f64 = 1.5;

/// `x = -d ln a_r / d ln zeta` of one realization over the steps with `zeta` in
/// `[lo, hi]` (none with fewer than two such steps).
pub fn slope_over(run: &ModeResult, lo: f64, hi: f64) -> Option<f64> {
    let (ln_z, ln_a): (Vec<f64>, Vec<f64>) = run
        .zetas
        .iter()
        .zip(&run.contact_area)
        .filter(|(z, _)| **z >= lo * (1.0 - ZETA_SLACK) && **z <= hi * (1.0 + ZETA_SLACK))
        .map(|(z, a)| (z.ln(), a.ln()))
        .unzip();
    LineFit::fit(&ln_z, &ln_a).map(|f| -f.slope.value)
}

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

/// One target at one load after resolution.
#[derive(Debug, Clone, PartialEq)]
pub struct AfterResolution {
    /// The load, as the contact area at full resolution.
    pub load: f64,
    /// Index of the target.
    pub target: usize,
    /// The step where the frozen window starts.
    pub from: usize,
    /// `E_norm(zeta_end) - E_norm(frozen_from zeta_t)`.
    pub change: Estimate,
    /// The asymptote `E_inf`, over realizations.
    pub asymptote: Estimate,
    /// `x = -d ln a_r / d ln zeta` over the frozen window, over realizations.
    pub x: Estimate,
    /// `x` at the mode's own magnification ([`MODE_WINDOW`]), over realizations.
    pub x_mode: Estimate,
    /// The measured contact area at `zeta_t` (the mode's own resolution), over
    /// realizations.
    pub a_t: f64,
    /// The correction factor `S(a_r(zeta_t))` (Persson's asymptote).
    pub s: f64,
    /// The measured contact area at the end of the sweep.
    pub a_end: f64,
}

/// The statistics of target `t` at `load`.
fn after_resolution(scene: &ModeScene, steps: &[f64], load: &Load, t: usize) -> AfterResolution {
    let zt = scene.targets[t];
    let end = steps.len() - 1;
    let from = step_of(steps, scene.frozen_from * zt);
    let fits: Vec<(f64, f64)> = load
        .runs
        .iter()
        .filter_map(|r| asymptote(scene, r, t))
        .collect();
    let mean =
        |f: fn(&(f64, f64)) -> f64| Estimate::mean_of(&fits.iter().map(f).collect::<Vec<_>>());
    let a_t = load.contact_area_at(step_of(steps, zt)).value;
    AfterResolution {
        load: load.contact_area,
        target: t,
        from,
        change: load.change(t, zt, from, end),
        asymptote: mean(|f| f.0),
        x: mean(|f| f.1),
        x_mode: Estimate::mean_of(
            &load
                .runs
                .iter()
                .filter_map(|r| slope_over(r, zt / MODE_WINDOW, MODE_WINDOW * zt))
                .collect::<Vec<_>>(),
        ),
        a_t,
        s: scene.correction.factor(a_t),
        a_end: load.contact_area_at(end).value,
    }
}

/// Every statistic of assumption (e).
#[derive(Debug, Clone)]
pub struct FrozenStats {
    /// Every load and target, loads outermost.
    pub after: Vec<AfterResolution>,
    /// The lowest and the highest load.
    pub lowest: f64,
    /// The highest load.
    pub highest: f64,
    /// The asymptote of the first target minus that of the last at the lowest load, per
    /// realization (with more than one target).
    pub long_minus_short: Option<Estimate>,
    /// `(x, ln E_inf)` of the partial-contact points with a positive asymptote.
    pub k_points: Vec<(f64, f64)>,
    /// The line through `k_points`: `ln K1 - K2 x`.
    pub k_fit: Option<LineFit>,
    /// The same points with `x` at the mode's own magnification: `(x_mode, ln E_inf)`.
    pub k_mode_points: Vec<(f64, f64)>,
    /// The line through `k_mode_points`.
    pub k_mode_fit: Option<LineFit>,
    /// Over the same points, the share of the variance of `ln E_inf` a line in `x` (at
    /// the mode's own magnification) explains minus the share a line in `ln a_r(zeta_t)`
    /// explains, with its jackknife error over realizations.
    pub r2_x_minus_r2_ar: Option<Estimate>,
    /// `(K1, K2)` of the reference surface's law, `x` at the mode's own magnification
    /// (none without a reference; set by [`FrozenStats::with_reference`]).
    pub k_mode_reference: Option<(Estimate, Estimate)>,
    /// The change of largest magnitude over the targets at the highest load.
    pub change_full_contact_max: Option<Estimate>,
    /// End-of-sweep `E_norm` of the first target minus that of the last, at the loads of
    /// the paper's panels c and d ([`PANEL_LOADS`]).
    pub end_long_minus_short: Option<Estimate>,
    /// The largest ensemble `E_norm` of the last target, mean over the partial loads.
    pub peak_short_partial: Option<Estimate>,
    /// `E_norm` of the first target against a chord linear in `zeta` over the frozen window.
    pub falloff_mid_chord: Option<Estimate>,
    /// The onset (mean over targets of `E_norm(onset_ratio zeta_t)`) of every load.
    pub onsets: Vec<(f64, Estimate)>,
}

impl FrozenStats {
    /// The statistics of the loads' sweeps.
    pub fn of(scene: &ModeScene, loads: &[Load]) -> Self {
        let steps = scene.steps();
        let after: Vec<AfterResolution> = loads
            .iter()
            .flat_map(|load| {
                let steps = &steps;
                (0..scene.targets.len()).map(move |t| after_resolution(scene, steps, load, t))
            })
            .collect();
        let k_points: Vec<(f64, f64)> = fitted(&after)
            .map(|a| (a.x.value, a.asymptote.value.ln()))
            .collect();
        let k_mode_points: Vec<(f64, f64)> = mode_points(&after)
            .map(|a| (a.x_mode.value, a.asymptote.value.ln()))
            .collect();
        let line = |points: &[(f64, f64)]| {
            let (xs, ys): (Vec<f64>, Vec<f64>) = points.iter().copied().unzip();
            LineFit::fit(&xs, &ys)
        };
        let (lowest, highest) = load_range(&scene.contact_areas);
        Self {
            change_full_contact_max: change_max_at(&after, highest),
            end_long_minus_short: end_long_minus_short(scene, loads),
            peak_short_partial: peak_short_partial(scene, loads),
            falloff_mid_chord: falloff_mid_chord(scene, loads),
            onsets: loads
                .iter()
                .map(|l| (l.contact_area, l.mean(|r| mean_onset(scene, r))))
                .collect(),
            long_minus_short: long_minus_short(scene, group(loads, lowest)),
            k_fit: line(&k_points),
            k_mode_fit: line(&k_mode_points),
            r2_x_minus_r2_ar: r2_x_minus_r2_ar(scene, loads),
            k_mode_reference: None,
            k_points,
            k_mode_points,
            after,
            lowest,
            highest,
        }
    }

    /// Target `t` at load `load`.
    pub fn at(&self, load: f64, t: usize) -> &AfterResolution {
        self.after
            .iter()
            .find(|a| a.load == load && a.target == t)
            .expect("every load and target")
    }

    /// The headline: the change of the first (longest-wavelength) target at the lowest
    /// load.
    pub fn headline(&self) -> Estimate {
        self.at(self.lowest, 0).change
    }

    /// `(K1, K2)` of the fitted law (`x` over the frozen window), with their standard
    /// errors.
    pub fn k(&self) -> Option<(Estimate, Estimate)> {
        self.k_fit.map(law_constants)
    }

    /// `(K1, K2)` with `x` at the mode's own magnification.
    pub fn k_mode(&self) -> Option<(Estimate, Estimate)> {
        self.k_mode_fit.map(law_constants)
    }

    /// These statistics with the reference surface's law (its statistics `reference`).
    pub fn with_reference(self, reference: &FrozenStats) -> Self {
        Self {
            k_mode_reference: reference.k_mode(),
            ..self
        }
    }

    /// `(K1, K2)` of this surface's law minus the reference surface's, `x` at the mode's
    /// own magnification; errors combined as of independent surfaces.
    pub fn k_mode_minus_reference(&self) -> Option<(Estimate, Estimate)> {
        let ((k1, k2), (r1, r2)) = (self.k_mode()?, self.k_mode_reference?);
        Some((Estimate::difference(k1, r1), Estimate::difference(k2, r2)))
    }
}

/// The partial-contact points of the asymptote law: a positive asymptote, and contact
/// still partial at the end of the sweep.
fn fitted(after: &[AfterResolution]) -> impl Iterator<Item = &AfterResolution> {
    after
        .iter()
        .filter(|a| a.asymptote.value > 0.0 && a.a_end < FULL_CONTACT)
}

/// The points of the law with `x` at the mode's own magnification: those of [`fitted`]
/// where that `x` is measured.
fn mode_points(after: &[AfterResolution]) -> impl Iterator<Item = &AfterResolution> {
    fitted(after).filter(|a| a.x_mode.value.is_finite())
}

/// Which of the two variables tracks the asymptotes: over the law's points with `x` at
/// the mode's own magnification, `r^2(ln E_inf, x) - r^2(ln E_inf, ln a_r(zeta_t))`, the
/// squared Pearson correlations (the shares of the variance of `ln E_inf` that a line in
/// each explains). The value from all realizations, the standard error by jackknife over
/// realizations (the `i`-th run of every load left out in turn, every asymptote and slope
/// fitted again). None with fewer than three points.
pub fn r2_x_minus_r2_ar(scene: &ModeScene, loads: &[Load]) -> Option<Estimate> {
    let steps = scene.steps();
    let stat = |skip: Option<usize>| {
        let after: Vec<AfterResolution> = loads
            .iter()
            .flat_map(|l| {
                let kept = Load {
                    contact_area: l.contact_area,
                    runs: l
                        .runs
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| Some(*i) != skip)
                        .map(|(_, r)| *r)
                        .collect(),
                };
                (0..scene.targets.len())
                    .map(|t| after_resolution(scene, &steps, &kept, t))
                    .collect::<Vec<_>>()
            })
            .collect();
        let (x, (ln_a, ln_e)): (Vec<f64>, (Vec<f64>, Vec<f64>)) = mode_points(&after)
            .map(|a| (a.x_mode.value, (a.a_t.ln(), a.asymptote.value.ln())))
            .unzip();
        if x.len() < 3 {
            return f64::NAN;
        }
        pearson(&ln_e, &x).powi(2) - pearson(&ln_e, &ln_a).powi(2)
    };
    let n = loads.iter().map(|l| l.runs.len()).min()?;
    let e = Estimate::jackknife(n, stat);
    e.value.is_finite().then_some(e)
}

/// `(K1, K2)` of a line `ln K1 - K2 x`, with their standard errors.
fn law_constants(f: LineFit) -> (Estimate, Estimate) {
    let k1 = Estimate::new(
        f.intercept.value.exp(),
        f.intercept.std_error * f.intercept.value.exp(),
    );
    (k1, Estimate::new(-f.slope.value, f.slope.std_error))
}

/// The asymptote of the first target minus that of the last at `load`, per realization.
fn long_minus_short(scene: &ModeScene, load: &Load) -> Option<Estimate> {
    let last = scene.targets.len().checked_sub(1).filter(|&l| l > 0)?;
    let diffs: Vec<f64> = load
        .runs
        .iter()
        .filter_map(|r| Some(asymptote(scene, r, 0)?.0 - asymptote(scene, r, last)?.0))
        .collect();
    Some(Estimate::mean_of(&diffs))
}

/// The key of the onset detail of load `load` (the mean over targets of `E_norm` at
/// `onset_ratio zeta_t`).
pub fn onset_key(load: f64) -> DetailKey {
    DetailKey::new("onset").at(Tag::ContactArea, load)
}

/// The loads of the paper's fig. elastic_energy_H08 panels c and d (contact area at full
/// resolution); the scene's loads nearest them are read.
pub const PANEL_LOADS: [f64; 2] = [0.083, 0.009];

/// The scene's load nearest `a`.
fn nearest_load<'g, 'a>(loads: &'g [Load<'a>], a: f64) -> Option<&'g Load<'a>> {
    loads.iter().min_by(|x, y| {
        (x.contact_area - a)
            .abs()
            .total_cmp(&(y.contact_area - a).abs())
    })
}

/// Of the changes after resolution at `load`, the one of largest magnitude.
pub fn change_max_at(after: &[AfterResolution], load: f64) -> Option<Estimate> {
    after
        .iter()
        .filter(|a| a.load == load)
        .map(|a| a.change)
        .max_by(|a, b| a.value.abs().total_cmp(&b.value.abs()))
}

/// Per realization, `E_norm` of the first target minus that of the last at the end of the
/// sweep; mean and standard error over realizations at each of the loads nearest
/// [`PANEL_LOADS`], then the mean of the loads (errors combined). None with one target.
pub fn end_long_minus_short(scene: &ModeScene, loads: &[Load]) -> Option<Estimate> {
    let last = scene.targets.len().checked_sub(1).filter(|&l| l > 0)?;
    let (z0, zl) = (scene.targets[0], scene.targets[last]);
    let per_load: Vec<Estimate> = PANEL_LOADS
        .iter()
        .map(|&a| {
            let load = nearest_load(loads, a)?;
            Some(load.mean(|r| {
                let end = r.zetas.len() - 1;
                r.e_norm(0, z0)[end] - r.e_norm(last, zl)[end]
            }))
        })
        .collect::<Option<_>>()?;
    let n = per_load.len() as f64;
    Some(Estimate::new(
        per_load.iter().map(|e| e.value).sum::<f64>() / n,
        per_load
            .iter()
            .map(|e| e.std_error.powi(2))
            .sum::<f64>()
            .sqrt()
            / n,
    ))
}

/// Whether target `t` is in partial contact at its own resolution at `load`: the
/// ensemble's measured contact area at `zeta_t` below [`PARTIAL`].
fn partial_at(scene: &ModeScene, load: &Load, t: usize) -> bool {
    let steps = scene.steps();
    load.contact_area_at(step_of(&steps, scene.targets[t]))
        .value
        < PARTIAL
}

/// The largest ensemble `E_norm` over the sweep of the last (shortest-wavelength) target,
/// mean over the loads in partial contact at its `zeta_t`: the value from all
/// realizations, the standard error by jackknife over realizations (the `i`-th run of
/// every load left out in turn).
pub fn peak_short_partial(scene: &ModeScene, loads: &[Load]) -> Option<Estimate> {
    let t = scene.targets.len().checked_sub(1)?;
    let zt = scene.targets[t];
    let partial: Vec<&Load> = loads.iter().filter(|l| partial_at(scene, l, t)).collect();
    let n = partial.iter().map(|l| l.runs.len()).min()?;
    Some(Estimate::jackknife(n, |skip| {
        partial
            .iter()
            .map(|l| {
                ensemble_curve(&without(&l.runs, skip), t, zt)
                    .into_iter()
                    .fold(f64::NEG_INFINITY, f64::max)
            })
            .sum::<f64>()
            / partial.len() as f64
    }))
}

/// `runs` without the one at index `skip` (all of them for `None`): a jackknife's sample.
fn without<'a>(runs: &[&'a ModeResult], skip: Option<usize>) -> Vec<&'a ModeResult> {
    runs.iter()
        .enumerate()
        .filter(|&(i, _)| Some(i) != skip)
        .map(|(_, r)| *r)
        .collect()
}

/// The magnification where a curve `e` over `zetas` peaks: at its largest point (the last
/// of equal ones), refined to the vertex of the parabola through that point and its two
/// neighbours in `ln zeta`; the point itself at an end of the sweep. The middle point is
/// the highest of the three and above the right one, so the parabola opens downwards
/// and its vertex lies between the neighbours.
pub fn interpolated_peak(zetas: &[f64], e: &[f64]) -> f64 {
    let k = (0..e.len())
        .max_by(|&a, &b| e[a].total_cmp(&e[b]))
        .expect("a sweep has steps");
    if k == 0 || k + 1 == e.len() {
        return zetas[k];
    }
    let x = |i: usize| zetas[i].ln();
    let (x0, x1, x2) = (x(k - 1), x(k), x(k + 1));
    let (y0, y1, y2) = (e[k - 1], e[k], e[k + 1]);
    let num = (x1 - x0).powi(2) * (y1 - y2) - (x1 - x2).powi(2) * (y1 - y0);
    let den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0);
    (x1 - 0.5 * num / den).exp()
}

/// The ensemble `E_norm` curve of target `t` over `runs` (as [`ModeEnsemble::e_norm`]):
/// at each step the sum of the runs' band energies over the sum of their denominators.
fn ensemble_curve(runs: &[&ModeResult], t: usize, zeta_t: f64) -> Vec<f64> {
    let d: f64 = runs.iter().map(|r| r.denominator(t, zeta_t)).sum();
    (0..runs[0].zetas.len())
        .map(|k| runs.iter().map(|r| r.band_energy[t][k]).sum::<f64>() / d)
        .collect()
}

/// The shift of the ensemble curve's peak that the band's width makes: for every target
/// of every load in partial contact at its `zeta_t` (measured `a_r` there below
/// [`PARTIAL`]), `zeta_peak / zeta_t` of the ensemble curve ([`interpolated_peak`]) with
/// the scene's bands (`wide`) minus that with the narrow bands (`narrow`: the same
/// realizations and solves, recorded with narrower bands), mean over those targets and
/// loads. The standard error is the jackknife's over realizations (the `i`-th run of
/// every load left out of both curves). `None` when the two sets of sweeps do not pair up
/// (a partial run) or no band is in partial contact.
pub fn ensemble_peak_shift(scene: &ModeScene, wide: &[Load], narrow: &[Load]) -> Option<Estimate> {
    let paired = wide.len() == narrow.len()
        && wide
            .iter()
            .zip(narrow)
            .all(|(w, n)| w.contact_area == n.contact_area && w.runs.len() == n.runs.len());
    let cells: Vec<(usize, usize)> = (0..wide.len())
        .flat_map(|l| (0..scene.targets.len()).map(move |t| (l, t)))
        .filter(|&(l, t)| partial_at(scene, &wide[l], t))
        .collect();
    if !paired || cells.is_empty() {
        return None;
    }
    let runs = cells.iter().map(|&(l, _)| wide[l].runs.len()).min()?;
    let peak = |load: &Load, t: usize, skip: Option<usize>| {
        let kept = without(&load.runs, skip);
        let zt = scene.targets[t];
        interpolated_peak(&kept[0].zetas, &ensemble_curve(&kept, t, zt)) / zt
    };
    Some(Estimate::jackknife(runs, |skip| {
        cells
            .iter()
            .map(|&(l, t)| peak(&wide[l], t, skip) - peak(&narrow[l], t, skip))
            .sum::<f64>()
            / cells.len() as f64
    }))
}

/// One realization's `E_norm` of target `t` at the step nearest the middle of the frozen
/// window (`zeta_a = frozen_from zeta_t` to `zeta_b = zeta_end`), minus the chord linear
/// in `zeta` through the window's ends.
pub fn mid_chord(scene: &ModeScene, run: &ModeResult, t: usize) -> f64 {
    let zt = scene.targets[t];
    let e = run.e_norm(t, zt);
    let a = step_of(&run.zetas, scene.frozen_from * zt);
    let b = run.zetas.len() - 1;
    let (za, zb) = (run.zetas[a], run.zetas[b]);
    let mid = 0.5 * (za + zb);
    let m = (0..run.zetas.len())
        .min_by(|&i, &j| {
            (run.zetas[i] - mid)
                .abs()
                .total_cmp(&(run.zetas[j] - mid).abs())
        })
        .expect("a sweep has steps");
    let chord = e[a] + (e[b] - e[a]) * (run.zetas[m] - za) / (zb - za);
    e[m] - chord
}

/// [`mid_chord`] of the first (longest-wavelength) target, mean and standard error over
/// the realizations of every load in partial contact at its `zeta_t`.
pub fn falloff_mid_chord(scene: &ModeScene, loads: &[Load]) -> Option<Estimate> {
    let values: Vec<f64> = loads
        .iter()
        .filter(|l| partial_at(scene, l, 0))
        .flat_map(|l| l.runs.iter().map(|r| mid_chord(scene, r, 0)))
        .collect();
    (!values.is_empty()).then(|| Estimate::mean_of(&values))
}
