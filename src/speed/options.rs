//! What the speed study runs: grids, tolerances, repeats.

use super::*;

/// What the study runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpeedOptions {
    /// Grid of the tolerance and thread studies.
    pub n: usize,
    /// Grids of the size study (those too small for `lambda_s` are left out).
    pub sizes: Vec<usize>,
    /// Tolerances of the cold solves.
    pub tols: Vec<f64>,
    /// Tolerance of the reference solve (CG).
    pub reference_tol: f64,
    /// Tolerance of the size and thread studies (the solves' default).
    pub size_tol: f64,
    /// Pool sizes of the thread study.
    pub threads: Vec<usize>,
    /// Grids of the floor and warm-start studies.
    pub floor_sizes: Vec<usize>,
    /// Magnification near which the warm-start study adds one shell.
    pub shell_zeta: f64,
    /// Timed solves per row; the fastest counts.
    pub repeats: usize,
    /// Hurst exponent.
    pub hurst: f64,
    /// Short-wavelength cutoff, grid spacings (`lambda_l = N/2`).
    pub lambda_s: f64,
    /// Mean pressure, units of `E*` (surfaces have unit rms gradient).
    pub p0: f64,
    /// Seed of the realization.
    pub seed: u64,
}

impl Default for SpeedOptions {
    fn default() -> Self {
        Self::with_n(256)
    }
}

impl SpeedOptions {
    /// The standard study on an `n x n` grid: sizes `n/4, n/2, n, 2n`, tolerances
    /// `1e-4 ... 1e-10`, pools of 1, 2 and all available threads, floor and warm starts on
    /// `n` and `2n` with one shell added near `zeta = 32`.
    pub fn with_n(n: usize) -> Self {
        let avail = std::thread::available_parallelism()
            .map(|k| k.get())
            .unwrap_or(1);
        let mut threads = vec![1, 2, avail];
        threads.sort_unstable();
        threads.dedup();
        Self {
            n,
            sizes: vec![n / 4, n / 2, n, 2 * n],
            tols: vec![1e-4, 1e-6, 1e-8, 1e-10],
            reference_tol: 1e-12,
            size_tol: crate::engine::solver::SolveOptions::DEFAULT_TOL,
            threads,
            floor_sizes: vec![n, 2 * n],
            shell_zeta: 32.0,
            repeats: 3,
            hurst: 0.8,
            lambda_s: 8.0,
            p0: 0.1,
            seed: 1,
        }
    }

    /// Checks the ranges; errors name the option.
    pub fn validate(&self) -> Result<()> {
        self.params(self.n)
            .spectrum()
            .validate(&crate::engine::grid::Grid::new(self.n, 1.0)?)
            .map_err(|e| {
                Error::invalid(
                    "speed n",
                    self.n,
                    format!("a grid that fits the scene ({e})"),
                )
            })?;
        for &tol in self
            .tols
            .iter()
            .chain([&self.reference_tol, &self.size_tol])
        {
            SolveOptions::with_tol(tol).validate()?;
        }
        if self.tols.is_empty() {
            return Err(Error::invalid("speed tols", "[]", "at least one tolerance"));
        }
        if self.threads.contains(&0) {
            return Err(Error::invalid("speed threads", 0, "pool sizes >= 1"));
        }
        if self.repeats == 0 {
            return Err(Error::invalid("speed repeats", 0, ">= 1"));
        }
        for &n in &self.floor_sizes {
            crate::engine::grid::Grid::new(n, 1.0)
                .and_then(|g| self.params(n).spectrum().validate(&g))
                .map_err(|e| {
                    Error::invalid(
                        "speed floor sizes",
                        n,
                        format!("grids that fit the scene ({e})"),
                    )
                })?;
        }
        if !(self.shell_zeta.is_finite() && self.shell_zeta > 1.0) {
            return Err(Error::invalid("speed shell zeta", self.shell_zeta, "> 1"));
        }
        check_positive("speed p0", self.p0)
    }

    pub(super) fn params(&self, n: usize) -> SurfaceModel {
        SurfaceModel::new(n, self.hurst, n as f64 / 2.0, self.lambda_s, self.seed)
    }

    /// The sizes of the size study whose scene is valid.
    pub(super) fn valid_sizes(&self) -> Vec<usize> {
        let mut sizes: Vec<usize> = self
            .sizes
            .iter()
            .copied()
            .filter(|&n| {
                crate::engine::grid::Grid::new(n, 1.0)
                    .and_then(|g| self.params(n).spectrum().validate(&g))
                    .is_ok()
            })
            .collect();
        sizes.sort_unstable();
        sizes.dedup();
        sizes
    }
}

#[cfg(test)]
impl SpeedOptions {
    /// The smallest study that exercises every part (for tests): N = 32, sizes 32 and 64
    /// (8 and 16 cannot hold lambda_s = 8), two tolerances, pools of 1 and 2 threads, the
    /// floor and warm starts on N = 32, one repeat.
    pub(crate) fn tiny() -> Self {
        Self {
            tols: vec![1e-4, 1e-8],
            reference_tol: 1e-11,
            threads: vec![1, 2],
            floor_sizes: vec![32],
            repeats: 1,
            ..Self::with_n(32)
        }
    }
}
