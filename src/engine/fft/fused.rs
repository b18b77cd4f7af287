//! The convolution `out = F^-1[kernel F[x]]` fused with a solver's passes over its fields:
//! the row transforms of the forward pass read `x` as a [`FusedPass`] generates it, row by
//! row, and those of the inverse pass hand each row of the result to the same pass as soon
//! as it is written. A row is generated, and consumed, while it is in cache, so the input
//! and output passes of a solver iteration cost no extra sweep over memory.
//!
//! A convolution may carry a second field, `side`, that the pass writes while it generates
//! `x` and reads again beside the result (CG's search direction, its pressure); without
//! one, the pass sees empty rows of it. Each task of the row passes takes `rows` rows (see
//! `rows_per_task`); the values the pass returns come back in row order, so reductions
//! over them do not depend on the number of threads.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use super::{at_least, rows_per_task, Fft2, Kernel, Scratch, SCRATCH};
use crate::engine::wide::wide;

/// A solver's work on the rows of a fused convolution ([`Fft2::convolve`]): it generates
/// each row of the input `x`, and consumes each row of the result. Both are called on any
/// thread, each row once; the values they return come back in row order.
///
/// An implementation whose loops are hot marks both methods `#[inline(always)]`, so that
/// they are compiled into the AVX2 build of the row loop ([`crate::engine::wide`]).
pub trait FusedPass: Sync {
    /// What generating a row returns (its partial sums, or `()`).
    type Generated: Send;
    /// What consuming a row returns.
    type Consumed: Send;

    /// Writes row `i` of `x` into `x` (and may write row `i` of `side`, empty without
    /// one). `old` is row `i` of the output before the convolution, so that a field only
    /// read to generate `x` can share its memory with the result: every row is generated
    /// before the first one is written.
    fn generate(&self, i: usize, x: &mut [f64], side: &mut [f64], old: &[f64]) -> Self::Generated;

    /// Sees row `i` of the result once it is in the output, with row `i` of `side` (empty
    /// without one).
    fn consume(&self, i: usize, result: &[f64], side: &[f64]) -> Self::Consumed;
}

/// The values a fused convolution's pass returned, in row order.
pub type PassValues<P> = (
    Vec<<P as FusedPass>::Generated>,
    Vec<<P as FusedPass>::Consumed>,
);

impl Fft2 {
    /// A fused convolution `out = F^-1[kernel F[x]]`, with `x` generated, and the result
    /// consumed, row by row by `pass` (see the module docs). `kernel` comes from
    /// [`Fft2::kernel`]; `side`, if given, is a second field the pass keeps; `spec` is
    /// work space. Returns what the pass returned for each row, in row order.
    ///
    /// # Panics
    ///
    /// If `kernel` was planned for another grid, or `spec`, `out` or `side` is not of the
    /// planned grid's length (a half spectrum; `rows x cols`).
    pub fn convolve<P: FusedPass>(
        &self,
        kernel: &Kernel,
        spec: &mut [Complex64],
        side: Option<&mut [f64]>,
        pass: &P,
        out: &mut [f64],
    ) -> PassValues<P> {
        assert_eq!(
            kernel.shape,
            (self.rows, self.cols),
            "kernel planned for another grid"
        );
        assert_eq!(spec.len(), self.spectrum_len(), "spectrum length");
        assert_eq!(out.len(), self.field_len(), "output length");
        if let Some(s) = &side {
            assert_eq!(s.len(), self.field_len(), "side length");
        }
        self.count(2);
        let rows = rows_per_task(self.rows);
        let mut side = side;
        let generated = self.generate(spec, side.as_deref_mut(), out, rows, pass);
        self.columns_with(spec, kernel);
        let consumed = self.consume(spec, out, side, rows, pass);
        (
            generated.into_iter().flatten().collect(),
            consumed.into_iter().flatten().collect(),
        )
    }

    /// The input pass: row `i` of `x` from the pass (with its rows of `side` and of
    /// `old`), transformed along the row into `spec`, `rows` rows per task; the values of
    /// each task's rows, in order.
    fn generate<P: FusedPass>(
        &self,
        spec: &mut [Complex64],
        side: Option<&mut [f64]>,
        old: &[f64],
        rows: usize,
        pass: &P,
    ) -> Vec<Vec<P::Generated>> {
        let (n, m) = (self.cols, self.m);
        spec.par_chunks_mut(m * rows)
            .zip(side_chunks(side, n * rows, self.rows.div_ceil(rows)))
            .zip(old.par_chunks(n * rows))
            .enumerate()
            .map(|(c, ((spec_chunk, side_chunk), old_chunk))| {
                SCRATCH.with(|cell| {
                    let mut guard = cell.borrow_mut();
                    let Scratch { real, complex, .. } = &mut *guard;
                    let row = at_least(real, n);
                    let scratch = at_least(complex, self.r2c.get_scratch_len());
                    let mut values = Vec::with_capacity(rows);
                    for (k, o) in spec_chunk.chunks_exact_mut(m).enumerate() {
                        let side_row = side_row(side_chunk, k, n);
                        let old_row = &old_chunk[k * n..(k + 1) * n];
                        values.push(wide(
                            #[inline(always)]
                            || pass.generate(c * rows + k, row, side_row, old_row),
                        ));
                        self.row_forward(row, o, scratch);
                    }
                    values
                })
            })
            .collect()
    }

    /// The output pass: `spec` transformed back along the rows into `out`, `rows` rows
    /// per task, and each row of the result handed to the pass with its row of `side`;
    /// the values of each task's rows, in order.
    fn consume<P: FusedPass>(
        &self,
        spec: &mut [Complex64],
        out: &mut [f64],
        side: Option<&mut [f64]>,
        rows: usize,
        pass: &P,
    ) -> Vec<Vec<P::Consumed>> {
        let (n, m) = (self.cols, self.m);
        spec.par_chunks_mut(m * rows)
            .zip(out.par_chunks_mut(n * rows))
            .zip(side_chunks(side, n * rows, self.rows.div_ceil(rows)))
            .enumerate()
            .map(|(c, ((spec_chunk, out_chunk), side_chunk))| {
                SCRATCH.with(|cell| {
                    let mut guard = cell.borrow_mut();
                    let scratch = at_least(&mut guard.complex, self.c2r.get_scratch_len());
                    let mut values = Vec::with_capacity(rows);
                    for (k, (i_row, o)) in spec_chunk
                        .chunks_exact_mut(m)
                        .zip(out_chunk.chunks_exact_mut(n))
                        .enumerate()
                    {
                        self.row_inverse(i_row, o, scratch);
                        let side_row: &[f64] = side_row(side_chunk, k, n);
                        values.push(wide(
                            #[inline(always)]
                            || pass.consume(c * rows + k, o, side_row),
                        ));
                    }
                    values
                })
            })
            .collect()
    }
}

/// The tasks' chunks of `side` (`len` values each), or `tasks` empty chunks without one.
fn side_chunks(side: Option<&mut [f64]>, len: usize, tasks: usize) -> Vec<&mut [f64]> {
    match side {
        Some(side) => side.chunks_mut(len).collect(),
        None => std::iter::repeat_with(|| &mut [][..]).take(tasks).collect(),
    }
}

/// Row `k` (of `n` values, the grid's columns) of a task's chunk of `side`; empty without
/// one.
#[inline(always)]
fn side_row(chunk: &mut [f64], k: usize, n: usize) -> &mut [f64] {
    if chunk.is_empty() {
        chunk
    } else {
        &mut chunk[k * n..(k + 1) * n]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::grid::Grid;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `x` copied from a field; nothing consumed.
    struct Copy<'a> {
        field: &'a [f64],
        n: usize,
    }

    impl FusedPass for Copy<'_> {
        type Generated = ();
        type Consumed = ();
        fn generate(&self, i: usize, x: &mut [f64], _: &mut [f64], _: &[f64]) {
            x.copy_from_slice(&self.field[i * self.n..(i + 1) * self.n]);
        }
        fn consume(&self, _: usize, _: &[f64], _: &[f64]) {}
    }

    /// `x` copied from a field and kept in `side`; the row index and the row sums
    /// returned, and the side checked.
    struct Kept<'a> {
        x: &'a [f64],
        n: usize,
    }

    impl FusedPass for Kept<'_> {
        type Generated = usize;
        type Consumed = (usize, f64);
        fn generate(&self, i: usize, row: &mut [f64], keep: &mut [f64], _: &[f64]) -> usize {
            row.copy_from_slice(&self.x[i * self.n..(i + 1) * self.n]);
            keep.copy_from_slice(row);
            i
        }
        fn consume(&self, i: usize, row: &[f64], kept: &[f64]) -> (usize, f64) {
            assert_eq!(kept, &self.x[i * self.n..(i + 1) * self.n]);
            (i, row.iter().sum::<f64>())
        }
    }

    /// `x` read from the output's old values.
    struct InPlace;

    impl FusedPass for InPlace {
        type Generated = ();
        type Consumed = ();
        fn generate(&self, _: usize, x: &mut [f64], _: &mut [f64], old: &[f64]) {
            x.copy_from_slice(old);
        }
        fn consume(&self, _: usize, _: &[f64], _: &[f64]) {}
    }

    #[test]
    fn both_orders_of_the_column_pass_give_the_same_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for (rows, cols) in [
            (6usize, 6usize),
            (16, 16),
            (33, 33),
            (64, 64),
            (12, 20),
            (33, 8),
        ] {
            let grid = Grid::rectangle(rows, cols, 1.0).unwrap();
            let by_column = Fft2::new(&grid);
            let mut by_row = Fft2::new(&grid);
            by_row.by_column = false;
            assert!(
                by_column.by_column,
                "{rows} x {cols}: small grids go column by column"
            );
            let points = rows * cols;
            let field: Vec<f64> = (0..points).map(|_| rng.random::<f64>() - 0.5).collect();
            let mut specs = [by_column.new_spectrum(), by_row.new_spectrum()];
            by_column.forward(&field, &mut specs[0]);
            by_row.forward(&field, &mut specs[1]);
            assert_eq!(specs[0], specs[1], "{rows} x {cols}: forward");
            let table: Vec<f64> = (0..by_row.spectrum_len()).map(|i| i as f64).collect();
            let kernel = by_row.kernel(&table);
            let mut outs = [vec![0.0; points], vec![0.0; points]];
            for (fft, (spec, out)) in [&by_column, &by_row]
                .into_iter()
                .zip(specs.iter_mut().zip(outs.iter_mut()))
            {
                let copy = Copy {
                    field: &field,
                    n: cols,
                };
                fft.convolve(&kernel, spec, None, &copy, out);
            }
            assert_eq!(outs[0], outs[1], "{rows} x {cols}: convolution");
        }
    }

    #[test]
    fn fused_convolution_equals_transform_multiply_transform() {
        for (rows, cols) in [
            (8usize, 8usize),
            (9, 9),
            (16, 16),
            (30, 30),
            (10, 6),
            (7, 12),
        ] {
            let grid = Grid::rectangle(rows, cols, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let points = rows * cols;
            let mut rng = ChaCha8Rng::seed_from_u64((rows * 100 + cols) as u64);
            let x: Vec<f64> = (0..points).map(|_| rng.random::<f64>() - 0.5).collect();
            let kernel: Vec<f64> = (0..grid.modes()).map(|s| 1.0 + grid.q(s)).collect();
            // Reference: forward, multiply, inverse.
            let mut spec = fft.new_spectrum();
            fft.forward(&x, &mut spec);
            for (c, k) in spec.iter_mut().zip(&kernel) {
                *c *= *k;
            }
            let mut want = vec![0.0; points];
            fft.inverse_in_place(&mut spec, &mut want);
            // Fused, with the input kept in `side` and row sums returned.
            let mut side = vec![0.0; points];
            let mut got = vec![0.0; points];
            let (ins, outs) = fft.convolve(
                &fft.kernel(&kernel),
                &mut spec,
                Some(&mut side),
                &Kept { x: &x, n: cols },
                &mut got,
            );
            assert_eq!(side, x);
            assert_eq!(ins, (0..rows).collect::<Vec<_>>());
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() < 1e-13, "{rows} x {cols}");
            }
            for (i, (k, s)) in outs.iter().enumerate() {
                assert_eq!(*k, i);
                let direct: f64 = got[i * cols..(i + 1) * cols].iter().sum();
                assert_eq!(*s, direct);
            }
        }
    }

    #[test]
    fn inverse_kernel_undoes_the_kernel_in_place() {
        // x -> k x -> (1/k) (k x) returns x minus its mean (k = 0 at q = 0), with the
        // second convolution reading its input from the buffer it writes.
        for (rows, cols) in [(8usize, 8usize), (15, 15), (32, 32), (15, 8), (8, 22)] {
            let grid = Grid::rectangle(rows, cols, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let points = rows * cols;
            let mut rng = ChaCha8Rng::seed_from_u64(7 + (rows * 100 + cols) as u64);
            let x: Vec<f64> = (0..points).map(|_| rng.random::<f64>() - 0.5).collect();
            let mean = x.iter().sum::<f64>() / points as f64;
            let table: Vec<f64> = (0..grid.modes()).map(|s| grid.q(s)).collect();
            let k = fft.kernel(&table);
            let mut spec = fft.new_spectrum();
            let mut y = vec![0.0; points];
            let copy = Copy { field: &x, n: cols };
            fft.convolve(&k, &mut spec, None, &copy, &mut y);
            fft.convolve(&k.inverse(), &mut spec, None, &InPlace, &mut y);
            for (a, b) in y.iter().zip(&x) {
                assert!(
                    (a - (b - mean)).abs() < 1e-13,
                    "{rows} x {cols}: {a} vs {}",
                    b - mean
                );
            }
        }
    }
}
