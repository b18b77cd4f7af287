//! The cross-section waterfall of the paper's figure "reentry_waterfall" (section 3.3,
//! "No re-entry"): one cut through the same contact at several magnifications, at the
//! fixed load that gives the stated contact area at the largest of them.
//!
//! The realization is solved at every magnification of the list (warm-started); the cut
//! is the grid row with the most re-entered points, a point counting as re-entered in a
//! panel when it is in contact there and was out of contact in a panel above (only the
//! listed magnifications are looked at, not every shell between them). The paper did not
//! choose its cut; this one is chosen to show the effect, and the title says so.
//!
//! Two details read the caption ("the overall shape does not change at large
//! magnification, the local topology does"): the shape change between the last two
//! panels, `1 - r` with `r` the Pearson correlation of the elastic body's displacement
//! along the cut, and the share of the cut's points re-entered in the last panel. With the
//! plan's further seeds (`more_seeds`, each run as the figure's seed is, its own busiest
//! row cut) each is a mean over the realizations with its standard error; with one
//! realization, neither has an error bar.
//!
//! A third reads the text ("even though we did not select the location of the cut
//! specifically for this effect, we happened to find a re-entry point", tex 705-706): the
//! share of grid rows that hold a re-entered point in some panel, i.e. the chance that an
//! unselected cut shows one. With one realization its error is the standard error over
//! [`ROW_BLOCKS`] blocks of consecutive rows (rows next to each other cut the same contact
//! patches, so single rows are not independent); with several, over the realizations.

use serde::{Deserialize, Serialize};

use crate::engine::solver::SolverKind;
use crate::error::{check_open, Error, Result};
use crate::experiments::declared::DetailTable;
use crate::experiments::flux::FluxScene;
use crate::plot::{CutPanel, Waterfall};
use crate::stats::{pearson, Estimate};

/// The key of the shape change of the cut between the last two panels.
pub const SHAPE_CHANGE: &str = "waterfall_shape_change";
/// The key of the share of the cut's points re-entered in the last panel.
pub const REENTERED_LAST: &str = "waterfall_reentered_last";
/// The key of the share of rows that hold a re-entered point.
pub const ROWS_WITH_REENTRY: &str = "waterfall_rows_with_reentry";
/// Blocks of consecutive rows over which the share of rows with re-entry is averaged.
pub const ROW_BLOCKS: usize = 16;

/// The waterfall, as a scene states it (`[reduced.waterfall]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaterfallPlan {
    /// The realization of the figure.
    pub seed: u64,
    /// Further realizations, for the details' error bars (the jobs' keys leave this list
    /// out, so the figure's stored result keeps its key).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub more_seeds: Vec<u64>,
    /// Magnifications of the panels, increasing.
    pub zetas: Vec<f64>,
    /// Contact area at the largest magnification (sets the load).
    pub contact_area: f64,
    /// The solver (a figure needs no cross-check; CG is the cheaper one here).
    pub solver: SolverKind,
}

/// One panel's cut.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cut {
    /// Magnification.
    pub zeta: f64,
    /// Contact area of the whole interface.
    pub a_r: f64,
    /// Heights of the rough body along the cut.
    pub heights: Vec<f64>,
    /// Displacement of the elastic body along the cut.
    pub displacement: Vec<f64>,
    /// Re-entered points along the cut.
    pub reentered: Vec<bool>,
}

/// What the waterfall job measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaterfallResult {
    /// The grid row of the cut.
    pub row: usize,
    /// Load.
    pub p0: f64,
    /// The panels.
    pub cuts: Vec<Cut>,
    /// Re-entered points of every grid row, summed over the panels.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub row_reentries: Vec<u32>,
}

impl WaterfallPlan {
    /// Checks the ranges against the scene's `zeta_max`; errors name the field.
    pub fn validate(&self, zeta_max: f64) -> Result<()> {
        check_open("waterfall.contact_area", self.contact_area, 0.0, 1.0)?;
        if self.zetas.is_empty() || self.zetas.windows(2).any(|w| w[0] >= w[1]) {
            return Err(Error::invalid(
                "waterfall.zetas",
                format!("{:?}", self.zetas),
                "at least one magnification, increasing",
            ));
        }
        for &z in &self.zetas {
            crate::engine::scene::check_zeta(z, zeta_max)
                .map_err(|e| e.with_field("waterfall.zetas"))?;
        }
        Ok(())
    }
}

/// Re-entered points of every panel: in contact there, out of contact in a panel above.
pub fn reentered(contact: &[Vec<bool>]) -> Vec<Vec<bool>> {
    let points = contact.first().map_or(0, Vec::len);
    let mut was_out = vec![false; points];
    contact
        .iter()
        .map(|c| {
            let marks: Vec<bool> = c
                .iter()
                .zip(&was_out)
                .map(|(&now, &out)| now && out)
                .collect();
            for (o, &now) in was_out.iter_mut().zip(c) {
                *o |= !now;
            }
            marks
        })
        .collect()
}

/// The marked points of every row of an `n x n` grid, summed over the panels.
pub fn row_counts(marks: &[Vec<bool>], n: usize) -> Vec<u32> {
    (0..n)
        .map(|row| {
            marks
                .iter()
                .map(|m| m[row * n..(row + 1) * n].iter().filter(|&&x| x).count() as u32)
                .sum()
        })
        .collect()
}

/// The row with the most marked points (the first of equals).
pub fn busiest_row(counts: &[u32]) -> usize {
    counts
        .iter()
        .enumerate()
        .fold(
            (0, 0),
            |best, (row, &c)| if c > best.1 { (row, c) } else { best },
        )
        .0
}

/// The share of rows holding a marked point, with its standard error over
/// [`ROW_BLOCKS`] blocks of consecutive rows (`None` without rows).
pub fn rows_with_reentry(counts: &[u32]) -> Option<Estimate> {
    if counts.is_empty() {
        return None;
    }
    let blocks = ROW_BLOCKS.min(counts.len());
    let size = counts.len().div_ceil(blocks);
    let shares: Vec<f64> = counts
        .chunks(size)
        .map(|b| b.iter().filter(|&&c| c > 0).count() as f64 / b.len() as f64)
        .collect();
    let all = counts.iter().filter(|&&c| c > 0).count() as f64 / counts.len() as f64;
    Some(Estimate::new(all, Estimate::mean_of(&shares).std_error))
}

/// Solves the panels of realization `seed` and cuts the busiest row.
pub fn run(scene: &FluxScene, plan: &WaterfallPlan, seed: u64) -> Result<WaterfallResult> {
    let base = scene.base();
    let r = base.realization(seed)?;
    let mut sweep = base.sweep(&r, plan.solver);
    let last = *plan.zetas.last().expect("validated: not empty");
    let p0 = sweep.find_load(last, plan.contact_area)?;
    // The load search's own solution is the last panel's; the others climb from the first.
    let at_last = sweep.take_solution().expect("find_load keeps its solution");
    let heights_last = sweep.heights().to_vec();
    let mut fields = Vec::new();
    for &zeta in &plan.zetas[..plan.zetas.len() - 1] {
        let s = sweep.solve_at(zeta, p0)?.clone();
        let heights = sweep.heights().to_vec();
        fields.push((zeta, s, heights));
    }
    fields.push((last, at_last, heights_last));
    let fields: Vec<_> = fields
        .into_iter()
        .map(|(zeta, s, h)| {
            let contact: Vec<bool> = s.pressure.iter().map(|&p| p > 0.0).collect();
            (zeta, s.contact_area(), h, s.displacement, contact)
        })
        .collect();
    let contact: Vec<Vec<bool>> = fields.iter().map(|f| f.4.clone()).collect();
    let marks = reentered(&contact);
    let n = scene.n;
    let row_reentries = row_counts(&marks, n);
    let row = busiest_row(&row_reentries);
    let cut = |v: &[f64]| v[row * n..(row + 1) * n].to_vec();
    let cuts = fields
        .iter()
        .zip(&marks)
        .map(|((zeta, a_r, h, u, _), m)| Cut {
            zeta: *zeta,
            a_r: *a_r,
            heights: cut(h),
            displacement: cut(u),
            reentered: m[row * n..(row + 1) * n].to_vec(),
        })
        .collect();
    Ok(WaterfallResult {
        row,
        p0,
        cuts,
        row_reentries,
    })
}

/// The shape change of the cut between its last two panels, `1 - r` with `r` the
/// Pearson correlation of the displacements (`None` with fewer than two panels).
pub fn shape_change(r: &WaterfallResult) -> Option<f64> {
    let [.., before, last] = r.cuts.as_slice() else {
        return None;
    };
    Some(1.0 - pearson(&before.displacement, &last.displacement))
}

/// The share of the cut's points re-entered in the last panel.
pub fn reentered_last(r: &WaterfallResult) -> Option<f64> {
    let last = r.cuts.last()?;
    let marked = last.reentered.iter().filter(|&&m| m).count();
    Some(marked as f64 / last.reentered.len().max(1) as f64)
}

/// The waterfall's statistics over its realizations (the figure's first): means with
/// their standard errors over the realizations, or, for one, the figure's own values
/// without error bars (the rows' share with its error over blocks of rows).
#[derive(Debug, Clone, PartialEq)]
pub struct WaterfallStats {
    /// Realizations.
    pub realizations: usize,
    /// The grid row of the figure's cut.
    pub row: usize,
    /// The shape change of the cut between the last two panels ([`shape_change`]).
    pub shape_change: Estimate,
    /// The share of the cut's points re-entered in the last panel ([`reentered_last`]).
    pub reentered_last: Estimate,
    /// The share of the grid rows holding a re-entered point ([`rows_with_reentry`]);
    /// none where a result stored before the rows were counted has none.
    pub rows_with_reentry: Option<Estimate>,
}

impl WaterfallStats {
    /// The statistics of the waterfall's results, the figure's first (none without one).
    pub fn of(results: &[&WaterfallResult]) -> Option<Self> {
        let first = results.first()?;
        let n = results.len();
        let over = |f: &dyn Fn(&WaterfallResult) -> Option<f64>| {
            if n == 1 {
                Estimate::new(f(first).unwrap_or(f64::NAN), f64::NAN)
            } else {
                Estimate::mean_of(&results.iter().filter_map(|r| f(r)).collect::<Vec<_>>())
            }
        };
        let rows_with_reentry = if n == 1 {
            rows_with_reentry(&first.row_reentries)
        } else {
            let shares: Vec<f64> = results
                .iter()
                .filter_map(|r| rows_with_reentry(&r.row_reentries).map(|e| e.value))
                .collect();
            (shares.len() == n).then(|| Estimate::mean_of(&shares))
        };
        Some(Self {
            realizations: n,
            row: first.row,
            shape_change: over(&shape_change),
            reentered_last: over(&reentered_last),
            rows_with_reentry,
        })
    }
}

/// The waterfall's details over its realizations, from the scene's `plan` (written where
/// the run has the waterfall's results). Two labels name the run's realizations and one the
/// figure's row, so they are read with the values. `of` finds the waterfall's statistics
/// among the experiment's `S`.
pub fn rows<'s, S: 's>(
    t: &mut DetailTable<'s, S>,
    plan: &WaterfallPlan,
    of: fn(&S) -> Option<&WaterfallStats>,
) {
    let zetas = |k: usize| plan.zetas.iter().rev().nth(k).copied().unwrap_or(f64::NAN);
    let (before, last) = (zetas(1), zetas(0));
    t.row_labelled(SHAPE_CHANGE, move |s: &S| {
        let w = of(s)?;
        let realizations = match w.realizations {
            1 => format!("row {}, one realization", w.row),
            n => format!("each realization's busiest row, {n} realizations"),
        };
        let name = format!(
            "1 - Pearson correlation of the displacement along the waterfall's cut, zeta = \
             {before} against {last} ({realizations})",
        );
        Some((name, w.shape_change))
    });
    t.row(
        REENTERED_LAST,
        format!(
            "share of the cut's points re-entered at zeta = {last} (in contact, out in a panel \
             above)"
        ),
        move |s: &S| Some(of(s)?.reentered_last),
    );
    let panels = plan
        .zetas
        .iter()
        .map(|z| z.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    t.row_labelled(ROWS_WITH_REENTRY, move |s: &S| {
        let w = of(s)?;
        let error = match w.realizations {
            1 => format!("error over {ROW_BLOCKS} blocks of rows, one realization"),
            n => format!("error over {n} realizations"),
        };
        let name = format!(
            "share of the grid rows holding a point re-entered in some panel (in contact, \
             out in a panel above), zeta = {panels}; {error}"
        );
        Some((name, w.rows_with_reentry?))
    });
}

/// The figure of a result.
pub fn figure(scene: &FluxScene, plan: &WaterfallPlan, r: &WaterfallResult) -> Waterfall {
    let last = plan.zetas.last().copied().unwrap_or(0.0);
    Waterfall {
        name: "reentry_waterfall".into(),
        title: format!(
            "Cut through one contact as the magnification grows (top to bottom): row {} of \
             seed {}, {}x{}, H = {}, a_r = {} at zeta = {last} ({}); the row with the most \
             re-entered points",
            r.row,
            plan.seed,
            scene.n,
            scene.n,
            scene.hurst,
            plan.contact_area,
            plan.solver.name()
        ),
        x_label: "position along the cut (grid spacings)".into(),
        y_label: "height".into(),
        mark_label: "re-entered (out in a panel above)".into(),
        panels: r
            .cuts
            .iter()
            .map(|c| CutPanel {
                label: format!(
                    "zeta = {} (a_r = {:.3}, {} re-entered)",
                    c.zeta,
                    c.a_r,
                    c.reentered.iter().filter(|&&m| m).count()
                ),
                upper: c.displacement.clone(),
                lower: c.heights.clone(),
                marked: c.reentered.clone(),
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reentry_needs_an_earlier_panel_out_of_contact() {
        let contact = vec![
            vec![true, false, true, true],
            vec![true, true, false, true],
            vec![false, true, true, true],
        ];
        let m = reentered(&contact);
        assert_eq!(m[0], vec![false; 4]);
        assert_eq!(m[1], vec![false, true, false, false]);
        assert_eq!(m[2], vec![false, true, true, false]);
        // 2 x 2 grid: row 0 holds points 0 and 1, row 1 points 2 and 3.
        let counts = row_counts(&m, 2);
        assert_eq!(counts, vec![2, 1]);
        assert_eq!(busiest_row(&counts), 0);
        assert_eq!(busiest_row(&[0, 3, 3, 1]), 1);
    }

    #[test]
    fn rows_with_reentry_is_the_share_of_rows_with_a_mark_blocked_for_its_error() {
        // 32 rows in 16 blocks of two: blocks alternate between one marked row and none.
        let counts: Vec<u32> = (0..32).map(|r| u32::from(r % 4 == 0) * 3).collect();
        let e = rows_with_reentry(&counts).unwrap();
        assert_eq!(e.value, 0.25);
        // Block shares 0.5 and 0 alternating: standard deviation 0.258, over sqrt(16).
        let sd = (16.0 * 0.25 * 0.25 / 15.0_f64).sqrt();
        assert!((e.std_error - sd / 4.0).abs() < 1e-12, "{}", e.std_error);
        assert_eq!(rows_with_reentry(&[]), None);
    }

    fn cut(zeta: f64, displacement: Vec<f64>, reentered: Vec<bool>) -> Cut {
        let n = displacement.len();
        Cut {
            zeta,
            a_r: 0.5,
            heights: vec![0.0; n],
            displacement,
            reentered,
        }
    }

    #[test]
    fn shape_change_is_one_minus_the_correlation_of_the_last_two_cuts() {
        let u = vec![0.0, 1.0, 3.0, 2.0];
        // An affine copy keeps the shape; a reversed profile is anti-correlated.
        let scaled: Vec<f64> = u.iter().map(|x| 2.0 * x + 5.0).collect();
        let reversed: Vec<f64> = u.iter().rev().copied().collect();
        let marks = vec![false, true, false, false];
        let r = |cuts| WaterfallResult {
            row: 0,
            p0: 0.1,
            cuts,
            row_reentries: vec![0, 1, 0, 2],
        };
        let kept = r(vec![
            cut(2.0, reversed.clone(), vec![false; 4]),
            cut(4.0, u.clone(), vec![false; 4]),
            cut(8.0, scaled, marks.clone()),
        ]);
        assert!(shape_change(&kept).unwrap().abs() < 1e-15);
        assert_eq!(reentered_last(&kept), Some(0.25));
        let flipped = r(vec![
            cut(4.0, u.clone(), marks.clone()),
            cut(8.0, reversed, marks),
        ]);
        // r(u, reversed u) = -0.6 for this profile: 1 - r = 1.6.
        assert!((shape_change(&flipped).unwrap() - 1.6).abs() < 1e-12);
        assert_eq!(shape_change(&r(vec![cut(8.0, u, vec![false; 4])])), None);
        let one = WaterfallStats::of(&[&kept]).unwrap();
        assert_eq!((one.realizations, one.row), (1, 0));
        assert!(one.shape_change.std_error.is_nan());
        assert_eq!(one.rows_with_reentry.unwrap().value, 0.5);
        // Two realizations: means over them, with error bars.
        let two = WaterfallStats::of(&[&kept, &flipped]).unwrap();
        assert!((two.shape_change.value - 0.8).abs() < 1e-12, "{two:?}");
        assert!(two.shape_change.std_error > 0.0);
        // A result stored before the rows were counted; no result at all.
        let old = WaterfallResult {
            row_reentries: Vec::new(),
            ..kept
        };
        assert_eq!(WaterfallStats::of(&[&old]).unwrap().rows_with_reentry, None);
        assert_eq!(WaterfallStats::of(&[]), None);
    }

    #[test]
    fn the_labels_name_the_plans_panels_and_the_runs_realizations() {
        let plan = WaterfallPlan {
            seed: 1,
            more_seeds: Vec::new(),
            zetas: vec![4.0, 8.5],
            contact_area: 0.1,
            solver: SolverKind::Cg,
        };
        let u = vec![0.0, 1.0, 3.0, 2.0];
        let result = WaterfallResult {
            row: 3,
            p0: 0.1,
            cuts: vec![
                cut(4.0, u.clone(), vec![false; 4]),
                cut(8.5, u, vec![false, true, false, false]),
            ],
            row_reentries: vec![0, 0, 0, 1],
        };
        // The waterfall's statistics stand for the experiment's.
        let stats = |results: &[&WaterfallResult]| WaterfallStats::of(results);
        let details = |plan: &WaterfallPlan, s: &Option<WaterfallStats>| {
            let mut t = DetailTable::default();
            rows(&mut t, plan, Option::as_ref);
            t.details(s)
        };
        // One realization: the figure's row and the error over blocks of rows.
        let one = stats(&[&result]);
        let d = details(&plan, &one);
        assert_eq!(d.len(), 3);
        assert_eq!(
            d[0].name,
            "1 - Pearson correlation of the displacement along the waterfall's cut, zeta = \
             4 against 8.5 (row 3, one realization)"
        );
        assert_eq!(
            d[1].name,
            "share of the cut's points re-entered at zeta = 8.5 (in contact, out in a panel \
             above)"
        );
        assert_eq!(
            d[2].name,
            "share of the grid rows holding a point re-entered in some panel (in contact, \
             out in a panel above), zeta = 4, 8.5; error over 16 blocks of rows, one \
             realization"
        );
        assert_eq!(d[1].value.value, 0.25);
        // Two: the realizations, each its busiest row.
        let more = WaterfallPlan {
            more_seeds: vec![2],
            ..plan.clone()
        };
        let d = details(&more, &stats(&[&result, &result]));
        assert!(d[0]
            .name
            .ends_with("(each realization's busiest row, 2 realizations)"));
        assert!(d[2].name.ends_with("; error over 2 realizations"));
        // Without a waterfall's result: declared, not written.
        let mut t = DetailTable::default();
        rows(&mut t, &plan, Option::as_ref);
        assert_eq!(t.keys().detail_names().len(), 3);
        assert!(t.details(&stats(&[])).is_empty());
    }
}
