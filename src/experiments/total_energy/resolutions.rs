//! `S~` on finer grids: the paper's check that the incremental correction factor of
//! eq. (S_q_numerical) is converged (sec. 3.5, fig. dS: "N = 512 and N = 2048 data,
//! size-scaled, lie on the N = 1024 lines").
//!
//! A resolution (`[[full.resolutions]]`) is the headline's scene on another grid,
//! *size-scaled*: `lambda_l / L` and `zeta_max = lambda_l / lambda_s` are the headline's, so
//! that a magnification `zeta = q / q_l` names the same shell `k2 = mx^2 + my^2` on every
//! grid and every increment window holds the same shells; only the points per shortest
//! wavelength (`lambda_s` in grid units) grow with the grid. Each job is one realization at
//! one load, climbed exactly as the headline's sweep (`run_sweep` of the module above).
//!
//! Per load, the statistic is the windows' `S~` averaged per realization (the mean of
//! [`EnergyResult::window_mean`] over the scene's increment windows), then over realizations; its shift
//! from the headline grid's is the difference of two means over independent realizations
//! (different grids draw different surfaces), with the combined standard error.

use crate::experiments::keys::{DetailKey, Tag};
use serde::{Deserialize, Serialize};

use super::{EnergyResult, EnergyScene};
use crate::engine::tolerance::ZETA_SLACK;
use crate::error::{check_key_name, check_seeds, Error, Result};
use crate::experiments::declared::DetailTable;
use crate::experiments::ensemble::{check_contact_areas, SeedLoad};
use crate::experiments::other_grid::other_grid;
use crate::experiments::study::{with_settings, Cell, Study};
use crate::stats::Estimate;

other_grid! {
    /// The headline's scene on another grid, as a definition states it
    /// (`[[full.resolutions]]`): `lambda_l / n` and `lambda_l / lambda_s` as the
    /// headline's.
    pub struct Resolution {
        /// Short name: the prefix of its statistics' keys.
        pub name: String,
        /// Realizations.
        pub seeds: Vec<u64>,
        /// Loads, a subset of the headline's contact areas.
        pub contact_areas: Vec<f64>,
    }
}

other_grid! {
    /// One sweep on a finer grid: everything it depends on besides the headline's scene.
    pub struct ResolutionJob {
        /// Realization.
        pub seed: u64,
        /// Load: the contact area at `zeta_max`.
        pub contact_area: f64,
    }
}

impl Resolution {
    /// Every sweep, loads outermost.
    pub fn jobs(&self) -> Vec<ResolutionJob> {
        self.contact_areas
            .iter()
            .flat_map(|&a| {
                self.seeds.iter().map(move |&seed| ResolutionJob {
                    n: self.n,
                    lambda_l: self.lambda_l,
                    lambda_s: self.lambda_s,
                    seed,
                    contact_area: a,
                })
            })
            .collect()
    }

    /// Checks the resolution against the headline's scene: a valid scene on its grid,
    /// size-scaled, loads among the headline's; errors name the field.
    pub fn validate(&self, headline: &EnergyScene) -> Result<()> {
        check_key_name("resolutions.name", &self.name)?;
        // Its grid's ranges (n, lambda_l, lambda_s), under the headline's own names.
        self.base(headline.hurst, &headline.seeds, headline.tol)
            .validate()?;
        check_seeds(&self.seeds).map_err(|e| e.with_field("resolutions.seeds"))?;
        check_contact_areas(&self.contact_areas)
            .map_err(|e| e.with_field("resolutions.contact_areas"))?;
        let same = |a: f64, b: f64| (a - b).abs() <= ZETA_SLACK * b.abs();
        let (l, z) = (
            headline.lambda_l / headline.n as f64,
            headline.lambda_l / headline.lambda_s,
        );
        if !same(self.lambda_l / self.n as f64, l) {
            return Err(Error::invalid(
                "resolutions.lambda_l",
                self.lambda_l,
                format!("lambda_l / n = {l} as the headline's (size-scaled)"),
            ));
        }
        if !same(self.lambda_l / self.lambda_s, z) {
            return Err(Error::invalid(
                "resolutions.lambda_s",
                self.lambda_s,
                format!("lambda_l / lambda_s = {z} as the headline's (the same windows)"),
            ));
        }
        if let Some(a) = self
            .contact_areas
            .iter()
            .find(|a| !headline.contact_areas.contains(a))
        {
            return Err(Error::invalid(
                "resolutions.contact_areas",
                a,
                format!("one of the headline's {:?}", headline.contact_areas),
            ));
        }
        Ok(())
    }
}

/// Checks a list of resolutions: each valid, names and grids distinct, none the
/// headline's grid.
pub fn validate_all(resolutions: &[Resolution], headline: &EnergyScene) -> Result<()> {
    for (k, r) in resolutions.iter().enumerate() {
        r.validate(headline)?;
        if resolutions[..k].iter().any(|o| o.name == r.name) {
            return Err(Error::invalid(
                "resolutions.name",
                &r.name,
                "each name once",
            ));
        }
        if r.n == headline.n || resolutions[..k].iter().any(|o| o.n == r.n) {
            return Err(Error::invalid(
                "resolutions.n",
                r.n,
                "a grid other than the headline's and the other resolutions'",
            ));
        }
    }
    Ok(())
}

/// The headline's scene on the job's grid, with the job's realization only.
pub fn scene_on(headline: &EnergyScene, job: &ResolutionJob) -> EnergyScene {
    let mut scene = headline.clone();
    scene.n = job.n;
    scene.lambda_l = job.lambda_l;
    scene.lambda_s = job.lambda_s;
    scene.seeds = vec![job.seed];
    scene.low_load_seeds.clear();
    scene.resolutions.clear();
    scene
}

/// The job's seed and load, as the headline's sweep takes them.
pub fn seed_load(job: &ResolutionJob) -> SeedLoad {
    SeedLoad {
        seed: job.seed,
        contact_area: job.contact_area,
    }
}

/// One realization's `S~` averaged over every increment window.
fn windows_mean(r: &EnergyResult) -> f64 {
    r.windows.iter().map(|w| r.window_mean(w)).sum::<f64>() / r.windows.len().max(1) as f64
}

/// The windows' `S~` at one load on one grid, over its realizations.
fn mean_at<'a>(results: impl Iterator<Item = &'a EnergyResult>) -> (Estimate, usize) {
    let samples: Vec<f64> = results.map(windows_mean).collect();
    (Estimate::mean_of(&samples), samples.len())
}

/// One load of a resolution beside the headline grid's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResolutionLoad {
    /// The load (contact area at `zeta_max`).
    pub contact_area: f64,
    /// Realizations that ran.
    pub realizations: usize,
    /// The windows' `S~` on this grid.
    pub s_tilde: Estimate,
    /// The same on the headline's grid.
    pub headline: Estimate,
}

/// A resolution's statistics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResolutionStats {
    /// The definition.
    pub resolution: Resolution,
    /// Its loads that have results.
    pub loads: Vec<ResolutionLoad>,
}

/// Every resolution's statistics from its sweeps and the headline's.
pub fn stats(
    resolutions: &[Resolution],
    sweeps: &[(ResolutionJob, EnergyResult)],
    headline: &[(SeedLoad, EnergyResult)],
) -> Vec<ResolutionStats> {
    resolutions
        .iter()
        .map(|res| {
            let loads = res
                .contact_areas
                .iter()
                .filter_map(|&a| {
                    let (s_tilde, realizations) = mean_at(
                        sweeps
                            .iter()
                            .filter(|(j, _)| j.n == res.n && j.contact_area == a)
                            .map(|(_, r)| r),
                    );
                    let (head, _) = mean_at(
                        headline
                            .iter()
                            .filter(|(j, _)| j.contact_area == a)
                            .map(|(_, r)| r),
                    );
                    (realizations > 0).then_some(ResolutionLoad {
                        contact_area: a,
                        realizations,
                        s_tilde,
                        headline: head,
                    })
                })
                .collect();
            ResolutionStats {
                resolution: res.clone(),
                loads,
            }
        })
        .collect()
}

/// The keys of a resolution's details at load `a`: its `S~` and the shift from the
/// headline grid's.
fn s_tilde_key(name: &str, a: f64) -> DetailKey {
    DetailKey::new(format!("{name}_s_tilde")).at(Tag::ContactArea, a)
}
fn shift_key(name: &str, a: f64) -> DetailKey {
    DetailKey::new(format!("{name}_s_tilde_shift")).at(Tag::ContactArea, a)
}

/// The study of the resolutions: its key and columns, `(key, label)`.
pub const STUDY: &str = "resolutions";

/// The columns of [`STUDY`].
pub fn columns() -> Vec<(&'static str, &'static str)> {
    with_settings(
        &["n", "lambda_s", "contact_area", "realizations"],
        &[
            ("s_tilde", "S~, windows averaged"),
            ("headline", "the same on the headline's grid"),
            ("shift", "this grid minus the headline's"),
        ],
    )
}

/// The statistics of resolution `name` at load `a`, where it has realizations.
fn load_of<'a>(s: &'a [ResolutionStats], name: &str, a: f64) -> Option<&'a ResolutionLoad> {
    s.iter()
        .find(|r| r.resolution.name == name)?
        .loads
        .iter()
        .find(|l| l.contact_area == a)
}

/// Declares the windows' `S~` of each resolution and load, and its shift from the
/// headline grid's; a load without realizations has neither. `of` finds the resolutions'
/// statistics among the experiment's `S`.
pub fn declare<'s, S: 's>(
    t: &mut DetailTable<'s, S>,
    resolutions: &'s [Resolution],
    of: fn(&S) -> &[ResolutionStats],
) {
    for r in resolutions {
        let (name, n) = (r.name.as_str(), r.n);
        for &a in &r.contact_areas {
            // The label counts the realizations that ran.
            t.row_labelled(s_tilde_key(name, a), move |s: &S| {
                let l = load_of(of(s), name, a)?;
                let text = format!(
                    "S~ averaged over the increment windows, a_r = {a}, {n}^2 \
                     (size-scaled), {} realizations",
                    l.realizations
                );
                Some((text, l.s_tilde))
            });
            t.row(
                shift_key(name, a),
                format!(
                    "S~ averaged over the increment windows, a_r = {a}: {n}^2 minus the \
                     headline's grid"
                ),
                move |s: &S| {
                    load_of(of(s), name, a).map(|l| Estimate::difference(l.s_tilde, l.headline))
                },
            );
        }
    }
}

/// The table of the resolutions: one row per grid and load.
pub fn study(stats: &[ResolutionStats], headline_n: usize) -> Study {
    let mut study = Study::new(STUDY, "S~ on finer grids, size-scaled", &columns()).about(format!(
        "Each row: the headline's scene on another grid with lambda_l / L and lambda_l / \
         lambda_s unchanged, so that every increment window holds the same shells; S~ of each \
         window (eq. S_q_numerical) averaged over the windows per realization, then over the \
         realizations, beside the same on the headline's {headline_n}^2 grid (different \
         realizations: the shift's error combines both)."
    ));
    for s in stats {
        let r = &s.resolution;
        for l in &s.loads {
            study.push(
                format!("{}_ar{}", r.name, l.contact_area),
                format!("{}^2, a_r {}", r.n, l.contact_area),
                vec![
                    Cell::from(r.n as f64),
                    Cell::from(r.lambda_s),
                    Cell::from(l.contact_area),
                    Cell::from(l.realizations as f64),
                    Cell::from(l.s_tilde),
                    Cell::from(l.headline),
                    Cell::from(Estimate::difference(l.s_tilde, l.headline)),
                ],
            );
        }
    }
    study
}

#[cfg(test)]
mod tests {
    use super::*;

    fn headline() -> EnergyScene {
        toml::from_str(
            "n = 64\nhurst = 0.8\nlambda_l = 32\nlambda_s = 4\nseeds = [1, 2]\n\
             tol = 1e-8\ncontact_areas = [0.1, 0.3]\nheadline_contact_area = 0.3\n\
             zeta_start = 1.0\nsteps_per_octave = 2\nincrements_at = [2.0]\nincrements = 2\n",
        )
        .expect("a scene")
    }

    fn finer() -> Resolution {
        Resolution {
            name: "n128".into(),
            n: 128,
            lambda_l: 64.0,
            lambda_s: 8.0,
            seeds: vec![1, 2],
            contact_areas: vec![0.3],
        }
    }

    #[test]
    fn resolutions_are_checked_field_by_field() {
        let h = headline();
        finer().validate(&h).expect("valid");
        let field = |r: Resolution| validate_all(&[r], &h).unwrap_err().to_string();
        let names = |r: Resolution, f: &str| {
            let e = field(r);
            assert!(e.contains(f), "{e} does not name {f}");
        };
        let mut r = finer();
        r.lambda_l = 32.0;
        r.lambda_s = 4.0;
        names(r, "resolutions.lambda_l");
        let mut r = finer();
        r.lambda_s = 4.0;
        names(r, "resolutions.lambda_s");
        let mut r = finer();
        r.contact_areas = vec![0.2];
        names(r, "resolutions.contact_areas");
        let mut r = finer();
        r.seeds = vec![3, 3];
        names(r, "resolutions.seeds");
        let mut r = finer();
        r.name = "n 128".into();
        names(r, "resolutions.name");
        let mut r = finer();
        r.n = 64;
        r.lambda_l = 32.0;
        r.lambda_s = 4.0;
        names(r, "resolutions.n");
        let e = validate_all(&[finer(), finer()], &h)
            .unwrap_err()
            .to_string();
        assert!(e.contains("each name once"), "{e}");
    }

    /// A sweep whose every single-shell increment has `S~ = s`.
    fn sweep(s: f64) -> EnergyResult {
        EnergyResult {
            p0: 0.1,
            zetas: vec![1.0, 2.0, 3.0],
            contact_area: vec![0.3; 3],
            e_exa: vec![0.0, s, 3.0 * s],
            e_p: vec![0.0, 1.0, 3.0],
            e_c: vec![0.0, 1.0, 3.0],
            area_original: vec![0.3; 3],
            area_corrected: vec![0.3; 3],
            windows: vec![vec![0, 1, 2]],
            max_residual: 0.0,
        }
    }

    #[test]
    fn the_shift_is_the_difference_of_the_windows_means() {
        let res = finer();
        let job = |seed| res.jobs().into_iter().find(|j| j.seed == seed).unwrap();
        let sweeps = vec![(job(1), sweep(0.8)), (job(2), sweep(0.9))];
        let head = |seed| SeedLoad {
            seed,
            contact_area: 0.3,
        };
        let sweeps_512 = vec![(head(1), sweep(0.5)), (head(2), sweep(0.7))];
        let s = stats(std::slice::from_ref(&res), &sweeps, &sweeps_512);
        let l = &s[0].loads[0];
        assert_eq!(l.realizations, 2);
        assert!((l.s_tilde.value - 0.85).abs() < 1e-12);
        assert!((l.headline.value - 0.6).abs() < 1e-12);
        let mut t = DetailTable::default();
        // The resolutions' statistics stand for the experiment's.
        declare(&mut t, std::slice::from_ref(&res), Vec::as_slice);
        let d = t.details(&s);
        assert_eq!(
            d[0].name,
            "S~ averaged over the increment windows, a_r = 0.3, 128^2 (size-scaled), 2 \
             realizations"
        );
        let shift = d
            .iter()
            .find(|d| d.key == "n128_s_tilde_shift_ar0.3")
            .expect("the shift");
        assert!((shift.value.value - 0.25).abs() < 1e-12);
        let e = 0.05f64.hypot(0.1);
        assert!((shift.value.std_error - e).abs() < 1e-12);
        // The same grid's sweeps run on the job's grid with the job's realization only.
        let scene = scene_on(&headline(), &job(2));
        assert_eq!((scene.n, scene.seeds.clone()), (128, vec![2]));
        assert_eq!(scene.lambda_l / scene.lambda_s, 8.0);
    }
}
