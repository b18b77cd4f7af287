//! The column pass of the 2D transforms: blocks of a few columns of the half spectrum, in
//! parallel, each gathered into a small contiguous buffer (`blocks`), transformed
//! (rustfft) and scattered back; in a convolution the kernel multiplies each block between
//! its forward and inverse transforms, so the spectrum is gathered and scattered once.

use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex64;
use rustfft::Fft;

use super::blocks::{gather, scatter, SharedMut};
use super::{at_least, Fft2, Kernel, Scratch, SCRATCH};
use crate::engine::wide::wide;

/// Complex values in a gathered block of columns: 256 KiB, so that the block stays in a
/// core's L2 cache (a size from the cache, not a measurement).
const BLOCK_VALUES: usize = 16384;
/// Fewest columns in a block: four complex values are one 64-byte cache line, so the
/// gather reads whole lines of every row.
const BLOCK_COLUMNS_MIN: usize = 4;
/// Most columns in a block (small grids): enough for whole lines, few enough for several
/// blocks per thread.
const BLOCK_COLUMNS_MAX: usize = 16;

/// Columns in a block of the column pass on a grid of `rows` rows (the length of a
/// column).
pub(super) fn block_width(rows: usize) -> usize {
    (BLOCK_VALUES / rows).clamp(BLOCK_COLUMNS_MIN, BLOCK_COLUMNS_MAX)
}

impl Fft2 {
    /// Column pass of a convolution: forward transform, multiplication by the kernel,
    /// inverse transform, block by block.
    pub(super) fn columns_with(&self, spec: &mut [Complex64], kernel: &Kernel) {
        let n = self.rows;
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
    pub(super) fn columns(&self, spec: &mut [Complex64], fft: &Arc<dyn Fft<f64>>, scale: f64) {
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
        // `n`: the length of a column, the grid's rows.
        let (n, m, block, by_column) = (self.rows, self.m, self.block, self.by_column);
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
