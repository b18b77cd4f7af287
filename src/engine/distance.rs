//! The Euclidean distance transform of the periodic grid: for every point, the distance
//! (in grid spacings, on the torus) to the nearest point of a set, such as the points out
//! of contact.
//!
//! The squared distance separates into two passes of a one-dimensional transform, first
//! along the columns, then along the rows: `d^2(i, j) = min_k [g(k, j) + (i - k)^2]`, with
//! `g` the squared distance along the column. Each one-dimensional transform is the lower
//! envelope of the parabolas `f(q) + (x - q)^2` (Felzenszwalb and Huttenlocher, Theory of
//! Computing 8, 415 (2012)), linear in the length of the line. A periodic line is unrolled
//! over three periods and read in the middle one, so that the nearest point may lie across
//! the boundary (on the torus it is at most half a period away along each axis).

use rayon::prelude::*;

/// The squared distance from every point of a `rows x cols` periodic grid (row-major) to
/// the nearest point where `set` holds, in grid spacings squared; `f64::INFINITY`
/// everywhere when the set is empty.
pub fn squared_distance_to(set: &[bool], rows: usize, cols: usize) -> Vec<f64> {
    assert_eq!(set.len(), rows * cols, "a row-major rows x cols grid");
    let mut d: Vec<f64> = set
        .iter()
        .map(|&s| if s { 0.0 } else { f64::INFINITY })
        .collect();
    // Along the columns: gather each column, transform it, scatter it back.
    let columns: Vec<Vec<f64>> = (0..cols)
        .into_par_iter()
        .map(|j| {
            let line: Vec<f64> = (0..rows).map(|i| d[i * cols + j]).collect();
            periodic_line(&line)
        })
        .collect();
    for (j, column) in columns.iter().enumerate() {
        for (i, &v) in column.iter().enumerate() {
            d[i * cols + j] = v;
        }
    }
    // Along the rows.
    d.par_chunks_mut(cols).for_each(|row| {
        let out = periodic_line(row);
        row.copy_from_slice(&out);
    });
    d
}

/// The one-dimensional transform of a periodic line: `min_q [f(q) + |x - q|^2]` over `q`
/// and its images one period to either side.
fn periodic_line(f: &[f64]) -> Vec<f64> {
    let n = f.len();
    let unrolled: Vec<f64> = (0..3 * n).map(|k| f[k % n]).collect();
    lower_envelope(&unrolled)[n..2 * n].to_vec()
}

/// `min_q [f(q) + (x - q)^2]` at every `x` of the line, by the lower envelope of the
/// parabolas rooted at the finite values of `f`.
fn lower_envelope(f: &[f64]) -> Vec<f64> {
    let n = f.len();
    // Roots of the envelope's parabolas, and where each starts to be the lowest.
    let mut roots: Vec<usize> = Vec::with_capacity(n);
    let mut starts: Vec<f64> = Vec::with_capacity(n + 1);
    for q in (0..n).filter(|&q| f[q].is_finite()) {
        let fq = f[q] + (q * q) as f64;
        loop {
            let Some(&v) = roots.last() else {
                roots.push(q);
                starts.push(f64::NEG_INFINITY);
                break;
            };
            // Where the parabola of q falls below that of v.
            let s = (fq - (f[v] + (v * v) as f64)) / (2.0 * (q - v) as f64);
            if s <= *starts.last().expect("one start per root") {
                roots.pop();
                starts.pop();
            } else {
                roots.push(q);
                starts.push(s);
                break;
            }
        }
    }
    if roots.is_empty() {
        return vec![f64::INFINITY; n];
    }
    let mut k = 0;
    (0..n)
        .map(|x| {
            let x_f = x as f64;
            while k + 1 < roots.len() && starts[k + 1] < x_f {
                k += 1;
            }
            let dx = x_f - roots[k] as f64;
            dx * dx + f[roots[k]]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The squared torus distance by trying every point of the set.
    fn brute_force(set: &[bool], rows: usize, cols: usize) -> Vec<f64> {
        let torus = |a: usize, b: usize, n: usize| {
            let d = a.abs_diff(b);
            d.min(n - d) as f64
        };
        (0..rows * cols)
            .map(|p| {
                (0..rows * cols)
                    .filter(|&s| set[s])
                    .map(|s| {
                        let di = torus(p / cols, s / cols, rows);
                        let dj = torus(p % cols, s % cols, cols);
                        di * di + dj * dj
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    }

    #[test]
    fn the_transform_is_the_nearest_point_on_the_torus() {
        // Sparse and dense sets on square and rectangular grids, odd and even sides, from
        // a fixed pseudo-random sequence.
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as f64 / (1u64 << 31) as f64
        };
        for &(rows, cols, density) in &[
            (7, 9, 0.05),
            (16, 16, 0.02),
            (13, 5, 0.5),
            (1, 11, 0.2),
            (20, 20, 0.9),
        ] {
            let set: Vec<bool> = (0..rows * cols).map(|_| next() < density).collect();
            assert_eq!(
                squared_distance_to(&set, rows, cols),
                brute_force(&set, rows, cols),
                "{rows} x {cols}, density {density}"
            );
        }
    }

    #[test]
    fn one_point_is_nearest_across_the_boundary_and_an_empty_set_is_nowhere() {
        let (rows, cols) = (8, 10);
        let mut set = vec![false; rows * cols];
        set[0] = true;
        let d = squared_distance_to(&set, rows, cols);
        // The last point of the first row is one spacing from the corner, across the edge;
        // the point (4, 5) is half a period away along both axes.
        assert_eq!(d[cols - 1], 1.0);
        assert_eq!(d[(rows - 1) * cols + cols - 1], 2.0);
        assert_eq!(d[4 * cols + 5], 16.0 + 25.0);
        let none = squared_distance_to(&vec![false; rows * cols], rows, cols);
        assert!(none.iter().all(|v| v.is_infinite()));
    }
}
