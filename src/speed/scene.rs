//! The study's scene and the timed solves on it.

use super::*;

/// One prepared scene: the surface, its heights at full resolution, and the model.
pub(super) struct Scene {
    surface: Surface,
    model: Model,
    heights: Vec<f64>,
    p0: f64,
}

/// What one solve on the scene's grid solves: the heights, the mean pressure, and where
/// it starts.
#[derive(Clone, Copy)]
struct Case<'a> {
    heights: &'a [f64],
    p0: f64,
    start: Start<'a>,
}

/// A cold solve and a warm re-solve of the same problem, each with its wall time.
type ColdAndWarm = ((ContactSolution, f64), (ContactSolution, f64));

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

    /// The scene itself: its full heights at its load, from scratch.
    fn cold(&self) -> Case<'_> {
        Case {
            heights: &self.heights,
            p0: self.p0,
            start: Start::Cold,
        }
    }

    /// One solve of `case` with a fresh solver; returns the solution and its wall time.
    fn solve_case(&self, kind: SolverKind, case: Case, tol: f64) -> Result<(ContactSolution, f64)> {
        let problem = ContactProblem::new(&self.model, case.heights, case.p0)?;
        let mut solver = kind.build();
        let timer = Instant::now();
        let solution = solver.solve(&problem, case.start, &SolveOptions::with_tol(tol))?;
        Ok((solution, timer.elapsed().as_secs_f64()))
    }

    /// The fastest of `repeats` solves of `case`.
    fn fastest(
        &self,
        kind: SolverKind,
        case: Case,
        tol: f64,
        repeats: usize,
    ) -> Result<(ContactSolution, f64)> {
        let (mut best, mut t) = self.solve_case(kind, case, tol)?;
        for _ in 1..repeats {
            let (s, dt) = self.solve_case(kind, case, tol)?;
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
        self.fastest(kind, self.cold(), tol, repeats)
    }

    /// A cold solve of the scene; returns the solution and its wall time.
    pub(super) fn solve(&self, kind: SolverKind, tol: f64) -> Result<(ContactSolution, f64)> {
        self.solve_case(kind, self.cold(), tol)
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
        let before = self.model.fft.transforms();
        let counted = self.solve(kind, tol).and_then(|(s, _)| {
            let pairs = (self.model.fft.transforms() - before) as f64 / 2.0;
            let (_, t) = self.timed(kind, tol, repeats)?;
            Ok((s.stats.iterations, t, pairs))
        });
        FloorRow::of(kind, self.model.grid.n(), fft_pair_s, counted)
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
        let mut rows = Vec::new();
        // Load +1%, from the converged solution at p0.
        let load = self.solve(kind, tol).and_then(|(from, _)| {
            let changed = Case {
                p0: 1.01 * self.p0,
                ..self.cold()
            };
            self.cold_and_warm(kind, changed, &from, tol, repeats)
        });
        rows.push(WarmRow::of(kind, n, "load +1%".into(), load));
        // One shell: the last at or below shell_zeta, from the solution one shell lower.
        let top = shell_zeta.min(self.surface.zeta_max());
        let steps = shell_steps(&self.surface, 1.0, top);
        match steps.as_slice() {
            [.., below, at] => {
                let h_below = self.surface.heights_at(*below, &self.model.fft);
                let h_at = self.surface.heights_at(*at, &self.model.fft);
                let lower = Case {
                    heights: &h_below,
                    ..self.cold()
                };
                let shell = self.solve_case(kind, lower, tol).and_then(|(from, _)| {
                    let added = Case {
                        heights: &h_at,
                        ..self.cold()
                    };
                    self.cold_and_warm(kind, added, &from, tol, repeats)
                });
                let change = format!("one shell at zeta = {}", round_sig(*at, 4));
                rows.push(WarmRow::of(kind, n, change, shell));
            }
            _ => rows.push(WarmRow::of(
                kind,
                n,
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

    /// The fastest cold solve of `case` and the fastest warm solve of it from `from`.
    fn cold_and_warm(
        &self,
        kind: SolverKind,
        case: Case,
        from: &ContactSolution,
        tol: f64,
        repeats: usize,
    ) -> Result<ColdAndWarm> {
        let cold = self.fastest(kind, case, tol, repeats)?;
        let warm_case = Case {
            start: Start::Warm(from),
            ..case
        };
        let warm = self.fastest(kind, warm_case, tol, repeats)?;
        Ok((cold, warm))
    }
}
