//! Assumption (a): the diffusion coefficient does not depend on the pressure. Statistics,
//! then findings (details, checks, golden values), then the account and the figure.

use std::collections::BTreeMap;

use super::figures::{bin_figure, bin_points, bin_table, common_account, level, transition_table};
use super::stats::{
    bin_broadening_share, bin_fits, bin_rows, bin_spread_over_half_width, contact_line_distances,
    lost_unsuited, lowest_minus_top_unsuited, mean_of, mean_where, over_realizations, region_mean,
    small_pressure_exponent, unsuited_minus_suited, BinRow, SMALL_PRESSURE,
};
use super::{distances, others, own, TransitionResult, TransitionScene};
use crate::error::Result;
use crate::experiments::declared::DetailTable;
use crate::experiments::{Criteria, Experiment, Table};
use crate::persson::moments;
use crate::persson::Correction;
use crate::plot::{Figure, Series, Style};
use crate::stats::{round_sig, Estimate};

/// The keys of the details ([`Experiment::detail_table`]).
const D_RATIO_HIGH: &str = "d_ratio_high";
const S_CORRECTED: &str = "s_corrected";
const APPROX_DELTA_P_ERROR: &str = "approx_delta_p_error";
const SMALL_P_EXPONENT: &str = "small_p_exponent";
const FIT_TV_UNSUITED_MINUS_SUITED: &str = "fit_tv_unsuited_minus_suited";
const FIT_TV_LOWEST_MINUS_TOP_UNSUITED: &str = "fit_tv_lowest_minus_top_unsuited";
const BIN_SPREAD_OVER_HALF_WIDTH: &str = "bin_spread_over_half_width";
const BIN_BROADENING_SHARE: &str = "bin_broadening_share";
const MIRROR_MOMENT_ERROR: &str = "mirror_moment_error";
const HIGH_CLOSER_TO_ORIGINAL: &str = "d_ratio_high_closer_to_original";
const LOST_UNSUITED: &str = "lost_unsuited_bins";
const APPROX_DELTA_P_LIMITS: &str = "approx_delta_p_error_limits";

/// The other scene's headline (with an other scene).
const OTHER_D_RATIO_LOW: &str = "other_scene_d_ratio_low";
/// The walkers' distances to the nearest point out of contact (with the distance jobs).
const DISTANCE_LOW: &str = "contact_line_distance_low";
const DISTANCE_HIGH: &str = "contact_line_distance_high";
const DISTANCE_HIGH_MINUS_LOW: &str = "contact_line_distance_high_minus_low";

/// The diffusion validation, assumption (a).
pub struct Diffusion;

/// The statistics of the diffusion validation.
#[derive(Debug, Clone)]
pub struct DiffusionStats {
    /// `D_n / D_P` in the low-pressure region (suited bins): the headline.
    pub low: Estimate,
    /// `D_n / D_P` in the high-pressure region (suited bins).
    pub high: Estimate,
    /// The contact area at `zeta`.
    pub a_r: Estimate,
    /// The corrected theory's `S(a_r)`, eq. (gamma).
    pub s_corrected: f64,
    /// The exponent of `Pr(p) ~ p^alpha` at small pressure, at `zeta`.
    pub small_p_exponent: Estimate,
    /// Every analysed bin.
    pub rows: Vec<BinRow>,
    /// Mean total-variation distance between a bin's transitions and its mirror Gaussian,
    /// unsuited bins minus suited bins.
    pub fit_unsuited_minus_suited: Estimate,
    /// That distance in the lowest unsuited bin minus that in the highest.
    pub fit_lowest_minus_top_unsuited: Estimate,
    /// Mean over analysed bins of `dp_n` over the bin's half width.
    pub bin_spread_over_half_width: Estimate,
    /// Mean over suited bins of `dp_n^2 / Dp_n^2`.
    pub bin_broadening_share: Estimate,
    /// The share of the walkers in bins whose mean lies below the broadening that left
    /// contact over the step.
    pub lost_unsuited: Estimate,
    /// The other scene's `D_n / D_P` in its low-pressure region and its contact area at
    /// `zeta` (none without an other scene).
    pub other: Option<(Estimate, Estimate)>,
    /// The walkers' mean distance to the nearest point out of contact (grid spacings)
    /// below `low_pressure` and from `high_pressure` up, and high minus low, over
    /// realizations (none without the distance jobs).
    pub distances: Option<[Estimate; 3]>,
}

impl DiffusionStats {
    /// The statistics of the realizations' transitions.
    pub fn of(scene: &TransitionScene, results: &[(u64, TransitionResult)]) -> Self {
        let region = |keep: &dyn Fn(f64) -> bool| {
            over_realizations(scene, results, |bins| {
                region_mean(bins, |b| b.suited && keep(b.mean_old), |b| b.ratio)
            })
        };
        let a_r = mean_of(results, |r| r.a_r_old);
        Self {
            low: region(&|p| p < scene.low_pressure),
            high: region(&|p| p >= scene.high_pressure),
            a_r,
            s_corrected: Correction::yang_persson().factor(a_r.value),
            small_p_exponent: Estimate::mean_of(
                &results
                    .iter()
                    .filter_map(|(_, r)| small_pressure_exponent(&r.bins, scene.bin_width))
                    .collect::<Vec<_>>(),
            ),
            rows: bin_rows(scene, results),
            fit_unsuited_minus_suited: mean_where(results, |r| {
                unsuited_minus_suited(&bin_fits(scene, r))
            }),
            fit_lowest_minus_top_unsuited: mean_where(results, |r| {
                lowest_minus_top_unsuited(&bin_fits(scene, r))
            }),
            bin_spread_over_half_width: mean_where(results, |r| {
                bin_spread_over_half_width(scene, r)
            }),
            bin_broadening_share: mean_where(results, |r| bin_broadening_share(scene, r)),
            lost_unsuited: mean_where(results, |r| lost_unsuited(scene, r)),
            other: None,
            distances: None,
        }
    }

    /// Analysed bins whose mean is below the broadening (not used for diffusion).
    pub fn unsuited(&self) -> usize {
        self.rows.iter().filter(|r| !r.suited).count()
    }
}

/// Points of the scan over `Dp_n / p'` of eq. (approxDeltaPress)'s error.
const ERROR_POINTS: usize = 2001;

type Run<'a> = crate::experiments::Run<'a, Diffusion>;

impl Experiment for Diffusion {
    type Scene = TransitionScene;
    type Stats = DiffusionStats;

    fn stats(run: &Run) -> Result<DiffusionStats> {
        let mut s = DiffusionStats::of(run.scene, &own(run.results));
        if let Some(other) = run.scene.other_step_scene() {
            let o = DiffusionStats::of(&other, &others(run.results));
            s.other = Some((o.low, o.a_r));
        }
        let per_realization: Vec<(f64, f64)> = distances(run.results)
            .into_iter()
            .filter_map(|d| contact_line_distances(run.scene, d))
            .collect();
        if !per_realization.is_empty() {
            let over = |f: fn(&(f64, f64)) -> f64| {
                Estimate::mean_of(&per_realization.iter().map(f).collect::<Vec<_>>())
            };
            s.distances = Some([over(|d| d.0), over(|d| d.1), over(|d| d.1 - d.0)]);
        }
        Ok(s)
    }

    fn headline(s: &DiffusionStats) -> (Estimate, f64) {
        (s.low, 1.0)
    }

    /// The high-pressure ratio and the corrected theory's `S(a_r)` beside it, the shape of
    /// the transitions, the other scene's ratio and the walkers' distances to the contact
    /// line (`table`).
    fn detail_table<'s>(
        scene: &'s TransitionScene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, DiffusionStats> {
        table(scene)
    }

    fn golden(_run: &Run, s: &DiffusionStats) -> BTreeMap<String, f64> {
        BTreeMap::from([
            ("d_ratio_low".into(), round_sig(s.low.value, 3)),
            ("d_ratio_high".into(), round_sig(s.high.value, 3)),
            ("a_r".into(), round_sig(s.a_r.value, 4)),
        ])
    }

    fn account(run: &Run, s: &DiffusionStats) -> String {
        format!(
            "{} In the low-pressure region (p < {} p0/a_r) the diffusion coefficient from \
             the moment analysis is D_n / D_P = {} times Persson's; at p >= {} p0/a_r it is {} \
             (the corrected theory's S(a_r) would be {:.2}). {} of the analysed bins have a \
             mean below the broadening and are not used for diffusion.",
            common_account(run.scene, &own(run.results)),
            run.scene.low_pressure,
            s.low.text(1.0, 2, ""),
            run.scene.high_pressure,
            s.high.text(1.0, 2, ""),
            s.s_corrected,
            s.unsuited()
        )
    }

    fn tables(run: &Run, s: &DiffusionStats) -> Vec<Table> {
        vec![
            bin_table(&s.rows),
            transition_table(run.scene, &own(run.results)),
        ]
    }

    fn figures(run: &Run, s: &DiffusionStats) -> Vec<Figure> {
        vec![diffusion_figure(run.scene, s)]
    }
}

/// The details a run of `scene` can have, in the order a run writes them: which rows, their
/// keys and how their values are read come from the scene alone. Two labels and Persson's
/// value of `S(a_r)` name a measured number (the corrected theory's `S(a_r)` at the
/// measured `a_r`, the other scene's measured `a_r`): they are read with the value.
fn table(scene: &TransitionScene) -> DetailTable<'_, DiffusionStats> {
    let mut t = DetailTable::default();
    broadening_rows(&mut t, scene);
    transition_shape_rows(&mut t);
    other_scene_row(&mut t, scene);
    distance_rows(&mut t, scene);
    t
}

/// The broadening against the two theories at high pressure (Persson's value of the
/// corrected theory's `S(a_r)`: at the measured `a_r`), the walkers it leaves unsuited, and
/// eq. (approxDeltaPress) against the exact inversion of eq. (2ndMoment).
fn broadening_rows(t: &mut DetailTable<'_, DiffusionStats>, scene: &TransitionScene) {
    let high = scene.high_pressure;
    t.always(
        D_RATIO_HIGH,
        format!("D_n / D_P at p >= {high} p0/a_r"),
        |s: &DiffusionStats| s.high,
    )
    .persson(1.0);
    t.always(
        S_CORRECTED,
        "corrected theory's S(a_r) (eq. gamma)",
        |s: &DiffusionStats| Estimate::new(s.s_corrected, f64::NAN),
    )
    .persson_from(|s: &DiffusionStats| Some(s.s_corrected));
    t.row_labelled(HIGH_CLOSER_TO_ORIGINAL, move |s: &DiffusionStats| {
        let name = format!(
            "D_n / D_P at p >= {high} p0/a_r minus the midpoint of the original theory's 1 \
             and the corrected theory's S(a_r) = {:.3}: above 0 where the broadening is \
             closer to the original theory",
            s.s_corrected
        );
        let v = Estimate::new(s.high.value - 0.5 * (1.0 + s.s_corrected), s.high.std_error);
        Some((name, v))
    });
    t.always(
        LOST_UNSUITED,
        "share of the walkers in the analysed bins whose mean lies below the broadening \
         that left contact over the step",
        |s: &DiffusionStats| s.lost_unsuited,
    );
    t.always(
        APPROX_DELTA_P_LIMITS,
        "relative error of eq. (approxDeltaPress) against the exact inversion of eq. \
         (2ndMoment) in its limits, the larger at Dp_n / p' = 1e-6 and 1e8 (exact: no error \
         bar)",
        |_: &DiffusionStats| Estimate::new(moments::estimate_error_in_the_limits(), 0.0),
    );
    t.always(
        APPROX_DELTA_P_ERROR,
        "largest relative error of eq. (approxDeltaPress) against the exact inversion of eq. \
         (2ndMoment), Dp_n / p' from 1e-3 to 1e3 (exact: no error bar)",
        |_: &DiffusionStats| Estimate::new(moments::estimate_largest_error(ERROR_POINTS), 0.0),
    );
}

/// The shape of the transitions: the small-pressure exponent of `Pr(p)`, the distance of
/// each bin's transitions from eq. (transitionFinal), the bins' own width against the
/// broadening, and the quadrature of eq. (transitionFinal)'s moments.
fn transition_shape_rows(t: &mut DetailTable<'_, DiffusionStats>) {
    t.always(
        SMALL_P_EXPONENT,
        format!(
            "exponent alpha of Pr(p) ~ p^alpha at zeta, fitted over the bins below \
             {SMALL_PRESSURE} p0/a_r (Persson's eq. pressureDistOri: 1)"
        ),
        |s: &DiffusionStats| s.small_p_exponent,
    )
    .persson(1.0);
    t.always(
        FIT_TV_UNSUITED_MINUS_SUITED,
        "mean total-variation distance between a bin's transitions and the mirror Gaussian \
         with its moments (eq. transitionFinal), bins with mean below the broadening minus \
         bins above",
        |s: &DiffusionStats| s.fit_unsuited_minus_suited,
    );
    t.always(
        FIT_TV_LOWEST_MINUS_TOP_UNSUITED,
        "that total-variation distance in the lowest bin with mean below the broadening \
         minus that in the highest",
        |s: &DiffusionStats| s.fit_lowest_minus_top_unsuited,
    );
    t.always(
        BIN_SPREAD_OVER_HALF_WIDTH,
        "spread dp_n of the old pressures in a bin over the bin's half width, mean over \
         analysed bins (a flat density: 1/sqrt3)",
        |s: &DiffusionStats| s.bin_spread_over_half_width,
    );
    t.always(
        BIN_BROADENING_SHARE,
        "dp_n^2 / Dp_n^2, the share of the broadening the bin's own width makes up (the \
         relative change of D_n its correction makes), mean over suited bins",
        |s: &DiffusionStats| s.bin_broadening_share,
    );
    t.always(
        MIRROR_MOMENT_ERROR,
        "largest relative error of the quadrature of the first two moments of eq. \
         (transitionFinal) against p' and eq. (2ndMoment), Dp_n / p' from 1e-3 to 1e3 \
         (exact: no error bar)",
        |_: &DiffusionStats| Estimate::new(moments::mirror_moment_largest_error(ERROR_POINTS), 0.0),
    );
}

/// The ratio at low pressure in the other scene, where the scene has one, its label quoting
/// the other scene's measured contact area.
fn other_scene_row(t: &mut DetailTable<'_, DiffusionStats>, scene: &TransitionScene) {
    let Some(other) = &scene.other_scene else {
        return;
    };
    let (low, (hurst, a, zeta, dzeta)) = (
        scene.low_pressure,
        (other.hurst, other.contact_area, other.zeta, other.dzeta),
    );
    t.row_labelled(OTHER_D_RATIO_LOW, move |s: &DiffusionStats| {
        let (ratio, a_r) = s.other?;
        let name = format!(
            "D_n / D_P at p < {low} p0/a_r in the other scene: H = {hurst}, a_r = {a} at zeta \
             {zeta} -> {} (measured a_r {})",
            zeta + dzeta,
            a_r.text(1.0, 4, ""),
        );
        Some((name, ratio))
    })
    .persson(1.0);
}

/// How far the walkers at low and at high pressure lie from the nearest point out of
/// contact, where the scene measures it.
fn distance_rows(t: &mut DetailTable<'_, DiffusionStats>, scene: &TransitionScene) {
    if !scene.contact_line_distances {
        return;
    }
    let (lo, hi) = (scene.low_pressure, scene.high_pressure);
    let walkers = |which: &str| {
        format!(
            "mean distance to the nearest point out of contact at zeta = {}, grid \
             spacings, of the walkers {which} (per realization, then over realizations)",
            scene.zeta
        )
    };
    t.row(
        DISTANCE_LOW,
        walkers(&format!("at p < {lo} p0/a_r")),
        |s: &DiffusionStats| s.distances.map(|d| d[0]),
    );
    t.row(
        DISTANCE_HIGH,
        walkers(&format!("at p >= {hi} p0/a_r")),
        |s: &DiffusionStats| s.distances.map(|d| d[1]),
    );
    t.row(
        DISTANCE_HIGH_MINUS_LOW,
        walkers(&format!(
            "at p >= {hi} p0/a_r minus that of those at p < {lo} p0/a_r"
        )),
        |s: &DiffusionStats| s.distances.map(|d| d[2]),
    );
}

/// `D_n / D_P` by pressure bin, suited and unsuited, against both theories.
fn diffusion_figure(scene: &TransitionScene, s: &DiffusionStats) -> Figure {
    let series = vec![
        Series::with_errors(
            "suited bins",
            Style::Points,
            bin_points(&s.rows, |r| r.suited, |r| r.ratio),
        ),
        Series::with_errors(
            "unsuited (mean below broadening)",
            Style::Points,
            bin_points(&s.rows, |r| !r.suited, |r| r.ratio),
        ),
        Series::xy("Persson (original)", Style::Line, level(scene, 1.0)),
        Series::xy(
            "corrected S(a_r)",
            Style::Dashed,
            level(scene, s.s_corrected),
        ),
    ];
    let title = "Diffusion coefficient by pressure bin";
    bin_figure("diffusion", title, "D_n / D_P", series)
}
