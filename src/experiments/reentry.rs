//! Re-entry into contact: assumption (c), `p = 0` absorbs (SPEC section 5, row c; paper
//! section 3.3).
//!
//! In Persson's diffusion picture a walker that reaches `p = 0` is lost to non-contact for
//! good. Here every distinct shell `|q|^2` of a realization is added one at a time, from the
//! flat interface (every point in contact) up to `zeta_max`, at the fixed load `p0` that
//! gives the scene's contact area at `zeta_max`; each solve is warm-started from the last.
//! For every point the sweep records how often it left contact and how often it came back.
//!
//! * **Re-entry share** (SPEC's convention): among the points in contact at `zeta_max`, the
//!   share that was out of contact at some earlier step, the first shell (`zeta = 1`)
//!   included. Also reported: the share that left contact *after* the first shell and came
//!   back, so both readings are visible. Persson: 0. Paper (H = 0.8, 1024^2,
//!   lambda_l = 512): ~62% at a_r = 0.14, ~100% at 0.014, ~8% at 0.88.
//! * **Flux** between `flux_zeta` and `flux_zeta + flux_dzeta`: the fractions of the nominal
//!   area that enter and leave contact, the net flux over the mean one-way flux (paper,
//!   zeta 128 -> 129.5: in 0.675%, out 0.597% of A0, net ~ 0.12 of either), and the
//!   transition probability out of the `p = 0` bin, the share of non-contact that enters
//!   contact (paper: ~1% from zeta = 63 to 63.3). Persson: no flux into contact.
//! * **Contact map** at `zeta_max` coloured as the paper's re-entry figures: grey, in
//!   contact at every step; red, in contact after having been out (re-entered); white, out
//!   of contact and never back; blue, out of contact after having come back at least once.
//!
//! The sweep checkpoints its state every `checkpoint_seconds` ([`crate::io::checkpoint`]); a run
//! killed mid-sweep resumes (`--resume`) from the last checkpoint and ends with the same
//! numbers as an uninterrupted run (solves are deterministic, and the warm start is part of
//! the state). A run without `--resume` starts every sweep afresh.

use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::engine::contact::{ContactSolution, Model, Residual, SolveStats};
use crate::engine::solver::SolveOptions;
use crate::engine::solver::SolverKind;
use crate::engine::surface::{Surface, SurfaceParams};
use crate::engine::sweep::{shell_steps, Sweep};
use crate::error::{check_open, check_positive, Error, Result};
use crate::io::checkpoint::{Array, Checkpoints};
use crate::plot::Raster;
use crate::stats::{round_sig, Estimate};
use crate::validation::{Check, Conclusion, Definition, Detail, Experiment, JobContext, Table};

/// Scene of the re-entry experiment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReentryScene {
    /// Points per side.
    pub n: usize,
    /// Hurst exponent.
    pub hurst: f64,
    /// Long-wavelength cutoff.
    pub lambda_l: f64,
    /// Short-wavelength cutoff.
    pub lambda_s: f64,
    /// Realizations.
    pub seeds: Vec<u64>,
    /// Contact areas at `zeta_max` (the first is the headline).
    pub contact_areas: Vec<f64>,
    /// The paper's re-entry share at each contact area, for comparison.
    pub paper_shares: Vec<f64>,
    /// Start of the flux interval.
    pub flux_zeta: f64,
    /// Length of the flux interval.
    pub flux_dzeta: f64,
    /// Seconds between checkpoints of a sweep.
    pub checkpoint_seconds: f64,
    /// Solver.
    pub solver: SolverKind,
    /// Residual tolerance.
    pub tol: f64,
}

/// One realization at one final contact area.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReentryJob {
    /// Seed.
    pub seed: u64,
    /// Contact area at `zeta_max`.
    pub contact_area: f64,
}

/// What one history sweep measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReentryResult {
    /// Load.
    pub p0: f64,
    /// Contact area at `zeta_max` from the sweep.
    pub a_r: f64,
    /// Points in contact at `zeta_max`.
    pub contact_points: u64,
    /// Of those, points that were out of contact at some step (first shell included).
    pub reentered: u64,
    /// Of those, points that left contact after the first shell and came back.
    pub reentered_after_first: u64,
    /// Fraction of the nominal area entering contact over the flux interval.
    pub flux_in: f64,
    /// Fraction of the nominal area leaving contact over the flux interval.
    pub flux_out: f64,
    /// Share of the non-contact at `flux_zeta` in contact at `flux_zeta + flux_dzeta`.
    pub zero_bin_reentry: f64,
    /// Shells added.
    pub shells: usize,
    /// Solver iterations over the sweep.
    pub iterations: u64,
    /// Wall time of the sweep (seconds, resumed runs included).
    pub wall_s: f64,
    /// Largest residual.
    pub max_residual: f64,
    /// Map categories at `zeta_max` (2 bits a point, hex), for the first seed only.
    pub map: Option<String>,
    /// Flux categories over the flux interval (2 bits a point, hex), first seed only.
    pub flux_map: Option<String>,
}

/// The experiment.
pub struct Reentry;

/// Per-point history of a sweep.
struct History {
    in_contact: Vec<u8>,
    left: Vec<u16>,
    returned: Vec<u16>,
    left_after_first: Vec<u8>,
    flux_start: Option<Vec<u8>>,
    flux: Option<(f64, f64, f64, Vec<u8>)>,
}

/// Checkpoint header.
#[derive(Serialize, Deserialize)]
struct Progress {
    step: usize,
    p0: f64,
    iterations: u64,
    wall_s: f64,
    max_residual: f64,
    flux: Option<(f64, f64, f64)>,
    has_flux_start: bool,
}

impl ReentryScene {
    fn params(&self, seed: u64) -> SurfaceParams {
        SurfaceParams::new(self.n, self.hurst, self.lambda_l, self.lambda_s, seed)
    }
}

impl History {
    fn new(points: usize) -> Self {
        Self {
            in_contact: vec![1; points],
            left: vec![0; points],
            returned: vec![0; points],
            left_after_first: vec![0; points],
            flux_start: None,
            flux: None,
        }
    }

    /// Records the contact state of step `step` (0 = first shell).
    fn record(&mut self, step: usize, pressure: &[f64]) {
        for (i, &p) in pressure.iter().enumerate() {
            let now = u8::from(p > 0.0);
            let was = self.in_contact[i];
            if was == 1 && now == 0 {
                self.left[i] = self.left[i].saturating_add(1);
                if step > 0 {
                    self.left_after_first[i] = 1;
                }
            } else if was == 0 && now == 1 {
                self.returned[i] = self.returned[i].saturating_add(1);
            }
            self.in_contact[i] = now;
        }
    }

    /// Closes the flux interval: fluxes against the state at its start.
    fn close_flux(&mut self) {
        let start = self.flux_start.as_ref().expect("flux interval opened");
        let n = start.len() as f64;
        let (mut enter, mut leave, mut out_before) = (0.0, 0.0, 0.0);
        let mut map = Vec::with_capacity(start.len());
        for (&a, &b) in start.iter().zip(&self.in_contact) {
            out_before += f64::from(1 - a);
            map.push(match (a, b) {
                (1, 1) => 0,
                (0, 1) => {
                    enter += 1.0;
                    1
                }
                (0, 0) => 2,
                _ => {
                    leave += 1.0;
                    3
                }
            });
        }
        let zero = if out_before > 0.0 {
            enter / out_before
        } else {
            0.0
        };
        self.flux = Some((enter / n, leave / n, zero, map));
    }

    fn categories(&self) -> Vec<u8> {
        self.in_contact
            .iter()
            .zip(self.left.iter().zip(&self.returned))
            .map(|(&c, (&l, &r))| match (c, l > 0, r > 0) {
                (1, false, _) => 0,
                (1, true, _) => 1,
                (_, _, false) => 2,
                _ => 3,
            })
            .collect()
    }
}

/// Packs 2-bit categories, four to a byte, as hex.
pub fn pack_categories(c: &[u8]) -> String {
    c.chunks(4)
        .map(|q| {
            let b = q
                .iter()
                .enumerate()
                .fold(0u8, |acc, (k, &v)| acc | ((v & 3) << (2 * k)));
            format!("{b:02x}")
        })
        .collect()
}

/// Unpacks [`pack_categories`] into `len` categories.
pub fn unpack_categories(hex: &str, len: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(len);
    for k in (0..hex.len()).step_by(2) {
        let b = u8::from_str_radix(&hex[k..k + 2], 16).unwrap_or(0);
        for j in 0..4 {
            if out.len() < len {
                out.push((b >> (2 * j)) & 3);
            }
        }
    }
    out
}

/// Runs (or resumes) one history sweep.
fn run_history(
    scene: &ReentryScene,
    job: &ReentryJob,
    ctx: &JobContext,
    keep_maps: bool,
) -> Result<ReentryResult> {
    let timer = Instant::now();
    let surface = Surface::generate(&scene.params(job.seed))?;
    let model = Model::new(surface.grid().clone(), 1.0)?;
    let points = model.grid.points();
    let zeta_max = surface.zeta_max();
    let steps = shell_steps(&surface, 0.0, zeta_max);
    let flux_end = scene.flux_zeta + scene.flux_dzeta;
    let mut sweep = Sweep::new(
        &surface,
        &model,
        scene.solver,
        SolveOptions::with_tol(scene.tol),
    );
    let mut history = History::new(points);
    let mut checkpoints = Checkpoints::new(&ctx.state_dir);

    let (mut first, p0, mut iterations, wall_before, mut max_residual);
    match checkpoints.load_meta::<Progress>() {
        Some(pr) => {
            // Resume: the state after step `pr.step - 1`.
            history.in_contact = checkpoints.load_u8("in_contact")?;
            history.left = checkpoints.load_u16("left")?;
            history.returned = checkpoints.load_u16("returned")?;
            history.left_after_first = checkpoints.load_u8("left_after_first")?;
            if pr.has_flux_start {
                history.flux_start = Some(checkpoints.load_u8("flux_start")?);
            }
            if let Some((a, b, c)) = pr.flux {
                let map = checkpoints.load_u8("flux_map")?;
                history.flux = Some((a, b, c, map));
            }
            let solution = ContactSolution {
                pressure: checkpoints.load_f64("pressure")?,
                displacement: checkpoints.load_f64("displacement")?,
                p0: pr.p0,
                stats: SolveStats {
                    solver: scene.solver.name(),
                    iterations: 0,
                    residual: Residual::default(),
                    wall_s: 0.0,
                    warm: true,
                },
            };
            if solution.pressure.len() != points {
                return Err(Error::bad_file(
                    &ctx.state_dir,
                    "checkpoint of another grid",
                ));
            }
            sweep.restore(steps[pr.step - 1], solution);
            first = pr.step;
            p0 = pr.p0;
            iterations = pr.iterations;
            wall_before = pr.wall_s;
            max_residual = pr.max_residual;
        }
        None => {
            p0 = sweep.find_load(zeta_max, job.contact_area)?;
            sweep.take_solution();
            first = 0;
            iterations = 0;
            wall_before = 0.0;
            max_residual = 0.0;
        }
    }

    let mut last_save = Instant::now();
    while first < steps.len() {
        let zeta = steps[first];
        if history.flux_start.is_none() && zeta > scene.flux_zeta * (1.0 + 1e-12) {
            history.flux_start = Some(history.in_contact.clone());
        }
        if history.flux.is_none() && history.flux_start.is_some() && zeta > flux_end * (1.0 + 1e-12)
        {
            history.close_flux();
        }
        let s = sweep.solve_at(zeta, p0)?;
        iterations += s.stats.iterations as u64;
        max_residual = max_residual.max(s.stats.residual.value());
        history.record(first, &s.pressure);
        first += 1;
        if last_save.elapsed().as_secs_f64() >= scene.checkpoint_seconds && first < steps.len() {
            let s = sweep.solution().expect("just solved");
            let progress = Progress {
                step: first,
                p0,
                iterations,
                wall_s: wall_before + timer.elapsed().as_secs_f64(),
                max_residual,
                flux: history.flux.as_ref().map(|f| (f.0, f.1, f.2)),
                has_flux_start: history.flux_start.is_some(),
            };
            let empty: Vec<u8> = Vec::new();
            let mut arrays = vec![
                ("pressure", Array::F64(&s.pressure)),
                ("displacement", Array::F64(&s.displacement)),
                ("in_contact", Array::U8(&history.in_contact)),
                ("left", Array::U16(&history.left)),
                ("returned", Array::U16(&history.returned)),
                ("left_after_first", Array::U8(&history.left_after_first)),
            ];
            arrays.push((
                "flux_start",
                Array::U8(history.flux_start.as_deref().unwrap_or(&empty)),
            ));
            arrays.push((
                "flux_map",
                Array::U8(history.flux.as_ref().map_or(&empty[..], |f| &f.3[..])),
            ));
            checkpoints.save(&progress, &arrays)?;
            last_save = Instant::now();
        }
    }
    if history.flux.is_none() && history.flux_start.is_some() {
        history.close_flux();
    }
    let (flux_in, flux_out, zero_bin_reentry, flux_map) =
        history.flux.clone().ok_or_else(|| {
            Error::invalid(
                "flux_zeta",
                scene.flux_zeta,
                format!("below zeta_max = {zeta_max}"),
            )
        })?;
    let final_solution = sweep.solution().expect("at least one shell");
    let mut contact_points = 0u64;
    let mut reentered = 0u64;
    let mut after_first = 0u64;
    for i in 0..points {
        if history.in_contact[i] == 1 {
            contact_points += 1;
            reentered += u64::from(history.left[i] > 0);
            after_first += u64::from(history.left_after_first[i] == 1);
        }
    }
    let result = ReentryResult {
        p0,
        a_r: final_solution.contact_area(),
        contact_points,
        reentered,
        reentered_after_first: after_first,
        flux_in,
        flux_out,
        zero_bin_reentry,
        shells: steps.len(),
        iterations,
        wall_s: wall_before + timer.elapsed().as_secs_f64(),
        max_residual,
        map: keep_maps.then(|| pack_categories(&history.categories())),
        flux_map: keep_maps.then(|| pack_categories(&flux_map)),
    };
    // The checkpoints stay until the runner has stored the result (it then removes them):
    // a run killed in between still resumes from the last one.
    Ok(result)
}

impl Experiment for Reentry {
    const FAMILY: &'static str = "reentry";
    type Scene = ReentryScene;
    type Job = ReentryJob;
    type JobResult = ReentryResult;

    fn validate(scene: &ReentryScene) -> Result<()> {
        let grid = crate::engine::grid::Grid::new(scene.n, 1.0)?;
        scene.params(0).spectrum.validate(&grid)?;
        crate::error::check_seeds(&scene.seeds)?;
        if scene.contact_areas.is_empty() {
            return Err(Error::invalid(
                "contact_areas",
                "[]",
                "at least one contact area",
            ));
        }
        for &a in &scene.contact_areas {
            check_open("contact_areas", a, 0.0, 1.0)?;
        }
        if scene.paper_shares.len() != scene.contact_areas.len() {
            return Err(Error::invalid(
                "paper_shares",
                format!("{} values", scene.paper_shares.len()),
                format!("one per contact area ({})", scene.contact_areas.len()),
            ));
        }
        let zeta_max = scene.lambda_l / scene.lambda_s;
        crate::engine::scene::check_zeta(scene.flux_zeta, zeta_max)?;
        check_positive("flux_dzeta", scene.flux_dzeta)?;
        if scene.flux_zeta + scene.flux_dzeta > zeta_max {
            return Err(Error::invalid(
                "flux_dzeta",
                scene.flux_dzeta,
                format!("with flux_zeta + flux_dzeta <= zeta_max = {zeta_max}"),
            ));
        }
        check_positive("checkpoint_seconds", scene.checkpoint_seconds)?;
        SolveOptions::with_tol(scene.tol).validate()
    }

    fn jobs(scene: &ReentryScene) -> Vec<ReentryJob> {
        let mut jobs = Vec::new();
        for &contact_area in &scene.contact_areas {
            for &seed in &scene.seeds {
                jobs.push(ReentryJob { seed, contact_area });
            }
        }
        jobs
    }

    fn run_job(scene: &ReentryScene, job: &ReentryJob, ctx: &JobContext) -> Result<ReentryResult> {
        let keep_maps = job.seed == scene.seeds[0];
        run_history(scene, job, ctx, keep_maps)
    }

    fn conclude(
        def: &Definition<ReentryScene>,
        scene: &ReentryScene,
        results: &[(ReentryJob, ReentryResult)],
    ) -> Result<Conclusion> {
        let mut c = Conclusion {
            persson: 0.0,
            max_residual: results.iter().map(|r| r.1.max_residual).fold(0.0, f64::max),
            ..Default::default()
        };
        let mut table = Table::new(
            def.name.clone(),
            &[
                "contact_area_target",
                "seed",
                "a_r",
                "share",
                "share_after_first",
                "flux_in",
                "flux_out",
                "zero_bin_reentry",
                "shells",
                "iterations",
                "wall_s",
            ],
        );
        let mut shares = Vec::new();
        for (k, &target) in scene.contact_areas.iter().enumerate() {
            let mine: Vec<&ReentryResult> = results
                .iter()
                .filter(|(j, _)| j.contact_area == target)
                .map(|(_, r)| r)
                .collect();
            for (j, r) in results.iter().filter(|(j, _)| j.contact_area == target) {
                table.push(vec![
                    target,
                    j.seed as f64,
                    r.a_r,
                    r.reentered as f64 / r.contact_points.max(1) as f64,
                    r.reentered_after_first as f64 / r.contact_points.max(1) as f64,
                    r.flux_in,
                    r.flux_out,
                    r.zero_bin_reentry,
                    r.shells as f64,
                    r.iterations as f64,
                    r.wall_s,
                ]);
            }
            let share = Estimate::mean_of(
                &mine
                    .iter()
                    .map(|r| r.reentered as f64 / r.contact_points.max(1) as f64)
                    .collect::<Vec<_>>(),
            );
            let after = Estimate::mean_of(
                &mine
                    .iter()
                    .map(|r| r.reentered_after_first as f64 / r.contact_points.max(1) as f64)
                    .collect::<Vec<_>>(),
            );
            if k == 0 {
                c.measured = Some(share);
            }
            shares.push(share);
            c.details.push(Detail {
                name: format!("re-entry share at a_r = {target}"),
                value: share,
                persson: Some(0.0),
                paper: Some(scene.paper_shares[k]),
                grid: None,
            });
            c.details.push(Detail {
                name: format!("share that left after zeta = 1 and came back, a_r = {target}"),
                value: after,
                persson: Some(0.0),
                paper: None,
                grid: None,
            });
            c.golden
                .insert(format!("share_{target}"), round_sig(share.value, 3));
            c.golden.insert(
                format!("share_after_first_{target}"),
                round_sig(after.value, 3),
            );
        }
        // Flux statistics at the headline contact area.
        let head = scene.contact_areas[0];
        let mine: Vec<&ReentryResult> = results
            .iter()
            .filter(|(j, _)| j.contact_area == head)
            .map(|(_, r)| r)
            .collect();
        let est = |f: &dyn Fn(&ReentryResult) -> f64| {
            Estimate::mean_of(&mine.iter().map(|r| f(r)).collect::<Vec<_>>())
        };
        let flux_in = est(&|r| r.flux_in);
        let flux_out = est(&|r| r.flux_out);
        let ratio = est(&|r| {
            (r.flux_out - r.flux_in).abs() / (0.5 * (r.flux_out + r.flux_in)).max(f64::MIN_POSITIVE)
        });
        let zero = est(&|r| r.zero_bin_reentry);
        for (name, e, paper) in [
            (
                format!(
                    "flux into contact, zeta {} -> {} (fraction of A0)",
                    scene.flux_zeta,
                    scene.flux_zeta + scene.flux_dzeta
                ),
                flux_in,
                Some(0.00675),
            ),
            (
                "flux out of contact (fraction of A0)".to_string(),
                flux_out,
                Some(0.00597),
            ),
            (
                "net flux / mean one-way flux".to_string(),
                ratio,
                Some(0.12),
            ),
            (
                "share of non-contact entering contact (transition out of p = 0)".to_string(),
                zero,
                Some(0.01),
            ),
        ] {
            c.details.push(Detail {
                name,
                value: e,
                persson: Some(0.0),
                paper,
                grid: None,
            });
        }
        c.golden
            .insert("flux_in".into(), round_sig(flux_in.value, 3));
        c.golden
            .insert("flux_out".into(), round_sig(flux_out.value, 3));
        let z = def.verdict.significance;
        c.checks.push(Check {
            name: format!("flux into contact above zero beyond {z} standard errors"),
            passed: flux_in.value > z * flux_in.std_error && flux_in.value > 0.0,
            detail: format!("{:.5} +- {:.5} of A0", flux_in.value, flux_in.std_error),
        });
        // The paper's ordering: lower load, more re-entry.
        let mut order: Vec<(f64, Estimate)> = scene
            .contact_areas
            .iter()
            .copied()
            .zip(shares.iter().copied())
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        c.checks.push(Check {
            name: "re-entry share falls as the contact area grows".into(),
            passed: order.windows(2).all(|w| w[0].1.value >= w[1].1.value),
            detail: order
                .iter()
                .map(|(a, s)| format!("a_r {a}: {:.3}", s.value))
                .collect::<Vec<_>>()
                .join(", "),
        });
        let wall = Estimate::mean_of(&results.iter().map(|r| r.1.wall_s).collect::<Vec<_>>());
        let shells = results.first().map_or(0, |r| r.1.shells);
        c.account = format!(
            "{} realizations ({}x{}, H = {}, lambda_l = {}, lambda_s = {}) were swept through all \
             {} shells one at a time at fixed load, from the flat interface to zeta_max = {}. \
             Of the points in contact at zeta_max, {} had been out of contact at a lower \
             magnification (paper: {}). Between zeta = {} and {}, {:.3}% of the nominal area \
             entered contact and {:.3}% left it, at a_r = {head}. A sweep took {:.1} s on \
             average ({} solver iterations).",
            scene.seeds.len(),
            scene.n,
            scene.n,
            scene.hurst,
            scene.lambda_l,
            scene.lambda_s,
            shells,
            scene.lambda_l / scene.lambda_s,
            scene
                .contact_areas
                .iter()
                .zip(&shares)
                .map(|(a, s)| format!(
                    "{:.1}% +- {:.1}% at a_r = {a}",
                    100.0 * s.value,
                    100.0 * s.std_error
                ))
                .collect::<Vec<_>>()
                .join(", "),
            scene
                .contact_areas
                .iter()
                .zip(&scene.paper_shares)
                .map(|(a, s)| format!("{:.0}% at {a}", 100.0 * s))
                .collect::<Vec<_>>()
                .join(", "),
            scene.flux_zeta,
            scene.flux_zeta + scene.flux_dzeta,
            100.0 * flux_in.value,
            100.0 * flux_out.value,
            wall.value,
            results.iter().map(|r| r.1.iterations).sum::<u64>() / results.len().max(1) as u64,
        );
        if let Some((job, r)) = results
            .iter()
            .find(|(j, r)| j.contact_area == head && r.map.is_some())
        {
            let n2 = scene.n * scene.n;
            c.rasters.push(Raster {
                name: "reentry_map".into(),
                title: format!(
                    "Contact at zeta_max, a_r = {:.3} (seed {}): history of every point",
                    r.a_r, job.seed
                ),
                n: scene.n,
                pixels: unpack_categories(r.map.as_deref().unwrap_or(""), n2),
                palette: vec![
                    ([150, 150, 150], "in contact throughout".into()),
                    ([220, 40, 40], "in contact, re-entered".into()),
                    ([255, 255, 255], "out of contact, never back".into()),
                    ([40, 80, 220], "out of contact after re-entering".into()),
                ],
            });
            c.rasters.push(Raster {
                name: "flux_map".into(),
                title: format!(
                    "Changes between zeta = {} and {} (seed {})",
                    scene.flux_zeta,
                    scene.flux_zeta + scene.flux_dzeta,
                    job.seed
                ),
                n: scene.n,
                pixels: unpack_categories(r.flux_map.as_deref().unwrap_or(""), n2),
                palette: vec![
                    ([150, 150, 150], "in contact at both".into()),
                    ([220, 40, 40], "entered contact".into()),
                    ([255, 255, 255], "out of contact at both".into()),
                    ([40, 80, 220], "left contact".into()),
                ],
            });
        }
        c.tables.push(table);
        Ok(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn categories_pack_and_unpack() {
        let c: Vec<u8> = (0..37).map(|k| (k * 7 % 4) as u8).collect();
        assert_eq!(unpack_categories(&pack_categories(&c), c.len()), c);
    }

    #[test]
    fn history_counts_departures_and_returns() {
        let mut h = History::new(3);
        h.record(0, &[1.0, 0.0, 0.0]);
        h.record(1, &[0.0, 1.0, 0.0]);
        h.record(2, &[1.0, 1.0, 0.0]);
        assert_eq!(h.left, vec![1, 1, 1]);
        assert_eq!(h.returned, vec![1, 1, 0]);
        assert_eq!(h.left_after_first, vec![1, 0, 0]);
        assert_eq!(h.categories(), vec![1, 1, 2]);
    }
}
