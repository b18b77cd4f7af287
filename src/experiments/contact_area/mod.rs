//! The contact-area law: relative contact area against reduced pressure ([`crate::conventions`], section 6,
//! row "contact area"; paper section 3.1, eq. (contactArea)).
//!
//! For each Hurst exponent and realization the load is raised step by step at full
//! resolution (each solve warm-started from the previous load), and `a_r` is recorded
//! against the reduced pressure `p~0 = p0 / (E* g_bar)`. The statistics:
//!
//! * the low-load slope `kappa = a_r / p~0`, averaged over the loads with
//!   `p~0 <= low_load`, with its standard error over realizations; Persson's original
//!   theory predicts `a_r = erf(sqrt2 p~0)`, i.e. `kappa = sqrt(8/pi) = 1.596` (paper:
//!   `kappa ~ 2`, and `2 c1 = 2.15` in eq. contactArea);
//! * the largest relative deviation of the measured `a_r` from eq. (contactArea) over the
//!   loads whose `a_r` lies in `law_range` (paper: within `O(10%)` for H = 0.3, 0.5, 0.8);
//! * the law's shape (paper section 3.1, tex 433-500): the largest spread over `H` of
//!   `a_r / p~0` at one load (`a_r` a function of `p~0` alone), `c1 = kappa / 2`, `c2`
//!   solving eq. (contactArea) with the paper's `c1` at the highest load, the exponent `m`
//!   of the leading correction `kappa(0) - kappa(p~0) ~ p~0^m` (third order in `a_r`:
//!   `m = 2`) and the mean `a_r / p~0` over partial contact (`p~0 ~ a_r / 2`); with the
//!   fall of `a_r / p~0` at low load on every grid beside them.
//!
//! # Discretisation
//!
//! A grid counts a point as in contact when its pressure is positive, which overestimates
//! `a_r` when the smallest asperities span few points (`eps_c = a / lambda_s` not small):
//! at `lambda_s = 4` grid spacings `kappa` comes out near 2.7, falling by about half the
//! difference each time `eps_c` halves. The scene therefore lists `refinements`: the same
//! realizations (same seed, all lengths scaled, see [`crate::engine::surface`]) at grids `r` times
//! finer. With two or more, the headline statistics are first-order Richardson
//! extrapolations of the two finest grids, `x_inf = (r2 x2 - r1 x1) / (r2 - r1)` (error
//! proportional to `eps_c`); the per-grid values are reported beside them.
//!
//! # Files
//!
//! * `mod.rs`: the [`Experiment`] implementation: the statistics read as details, the
//!   golden values and the account;
//! * `scene.rs`: the scene, the checks of its parameters, and its jobs;
//! * `ladder.rs`: one realization at one Hurst exponent and grid, the load raised step by
//!   step (the headline's jobs), and the finer grid;
//! * `stats/`: the slope, the extrapolation to the continuum, the deviation from the
//!   law (`deviation.rs`), the law's shape (`shape.rs`) and the grid's error
//!   (`grid_error.rs`), as pure functions of the curves;
//! * `study.rs`: the readings of the law's deviation, the order of the grid error and the
//!   fall of `a_r / p~0` at low load per grid;
//! * `figures.rs`: the table and the figures;
//! * `scaling.rs`: the solvers' iterations against the system size (paper section 2.3),
//!   where the scene plans it (`[full.scaling]`): cold solves of one scene shape on
//!   several grids.

mod figures;
pub mod gap;
mod ladder;
pub mod scaling;
mod scene;
pub mod stats;
mod study;
pub mod system_size;

use crate::experiments::keys::{DetailKey, Tag};
use std::collections::BTreeMap;

use self::figures::{area_figures, area_table};
use self::gap::{GapJob, GapResult};
pub use self::ladder::{AreaJob, AreaResult, FinerGrid};
use self::scaling::{ScalingJob, ScalingResult};
pub use self::scene::{AreaScene, ContactAreaJob, ContactAreaOutput};
use self::stats::{AreaStats, NEAR_FULL_CONTACT};
use super::declared::{value_at, DetailTable};
use super::study::Study;
use super::{Criteria, Experiment, Keys, Table};
use crate::error::Result;
use crate::plot::Figure;
use crate::stats::{realizations, round_sig, Estimate};

/// The experiment.
pub struct ContactArea;

/// Persson's low-load slope: `a_r = erf(sqrt2 p~0)` has slope `sqrt(8/pi)` at `p~0 -> 0`.
pub fn persson_kappa() -> f64 {
    (8.0 / std::f64::consts::PI).sqrt()
}

/// The key of the slope at one Hurst exponent.
fn hurst_key(hurst: f64) -> DetailKey {
    DetailKey::new("kappa").at(Tag::Hurst, hurst)
}

/// The keys of the other details ([`Experiment::detail_table`]): the slope on each grid
/// (one key, measured on several grids), and the law's deviations and shape.
const KAPPA_ON_GRID: &str = "kappa_on_grid";
const LAW_DEVIATION: &str = "law_deviation";
const COMPLEMENT_DEVIATION: &str = "complement_deviation";
const KAPPA_SPREAD_H: &str = "kappa_spread_h";
const C2_FIT: &str = "c2_fit";
const C1_FIT: &str = "c1_fit";
const CORRECTION_EXPONENT: &str = "correction_exponent";
const KAPPA_PARTIAL_MEAN: &str = "kappa_partial_mean";

type Run<'a> = super::Run<'a, ContactArea>;

impl Experiment for ContactArea {
    type Scene = AreaScene;
    type Stats = AreaStats;

    fn stats(run: &Run) -> Result<AreaStats> {
        let ladders: Vec<(AreaJob, AreaResult)> = run
            .results
            .iter()
            .filter_map(|(j, r)| match (j, r) {
                (ContactAreaJob::Ladder(j), ContactAreaOutput::Ladder(r)) => {
                    Some((j.clone(), r.clone()))
                }
                _ => None,
            })
            .collect();
        let solves: Vec<(&ScalingJob, &ScalingResult)> = run
            .results
            .iter()
            .filter_map(|(j, r)| match (j, r) {
                (ContactAreaJob::Scaling(j), ContactAreaOutput::Scaling(r)) => Some((j, r)),
                _ => None,
            })
            .collect();
        let gaps: Vec<(&GapJob, &GapResult)> = run
            .results
            .iter()
            .filter_map(|(j, r)| match (j, r) {
                (ContactAreaJob::Gap(j), ContactAreaOutput::Gap(r)) => Some((j, r)),
                _ => None,
            })
            .collect();
        let mut stats = AreaStats::of(run.scene, &ladders);
        stats.iteration_exponent = scaling::exponent(&solves);
        if let Some(plan) = &run.scene.gap {
            stats.gap_slope_changes = gap::slope_changes(plan, &gaps);
        }
        if let Some(plan) = &run.scene.system_size {
            stats.size_changes = plan
                .hursts
                .iter()
                .filter_map(|&h| {
                    let larger: Vec<&AreaResult> = run
                        .results
                        .iter()
                        .filter_map(|(j, r)| match (j, r) {
                            (ContactAreaJob::Size(j), ContactAreaOutput::Size(r))
                                if j.hurst == h =>
                            {
                                Some(r)
                            }
                            _ => None,
                        })
                        .collect();
                    let own = system_size::scene_ladders(&ladders, h);
                    system_size::largest_change(plan, &run.scene.reduced_pressures, &larger, &own)
                        .map(|c| (h, c))
                })
                .collect();
        }
        Ok(stats)
    }

    fn headline(s: &AreaStats) -> (Estimate, f64) {
        (s.kappa, persson_kappa())
    }

    /// The slope on every grid and at every Hurst exponent, the law's deviation and shape,
    /// and the solvers' scaling, the mean gap and the system size where the scene plans
    /// them.
    fn detail_table<'s>(
        scene: &'s AreaScene,
        criteria: &'s Criteria,
    ) -> DetailTable<'s, AreaStats> {
        let mut t = DetailTable::default();
        let label = grid_label(scene);
        for &refine in &scene.refinements {
            let n = scene.n * refine;
            t.row(
                KAPPA_ON_GRID,
                format!(
                    "kappa on the {n}x{n} grid (lambda_s = {} grid spacings)",
                    scene.lambda_s * refine as f64
                ),
                move |s: &AreaStats| value_at(&s.on_grid, refine),
            )
            .persson(persson_kappa())
            .paper(criteria.paper_value)
            .on_grid(n);
        }
        for &h in &scene.hursts {
            t.row(
                hurst_key(h),
                format!("kappa, H = {h} ({label})"),
                move |s: &AreaStats| s.hursts.iter().find(|x| x.hurst == h).map(|x| x.kappa),
            )
            .persson(persson_kappa())
            .paper(criteria.paper_value);
        }
        t.always(
            LAW_DEVIATION,
            format!(
                "largest relative deviation from eq. (contactArea), |a_r - law| / a_r ({label})"
            ),
            |s: &AreaStats| s.law.estimate(),
        );
        t.always(
            COMPLEMENT_DEVIATION,
            format!(
                "largest relative deviation of 1 - a_r from eq. (contactArea)'s, a_r in [{}, {}] \
                 ({label})",
                NEAR_FULL_CONTACT.max(scene.law_range.0),
                scene.law_range.1
            ),
            |s: &AreaStats| s.complement.estimate(),
        );
        shape_rows(&mut t, scene);
        if let Some(plan) = &scene.scaling {
            scaling::declare(&mut t, plan);
        }
        if let Some(plan) = &scene.gap {
            gap::declare(&mut t, plan);
        }
        if let Some(plan) = &scene.system_size {
            system_size::declare(&mut t, plan, scene);
        }
        t
    }

    /// The studies: the readings and the fall always, the order of the grid error with a
    /// finer grid.
    fn declare_studies(scene: &AreaScene, keys: &mut Keys) {
        study::keys(scene, keys);
    }

    /// The golden values: the slopes and the law's deviation.
    fn golden(_run: &Run, s: &AreaStats) -> BTreeMap<String, f64> {
        let mut golden = BTreeMap::from([
            ("kappa".to_string(), round_sig(s.kappa.value, 4)),
            ("law_deviation".to_string(), round_sig(s.law.worst, 3)),
        ]);
        for (refine, k) in &s.on_grid {
            golden.insert(format!("kappa_refine{refine}"), round_sig(k.value, 4));
        }
        for h in &s.hursts {
            golden.insert(format!("kappa_H{}", h.hurst), round_sig(h.kappa.value, 4));
        }
        golden
    }

    /// The account, from the numbers.
    fn account(run: &Run, s: &AreaStats) -> String {
        let (scene, label) = (run.scene, grid_label(run.scene));
        format!(
            "Over {} of each of H = {:?} (grid {}x{} refined by {:?}, lambda_l = {} and \
             lambda_s = {} grid spacings on the coarsest grid), the low-load slope a_r / p~0 \
             (p~0 <= {}, {label}) is {}, against {:.3} from Persson's original theory and 2 c1 = \
             {:.2} from the paper's fit. Eq. (contactArea) matches the measured a_r to within \
             {:.1}% for a_r in [{}, {}].",
            realizations(scene.seeds.len()),
            scene.hursts,
            scene.n,
            scene.n,
            scene.refinements,
            scene.lambda_l,
            scene.lambda_s,
            scene.low_load,
            s.kappa.text(1.0, 3, ""),
            persson_kappa(),
            crate::persson::ContactAreaLaw::PAPER.kappa(),
            100.0 * s.law.worst,
            scene.law_range.0,
            scene.law_range.1,
        )
    }

    /// The readings of the law's deviation (denominator, grid) and the finer grid's
    /// order of the grid error.
    fn studies(run: &Run, s: &AreaStats) -> Vec<Study> {
        study::studies(run, s)
    }

    fn tables(run: &Run, s: &AreaStats) -> Vec<Table> {
        let name = &run.criteria.name;
        vec![area_table(name, &run.scene.reduced_pressures, s)]
    }

    fn figures(run: &Run, s: &AreaStats) -> Vec<Figure> {
        area_figures(&run.scene.reduced_pressures, s, grid_label(run.scene))
    }
}

/// The details of the law's shape: the spread over `H` (its label names the load and the
/// Hurst exponents measured apart the most), `c1` and `c2`, the order of the leading
/// correction, the mean slope over partial contact.
fn shape_rows(t: &mut DetailTable<'_, AreaStats>, scene: &AreaScene) {
    let label = grid_label(scene);
    let law = crate::persson::ContactAreaLaw::PAPER;
    let [p0, p1, p2] = stats::CORRECTION_LOADS;
    let top = scene.reduced_pressures[scene.reduced_pressures.len() - 1];
    let range = scene.law_range;
    t.row_labelled(KAPPA_SPREAD_H, move |s: &AreaStats| {
        let (p, hi, lo) = s.shape.spread.at;
        let name = format!(
            "largest spread over H of a_r / p~0 at one load, every a_r in [{}, {}] \
             (p~0 = {p}: H = {hi} against H = {lo}; {label})",
            range.0, range.1
        );
        Some((name, s.shape.spread.spread))
    })
    .persson(0.0);
    t.always(
        C2_FIT,
        format!(
            "c2 of eq. (contactArea) with c1 = {} for a_r pooled over H at p~0 = {top} \
             ({label})",
            law.c1
        ),
        |s: &AreaStats| s.shape.c2,
    )
    .persson(1.0)
    .paper(Some(law.c2));
    t.always(
        C1_FIT,
        format!("c1 = kappa / 2 ({label})"),
        |s: &AreaStats| s.shape.c1,
    )
    .paper(Some(law.c1));
    t.always(
        CORRECTION_EXPONENT,
        format!(
            "exponent m of kappa(0) - kappa(p~0) ~ p~0^m from p~0 = {p0}, {p1}, {p2}, \
             kappa pooled over H (jackknife over realizations; {label})"
        ),
        |s: &AreaStats| s.shape.correction,
    )
    .paper(Some(2.0));
    t.always(
        KAPPA_PARTIAL_MEAN,
        format!(
            "mean a_r / p~0 over H and the loads with a_r in [{}, {}] ({label})",
            stats::PARTIAL_RANGE.0,
            stats::PARTIAL_RANGE.1
        ),
        |s: &AreaStats| s.shape.partial_kappa,
    )
    .paper(Some(2.0));
}

/// How the headline statistics treat the grid.
fn grid_label(scene: &AreaScene) -> &'static str {
    if scene.refinements.len() > 1 {
        "extrapolated to eps_c -> 0"
    } else {
        "at the scene's grid"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shipped_scenes_are_valid() {
        crate::experiments::shipped_valid::<ContactArea>("contact_area");
    }
}
