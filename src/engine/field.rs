//! Reductions over real fields that give the same bits whatever the number of threads.
//!
//! Sums are split into fixed chunks of [`CHUNK`] elements; each chunk is summed in order,
//! and the chunk sums are added in order. The split depends only on the length, so a run
//! on one thread and a run on two threads add the same numbers in the same order.

use rayon::prelude::*;

use crate::engine::wide::wide;

/// Elements per chunk of a reduction.
pub const CHUNK: usize = 8192;

/// Deterministic parallel sum of `f(i, x_i)` over a slice.
pub fn sum_map<F>(x: &[f64], f: F) -> f64
where
    F: Fn(usize, f64) -> f64 + Sync,
{
    let partial: Vec<f64> = x
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let base = c * CHUNK;
            wide(
                #[inline(always)]
                || {
                    chunk
                        .iter()
                        .enumerate()
                        .map(|(k, &v)| f(base + k, v))
                        .sum::<f64>()
                },
            )
        })
        .collect();
    partial.iter().sum()
}

/// Deterministic parallel sum of `f(a_i, b_i)` over two slices of equal length.
///
/// # Panics
///
/// If `a` and `b` differ in length.
pub fn sum_zip<F>(a: &[f64], b: &[f64], f: F) -> f64
where
    F: Fn(f64, f64) -> f64 + Sync,
{
    assert_eq!(a.len(), b.len());
    let partial: Vec<f64> = a
        .par_chunks(CHUNK)
        .zip(b.par_chunks(CHUNK))
        .map(|(ca, cb)| {
            wide(
                #[inline(always)]
                || ca.iter().zip(cb).map(|(&x, &y)| f(x, y)).sum::<f64>(),
            )
        })
        .collect();
    partial.iter().sum()
}

/// Deterministic parallel fold: `f` maps each fixed chunk of indices `0..len` to a
/// partial result, and the partials are combined with `combine` in chunk order.
pub fn fold_chunks<T, F, C>(len: usize, init: T, f: F, combine: C) -> T
where
    T: Send,
    F: Fn(std::ops::Range<usize>) -> T + Sync,
    C: Fn(T, T) -> T,
{
    let chunks = len.div_ceil(CHUNK);
    let partial: Vec<T> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            wide(
                #[inline(always)]
                || f(c * CHUNK..((c + 1) * CHUNK).min(len)),
            )
        })
        .collect();
    partial.into_iter().fold(init, combine)
}

/// Deterministic parallel pass over two fields of equal length that it may change: `f`
/// maps each fixed chunk of indices, with the matching chunks of `a` and `b`, to a
/// partial result; the partials come back in chunk order, to be combined in that order.
///
/// # Panics
///
/// If `a` and `b` differ in length.
pub fn map_chunks_mut<T, F>(a: &mut [f64], b: &mut [f64], f: F) -> Vec<T>
where
    T: Send,
    F: Fn(std::ops::Range<usize>, &mut [f64], &mut [f64]) -> T + Sync,
{
    assert_eq!(a.len(), b.len(), "fields of one grid");
    a.par_chunks_mut(CHUNK)
        .zip(b.par_chunks_mut(CHUNK))
        .enumerate()
        .map(|(c, (ca, cb))| {
            wide(
                #[inline(always)]
                || f(c * CHUNK..c * CHUNK + ca.len(), ca, cb),
            )
        })
        .collect()
}

/// `K` sums added element by element.
pub fn add<const K: usize>(mut a: [f64; K], b: [f64; K]) -> [f64; K] {
    for (x, y) in a.iter_mut().zip(b) {
        *x += y;
    }
    a
}

/// Partial sums (of rows or chunks, say) added in order: the same bits whatever the number
/// of threads that computed them.
pub fn add_all<const K: usize>(parts: impl IntoIterator<Item = [f64; K]>) -> [f64; K] {
    parts.into_iter().fold([0.0; K], add)
}

/// Sum of a field.
pub fn sum(x: &[f64]) -> f64 {
    sum_map(x, |_, v| v)
}

/// Mean of a field.
pub fn mean(x: &[f64]) -> f64 {
    sum(x) / x.len() as f64
}

/// Dot product.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    sum_zip(a, b, |x, y| x * y)
}

/// Population standard deviation.
pub fn std_dev(x: &[f64]) -> f64 {
    std_dev_about(x, mean(x))
}

/// Population standard deviation of a field whose mean `m` is already known.
pub fn std_dev_about(x: &[f64], m: f64) -> f64 {
    (sum_map(x, |_, v| (v - m) * (v - m)) / x.len() as f64).sqrt()
}

/// The smaller of two numbers, NaN if either is (`f64::min` drops a NaN, which must not
/// hide in a residual or a statistic).
pub fn nan_min(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.min(b)
    }
}

/// The larger of two numbers, NaN if either is.
pub fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Minimum of a field (NaN if the field holds a NaN).
pub fn min(x: &[f64]) -> f64 {
    x.par_iter().copied().reduce(|| f64::INFINITY, nan_min)
}

/// Maximum of a field (NaN if the field holds a NaN).
pub fn max(x: &[f64]) -> f64 {
    x.par_iter().copied().reduce(|| f64::NEG_INFINITY, nan_max)
}

/// True when every element is finite.
pub fn all_finite(x: &[f64]) -> bool {
    x.par_iter().all(|v| v.is_finite())
}

/// Fraction of elements with `x > 0` (the contact fraction of a pressure field).
pub fn positive_fraction(x: &[f64]) -> f64 {
    let count: usize = x
        .par_chunks(CHUNK)
        .map(|c| c.iter().filter(|&&v| v > 0.0).count())
        .sum();
    count as f64 / x.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_are_independent_of_thread_count() {
        let x: Vec<f64> = (0..100_003)
            .map(|i| ((i as f64) * 0.37).sin() * 1e3)
            .collect();
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let two = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let a = one.install(|| sum(&x));
        let b = two.install(|| sum(&x));
        assert_eq!(a.to_bits(), b.to_bits());
    }

    #[test]
    fn min_max_std() {
        let x = [3.0, -1.0, 2.0, 0.0];
        assert_eq!(min(&x), -1.0);
        assert_eq!(max(&x), 3.0);
        assert!((std_dev(&x) - 2.5f64.sqrt()).abs() < 1e-15);
        assert_eq!(positive_fraction(&x), 0.5);
    }

    #[test]
    fn min_and_max_report_a_nan() {
        for x in [
            [f64::NAN, 1.0, 2.0],
            [1.0, f64::NAN, 2.0],
            [1.0, 2.0, f64::NAN],
        ] {
            assert!(min(&x).is_nan(), "{x:?}");
            assert!(max(&x).is_nan(), "{x:?}");
        }
    }
}
