//! Real two-dimensional FFTs on the half spectrum, parallel over rows and columns.
//!
//! Convention ([`crate::conventions`], section 2): `f~(q) = N^-2 sum_r f(r) exp(-i q.r)` and
//! `f(r) = sum_q f~(q) exp(i q.r)`, so that `mean(f^2) = sum_q |f~(q)|^2`. The forward
//! transform carries the whole `1/N^2`; the inverse carries none.
//!
//! Layout: see [`crate::engine::grid`]. The transform is done in two passes over the data, without
//! a transposed copy: real-to-complex transforms of every row (realfft) write the half
//! spectrum in place of its rows, then blocks of a few columns are gathered into a small
//! contiguous buffer, transformed (rustfft), and scattered back. Both passes run on rayon's
//! pool; the result does not depend on the number of threads (every 1D transform is the
//! same computation whichever thread runs it).

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};

use crate::engine::grid::Grid;
use crate::engine::wide::wide;

mod blocks;

use blocks::{gather, scatter, SharedMut, COLUMN_ORDER_MAX_N};

/// Precomputed plans for real 2D transforms on one grid size.
///
/// The plans are shared, immutable tables; per-thread scratch (a row or a block of
/// columns) is kept between calls. Every 2D transform is counted ([`Fft2::transforms`]),
/// so that the cost of a solver can be stated in FFT pairs.
pub struct Fft2 {
    n: usize,
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
        f.debug_struct("Fft2").field("n", &self.n).finish()
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
    n: usize,
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

/// Complex values in a gathered block of columns: 256 KiB, so that the block stays in a
/// core's L2 cache (a size from the cache, not a measurement).
const BLOCK_VALUES: usize = 16384;
/// Fewest columns in a block: four complex values are one 64-byte cache line, so the
/// gather reads whole lines of every row.
const BLOCK_COLUMNS_MIN: usize = 4;
/// Most columns in a block (small grids): enough for whole lines, few enough for several
/// blocks per thread.
const BLOCK_COLUMNS_MAX: usize = 16;
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
        let n = grid.n();
        let mut real_planner = RealFftPlanner::<f64>::new();
        let mut planner = FftPlanner::<f64>::new();
        let block = (BLOCK_VALUES / n).clamp(BLOCK_COLUMNS_MIN, BLOCK_COLUMNS_MAX);
        Self {
            n,
            m: grid.half_cols(),
            r2c: real_planner.plan_fft_forward(n),
            c2r: real_planner.plan_fft_inverse(n),
            col_fwd: planner.plan_fft_forward(n),
            col_inv: planner.plan_fft_inverse(n),
            block,
            by_column: n <= COLUMN_ORDER_MAX_N,
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
    pub fn kernel(&self, table: &[f64]) -> Kernel {
        let (n, m) = (self.n, self.m);
        assert_eq!(table.len(), n * m, "kernel table length");
        let norm = 1.0 / (n as f64 * n as f64);
        let mut values = vec![0.0; n * m];
        for (ky, row) in table.chunks_exact(m).enumerate() {
            for (kx, &v) in row.iter().enumerate() {
                values[kx * n + ky] = v * norm;
            }
        }
        Kernel {
            n,
            values: values.into(),
            norm,
            inverse: false,
        }
    }

    fn count(&self, k: u64) {
        self.transforms.fetch_add(k, Ordering::Relaxed);
    }

    /// Length of a half spectrum, `n (n/2 + 1)`.
    pub fn spectrum_len(&self) -> usize {
        self.n * self.m
    }

    /// A zeroed half spectrum.
    pub fn new_spectrum(&self) -> Vec<Complex64> {
        vec![Complex64::new(0.0, 0.0); self.spectrum_len()]
    }

    /// `spec = F[field]` with the `1/N^2` normalisation.
    pub fn forward(&self, field: &[f64], spec: &mut [Complex64]) {
        let (n, m) = (self.n, self.m);
        assert_eq!(field.len(), n * n, "field length");
        assert_eq!(spec.len(), n * m, "spectrum length");
        self.count(1);
        let rows = rows_per_task(n);
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
                        self.r2c
                            .process_with_scratch(row, o, scratch)
                            .expect("r2c lengths are planned");
                    }
                })
            });
        let scale = 1.0 / (n as f64 * n as f64);
        self.columns(spec, &self.col_fwd, scale);
    }

    /// `field = F^-1[spec]`. The spectrum is used as scratch and left holding garbage.
    ///
    /// `spec` must be the half spectrum of a real field (Hermitian on the columns
    /// `kx = 0` and, for even `n`, `kx = n/2`); the imaginary parts that a real field
    /// cannot have are ignored.
    pub fn inverse_in_place(&self, spec: &mut [Complex64], field: &mut [f64]) {
        let (n, m) = (self.n, self.m);
        assert_eq!(field.len(), n * n, "field length");
        assert_eq!(spec.len(), n * m, "spectrum length");
        self.count(1);
        self.columns(spec, &self.col_inv, 1.0);
        let rows = rows_per_task(n);
        let even = n % 2 == 0;
        spec.par_chunks_mut(m * rows)
            .zip(field.par_chunks_mut(n * rows))
            .for_each(|(input, out)| {
                SCRATCH.with(|cell| {
                    let mut guard = cell.borrow_mut();
                    let scratch = at_least(&mut guard.complex, self.c2r.get_scratch_len());
                    for (i, o) in input.chunks_exact_mut(m).zip(out.chunks_exact_mut(n)) {
                        i[0].im = 0.0;
                        if even {
                            i[m - 1].im = 0.0;
                        }
                        self.c2r
                            .process_with_scratch(i, o, scratch)
                            .expect("c2r lengths are planned and edge imaginary parts zeroed");
                    }
                })
            });
    }

    /// `field = F^-1[spec]`, keeping `spec`; `work` is resized and used as scratch.
    pub fn inverse(&self, spec: &[Complex64], field: &mut [f64], work: &mut Vec<Complex64>) {
        work.clear();
        work.extend_from_slice(spec);
        self.inverse_in_place(work, field);
    }

    /// A fused convolution `out = F^-1[kernel F[x]]`, with `x` generated row by row.
    ///
    /// `kernel` comes from [`Fft2::kernel`]. `input(i, row, side, old)` writes row `i` of `x`
    /// into `row` (and may write the matching row of `side`, a second field it keeps, e.g. a
    /// search direction) and returns a value; `old` is row `i` of `out` before the call, so
    /// a field that is only read to generate `x` can share its memory with the result. Every
    /// row is generated before the first one is written. `output(i, row, side)` sees row `i`
    /// of the result once it is in `out`, with the same row of `side` (empty without one),
    /// and returns a value. Both lists of values come back in row order, so reductions over
    /// them do not depend on the number of threads. `spec` is work space. Each row is
    /// generated, and consumed, while it is in cache: the input and output passes of a
    /// solver iteration cost no extra sweep over memory.
    #[allow(clippy::too_many_arguments)]
    pub fn convolve<A, B, I, O>(
        &self,
        kernel: &Kernel,
        spec: &mut [Complex64],
        side: Option<&mut [f64]>,
        input: I,
        out: &mut [f64],
        output: O,
    ) -> (Vec<B>, Vec<A>)
    where
        A: Send,
        B: Send,
        I: Fn(usize, &mut [f64], &mut [f64], &[f64]) -> B + Sync,
        O: Fn(usize, &[f64], &[f64]) -> A + Sync,
    {
        let n = self.n;
        assert_eq!(kernel.n, n, "kernel planned for another grid");
        assert_eq!(spec.len(), n * self.m, "spectrum length");
        assert_eq!(out.len(), n * n, "output length");
        if let Some(s) = &side {
            assert_eq!(s.len(), n * n, "side length");
        }
        self.count(2);
        let rows = rows_per_task(n);
        let mut side = side;
        let generated = self.generate(spec, side.as_deref_mut(), out, rows, &input);
        self.columns_with(spec, kernel);
        let consumed = self.consume(spec, out, side.as_deref(), rows, &output);
        (
            generated.into_iter().flatten().collect(),
            consumed.into_iter().flatten().collect(),
        )
    }

    /// The input pass of [`Fft2::convolve`]: row `i` of `x` from `input(i, row, side row,
    /// old row)`, transformed along the row into `spec`, `rows` rows per task; the values
    /// of each task's rows, in order.
    fn generate<B, I>(
        &self,
        spec: &mut [Complex64],
        side: Option<&mut [f64]>,
        old: &[f64],
        rows: usize,
        input: &I,
    ) -> Vec<Vec<B>>
    where
        B: Send,
        I: Fn(usize, &mut [f64], &mut [f64], &[f64]) -> B + Sync,
    {
        let (n, m) = (self.n, self.m);
        let side_rows = if side.is_some() { n } else { 0 };
        let forward =
            |c: usize, spec_chunk: &mut [Complex64], side_chunk: &mut [f64], old_chunk: &[f64]| {
                SCRATCH.with(|cell| {
                    let mut guard = cell.borrow_mut();
                    let Scratch { real, complex, .. } = &mut *guard;
                    let row = at_least(real, n);
                    let scratch = at_least(complex, self.r2c.get_scratch_len());
                    let mut values = Vec::with_capacity(rows);
                    for (k, o) in spec_chunk.chunks_exact_mut(m).enumerate() {
                        let i = c * rows + k;
                        let side_row: &mut [f64] = if side_rows > 0 {
                            &mut side_chunk[k * n..(k + 1) * n]
                        } else {
                            &mut []
                        };
                        values.push(wide(
                            #[inline(always)]
                            || input(i, row, side_row, &old_chunk[k * n..(k + 1) * n]),
                        ));
                        self.r2c
                            .process_with_scratch(row, o, scratch)
                            .expect("r2c lengths are planned");
                    }
                    values
                })
            };
        match side {
            Some(side) => spec
                .par_chunks_mut(m * rows)
                .zip(side.par_chunks_mut(n * rows))
                .zip(old.par_chunks(n * rows))
                .enumerate()
                .map(|(c, ((a, b), o))| forward(c, a, b, o))
                .collect(),
            None => spec
                .par_chunks_mut(m * rows)
                .zip(old.par_chunks(n * rows))
                .enumerate()
                .map(|(c, (chunk, o))| forward(c, chunk, &mut [], o))
                .collect(),
        }
    }

    /// The output pass of [`Fft2::convolve`]: `spec` transformed back along the rows into
    /// `out`, `rows` rows per task, and `output(i, out row, side row)` of every row; the
    /// values of each task's rows, in order.
    fn consume<A, O>(
        &self,
        spec: &mut [Complex64],
        out: &mut [f64],
        side: Option<&[f64]>,
        rows: usize,
        output: &O,
    ) -> Vec<Vec<A>>
    where
        A: Send,
        O: Fn(usize, &[f64], &[f64]) -> A + Sync,
    {
        let (n, m) = (self.n, self.m);
        let side_rows = if side.is_some() { n } else { 0 };
        let even = n % 2 == 0;
        let backward =
            |c: usize, spec_chunk: &mut [Complex64], out_chunk: &mut [f64], side_chunk: &[f64]| {
                SCRATCH.with(|cell| {
                    let mut guard = cell.borrow_mut();
                    let scratch = at_least(&mut guard.complex, self.c2r.get_scratch_len());
                    let mut values = Vec::with_capacity(rows);
                    for (k, (i_row, o)) in spec_chunk
                        .chunks_exact_mut(m)
                        .zip(out_chunk.chunks_exact_mut(n))
                        .enumerate()
                    {
                        i_row[0].im = 0.0;
                        if even {
                            i_row[m - 1].im = 0.0;
                        }
                        self.c2r
                            .process_with_scratch(i_row, o, scratch)
                            .expect("c2r lengths are planned and edge imaginary parts zeroed");
                        let side_row: &[f64] = if side_rows > 0 {
                            &side_chunk[k * n..(k + 1) * n]
                        } else {
                            &[]
                        };
                        values.push(wide(
                            #[inline(always)]
                            || output(c * rows + k, o, side_row),
                        ));
                    }
                    values
                })
            };
        match side {
            Some(side) => spec
                .par_chunks_mut(m * rows)
                .zip(out.par_chunks_mut(n * rows))
                .zip(side.par_chunks(n * rows))
                .enumerate()
                .map(|(c, ((a, b), d))| backward(c, a, b, d))
                .collect(),
            None => spec
                .par_chunks_mut(m * rows)
                .zip(out.par_chunks_mut(n * rows))
                .enumerate()
                .map(|(c, (a, b))| backward(c, a, b, &[]))
                .collect(),
        }
    }

    /// Column pass of a convolution: forward transform, multiplication by the kernel,
    /// inverse transform, block by block.
    fn columns_with(&self, spec: &mut [Complex64], kernel: &Kernel) {
        let n = self.n;
        let scratch_len = self
            .col_fwd
            .get_inplace_scratch_len()
            .max(self.col_inv.get_inplace_scratch_len());
        self.column_blocks(spec, scratch_len, 1.0, |c0, buf, scratch| {
            self.col_fwd.process_with_scratch(buf, scratch);
            let k = &kernel.values[c0 * n..c0 * n + buf.len()];
            wide(
                #[inline(always)]
                || {
                    if kernel.inverse {
                        // kv = k / N^2, and the inverse needs (1/k) / N^2 = N^-4 / kv.
                        let norm2 = kernel.norm * kernel.norm;
                        for (b, &kv) in buf.iter_mut().zip(k) {
                            *b *= if kv > 0.0 { norm2 / kv } else { 0.0 };
                        }
                    } else {
                        for (b, &kv) in buf.iter_mut().zip(k) {
                            *b *= kv;
                        }
                    }
                },
            );
            self.col_inv.process_with_scratch(buf, scratch);
        });
    }

    /// Transforms every column of the half spectrum with `fft`, scaling by `scale`.
    fn columns(&self, spec: &mut [Complex64], fft: &Arc<dyn Fft<f64>>, scale: f64) {
        self.column_blocks(
            spec,
            fft.get_inplace_scratch_len(),
            scale,
            |_, buf, scratch| fft.process_with_scratch(buf, scratch),
        );
    }

    /// The column pass: blocks of [`Fft2::new`]'s `block` columns of the half spectrum,
    /// in parallel, each gathered column by column into a contiguous buffer, handed to
    /// `body(first column, buffer, scratch of scratch_len)`, and scattered back times
    /// `scale`.
    fn column_blocks<F>(&self, spec: &mut [Complex64], scratch_len: usize, scale: f64, body: F)
    where
        F: Fn(usize, &mut [Complex64], &mut [Complex64]) + Sync,
    {
        let (n, m, block, by_column) = (self.n, self.m, self.block, self.by_column);
        let blocks = m.div_ceil(block);
        let base = SharedMut(spec.as_mut_ptr());
        (0..blocks).into_par_iter().for_each(|b| {
            SCRATCH.with(|cell| {
                let mut guard = cell.borrow_mut();
                let Scratch {
                    complex,
                    block: buf,
                    ..
                } = &mut *guard;
                let c0 = b * block;
                let width = block.min(m - c0);
                let buf = at_least(buf, width * n);
                let scratch = at_least(complex, scratch_len);
                // SAFETY: block `b` owns columns c0..c0+width of every row; no other task
                // touches them, and `spec` outlives this loop.
                wide(
                    #[inline(always)]
                    || unsafe { gather(base, m, c0, buf, n, by_column) },
                );
                body(c0, buf, scratch);
                // SAFETY: as above.
                wide(
                    #[inline(always)]
                    || unsafe { scatter(base, m, c0, buf, n, scale, by_column) },
                );
            })
        });
    }
}

/// Rows handed to one rayon task: a few tasks per thread for load balance.
fn rows_per_task(n: usize) -> usize {
    let tasks = TASKS_PER_THREAD * rayon::current_num_threads().max(1);
    n.div_ceil(tasks).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Direct O(N^4) transform with the crate's convention, the independent control.
    fn naive_forward(grid: &Grid, field: &[f64]) -> Vec<Complex64> {
        let n = grid.n();
        let mut out = vec![Complex64::new(0.0, 0.0); grid.modes()];
        for (s, o) in out.iter_mut().enumerate() {
            let (mx, my) = grid.wavevector(s);
            let mut acc = Complex64::new(0.0, 0.0);
            for i in 0..n {
                for j in 0..n {
                    let phase =
                        -2.0 * std::f64::consts::PI * (mx as f64 * j as f64 + my as f64 * i as f64)
                            / n as f64;
                    acc += Complex64::from_polar(field[i * n + j], phase);
                }
            }
            *o = acc / (n * n) as f64;
        }
        out
    }

    #[test]
    fn both_orders_of_the_column_pass_give_the_same_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for n in [6usize, 16, 33, 64] {
            let grid = Grid::new(n, 1.0).unwrap();
            let by_column = Fft2::new(&grid);
            let mut by_row = Fft2::new(&grid);
            by_row.by_column = false;
            assert!(
                by_column.by_column,
                "n = {n}: small grids go column by column"
            );
            let field: Vec<f64> = (0..n * n).map(|_| rng.random::<f64>() - 0.5).collect();
            let mut specs = [by_column.new_spectrum(), by_row.new_spectrum()];
            by_column.forward(&field, &mut specs[0]);
            by_row.forward(&field, &mut specs[1]);
            assert_eq!(specs[0], specs[1], "n = {n}: forward");
            let table: Vec<f64> = (0..by_row.spectrum_len()).map(|i| i as f64).collect();
            let kernel = by_row.kernel(&table);
            let mut outs = [vec![0.0; n * n], vec![0.0; n * n]];
            for (fft, (spec, out)) in [&by_column, &by_row]
                .into_iter()
                .zip(specs.iter_mut().zip(outs.iter_mut()))
            {
                fft.convolve(
                    &kernel,
                    spec,
                    None,
                    |i, row, _, _| row.copy_from_slice(&field[i * n..(i + 1) * n]),
                    out,
                    |_, _, _| (),
                );
            }
            assert_eq!(outs[0], outs[1], "n = {n}: convolution");
        }
    }

    #[test]
    fn forward_matches_direct_sum_and_inverse_round_trips() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for n in [4usize, 5, 6, 7, 8, 12, 15, 16, 31, 32] {
            let grid = Grid::new(n, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let field: Vec<f64> = (0..n * n).map(|_| rng.random::<f64>() - 0.5).collect();
            let mut spec = fft.new_spectrum();
            fft.forward(&field, &mut spec);
            let control = naive_forward(&grid, &field);
            for (a, b) in spec.iter().zip(&control) {
                assert!((a - b).norm() < 1e-14, "n = {n}: {a} vs {b}");
            }
            let mut back = vec![0.0; n * n];
            fft.inverse_in_place(&mut spec, &mut back);
            for (a, b) in back.iter().zip(&field) {
                assert!((a - b).abs() < 1e-14, "n = {n}: round trip");
            }
        }
    }

    #[test]
    fn fused_convolution_equals_transform_multiply_transform() {
        for n in [8usize, 9, 16, 30] {
            let grid = Grid::new(n, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let mut rng = ChaCha8Rng::seed_from_u64(n as u64);
            let x: Vec<f64> = (0..n * n).map(|_| rng.random::<f64>() - 0.5).collect();
            let kernel: Vec<f64> = (0..grid.modes()).map(|s| 1.0 + grid.q(s)).collect();
            // Reference: forward, multiply, inverse.
            let mut spec = fft.new_spectrum();
            fft.forward(&x, &mut spec);
            for (c, k) in spec.iter_mut().zip(&kernel) {
                *c *= *k;
            }
            let mut want = vec![0.0; n * n];
            fft.inverse_in_place(&mut spec, &mut want);
            // Fused, with the input kept in `side` and row sums returned.
            let mut side = vec![0.0; n * n];
            let mut got = vec![0.0; n * n];
            let (ins, outs) = fft.convolve(
                &fft.kernel(&kernel),
                &mut spec,
                Some(&mut side),
                |i, row, keep, _| {
                    row.copy_from_slice(&x[i * n..(i + 1) * n]);
                    keep.copy_from_slice(row);
                    i
                },
                &mut got,
                |i, row, kept| {
                    assert_eq!(kept, &x[i * n..(i + 1) * n]);
                    (i, row.iter().sum::<f64>())
                },
            );
            assert_eq!(side, x);
            assert_eq!(ins, (0..n).collect::<Vec<_>>());
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() < 1e-13, "n = {n}");
            }
            for (i, (k, s)) in outs.iter().enumerate() {
                assert_eq!(*k, i);
                let direct: f64 = got[i * n..(i + 1) * n].iter().sum();
                assert_eq!(*s, direct);
            }
        }
    }

    #[test]
    fn inverse_kernel_undoes_the_kernel_in_place() {
        // x -> k x -> (1/k) (k x) returns x minus its mean (k = 0 at q = 0), with the
        // second convolution reading its input from the buffer it writes.
        for n in [8usize, 15, 32] {
            let grid = Grid::new(n, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let mut rng = ChaCha8Rng::seed_from_u64(7 + n as u64);
            let x: Vec<f64> = (0..n * n).map(|_| rng.random::<f64>() - 0.5).collect();
            let mean = x.iter().sum::<f64>() / (n * n) as f64;
            let table: Vec<f64> = (0..grid.modes()).map(|s| grid.q(s)).collect();
            let k = fft.kernel(&table);
            let mut spec = fft.new_spectrum();
            let mut y = vec![0.0; n * n];
            fft.convolve(
                &k,
                &mut spec,
                None,
                |i, row, _, _| row.copy_from_slice(&x[i * n..(i + 1) * n]),
                &mut y,
                |_, _, _| (),
            );
            fft.convolve(
                &k.inverse(),
                &mut spec,
                None,
                |_, row, _, old| row.copy_from_slice(old),
                &mut y,
                |_, _, _| (),
            );
            for (a, b) in y.iter().zip(&x) {
                assert!(
                    (a - (b - mean)).abs() < 1e-13,
                    "n = {n}: {a} vs {}",
                    b - mean
                );
            }
        }
    }

    #[test]
    fn parseval_holds_with_half_spectrum_weights() {
        let n = 24;
        let grid = Grid::new(n, 1.0).unwrap();
        let fft = Fft2::new(&grid);
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let field: Vec<f64> = (0..n * n).map(|_| rng.random::<f64>()).collect();
        let mut spec = fft.new_spectrum();
        fft.forward(&field, &mut spec);
        let real: f64 = field.iter().map(|x| x * x).sum::<f64>() / (n * n) as f64;
        let fourier: f64 = spec
            .iter()
            .enumerate()
            .map(|(s, c)| grid.weight_of(s) * c.norm_sqr())
            .sum();
        assert!((real - fourier).abs() < 1e-14 * real);
    }
}
