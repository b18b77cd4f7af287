//! What a variant's histories add up to: the statistics of each load (means over its
//! realizations), the variants' study, the contact map of a variant's first history, and
//! the details the claims read, each keyed `<variant>_<statistic>_ar<load>` ([`key`]).

use super::{Variant, VariantJob, VariantResult};
use crate::experiments::contact_change::unpack_categories;
use crate::experiments::declared::{value_at, DetailTable};
use crate::experiments::keys::{DetailKey, Tag};
use crate::experiments::reentry::shells::ShellStats;
use crate::experiments::reentry::stats::Share;
use crate::experiments::reentry::RunStats;
use crate::experiments::study::{with_settings, Cell, Study};
use crate::plot::Raster;
use crate::stats::Estimate;

/// The statistics of one load of a variant, means over its realizations.
#[derive(Debug, Clone, PartialEq)]
pub struct VariantLoad {
    /// The load (contact area at `zeta_max`).
    pub load: f64,
    /// Realizations that have a result.
    pub realizations: usize,
    /// Re-entry share of the final contact.
    pub share: Estimate,
    /// Share of the contact at the first step in contact at every step.
    pub remained_of_start: Estimate,
    /// Coloured over grey points.
    pub coloured_over_grey: Estimate,
    /// Contact area at the first step.
    pub a_r_start: Estimate,
    /// Shells a history added after its first step.
    pub shells: Estimate,
    /// Solver iterations per shell.
    pub iterations_per_shell: Estimate,
    /// The shell statistics, where the variant records its shells.
    pub per_shell: Option<ShellStats>,
}

/// The statistics of every load of `variant` from its histories (`None` where a seed has
/// no result).
pub fn loads(variant: &Variant, results: &[(VariantJob, VariantResult)]) -> Vec<VariantLoad> {
    variant
        .contact_areas
        .iter()
        .map(|&a| {
            let runs: Vec<&VariantResult> = variant
                .seeds
                .iter()
                .filter_map(|&s| {
                    let job = variant.job(s, a);
                    results.iter().find(|(j, _)| *j == job).map(|(_, r)| r)
                })
                .collect();
            let mean = |f: &dyn Fn(&VariantResult) -> f64| {
                Estimate::mean_of(&runs.iter().map(|r| f(r)).collect::<Vec<_>>())
            };
            VariantLoad {
                load: a,
                realizations: runs.len(),
                share: mean(&VariantResult::share),
                remained_of_start: mean(&VariantResult::remained_of_start),
                coloured_over_grey: mean(&VariantResult::coloured_over_grey),
                a_r_start: mean(&|r| r.a_r_start(variant.n)),
                shells: crate::experiments::reentry::stats::shells(runs.iter().map(|r| r.shells)),
                iterations_per_shell: mean(&|r| r.iterations as f64 / r.shells.max(1) as f64),
                per_shell: ShellStats::of(
                    &runs
                        .iter()
                        .filter_map(|r| r.per_shell.as_ref())
                        .collect::<Vec<_>>(),
                ),
            }
        })
        .collect()
}

/// A variant scene's statistics.
pub struct VariantStats {
    /// The variant.
    pub variant: Variant,
    /// Its loads.
    pub loads: Vec<VariantLoad>,
    /// The map of its first history, if run.
    pub map: Option<String>,
    /// The shares of the grid with the same cutoffs on another number of points, where
    /// the scene has one ([`crate::experiments::reentry::range::same_cutoffs`]): its `n` and `(load, share)`.
    pub same_cutoffs: Option<(usize, Vec<(f64, Estimate)>)>,
}

/// The shares of the grid with a variant's cutoffs on another number of points.
pub type SameCutoffs<'a> = &'a dyn Fn(&Variant) -> Option<(usize, Vec<(f64, Estimate)>)>;

/// The statistics of every variant from the histories among `results`.
pub fn stats(
    variants: &[Variant],
    results: &[(VariantJob, VariantResult)],
    same_cutoffs: SameCutoffs,
) -> Vec<VariantStats> {
    variants
        .iter()
        .map(|v| VariantStats {
            variant: v.clone(),
            loads: loads(v, results),
            map: results
                .iter()
                .find(|(j, _)| *j == v.job(v.seeds[0], v.contact_areas[0]))
                .and_then(|(_, r)| r.map.clone()),
            same_cutoffs: same_cutoffs(v),
        })
        .collect()
}

/// The variants' study: its key and columns, `(key, label)`.
pub const STUDY: &str = "variants";

/// The columns of [`STUDY`].
pub fn columns() -> Vec<(&'static str, &'static str)> {
    with_settings(
        &[
            "n",
            "hurst",
            "lambda_l",
            "lambda_s",
            "zeta_from",
            "contact_area",
            "realizations",
            "tol",
        ],
        &[
            ("share", "re-entry share"),
            ("headline_share", "the headline's share at this load"),
            ("a_r_start", "a_r at the first step"),
            (
                "remained_of_start",
                "contact at the first step in contact throughout",
            ),
            (
                "coloured_over_grey",
                "re-entered (red, blue) over always in contact (grey)",
            ),
            ("shells", "shells added one at a time"),
            ("iterations_per_shell", "solver iterations a shell"),
        ],
    )
}

/// The variants' table: one row per variant and load, beside the headline's share at
/// that load.
pub fn study(variants: &[VariantStats], headline: &[Share]) -> Study {
    let mut study = Study::new(
        STUDY,
        "Re-entry histories of scenes beside the headline's",
        &columns(),
    )
    .about(
        "Each row: one variant scene at one load, the mean over its realizations with the \
         standard error. Every history climbs at fixed load through every shell, as the \
         headline's; a variant that starts at zeta_from > 0 solves its first step with every \
         shell up to zeta_from, and a point out of contact there counts as having been out.",
    )
    .percent(&["share", "headline_share", "a_r_start", "remained_of_start"]);
    for v in variants {
        let x = &v.variant;
        for l in &v.loads {
            let head = headline.iter().find(|h| h.load == l.load).map(|h| h.share);
            study.push(
                format!("{}_ar{}", x.name, l.load),
                format!("{}, a_r {}", x.what, l.load),
                vec![
                    Cell::from(x.n as f64),
                    Cell::from(x.hurst),
                    Cell::from(x.lambda_l),
                    Cell::from(x.lambda_s),
                    Cell::from(x.zeta_from),
                    Cell::from(l.load),
                    Cell::from(l.realizations as f64),
                    Cell::from(x.tol),
                    Cell::from(l.share),
                    Cell::from(head),
                    Cell::from(l.a_r_start),
                    Cell::from(l.remained_of_start),
                    Cell::from(l.coloured_over_grey),
                    Cell::from(l.shells),
                    Cell::from(l.iterations_per_shell),
                ],
            );
        }
    }
    study
}

/// The contact map at `zeta_max` of a variant's first history, coloured as the paper's
/// re-entry figures (none before it has run).
pub fn raster(v: &VariantStats) -> Option<Raster> {
    let map = v.map.as_deref()?;
    let x = &v.variant;
    Some(Raster {
        name: format!("reentry_map_{}", x.name),
        title: format!(
            "{}: contact at zeta_max = {}, a_r = {} (seed {}), history of every point from \
             zeta = {}",
            x.what,
            x.lambda_l / x.lambda_s,
            x.contact_areas[0],
            x.seeds[0],
            if x.zeta_from > 0.0 { x.zeta_from } else { 1.0 },
        ),
        n: x.n,
        pixels: unpack_categories(map, x.n * x.n),
        palette: crate::experiments::reentry::figures::history_palette(),
    })
}

/// The keys of a variant's details at load `a`: its share, the share's shift from the
/// headline's, and for a variant that starts later, the contact area at its start, the
/// share of it that remained, and the re-entered over the always-in-contact.
/// The key of statistic `stat` of variant `name` at load `a`.
pub fn key(name: &str, stat: &str, a: f64) -> DetailKey {
    DetailKey::new(format!("{name}_{stat}")).at(Tag::ContactArea, a)
}
const SHARE: &str = "share";
const SHIFT: &str = "share_shift";
const START: &str = "a_r_start";
const REMAINED: &str = "remained_of_start";
const COLOURED: &str = "coloured_over_grey";
const SIZE_SHIFT: &str = "size_shift";

/// The headline a variant is set against: its loads and its `zeta_max`.
#[derive(Debug, Clone, Copy)]
pub struct Headline<'a> {
    /// The headline's loads.
    pub loads: &'a [f64],
    /// The headline's `zeta_max`.
    pub zeta_max: f64,
}

impl Headline<'_> {
    /// Whether `variant`'s share at load `a` is set against the headline's: a variant from
    /// the flat interface over the headline's range of magnification, at one of its loads,
    /// that does not repeat the headline's scene (as one that records its shells does).
    pub fn compares(&self, variant: &Variant, a: f64) -> bool {
        let same_range = (variant.base().zeta_max() / self.zeta_max - 1.0).abs() < 1e-9;
        variant.zeta_from == 0.0 && same_range && !variant.record_shells && self.loads.contains(&a)
    }
}

/// The statistics of variant `name`, where the run has them.
fn stats_of<'a>(s: &'a RunStats, name: &str) -> Option<&'a VariantStats> {
    s.variants.iter().find(|v| v.variant.name == name)
}

/// The statistics of variant `name` at load `a`, where it has realizations.
fn at<'a>(s: &'a RunStats, name: &str, a: f64) -> Option<&'a VariantLoad> {
    stats_of(s, name)?
        .loads
        .iter()
        .find(|l| l.load == a && l.realizations > 0)
}

/// Declares the details of a variant, beside `headline`, with the `n` of a grid of the
/// same cutoffs on another number of points or without: its shares; their shift from
/// the headline's where it starts from the flat interface too over the same range on
/// another scene ([`Headline::compares`]); their shift from the shares of the grid with
/// the same cutoffs; where it starts later, the counts of the paper's 2048^2 figure; and
/// where it records its shells, their statistics ([`ShellStats::labels`]). A load without
/// realizations has none.
pub fn declare<'s>(
    t: &mut DetailTable<'s, RunStats>,
    variant: &'s Variant,
    headline: Headline,
    same_cutoffs: Option<usize>,
) {
    let (name, what) = (variant.name.as_str(), &variant.what);
    for &a in &variant.contact_areas {
        t.row(
            key(name, SHARE, a),
            format!("re-entry share at a_r = {a}, {what}"),
            move |s: &RunStats| at(s, name, a).map(|l| l.share),
        )
        .persson(0.0);
        if let Some(n) = same_cutoffs {
            t.row(
                key(name, SIZE_SHIFT, a),
                format!(
                    "re-entry share at a_r = {a}, {what}, minus that on {n}^2 with the \
                     same lambda_l, lambda_s and tolerance (independent realizations)"
                ),
                move |s: &RunStats| {
                    let l = at(s, name, a)?;
                    let (_, shares) = stats_of(s, name)?.same_cutoffs.as_ref()?;
                    let other = value_at(shares, a)?;
                    Some(Estimate::difference(l.share, other))
                },
            );
        }
        if variant.zeta_from == 0.0 {
            if headline.compares(variant, a) {
                t.row(
                    key(name, SHIFT, a),
                    format!("re-entry share at a_r = {a}, {what}, minus the headline's"),
                    move |s: &RunStats| {
                        let l = at(s, name, a)?;
                        let h = s.shares.iter().find(|h| h.load == a)?;
                        Some(Estimate::difference(l.share, h.share))
                    },
                );
            }
        } else {
            declare_start(t, variant, a);
        }
        if variant.record_shells {
            for (k, (stat, text)) in ShellStats::labels(a, what).into_iter().enumerate() {
                t.row(key(name, stat, a), text, move |s: &RunStats| {
                    Some(at(s, name, a)?.per_shell.as_ref()?.values()[k])
                });
            }
        }
    }
}

/// Declares the counts of the paper's 2048^2 figure at load `a` of a variant that starts
/// later: the contact area at its start, the share of it that remained, and the
/// re-entered over the always-in-contact.
fn declare_start<'s>(t: &mut DetailTable<'s, RunStats>, variant: &'s Variant, a: f64) {
    let (name, what, from) = (variant.name.as_str(), &variant.what, variant.zeta_from);
    t.row(
        key(name, START, a),
        format!("contact area at zeta = {from}, a_r = {a} at zeta_max, {what}"),
        move |s: &RunStats| at(s, name, a).map(|l| l.a_r_start),
    );
    t.row(
        key(name, REMAINED, a),
        format!(
            "share of the contact at zeta = {from} in contact at every step \
             (grey), a_r = {a}, {what}"
        ),
        move |s: &RunStats| at(s, name, a).map(|l| l.remained_of_start),
    );
    t.row(
        key(name, COLOURED, a),
        format!(
            "points that re-entered contact or non-contact (red, blue) over \
             points in contact throughout (grey), a_r = {a}, {what}"
        ),
        move |s: &RunStats| at(s, name, a).map(|l| l.coloured_over_grey),
    );
}

#[cfg(test)]
mod tests {
    use super::super::tests::variant;
    use super::*;

    #[test]
    fn only_a_variant_over_the_headline_s_range_is_set_against_it() {
        // variant(): 64^2, lambda_l = 32, lambda_s = 4: zeta 1 -> 8.
        let loads = [0.14, 0.014];
        let headline = Headline {
            loads: &loads,
            zeta_max: 8.0,
        };
        let v = variant();
        assert!(headline.compares(&v, 0.14));
        // A load the headline lacks, a later start, a repeat of the headline's scene and
        // another range are not.
        assert!(!headline.compares(&v, 0.88));
        for other in [
            Variant {
                zeta_from: 2.0,
                ..variant()
            },
            Variant {
                record_shells: true,
                ..variant()
            },
            Variant {
                lambda_s: 2.0,
                ..variant()
            },
        ] {
            assert!(!headline.compares(&other, 0.14), "{other:?}");
        }
        let keys = |same_cutoffs| {
            let mut t = DetailTable::default();
            declare(&mut t, &v, headline, same_cutoffs);
            t.keys().detail_keys().cloned().collect::<Vec<DetailKey>>()
        };
        let with = keys(Some(512));
        assert!(with.contains(&"h03_share_shift_ar0.14".into()));
        assert!(!with.contains(&"h03_share_shift_ar0.88".into()));
        assert!(with.contains(&"h03_size_shift_ar0.88".into()));
        assert!(!keys(None).iter().any(|k| k.stem().contains("size_shift")));
    }
}
