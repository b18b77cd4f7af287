//! Assumption (b): no drift. Statistics, then findings (details, checks, golden values),
//! then the account and the figure.

use std::collections::BTreeMap;

use super::figures::{bin_figure, bin_points, bin_table, common_account, level};
use super::stats::{
    bin_rows, lost_lowest_minus_high, lost_over_persson, mean_of, mean_where, over_realizations,
    region_mean, share_walkers_negative_drift, BinRow, MEAN_CONTACT_PRESSURE,
};
use super::{others, own, TransitionResult, TransitionScene};
use crate::error::Result;
use crate::experiments::declared::DetailTable;
use crate::experiments::{Criteria, Experiment, Table};
use crate::plot::{Figure, Series, Style};
use crate::stats::{round_sig, Estimate};

/// The keys of the details ([`Experiment::detail_table`]).
const MU_LOW: &str = "mu_low";
const MU_HIGH: &str = "mu_high";
const MU_LOWEST_BIN: &str = "mu_lowest_bin";
const A_R_RELATIVE_CHANGE: &str = "a_r_relative_change";
const LOST_OVER_PERSSON: &str = "lost_over_persson";
const SHARE_WALKERS_NEGATIVE_DRIFT: &str = "share_walkers_negative_drift";
const LOST_LOWEST_MINUS_HIGH: &str = "lost_lowest_minus_high";

/// The other scene's headline (with an other scene).
const OTHER_MU_C: &str = "other_scene_mu_c";

/// The drift validation, assumption (b).
pub struct Drift;

/// The statistics of the drift validation, in units of `p0 / a_r` per unit `zeta`.
#[derive(Debug, Clone)]
pub struct DriftStats {
    /// The contact-averaged drift `mu_c`: the headline.
    pub mu_c: Estimate,
    /// `mu_n` in the low-pressure region.
    pub low: Estimate,
    /// `mu_n` in the high-pressure region.
    pub high: Estimate,
    /// `mu_n` in the lowest analysed bin.
    pub lowest: Estimate,
    /// Every analysed bin.
    pub rows: Vec<BinRow>,
    /// Walkers lost over the step over the number Persson's drift-free mirror Gaussian
    /// loses (dimensionless).
    pub lost_over_persson: Estimate,
    /// Share of the walkers below `p0 / a_r` that sit in bins of negative drift.
    pub share_negative_drift: Estimate,
    /// Share of the lowest analysed bin's walkers that left contact, less the share of
    /// those at high pressure that did.
    pub lost_lowest_minus_high: Estimate,
    /// `a_r(zeta + dzeta) / a_r(zeta) - 1` over the realizations.
    pub a_r_relative_change: Estimate,
    /// The other scene's `mu_c` (none without an other scene).
    pub other_mu_c: Option<Estimate>,
}

/// `mu_c` of one realization: the mean change of pressure of the walkers in contact at
/// `zeta`, per unit `zeta`, in units of `p0 / a_r`.
pub fn contact_drift(scene: &TransitionScene, r: &TransitionResult) -> f64 {
    let (dp, n): (f64, f64) = r
        .bins
        .iter()
        .fold((0.0, 0.0), |(s, n), b| (s + b.new - b.old, n + b.count));
    dp / n / scene.dzeta / (r.p0 / r.a_r_old)
}

/// `a_r(zeta + dzeta) / a_r(zeta) - 1` over the realizations.
pub fn relative_area_change(results: &[(u64, TransitionResult)]) -> Estimate {
    Estimate::mean_of(
        &results
            .iter()
            .map(|(_, r)| r.a_r_new / r.a_r_old - 1.0)
            .collect::<Vec<_>>(),
    )
}

impl DriftStats {
    /// The statistics of the realizations' transitions.
    pub fn of(scene: &TransitionScene, results: &[(u64, TransitionResult)]) -> Self {
        let region = |keep: &dyn Fn(f64) -> bool| {
            over_realizations(scene, results, |bins| {
                region_mean(bins, |b| keep(b.mean_old), |b| b.drift)
            })
        };
        Self {
            mu_c: mean_of(results, |r| contact_drift(scene, r)),
            low: region(&|p| p < scene.low_pressure),
            high: region(&|p| p >= scene.high_pressure),
            lowest: over_realizations(scene, results, |bins| {
                bins.iter().flatten().next().map(|b| b.drift)
            }),
            rows: bin_rows(scene, results),
            lost_over_persson: mean_where(results, |r| lost_over_persson(scene, r)),
            share_negative_drift: mean_where(results, |r| share_walkers_negative_drift(scene, r)),
            lost_lowest_minus_high: mean_where(results, |r| {
                lost_lowest_minus_high(scene, r, scene.high_pressure)
            }),
            a_r_relative_change: relative_area_change(results),
            other_mu_c: None,
        }
    }
}

type Run<'a> = crate::experiments::Run<'a, Drift>;

impl Experiment for Drift {
    type Scene = TransitionScene;
    type Stats = DriftStats;

    fn stats(run: &Run) -> Result<DriftStats> {
        let mut s = DriftStats::of(run.scene, &own(run.results));
        if let Some(other) = run.scene.other_step_scene() {
            s.other_mu_c = Some(DriftStats::of(&other, &others(run.results)).mu_c);
        }
        Ok(s)
    }

    fn headline(s: &DriftStats) -> (Estimate, f64) {
        (s.mu_c, 0.0)
    }

    /// The drift by region (Persson: 0 everywhere), the change of `a_r` over the step, the
    /// walkers lost against Persson's mirror Gaussian, and the other scene's `mu_c`.
    fn detail_table<'s>(
        scene: &'s TransitionScene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, DriftStats> {
        let mut t = DetailTable::default();
        let low = format!("mu_n at p < {} p0/a_r", scene.low_pressure);
        t.always(MU_LOW, low, |s: &DriftStats| s.low).persson(0.0);
        let high = format!("mu_n at p >= {} p0/a_r", scene.high_pressure);
        t.always(MU_HIGH, high, |s: &DriftStats| s.high)
            .persson(0.0);
        t.always(
            MU_LOWEST_BIN,
            "mu_n in the lowest analysed bin",
            |s: &DriftStats| s.lowest,
        )
        .persson(0.0);
        t.always(
            A_R_RELATIVE_CHANGE,
            format!(
                "relative change of a_r over the step, zeta {} -> {}",
                scene.zeta,
                scene.zeta + scene.dzeta
            ),
            |s: &DriftStats| s.a_r_relative_change,
        );
        t.always(
            LOST_OVER_PERSSON,
            "walkers that left contact over the step over the number Persson's \
             drift-free mirror Gaussian with D_P absorbs at p = 0",
            |s: &DriftStats| s.lost_over_persson,
        )
        .persson(1.0);
        t.always(
            SHARE_WALKERS_NEGATIVE_DRIFT,
            format!(
                "share of the walkers below {MEAN_CONTACT_PRESSURE} p0/a_r in bins of \
                 negative drift"
            ),
            |s: &DriftStats| s.share_negative_drift,
        );
        t.always(
            LOST_LOWEST_MINUS_HIGH,
            format!(
                "share of the walkers of the lowest analysed bin that left contact over \
                 the step, less that of the walkers at p >= {} p0/a_r",
                scene.high_pressure
            ),
            |s: &DriftStats| s.lost_lowest_minus_high,
        );
        if let Some(other) = &scene.other_scene {
            t.row(
                OTHER_MU_C,
                format!(
                    "mu_c in the other scene: H = {}, a_r = {} at zeta {} -> {}",
                    other.hurst,
                    other.contact_area,
                    other.zeta,
                    other.zeta + other.dzeta
                ),
                |s: &DriftStats| s.other_mu_c,
            )
            .persson(0.0);
        }
        t
    }

    fn golden(_run: &Run, s: &DriftStats) -> BTreeMap<String, f64> {
        [("mu_c", s.mu_c), ("mu_low", s.low), ("mu_high", s.high)]
            .map(|(k, e)| (k.to_string(), round_sig(e.value, 3)))
            .into()
    }

    fn account(run: &Run, s: &DriftStats) -> String {
        format!(
            "{} The contact-averaged drift is mu_c = {} (p0/a_r per unit zeta; Persson: 0). \
             By region: {} below {} p0/a_r, {} above {} p0/a_r, and {} in the lowest \
             analysed bin.",
            common_account(run.scene, &own(run.results)),
            s.mu_c.text(1.0, 4, ""),
            s.low.text(1.0, 4, ""),
            run.scene.low_pressure,
            s.high.text(1.0, 4, ""),
            run.scene.high_pressure,
            s.lowest.text(1.0, 4, "")
        )
    }

    fn tables(_run: &Run, s: &DriftStats) -> Vec<Table> {
        vec![bin_table(&s.rows)]
    }

    fn figures(run: &Run, s: &DriftStats) -> Vec<Figure> {
        vec![drift_figure(run.scene, s)]
    }
}

/// The drift by pressure bin against Persson's none.
fn drift_figure(scene: &TransitionScene, s: &DriftStats) -> Figure {
    let series = vec![
        Series::with_errors(
            "drift mu_n",
            Style::Points,
            bin_points(&s.rows, |_| true, |r| r.drift),
        ),
        Series::xy("Persson: no drift", Style::Line, level(scene, 0.0)),
    ];
    let title = "Drift by pressure bin";
    bin_figure("drift", title, "mu_n / (p0 / a_r)", series)
}
