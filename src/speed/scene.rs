//! The study's scene and the timed solves on it.

use super::*;

/// One prepared scene: the surface, its heights at full resolution, and the model.
pub(super) struct Scene {
    surface: Surface,
    model: Model,
    heights: Vec<f64>,
    p0: f64,
}

impl Scene {
    pub(super) fn new(opts: &SpeedOptions, n: usize) -> Result<Self> {
        let surface = Surface::generate(&opts.params(n))?;
        let model = Model::new(surface.grid().clone(), 1.0)?;
        let heights = surface.heights_at(f64::INFINITY, &model.fft);
        Ok(Self {
            surface,
            model,
            heights,
            p0: opts.p0,
        })
    }

    /// A solve of `heights` at `p0` from `start` with a fresh solver; returns the solution
    /// and its wall time.
    pub(super) fn solve_with(
        &self,
        kind: SolverKind,
        heights: &[f64],
        p0: f64,
        start: Start,
        tol: f64,
    ) -> Result<(ContactSolution, f64)> {
        let problem = ContactProblem::new(&self.model, heights, p0)?;
        let mut solver = kind.build();
        let timer = Instant::now();
        let solution = solver.solve(&problem, start, &SolveOptions::with_tol(tol))?;
        Ok((solution, timer.elapsed().as_secs_f64()))
    }

    /// The fastest of `repeats` solves of `heights` at `p0` from `start`.
    pub(super) fn timed_with(
        &self,
        kind: SolverKind,
        heights: &[f64],
        p0: f64,
        start: Start,
        tol: f64,
        repeats: usize,
    ) -> Result<(ContactSolution, f64)> {
        let (mut best, mut t) = self.solve_with(kind, heights, p0, start, tol)?;
        for _ in 1..repeats {
            let (s, dt) = self.solve_with(kind, heights, p0, start, tol)?;
            if dt < t {
                (best, t) = (s, dt);
            }
        }
        Ok((best, t))
    }

    /// The fastest of `repeats` cold solves of the scene.
    pub(super) fn timed(
        &self,
        kind: SolverKind,
        tol: f64,
        repeats: usize,
    ) -> Result<(ContactSolution, f64)> {
        self.timed_with(kind, &self.heights, self.p0, Start::Cold, tol, repeats)
    }

    /// A cold solve of the scene; returns the solution and its wall time.
    pub(super) fn solve(&self, kind: SolverKind, tol: f64) -> Result<(ContactSolution, f64)> {
        self.solve_with(kind, &self.heights, self.p0, Start::Cold, tol)
    }

    /// Mean wall time of one forward + inverse FFT pair: the fastest of a few batches, each
    /// long enough (about 0.1 s) to be timed reliably.
    pub(super) fn fft_pair_s(&self) -> f64 {
        let fft = &self.model.fft;
        let mut field = self.heights.clone();
        let mut spec = fft.new_spectrum();
        let mut pair = || {
            fft.forward(&field, &mut spec);
            fft.inverse_in_place(&mut spec, &mut field);
        };
        let timer = Instant::now();
        pair();
        let once = timer.elapsed().as_secs_f64().max(1e-7);
        let per_batch = ((0.1 / once).ceil() as usize).clamp(1, 10_000);
        (0..5)
            .map(|_| {
                let timer = Instant::now();
                for _ in 0..per_batch {
                    pair();
                }
                timer.elapsed().as_secs_f64() / per_batch as f64
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The floor row of one solver: a cold solve counted in FFT pairs.
    pub(super) fn floor(
        &self,
        kind: SolverKind,
        fft_pair_s: f64,
        tol: f64,
        repeats: usize,
    ) -> FloorRow {
        let n = self.model.grid.n();
        let before = self.model.fft.transforms();
        let result = self.solve(kind, tol).and_then(|(s, _)| {
            let pairs = (self.model.fft.transforms() - before) as f64 / 2.0;
            let (_, t) = self.timed(kind, tol, repeats)?;
            Ok((s.stats.iterations, t, pairs))
        });
        match result {
            Ok((it, t, pairs)) => FloorRow {
                solver: kind,
                n,
                fft_pair_s,
                iterations: Some(it),
                wall_s: Some(t),
                pairs_per_iteration: Some(pairs / it.max(1) as f64),
                iteration_in_pairs: Some(t / (it.max(1) as f64 * fft_pair_s)),
                overhead: Some(t / (pairs * fft_pair_s)),
                error: None,
            },
            Err(e) => FloorRow {
                solver: kind,
                n,
                fft_pair_s,
                iterations: None,
                wall_s: None,
                pairs_per_iteration: None,
                iteration_in_pairs: None,
                overhead: None,
                error: Some(e.to_string()),
            },
        }
    }

    /// Warm re-solves of one solver: after a 1% load change, and after adding the last
    /// shell at or below `shell_zeta`.
    pub(super) fn warm(
        &self,
        kind: SolverKind,
        shell_zeta: f64,
        tol: f64,
        repeats: usize,
    ) -> Vec<WarmRow> {
        let n = self.model.grid.n();
        let row =
            |change: String, r: Result<((ContactSolution, f64), (ContactSolution, f64))>| match r {
                Ok(((cold, tc), (warm, tw))) => WarmRow {
                    solver: kind,
                    n,
                    change,
                    cold_iterations: Some(cold.stats.iterations),
                    cold_wall_s: Some(tc),
                    warm_iterations: Some(warm.stats.iterations),
                    warm_wall_s: Some(tw),
                    ratio: Some(tw / tc),
                    error: None,
                },
                Err(e) => WarmRow {
                    solver: kind,
                    n,
                    change,
                    cold_iterations: None,
                    cold_wall_s: None,
                    warm_iterations: None,
                    warm_wall_s: None,
                    ratio: None,
                    error: Some(e.to_string()),
                },
            };
        let mut rows = Vec::new();
        // Load +1%, from the converged solution at p0.
        let p1 = 1.01 * self.p0;
        let load = self.solve(kind, tol).and_then(|(from, _)| {
            let cold = self.timed_with(kind, &self.heights, p1, Start::Cold, tol, repeats)?;
            let warm =
                self.timed_with(kind, &self.heights, p1, Start::Warm(&from), tol, repeats)?;
            Ok((cold, warm))
        });
        rows.push(row("load +1%".into(), load));
        // One shell: the last at or below shell_zeta, from the solution one shell lower.
        let top = shell_zeta.min(self.surface.zeta_max());
        let steps = shell_steps(&self.surface, 1.0, top);
        match steps.as_slice() {
            [.., below, at] => {
                let h_below = self.surface.heights_at(*below, &self.model.fft);
                let h_at = self.surface.heights_at(*at, &self.model.fft);
                let shell = self
                    .solve_with(kind, &h_below, self.p0, Start::Cold, tol)
                    .and_then(|(from, _)| {
                        let cold =
                            self.timed_with(kind, &h_at, self.p0, Start::Cold, tol, repeats)?;
                        let warm = self.timed_with(
                            kind,
                            &h_at,
                            self.p0,
                            Start::Warm(&from),
                            tol,
                            repeats,
                        )?;
                        Ok((cold, warm))
                    });
                rows.push(row(
                    format!("one shell at zeta = {}", round_sig(*at, 4)),
                    shell,
                ));
            }
            _ => rows.push(row(
                format!("one shell below zeta = {top}"),
                Err(Error::invalid(
                    "speed shell zeta",
                    shell_zeta,
                    "a magnification with at least two shells below it",
                )),
            )),
        }
        rows
    }
}
