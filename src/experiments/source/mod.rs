//! The absorbing boundary as a source: the share of the zero-pressure bin that moves into
//! contact in one step of magnification, assumption (c) ([`crate::conventions`], section 6,
//! row c; paper section 3.3 and figure "reentry_histogram").
//!
//! In Persson's diffusion picture a walker at `p = 0` is absorbed: the transition
//! probability out of the zero-pressure bin is 0. The paper finds "about 1% of all points
//! previously in noncontact reenter contact" for a step from `zeta = 63` to `63.3`, and
//! calls the boundary a "source". Which scene and which bin it means is open: the text
//! states the transition scene (H = 0.5, a_r = 0.01), the bins of its transition analysis
//! are `n dp <= p < (n + 1) dp`, so a zero bin of finite width also holds the lowest
//! pressures in contact, and "of all points" may be read over the non-contact or over the
//! nominal area. This experiment measures every reading:
//!
//! * each row of the scene (`steps`: a Hurst exponent, the contact area that sets the load
//!   at `zeta`, `zeta` and the step `dzeta`) is solved at `zeta`, at the load that gives the
//!   row's contact area there, and again at `zeta + dzeta` at the same load (warm start),
//!   on every realization;
//! * for each width `w` of the zero bin (`bin_widths`, units of `p0 / a_r`, the mean
//!   pressure in contact at `zeta`), the points with `p(zeta)` in `[0, w p0 / a_r)` (for
//!   `w = 0`: `p = 0`, the non-contact) that lie above the bin after the step (for
//!   `w = 0`: in contact) are counted ([`count`], through the one classification of
//!   [`crate::experiments::contact_change`]), with the non-contact, the contact and all
//!   points;
//! * the statistics ([`stats`]) divide the count by each denominator per realization:
//!   the share of the non-contact, of the contact and of the nominal area `A0` (and of the
//!   bin itself), each a mean over realizations with its standard error.
//!
//! The headline is the share of the non-contact entering contact (`w = 0`) in the first
//! row, the paper's stated scene (Persson: 0). The study "one_percent_readings"
//! ([`study`]) shows every row, width and denominator, and its notes say which readings
//! come within the rule of the definition's claim of the paper's "about 1%".
//!
//! # Files
//!
//! * `mod.rs`: the scene, its jobs (the step and its counts) and the [`Experiment`]
//!   implementation;
//! * `stats.rs`: the shares, means over realizations;
//! * `study.rs`: the study of every reading, with its notes;
//! * `figures.rs`: the account, the table and the figure.

mod figures;
pub mod stats;
pub mod study;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use self::stats::SourceStats;
use super::contact_change::{above, across, ENTERED, NEITHER};
use super::declared::DetailTable;
use super::scene::{Base, Step};
use super::study::Study;
use super::{Criteria, Experiment, JobContext, Jobs, Keys, Table, Work};
use crate::engine::solver::SolverKind;
use crate::error::{Error, Result};
use crate::plot::Figure;
use crate::stats::{realizations, round_sig, Estimate};

/// One row of the scene: a surface and one step of magnification at fixed load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SourceStep {
    /// Hurst exponent, in (0, 1).
    pub hurst: f64,
    /// Relative contact area at `zeta` (sets the load).
    pub contact_area: f64,
    /// Magnification before the step.
    pub zeta: f64,
    /// The step.
    pub dzeta: f64,
}

/// The fields of a row, as errors name them inside `steps[k]`.
const ROW_FIELDS: [&str; 4] = ["hurst", "contact_area", "zeta", "dzeta"];

impl SourceStep {
    /// A stable key: `H0.5_a0.01_z63`.
    pub fn key(&self) -> String {
        format!("H{}_a{}_z{}", self.hurst, self.contact_area, self.zeta)
    }

    /// In words: `H = 0.5, a_r = 0.01, zeta 63 -> 63.3`.
    pub fn label(&self) -> String {
        format!(
            "H = {}, a_r = {}, zeta {} -> {}",
            self.hurst,
            self.contact_area,
            self.zeta,
            self.zeta + self.dzeta
        )
    }
}

/// Scene of the source experiment. The surface's Hurst exponent is a field of each row
/// (`steps`), so the scene lists the other common fields itself rather than through
/// `scene!`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SourceScene {
    /// Points per side.
    pub n: usize,
    /// Long-wavelength cutoff (grid units).
    pub lambda_l: f64,
    /// Short-wavelength cutoff (grid units).
    pub lambda_s: f64,
    /// Realizations.
    pub seeds: Vec<u64>,
    /// Residual tolerance.
    pub tol: f64,
    /// The solver of every solve (the scene fixes it: the readings compare scenes, not
    /// solvers).
    pub solver: SolverKind,
    /// The rows; the first is the headline's.
    pub steps: Vec<SourceStep>,
    /// Widths of the zero-pressure bin, units of `p0 / a_r`: increasing, from 0 (the
    /// non-contact alone).
    pub bin_widths: Vec<f64>,
}

impl SourceScene {
    /// The fields every scene shares, with the Hurst exponent `hurst` of a row.
    pub fn base(&self, hurst: f64) -> Base<'_> {
        Base::new(
            self.n,
            hurst,
            self.lambda_l,
            self.lambda_s,
            &self.seeds,
            self.tol,
        )
    }

    /// The grid and seeds in words: `"4 realizations (128x128, lambda_l = 64, lambda_s =
    /// 4)"`.
    fn runs(&self) -> String {
        format!(
            "{} ({}x{}, lambda_l = {}, lambda_s = {})",
            realizations(self.seeds.len()),
            self.n,
            self.n,
            self.lambda_l,
            self.lambda_s
        )
    }
}

/// An error about row `k` names the field inside `steps[k]`.
fn in_row(k: usize, e: Error) -> Error {
    let field = match &e {
        Error::InvalidInput { field, .. } if ROW_FIELDS.contains(&field.as_str()) => {
            format!("steps[{k}].{field}")
        }
        _ => return e,
    };
    e.with_field(&field)
}

/// A job: one realization of one row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SourceJob {
    /// The row.
    pub step: SourceStep,
    /// The realization.
    pub seed: u64,
}

/// What one realization's step measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SourceResult {
    /// Load.
    pub p0: f64,
    /// Contact area at `zeta`.
    pub a_r_before: f64,
    /// Contact area at `zeta + dzeta`.
    pub a_r_after: f64,
    /// The counts, for each bin width of the scene.
    pub counts: BinCounts,
    /// Largest solver residual.
    pub max_residual: f64,
}

/// Counts of one step, for bins `[0, t)` of several widths `t` (`t = 0`: the non-contact,
/// `p = 0`). Counts, not shares, so that the statistics can form any share.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct BinCounts {
    /// Every point of the grid.
    pub points: u64,
    /// Points out of contact before the step (`p = 0`).
    pub non_contact: u64,
    /// Points in contact before the step (`p > 0`).
    pub contact: u64,
    /// For each width, the points in the bin before the step.
    pub in_bin: Vec<u64>,
    /// For each width, the points in the bin before the step and above it after (for
    /// `t = 0`: the points that entered contact).
    pub rose: Vec<u64>,
}

/// The counts of a step from the pressures `before` and `after` of every point, for the
/// bins below each of `thresholds` (pressures, each `>= 0`).
pub fn count(before: &[f64], after: &[f64], thresholds: &[f64]) -> BinCounts {
    assert_eq!(before.len(), after.len(), "one pressure per point at both");
    let mut c = BinCounts {
        points: before.len() as u64,
        non_contact: 0,
        contact: 0,
        in_bin: vec![0; thresholds.len()],
        rose: vec![0; thresholds.len()],
    };
    for (&b, &a) in before.iter().zip(after) {
        if above(b, 0.0) {
            c.contact += 1;
        } else {
            c.non_contact += 1;
        }
        for (k, &t) in thresholds.iter().enumerate() {
            match across(b, a, t) {
                ENTERED => {
                    c.in_bin[k] += 1;
                    c.rose[k] += 1;
                }
                NEITHER => c.in_bin[k] += 1,
                _ => {}
            }
        }
    }
    c
}

impl Jobs for SourceScene {
    const FAMILY: &'static str = "source";
    type Job = SourceJob;
    type JobResult = SourceResult;

    fn validate(&self) -> Result<()> {
        if self.steps.is_empty() {
            return Err(Error::invalid(
                "steps",
                "[]",
                "at least one row { hurst, contact_area, zeta, dzeta }",
            ));
        }
        for (k, s) in self.steps.iter().enumerate() {
            self.base(s.hurst)
                .validate_step(s.contact_area, s.zeta, s.dzeta)
                .map_err(|e| in_row(k, e))?;
            if let Some(j) = self.steps[..k].iter().position(|o| o == s) {
                return Err(Error::invalid(
                    &format!("steps[{k}]"),
                    s.label(),
                    format!("a row different from steps[{j}]"),
                ));
            }
        }
        super::scene::check_increasing("bin_widths", &self.bin_widths)?;
        if self.bin_widths[0] != 0.0 || !self.bin_widths.iter().all(|w| w.is_finite()) {
            return Err(super::scene::list_error(
                "bin_widths",
                &self.bin_widths,
                "finite widths starting at 0 (the non-contact alone), e.g. [0, 0.01, 0.1]",
            ));
        }
        Ok(())
    }

    fn solver(&self) -> Option<SolverKind> {
        Some(self.solver)
    }

    fn jobs(&self) -> Vec<SourceJob> {
        self.steps
            .iter()
            .flat_map(|step| {
                self.seeds.iter().map(|&seed| SourceJob {
                    step: step.clone(),
                    seed,
                })
            })
            .collect()
    }

    fn work(&self, _job: &SourceJob) -> Work {
        // The load at zeta, then one step of dzeta.
        Work::search_then(self.n, 1, 0)
    }

    fn run_job(&self, job: &SourceJob, ctx: &JobContext) -> Result<SourceResult> {
        let s = &job.step;
        let base = self.base(s.hurst);
        let r = base.realization(job.seed)?;
        let Step { p0, before, after } =
            base.step(&r, ctx.solver, s.zeta, s.dzeta, s.contact_area)?;
        let a_r_before = before.contact_area();
        let unit = p0 / a_r_before;
        let thresholds: Vec<f64> = self.bin_widths.iter().map(|w| w * unit).collect();
        Ok(SourceResult {
            p0,
            a_r_before,
            a_r_after: after.contact_area(),
            counts: count(&before.pressure, &after.pressure, &thresholds),
            max_residual: before
                .stats
                .residual
                .value()
                .max(after.stats.residual.value()),
        })
    }

    fn residual(result: &SourceResult) -> f64 {
        result.max_residual
    }
}

/// The key of a row's detail: the share of its non-contact entering contact.
fn non_contact_key(step: &SourceStep) -> String {
    format!("non_contact_{}", step.key())
}

/// The keys of the headline row's other details ([`Experiment::detail_table`]).
const OF_CONTACT: &str = "of_contact";
const OF_NOMINAL: &str = "of_nominal";
const CONTACT_AREA_BEFORE: &str = "contact_area_before";
const CONTACT_AREA_AFTER: &str = "contact_area_after";

/// The experiment: Persson's absorbing boundary, read as a source of contact.
pub struct BoundarySource;

type Run<'a> = super::Run<'a, BoundarySource>;

impl Experiment for BoundarySource {
    type Scene = SourceScene;
    type Stats = SourceStats;
    const PAPER_CLAIMS: &'static [&'static str] = &[study::CLAIM];

    fn stats(run: &Run) -> Result<SourceStats> {
        SourceStats::of(run.scene, run.results)
    }

    fn headline(s: &SourceStats) -> (Estimate, f64) {
        (s.headline(), 0.0)
    }

    /// Every row's share of the non-contact entering contact, and the headline row's
    /// other shares and contact areas.
    fn detail_table<'s>(
        scene: &'s SourceScene,
        _criteria: &'s Criteria,
    ) -> DetailTable<'s, SourceStats> {
        let mut t = DetailTable::default();
        for step in &scene.steps {
            t.row(
                non_contact_key(step),
                format!(
                    "share of the non-contact at zeta in contact after the step ({})",
                    step.label()
                ),
                move |s: &SourceStats| s.row(step).map(|r| r.readings[0].of_non_contact),
            )
            .persson(0.0);
        }
        t.always(
            OF_CONTACT,
            "points entering contact, share of the contact at zeta (first row)",
            |s: &SourceStats| s.rows[0].readings[0].of_contact,
        );
        t.always(
            OF_NOMINAL,
            "points entering contact, share of the nominal area A0 (first row)",
            |s: &SourceStats| s.rows[0].readings[0].of_nominal,
        );
        t.always(
            CONTACT_AREA_BEFORE,
            "a_r at zeta (first row)",
            |s: &SourceStats| s.rows[0].contact_before,
        );
        t.always(
            CONTACT_AREA_AFTER,
            "a_r at zeta + dzeta (first row)",
            |s: &SourceStats| s.rows[0].contact_after,
        );
        t
    }

    fn declare_studies(_scene: &SourceScene, keys: &mut Keys) {
        keys.study(study::STUDY, &study::COLUMNS);
    }

    /// Every row's share of the non-contact entering contact and share of the widest bin
    /// rising above it, rounded.
    fn golden(_run: &Run, s: &SourceStats) -> BTreeMap<String, f64> {
        s.rows
            .iter()
            .flat_map(|r| {
                let widest = r.readings.last().expect("a reading per bin width");
                [
                    (
                        format!("non_contact_{}", r.step.key()),
                        round_sig(r.readings[0].of_non_contact.value, 2),
                    ),
                    (
                        format!("widest_bin_{}", r.step.key()),
                        round_sig(widest.of_bin.value, 2),
                    ),
                ]
            })
            .collect()
    }

    fn studies(run: &Run, s: &SourceStats) -> Vec<Study> {
        vec![study::study(run.criteria, s)]
    }

    fn account(run: &Run, s: &SourceStats) -> String {
        figures::account(&run.scene.runs(), run.criteria, s)
    }

    fn tables(run: &Run, s: &SourceStats) -> Vec<Table> {
        vec![figures::table(&run.criteria.name, s)]
    }

    fn figures(run: &Run, s: &SourceStats) -> Vec<Figure> {
        vec![figures::non_contact_figure(run.criteria, s)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::{assert_refused, shipped_valid};

    #[test]
    fn shipped_scenes_are_valid_and_open_with_the_papers_scene() {
        let (reduced, full) = shipped_valid::<BoundarySource>("c_source");
        let first = &full.steps[0];
        assert_eq!(
            (first.hurst, first.contact_area, first.zeta, first.dzeta),
            (0.5, 0.01, 63.0, 0.3)
        );
        assert_eq!(full.n, 1024);
        assert_eq!(reduced.steps[0].hurst, 0.5);
        assert_eq!(
            reduced.jobs().len(),
            reduced.steps.len() * reduced.seeds.len()
        );
    }

    #[test]
    fn bad_scenes_are_refused_naming_the_field() {
        let (scene, _) = shipped_valid::<BoundarySource>("c_source");
        let refused = |edit: &dyn Fn(&mut SourceScene), field: &str| {
            let mut s = scene.clone();
            edit(&mut s);
            assert_refused::<BoundarySource>(&s, field);
        };
        refused(&|s| s.steps.clear(), "steps");
        refused(&|s| s.steps[1].hurst = 1.2, "steps[1].hurst");
        refused(&|s| s.steps[0].contact_area = 0.0, "steps[0].contact_area");
        refused(&|s| s.steps[0].zeta = 0.5, "steps[0].zeta");
        refused(&|s| s.steps[1].dzeta = 1e3, "steps[1].dzeta");
        refused(&|s| s.steps[0].dzeta = -0.1, "steps[0].dzeta");
        refused(
            &|s| {
                let first = s.steps[0].clone();
                s.steps.push(first);
            },
            &format!("steps[{}]", scene.steps.len()),
        );
        refused(&|s| s.bin_widths = vec![0.01, 0.1], "bin_widths");
        refused(&|s| s.bin_widths = vec![0.0, 0.1, 0.05], "bin_widths");
        refused(&|s| s.bin_widths.clear(), "bin_widths");
        refused(&|s| s.seeds.clear(), "seeds");
        refused(&|s| s.lambda_s = 1.0, "lambda_s");
    }

    #[test]
    fn counts_follow_a_hand_made_step() {
        // Six points: two out of contact (one enters at 0.05, one stays out), a low one
        // (0.02) that rises to 0.3, a low one (0.04) that leaves, one at 0.5 that stays
        // high and one at 1.0 that falls to 0.08.
        let before = [0.0, 0.0, 0.02, 0.04, 0.5, 1.0];
        let after = [0.05, 0.0, 0.3, 0.0, 0.6, 0.08];
        let c = count(&before, &after, &[0.0, 0.1]);
        assert_eq!((c.points, c.non_contact, c.contact), (6, 2, 4));
        // t = 0: the bin holds the two out of contact, and the first entered contact.
        // t = 0.1: the bin [0, 0.1) holds the four points below 0.1; only 0.02 -> 0.3
        // rises above it (0 -> 0.05 stays in it, 0.04 -> 0 too).
        assert_eq!(c.in_bin, vec![2, 4]);
        assert_eq!(c.rose, vec![1, 1]);
        // A point that falls into the bin from above is not counted as rising.
        let c = count(&[1.0], &[0.0], &[0.0, 0.5]);
        assert_eq!((c.in_bin, c.rose), (vec![0, 0], vec![0, 0]));
    }
}
