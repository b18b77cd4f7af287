//! The column pass's data movement: copying a block of columns of the half spectrum into a
//! contiguous buffer (one column after the other) and back, in the order that suits the
//! grid's size. Pure data movement: the transforms see the same values in either order.

use rustfft::num_complex::Complex64;

/// Largest side (of the longer axis) of a grid whose column pass gathers (and scatters) one
/// column at a time; larger grids go row by row. Column by column, the block buffer is written contiguously but every row
/// of the spectrum is visited once per column: cheap while those rows stay in cache and in
/// the TLB. Row by row, each row is visited once but a row's values go to `block` places
/// `n` values apart, and with `n` a power of two more than eight of them share one L1
/// cache set. Measured (`benches/fft.rs`, one thread, against row by row): the transform
/// pair 28% faster at 256^2, 12-17% at 1024^2, equal at 2048^2, 48% slower at 4096^2.
pub(super) const COLUMN_ORDER_MAX_N: usize = 1024;

/// A raw pointer that may be shared between rayon tasks that touch disjoint elements.
#[derive(Clone, Copy)]
pub(super) struct SharedMut(pub(super) *mut Complex64);
// SAFETY: used only by the column pass, where each task reads and writes a disjoint set of
// columns of one buffer that outlives the parallel loop.
unsafe impl Send for SharedMut {}
unsafe impl Sync for SharedMut {}

impl SharedMut {
    /// The pointer (a method, so that closures capture the whole `Send` wrapper).
    pub(super) fn get(self) -> *mut Complex64 {
        self.0
    }
}

/// Copies columns `c0..c0 + buf.len() / n` of the half spectrum at `base` (`n` rows of `m`
/// values) into `buf`, column after column, `n` values each; visiting the spectrum one
/// column at a time or one row at a time ([`COLUMN_ORDER_MAX_N`]).
///
/// # Safety
/// `base` points to `n m` values and no other thread touches these columns meanwhile.
pub(super) unsafe fn gather(
    base: SharedMut,
    m: usize,
    c0: usize,
    buf: &mut [Complex64],
    n: usize,
    by_column: bool,
) {
    let width = buf.len() / n;
    if by_column {
        for (c, column) in buf.chunks_exact_mut(n).enumerate() {
            let top = base.get().add(c0 + c);
            for (ky, b) in column.iter_mut().enumerate() {
                *b = *top.add(ky * m);
            }
        }
    } else {
        for ky in 0..n {
            let row = base.get().add(ky * m + c0);
            for c in 0..width {
                *buf.get_unchecked_mut(c * n + ky) = *row.add(c);
            }
        }
    }
}

/// Writes `buf` (as filled by [`gather`]) back into its columns, times `scale`.
///
/// # Safety
/// As [`gather`].
pub(super) unsafe fn scatter(
    base: SharedMut,
    m: usize,
    c0: usize,
    buf: &[Complex64],
    n: usize,
    scale: f64,
    by_column: bool,
) {
    let width = buf.len() / n;
    if by_column {
        for (c, column) in buf.chunks_exact(n).enumerate() {
            let top = base.get().add(c0 + c);
            for (ky, b) in column.iter().enumerate() {
                *top.add(ky * m) = *b * scale;
            }
        }
    } else {
        for ky in 0..n {
            let row = base.get().add(ky * m + c0);
            for c in 0..width {
                *row.add(c) = *buf.get_unchecked(c * n + ky) * scale;
            }
        }
    }
}
