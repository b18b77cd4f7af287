//! Histories of scenes beside the headline's: the same protocol (every shell added one at a
//! time at fixed load, paper section 3.3) on another Hurst exponent, another continuum
//! resolution `eps_c = 1 / lambda_s` or another range of magnification, for the paper's
//! statements that compare scenes:
//!
//! * "the numbers for H = 0.3 lay within 4% of those for H = 0.8" (tex 792-794);
//! * "for eps_c = 1/8 and 1/16, the fractions remain the same" (tex 788-789);
//! * the 2048^2 history from `zeta = 3.2` to 32 (fig. reentry_visualization_allQ, tex
//!   796-816): the share of the points in contact at the start that stayed in contact at
//!   every step (grey), the coloured (re-entered: red and blue) points over the grey ones,
//!   and the share of the final contact that re-entered.
//!
//! A variant starting at `zeta_from > 0` solves its first step with every shell up to
//! `zeta_from` at once; a point out of contact there counts as having been out, as a point
//! out at `zeta = 1` does in the headline's histories (the paper's white: "out of contact
//! at zeta = 3.2 or lost contact exactly once"). The load is the one that gives the
//! variant's contact area at its `zeta_max`, as for the headline.
//!
//! A variant may record its history shell by shell (`record_shells`, [`super::shells`]):
//! the headline's own scene, run again, for the paper's statements about single shells.
//!
//! A variant runs at its own tolerance, the one the tolerance study ([`super::tolerance`])
//! accepted; the committed histories of the headline keep theirs.
//!
//! This file holds a variant's scene, its jobs and its run; what the runs add up to (the
//! statistics of each load, the study, the map and the details) is `findings.rs`.

mod findings;

pub use findings::{
    columns, declare, loads, raster, stats, study, Headline, SameCutoffs, VariantLoad,
    VariantStats, STUDY,
};

use serde::{Deserialize, Serialize};

use super::shells::{ShellLog, ShellRecord};
use super::stats::ratio;
use crate::engine::contact::ContactSolution;
use crate::engine::sweep::shell_steps;
use crate::error::{check_key_name, check_positive, Error, Result};
use crate::experiments::climb::{climb_job, Arrays, Recorder};
use crate::experiments::contact_change::pack_categories;
use crate::experiments::ensemble::check_contact_areas;
use crate::experiments::history::{self, History};
use crate::experiments::scene::{scene, Base};
use crate::experiments::{JobContext, Work};
use crate::io::checkpoint::Checkpoints;

scene! {
    /// A scene beside the headline's, as a definition states it (`[[full.variants]]`): the
    /// fields of every scene (its own Hurst exponent, grid, realizations and tolerance),
    /// then its own.
    pub struct Variant {
        /// Short name: the prefix of its statistics' keys.
        pub name: String,
        /// What differs from the headline, in words.
        pub what: String,
        /// Magnification of the first step (0: from the flat interface, the first shell).
        #[serde(default)]
        pub zeta_from: f64,
        /// Contact areas at `zeta_max` (the loads).
        pub contact_areas: Vec<f64>,
        /// Records every shell's entries and departures ([`super::shells`]).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        pub record_shells: bool,
    }
}

/// One history of a variant: everything it depends on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VariantJob {
    /// Points per side.
    pub n: usize,
    /// Hurst exponent.
    pub hurst: f64,
    /// Long-wavelength cutoff (grid units).
    pub lambda_l: f64,
    /// Short-wavelength cutoff (grid units).
    pub lambda_s: f64,
    /// Magnification of the first step (0: the first shell).
    pub zeta_from: f64,
    /// Realization.
    pub seed: u64,
    /// Contact area at `zeta_max`.
    pub contact_area: f64,
    /// Residual tolerance.
    pub tol: f64,
    /// Records every shell (absent from the keys of histories that do not).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub record_shells: bool,
}

/// What one history of a variant measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariantResult {
    /// Load.
    pub p0: f64,
    /// Points in contact at the first step.
    pub contact_at_start: u64,
    /// Points in contact at `zeta_max`.
    pub contact_points: u64,
    /// Of those, points that were out of contact at some step (the first included).
    pub reentered: u64,
    /// Points in contact at every step (grey).
    pub in_throughout: u64,
    /// Points that re-entered contact or non-contact (red and blue).
    pub coloured: u64,
    /// Shells added after the first step (the first step is one more solve).
    pub shells: usize,
    /// Solver iterations over the climb (the load search excluded).
    pub iterations: u64,
    /// Wall time of the climb, seconds.
    pub wall_s: f64,
    /// Largest residual.
    pub max_residual: f64,
    /// Map categories at `zeta_max` (2 bits a point, hex), for the first seed at the first
    /// load only.
    pub map: Option<String>,
    /// Every shell's entries and departures, where the variant records them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub per_shell: Option<ShellRecord>,
}

impl VariantResult {
    /// The re-entry share of the final contact.
    pub fn share(&self) -> f64 {
        ratio(self.reentered, self.contact_points)
    }

    /// The share of the points in contact at the first step that stayed in contact at
    /// every step.
    pub fn remained_of_start(&self) -> f64 {
        ratio(self.in_throughout, self.contact_at_start)
    }

    /// Coloured (re-entered) points over grey (always in contact) ones.
    pub fn coloured_over_grey(&self) -> f64 {
        ratio(self.coloured, self.in_throughout)
    }

    /// Contact area at the first step.
    pub fn a_r_start(&self, n: usize) -> f64 {
        self.contact_at_start as f64 / (n * n) as f64
    }
}

impl Variant {
    /// The job of `seed` at `contact_area`.
    pub fn job(&self, seed: u64, contact_area: f64) -> VariantJob {
        VariantJob {
            n: self.n,
            hurst: self.hurst,
            lambda_l: self.lambda_l,
            lambda_s: self.lambda_s,
            zeta_from: self.zeta_from,
            seed,
            contact_area,
            tol: self.tol,
            record_shells: self.record_shells,
        }
    }

    /// Every history, loads outermost.
    pub fn jobs(&self) -> Vec<VariantJob> {
        self.contact_areas
            .iter()
            .flat_map(|&a| self.all_seeds().into_iter().map(move |s| self.job(s, a)))
            .collect()
    }

    /// Checks the variant: a valid scene, loads in (0, 1), `zeta_from` in `[0,
    /// zeta_max)`, a name usable as a key; errors name the field.
    pub fn validate(&self) -> Result<()> {
        check_key_name("variants.name", &self.name)?;
        self.base().validate()?;
        check_contact_areas(&self.contact_areas)?;
        let zeta_max = self.base().zeta_max();
        if !(self.zeta_from >= 0.0 && self.zeta_from < zeta_max) {
            return Err(Error::invalid(
                "variants.zeta_from",
                self.zeta_from,
                format!("in [0, zeta_max = {zeta_max})"),
            ));
        }
        Ok(())
    }
}

/// Checks a list of variants: each valid, names and jobs distinct.
pub fn validate_all(variants: &[Variant]) -> Result<()> {
    for (k, v) in variants.iter().enumerate() {
        v.validate()?;
        if variants[..k].iter().any(|w| w.name == v.name) {
            return Err(Error::invalid("variants.name", &v.name, "each name once"));
        }
        let jobs = v.jobs();
        if variants[..k]
            .iter()
            .any(|w| w.jobs().iter().any(|j| jobs.contains(j)))
        {
            return Err(Error::invalid(
                "variants",
                &v.name,
                "scenes that share no history with another variant",
            ));
        }
    }
    Ok(())
}

/// The steps of a variant's climb: `zeta_from` (every shell up to it at once) unless 0,
/// then every shell above it one at a time.
fn steps(surface: &crate::engine::surface::Surface, zeta_from: f64) -> Vec<f64> {
    let mut steps = Vec::new();
    if zeta_from > 0.0 {
        steps.push(zeta_from);
    }
    steps.extend(shell_steps(surface, zeta_from, surface.zeta_max()));
    steps
}

/// What a job costs: a load search, the first step and every shell.
pub fn work(job: &VariantJob) -> Work {
    let b = job_base(job, &[]);
    Work::search_then(
        job.n,
        usize::from(job.zeta_from > 0.0),
        b.shells(job.zeta_from, b.zeta_max()),
    )
}

fn job_base<'a>(job: &VariantJob, seeds: &'a [u64]) -> Base<'a> {
    Base::new(job.n, job.hurst, job.lambda_l, job.lambda_s, seeds, job.tol)
}

/// A history that also counts the contact after its first step, and where asked, records
/// every shell.
struct FromStart {
    history: History,
    contact_at_start: Option<u64>,
    shells: Option<ShellLog>,
}

#[derive(Serialize, Deserialize)]
struct FromStartMeta {
    history: serde_json::Value,
    contact_at_start: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    shells: Option<serde_json::Value>,
}

impl Recorder for FromStart {
    fn record(&mut self, step: usize, zeta: f64, solution: &ContactSolution) -> Result<()> {
        if let Some(log) = self.shells.as_mut() {
            log.update(step, zeta, &solution.pressure);
        }
        self.history.record(step, zeta, solution)?;
        if step == 0 {
            self.contact_at_start =
                Some(self.history.in_contact.iter().map(|&c| u64::from(c)).sum());
        }
        Ok(())
    }

    fn state(&self) -> (serde_json::Value, Arrays<'_>) {
        let (meta, mut arrays) = self.history.state();
        let shells = self.shells.as_ref().map(|log| {
            let (meta, more) = log.state();
            arrays.extend(more);
            meta
        });
        let meta = FromStartMeta {
            history: meta,
            contact_at_start: self.contact_at_start,
            shells,
        };
        (
            serde_json::to_value(meta).expect("checkpoint metadata serialises"),
            arrays,
        )
    }

    fn restore(&mut self, meta: serde_json::Value, ck: &Checkpoints) -> Result<()> {
        let meta: FromStartMeta = serde_json::from_value(meta)
            .map_err(|e| Error::invalid("checkpoint", e, "a variant's re-entry history"))?;
        self.contact_at_start = meta.contact_at_start;
        match (self.shells.as_mut(), meta.shells) {
            (Some(log), Some(m)) => log.restore(m, ck)?,
            (None, None) => {}
            _ => {
                return Err(Error::invalid(
                    "checkpoint",
                    "a shell record",
                    "the same record_shells as the job",
                ))
            }
        }
        self.history.restore(meta.history, ck)
    }
}

/// Runs (or resumes) one history of a variant; `keep_map` keeps its contact map.
pub fn run(
    job: &VariantJob,
    ctx: &JobContext,
    seconds: f64,
    keep_map: bool,
) -> Result<VariantResult> {
    check_positive("variants.tol", job.tol)?;
    let seeds = [job.seed];
    let b = job_base(job, &seeds);
    let r = b.realization(job.seed)?;
    let steps = steps(&r.surface, job.zeta_from);
    let mut rec = FromStart {
        // No flux interval: a variant reads the history only.
        history: History::new(r.model.grid.points(), (f64::INFINITY, f64::INFINITY)),
        contact_at_start: None,
        shells: if job.record_shells {
            Some(ShellLog::new(r.model.grid.points(), steps.len())?)
        } else {
            None
        },
    };
    let climbed = climb_job(&b, ctx, &r, job.contact_area, &steps, &mut rec, seconds)?;
    let categories = rec.history.categories();
    let count = |c: u8| categories.iter().filter(|&&x| x == c).count() as u64;
    let (contact_points, reentered, _) = rec.history.counts();
    Ok(VariantResult {
        p0: climbed.p0,
        contact_at_start: rec.contact_at_start.unwrap_or(0),
        contact_points,
        reentered,
        in_throughout: count(history::IN_THROUGHOUT),
        coloured: count(history::REENTERED) + count(history::OUT_AFTER_RETURN),
        shells: steps.len() - usize::from(job.zeta_from > 0.0),
        iterations: climbed.iterations,
        wall_s: climbed.wall_s,
        max_residual: climbed.max_residual,
        map: keep_map.then(|| pack_categories(&categories)),
        per_shell: rec.shells.map(ShellLog::into_record),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(super) fn variant() -> Variant {
        Variant {
            name: "h03".into(),
            what: "H = 0.3".into(),
            n: 64,
            hurst: 0.3,
            lambda_l: 32.0,
            lambda_s: 4.0,
            zeta_from: 0.0,
            seeds: vec![1, 2],
            more_seeds: Vec::new(),
            contact_areas: vec![0.14, 0.88],
            tol: 1e-6,
            record_shells: false,
        }
    }

    #[test]
    fn variants_are_checked_field_by_field() {
        assert!(validate_all(&[variant()]).is_ok());
        let mut bad = variant();
        bad.name = "h 0.3".into();
        assert!(bad
            .validate()
            .unwrap_err()
            .to_string()
            .contains("variants.name"));
        let mut bad = variant();
        bad.zeta_from = 8.0;
        assert!(bad
            .validate()
            .unwrap_err()
            .to_string()
            .contains("zeta_from"));
        let mut twin = variant();
        twin.name = "other".into();
        let err = validate_all(&[variant(), twin]).unwrap_err().to_string();
        assert!(err.contains("variants"), "{err}");
        let err = validate_all(&[variant(), variant()])
            .unwrap_err()
            .to_string();
        assert!(err.contains("each name once"), "{err}");
    }

    #[test]
    fn counts_from_a_later_start_follow_the_paper_s_colours() {
        // Three points: in throughout; out at the start and in at the end (red); in at
        // the start, out, in, out (blue).
        let mut h = History::new(3, (f64::INFINITY, f64::INFINITY));
        h.update(0, &[1.0, 0.0, 1.0]);
        h.update(1, &[1.0, 1.0, 0.0]);
        h.update(2, &[1.0, 1.0, 1.0]);
        h.update(3, &[1.0, 1.0, 0.0]);
        assert_eq!(
            h.categories(),
            vec![
                history::IN_THROUGHOUT,
                history::REENTERED,
                history::OUT_AFTER_RETURN
            ]
        );
        let r = VariantResult {
            p0: 0.1,
            contact_at_start: 2,
            contact_points: 2,
            reentered: 1,
            in_throughout: 1,
            coloured: 2,
            shells: 3,
            iterations: 0,
            wall_s: 0.0,
            max_residual: 0.0,
            map: None,
            per_shell: None,
        };
        assert_eq!(r.remained_of_start(), 0.5);
        assert_eq!(r.coloured_over_grey(), 2.0);
        assert_eq!(r.share(), 0.5);
    }

    #[test]
    fn a_later_start_is_one_step_then_the_shells_above_it() {
        let v = Variant {
            zeta_from: 2.0,
            ..variant()
        };
        let b = v.base();
        let r = b.realization(1).unwrap();
        let s = steps(&r.surface, 2.0);
        let all = shell_steps(&r.surface, 0.0, b.zeta_max());
        assert_eq!(s[0], 2.0);
        // The shells above zeta_from, one at a time: the tail of the whole climb.
        let above: Vec<f64> = all.iter().copied().filter(|&z| z > 2.0).collect();
        assert_eq!(s[1..], above[..]);
        assert!(above.len() < all.len());
        assert_eq!(steps(&r.surface, 0.0), all);
    }
}
