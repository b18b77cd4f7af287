//! Real two-dimensional FFTs on the half spectrum, parallel over rows and columns.
//!
//! Convention ([`crate::conventions`], section 2): `f~(q) = N^-2 sum_r f(r) exp(-i q.r)` and
//! `f(r) = sum_q f~(q) exp(i q.r)`, so that `mean(f^2) = sum_q |f~(q)|^2`, where
//! `N^2 = rows cols` is the number of points (`n^2` on a square grid). The forward
//! transform carries the whole `1/N^2`; the inverse carries none.
//!
//! Layout: see [`crate::engine::grid`]. The transform is done in two passes over the data, without
//! a transposed copy: real-to-complex transforms of every row (realfft) write the half
//! spectrum in place of its rows, then blocks of a few columns are gathered into a small
//! contiguous buffer, transformed (rustfft), and scattered back. Both passes run on rayon's
//! pool; the result does not depend on the number of threads (every 1D transform is the
//! same computation whichever thread runs it).
//!
//! Three jobs, one module each:
//!
//! * here, the plans and the transforms ([`Fft2::forward`], [`Fft2::inverse`]), and the
//!   kernels of convolutions ([`Kernel`]);
//! * [`columns`]: the cache-blocked column pass, which in a convolution multiplies by the
//!   kernel between the column transforms;
//! * [`fused`]: the convolution ([`Fft2::convolve`]) fused with a solver's passes over its
//!   fields ([`FusedPass`]).

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};

use crate::engine::grid::Grid;

mod blocks;
pub mod columns;
pub mod fused;

pub use fused::{FusedPass, PassValues};

use blocks::COLUMN_ORDER_MAX_N;

/// Precomputed plans for real 2D transforms on one grid shape, `rows x cols`: real
/// transforms of length `cols` along the rows, complex ones of length `rows` along the
/// columns of the half spectrum.
///
/// The plans are shared, immutable tables; per-thread scratch (a row or a block of
/// columns) is kept between calls. Every 2D transform is counted ([`Fft2::transforms`]),
/// so that the cost of a solver can be stated in FFT pairs.
pub struct Fft2 {
    rows: usize,
    cols: usize,
    /// Columns of the half spectrum, `cols/2 + 1`.
    m: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    col_inv: Arc<dyn Fft<f64>>,
    block: usize,
    /// Whether the column pass visits the spectrum column by column
    /// ([`blocks::COLUMN_ORDER_MAX_N`]).
    by_column: bool,
    transforms: AtomicU64,
}

impl std::fmt::Debug for Fft2 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Fft2")
            .field("rows", &self.rows)
            .field("cols", &self.cols)
            .finish()
    }
}

/// A real multiplier on the half spectrum for [`Fft2::convolve`], stored column by column
/// with the forward transform's `1/N^2` folded in, so that the column pass reads it
/// contiguously (row-major, every value sits one spectrum row, several KiB, from the
/// last: a cache line and a TLB entry per value on large grids).
///
/// A kernel and its [`Kernel::inverse`] share one table (4 bytes per grid point): the
/// inverse divides as it reads, which costs little next to the transforms.
#[derive(Debug, Clone)]
pub struct Kernel {
    /// The planned grid's shape, `(rows, cols)`.
    shape: (usize, usize),
    values: Arc<[f64]>,
    /// `1/N^2`, folded into `values`.
    norm: f64,
    /// Multiply by `1/k` (0 where `k = 0`) instead of `k`.
    inverse: bool,
}

impl Kernel {
    /// The kernel `1/k` of this kernel `k`, with 0 where `k = 0` (the compliance of a
    /// stiffness, whose `q = 0` mode is the free rigid shift).
    pub fn inverse(&self) -> Kernel {
        Kernel {
            inverse: !self.inverse,
            ..self.clone()
        }
    }
}

/// Tasks per thread of a row pass: a few, for load balance on a shared machine (not a
/// measurement).
const TASKS_PER_THREAD: usize = 4;

/// Per-thread work space, kept between calls: allocating and zeroing scratch for every
/// task of every transform cost more than a tenth of a solve.
#[derive(Default)]
struct Scratch {
    real: Vec<f64>,
    complex: Vec<Complex64>,
    block: Vec<Complex64>,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Grows `v` to at least `len` elements (contents unspecified) and returns that prefix.
fn at_least<T: Clone + Default>(v: &mut Vec<T>, len: usize) -> &mut [T] {
    if v.len() < len {
        v.resize(len, T::default());
    }
    &mut v[..len]
}

impl Fft2 {
    /// Plans for `grid`.
    pub fn new(grid: &Grid) -> Self {
        let (rows, cols) = (grid.rows(), grid.cols());
        let mut real_planner = RealFftPlanner::<f64>::new();
        let mut planner = FftPlanner::<f64>::new();
        let block = columns::block_width(rows);
        Self {
            rows,
            cols,
            m: grid.half_cols(),
            r2c: real_planner.plan_fft_forward(cols),
            c2r: real_planner.plan_fft_inverse(cols),
            col_fwd: planner.plan_fft_forward(rows),
            col_inv: planner.plan_fft_inverse(rows),
            block,
            by_column: rows.max(cols) <= COLUMN_ORDER_MAX_N,
            transforms: AtomicU64::new(0),
        }
    }

    /// 2D transforms (forward or inverse) done with these plans so far; a convolution
    /// counts two.
    pub fn transforms(&self) -> u64 {
        self.transforms.load(Ordering::Relaxed)
    }

    /// The convolution kernel of `table`, a real multiplier in the half-spectrum layout of
    /// [`crate::engine::grid`] (e.g. the half-space's stiffness `q E*/2`).
    ///
    /// # Panics
    ///
    /// If `table` is not a half spectrum of the planned grid (length
    /// `rows (cols/2 + 1)`).
    pub fn kernel(&self, table: &[f64]) -> Kernel {
        let (rows, m) = (self.rows, self.m);
        assert_eq!(table.len(), rows * m, "kernel table length");
        let norm = self.norm();
        let mut values = vec![0.0; rows * m];
        for (ky, row) in table.chunks_exact(m).enumerate() {
            for (kx, &v) in row.iter().enumerate() {
                values[kx * rows + ky] = v * norm;
            }
        }
        Kernel {
            shape: (rows, self.cols),
            values: values.into(),
            norm,
            inverse: false,
        }
    }

    /// The forward transform's normalisation, `1/N^2 = 1/(rows cols)`.
    fn norm(&self) -> f64 {
        1.0 / (self.rows as f64 * self.cols as f64)
    }

    fn count(&self, k: u64) {
        self.transforms.fetch_add(k, Ordering::Relaxed);
    }

    /// Length of a half spectrum, `rows (cols/2 + 1)`.
    pub fn spectrum_len(&self) -> usize {
        self.rows * self.m
    }

    /// Length of a real field, `rows cols`.
    pub fn field_len(&self) -> usize {
        self.rows * self.cols
    }

    /// A zeroed half spectrum.
    pub fn new_spectrum(&self) -> Vec<Complex64> {
        vec![Complex64::new(0.0, 0.0); self.spectrum_len()]
    }

    /// `spec = F[field]` with the `1/N^2` normalisation.
    ///
    /// # Panics
    ///
    /// If `field` is not `rows x cols` or `spec` not a half spectrum
    /// ([`Fft2::spectrum_len`]).
    pub fn forward(&self, field: &[f64], spec: &mut [Complex64]) {
        let (n, m) = (self.cols, self.m);
        assert_eq!(field.len(), self.field_len(), "field length");
        assert_eq!(spec.len(), self.spectrum_len(), "spectrum length");
        self.count(1);
        let rows = rows_per_task(self.rows);
        spec.par_chunks_mut(m * rows)
            .zip(field.par_chunks(n * rows))
            .for_each(|(out, input)| {
                SCRATCH.with(|cell| {
                    let mut guard = cell.borrow_mut();
                    let Scratch { real, complex, .. } = &mut *guard;
                    let row = at_least(real, n);
                    let scratch = at_least(complex, self.r2c.get_scratch_len());
                    for (o, i) in out.chunks_exact_mut(m).zip(input.chunks_exact(n)) {
                        row.copy_from_slice(i);
                        self.row_forward(row, o, scratch);
                    }
                })
            });
        self.columns(spec, &self.col_fwd, self.norm());
    }

    /// `field = F^-1[spec]`. The spectrum is used as scratch and left holding garbage.
    ///
    /// `spec` must be the half spectrum of a real field (Hermitian on the columns
    /// `kx = 0` and, for even `cols`, `kx = cols/2`); the imaginary parts that a real
    /// field cannot have are ignored.
    ///
    /// # Panics
    ///
    /// If `field` is not `rows x cols` or `spec` not a half spectrum
    /// ([`Fft2::spectrum_len`]).
    pub fn inverse_in_place(&self, spec: &mut [Complex64], field: &mut [f64]) {
        let (n, m) = (self.cols, self.m);
        assert_eq!(field.len(), self.field_len(), "field length");
        assert_eq!(spec.len(), self.spectrum_len(), "spectrum length");
        self.count(1);
        self.columns(spec, &self.col_inv, 1.0);
        let rows = rows_per_task(self.rows);
        spec.par_chunks_mut(m * rows)
            .zip(field.par_chunks_mut(n * rows))
            .for_each(|(input, out)| {
                SCRATCH.with(|cell| {
                    let mut guard = cell.borrow_mut();
                    let scratch = at_least(&mut guard.complex, self.c2r.get_scratch_len());
                    for (i, o) in input.chunks_exact_mut(m).zip(out.chunks_exact_mut(n)) {
                        self.row_inverse(i, o, scratch);
                    }
                })
            });
    }

    /// The real-to-complex transform of one row, `row` (left holding garbage), into `out`,
    /// a row of the half spectrum.
    #[inline]
    fn row_forward(&self, row: &mut [f64], out: &mut [Complex64], scratch: &mut [Complex64]) {
        self.r2c
            .process_with_scratch(row, out, scratch)
            .expect("r2c lengths are planned");
    }

    /// The complex-to-real transform of one row of the half spectrum, `row` (left holding
    /// garbage), into `out`; the imaginary parts that a real row cannot have (at `kx = 0`
    /// and, for even `cols`, `kx = cols/2`) are ignored.
    #[inline]
    fn row_inverse(&self, row: &mut [Complex64], out: &mut [f64], scratch: &mut [Complex64]) {
        let m = self.m;
        row[0].im = 0.0;
        if self.cols % 2 == 0 {
            row[m - 1].im = 0.0;
        }
        self.c2r
            .process_with_scratch(row, out, scratch)
            .expect("c2r lengths are planned and edge imaginary parts zeroed");
    }

    /// `field = F^-1[spec]`, keeping `spec`; `work` is resized and used as scratch.
    ///
    /// # Panics
    ///
    /// As [`Fft2::inverse_in_place`]: if `field` is not `rows x cols` or `spec` not a
    /// half spectrum.
    pub fn inverse(&self, spec: &[Complex64], field: &mut [f64], work: &mut Vec<Complex64>) {
        work.clear();
        work.extend_from_slice(spec);
        self.inverse_in_place(work, field);
    }
}

/// Rows (of a grid of `rows` rows) handed to one rayon task: a few tasks per thread for
/// load balance.
fn rows_per_task(rows: usize) -> usize {
    let tasks = TASKS_PER_THREAD * rayon::current_num_threads().max(1);
    rows.div_ceil(tasks).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Square grids, and rectangles of even and odd sides either way round.
    const SHAPES: [(usize, usize); 17] = [
        (4, 4),
        (5, 5),
        (6, 6),
        (7, 7),
        (8, 8),
        (12, 12),
        (15, 15),
        (16, 16),
        (31, 31),
        (32, 32),
        (6, 10),
        (12, 8),
        (5, 9),
        (9, 4),
        (7, 12),
        (16, 5),
        (20, 33),
    ];

    #[test]
    fn forward_matches_direct_sum_and_inverse_round_trips() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for (rows, cols) in SHAPES {
            let grid = Grid::rectangle(rows, cols, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let field: Vec<f64> = (0..rows * cols)
                .map(|_| rng.random::<f64>() - 0.5)
                .collect();
            let mut spec = fft.new_spectrum();
            fft.forward(&field, &mut spec);
            let control = crate::engine::testing::naive_dft(&grid, &field);
            for (a, b) in spec.iter().zip(&control) {
                assert!((a - b).norm() < 1e-14, "{rows} x {cols}: {a} vs {b}");
            }
            let mut back = vec![0.0; rows * cols];
            fft.inverse_in_place(&mut spec, &mut back);
            for (a, b) in back.iter().zip(&field) {
                assert!((a - b).abs() < 1e-14, "{rows} x {cols}: round trip");
            }
        }
    }

    #[test]
    fn parseval_holds_with_half_spectrum_weights() {
        for (rows, cols) in [(24usize, 24usize), (24, 15), (15, 24), (10, 6)] {
            let grid = Grid::rectangle(rows, cols, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            let field: Vec<f64> = (0..rows * cols).map(|_| rng.random::<f64>()).collect();
            let mut spec = fft.new_spectrum();
            fft.forward(&field, &mut spec);
            let real: f64 = field.iter().map(|x| x * x).sum::<f64>() / (rows * cols) as f64;
            let fourier: f64 = spec
                .iter()
                .enumerate()
                .map(|(s, c)| grid.weight_of(s) * c.norm_sqr())
                .sum();
            assert!(
                (real - fourier).abs() < 1e-14 * real,
                "{rows} x {cols}: {real} vs {fourier}"
            );
        }
    }
}
