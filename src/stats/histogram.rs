//! Histograms: values sorted into bins of equal width on a linear or a logarithmic axis
//! ([`Bins`]), each bin holding what its users accumulate there ([`Histogram`]): a count,
//! or sums of weights and moments.
//!
//! On a linear axis from `lo` in bins of width `w`, bin `k` is `[lo + k w, lo + (k+1) w)`
//! and a value `x` falls in bin `floor((x - lo) / w)`. On a logarithmic axis from `lo`
//! with `d` bins per decade, bin `k` is `[lo 10^(k/d), lo 10^((k+1)/d))` and `x` falls in
//! bin `floor(d log10(x / lo))`. A value below the first edge counts in the first bin and
//! one at or beyond the last edge in the last: the last bin collects the rest. A value
//! that is not a number counts in the first bin; callers that must not count it leave it
//! out.
//!
//! The density of a bin is its count over the total and the bin's width,
//! `n_k / (N w)`: per unit of the axis, so that the densities integrate to the share of
//! the `N` values that the bins counted ([`Histogram::density`]).

/// The axis of a histogram: where its bins lie.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Spacing {
    /// Bins of width `width` from `lo`.
    Linear { lo: f64, width: f64 },
    /// `per_decade` bins per decade from `lo > 0`.
    Log10 { lo: f64, per_decade: f64 },
}

/// Bins of equal width on a linear or a logarithmic axis; the last collects the rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bins {
    spacing: Spacing,
    count: usize,
}

impl Bins {
    /// `count` bins of width `width` from `lo` (`width > 0`, `count >= 1`).
    pub fn linear(lo: f64, width: f64, count: usize) -> Self {
        assert!(count >= 1, "a histogram of no bins");
        debug_assert!(width > 0.0, "bins of width {width}");
        Self {
            spacing: Spacing::Linear { lo, width },
            count,
        }
    }

    /// `count` bins on a logarithmic axis from `lo`, `per_decade` of them per decade
    /// (`lo > 0`, `per_decade > 0`, `count >= 1`).
    pub fn log10(lo: f64, per_decade: f64, count: usize) -> Self {
        assert!(count >= 1, "a histogram of no bins");
        debug_assert!(
            lo > 0.0 && per_decade > 0.0,
            "log bins from {lo}, {per_decade} per decade"
        );
        Self {
            spacing: Spacing::Log10 { lo, per_decade },
            count,
        }
    }

    /// Bins on a logarithmic axis from `lo`, `per_decade` of them per decade, as many as
    /// reach `hi` (at least one): none collects values up to `hi`.
    pub fn log10_up_to(lo: f64, per_decade: f64, hi: f64) -> Self {
        let reach = Self::log10(lo, per_decade, 1).position(hi);
        Self::log10(lo, per_decade, reach.floor().max(0.0) as usize + 1)
    }

    /// The number of bins.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether there are no bins (never: a histogram has at least one).
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Where `x` lies on the axis, in bins from the first edge: `(x - lo) / w`, or
    /// `d log10(x / lo)`.
    pub fn position(&self, x: f64) -> f64 {
        match self.spacing {
            Spacing::Linear { lo, width } => (x - lo) / width,
            Spacing::Log10 { lo, per_decade } => (x / lo).log10() * per_decade,
        }
    }

    /// The bin of `x`: `floor` of its [`position`](Self::position), the first bin for a
    /// value below the first edge (or not a number), the last for one beyond the last.
    pub fn index(&self, x: f64) -> usize {
        (self.position(x).floor().max(0.0) as usize).min(self.count - 1)
    }

    /// The number of bins that lie wholly below `x` (their upper edge at most `x`, up to
    /// a billionth of a bin, so that an `x` on an edge computed in floating point counts
    /// the bin below it).
    pub fn below(&self, x: f64) -> usize {
        ((self.position(x) + 1e-9).floor().max(0.0) as usize).min(self.count)
    }

    /// The edge `k` (`0..=len`): `lo + k w`, or `lo 10^(k/d)`.
    pub fn edge(&self, k: usize) -> f64 {
        self.at(k as f64)
    }

    /// The centre of bin `k`: `lo + (k + 1/2) w` on a linear axis, the geometric centre
    /// `lo 10^((k + 1/2)/d)` on a logarithmic one.
    pub fn centre(&self, k: usize) -> f64 {
        self.at(k as f64 + 0.5)
    }

    /// The width of bin `k`.
    pub fn width(&self, k: usize) -> f64 {
        match self.spacing {
            Spacing::Linear { width, .. } => width,
            Spacing::Log10 { .. } => self.edge(k + 1) - self.edge(k),
        }
    }

    /// The point `t` bins from the first edge.
    fn at(&self, t: f64) -> f64 {
        match self.spacing {
            Spacing::Linear { lo, width } => lo + t * width,
            Spacing::Log10 { lo, per_decade } => lo * 10f64.powf(t / per_decade),
        }
    }
}

/// A histogram: [`Bins`], and in each what its users add there (`T`: a count by default,
/// or sums of weights and moments).
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram<T = usize> {
    bins: Bins,
    cells: Vec<T>,
}

impl<T: Default + Clone> Histogram<T> {
    /// An empty histogram over `bins`.
    pub fn new(bins: Bins) -> Self {
        Self {
            cells: vec![T::default(); bins.len()],
            bins,
        }
    }

    /// The bin that `x` falls in, to add to.
    pub fn at(&mut self, x: f64) -> &mut T {
        let k = self.bins.index(x);
        &mut self.cells[k]
    }

    /// The bins.
    pub fn bins(&self) -> &Bins {
        &self.bins
    }

    /// What each bin holds.
    pub fn cells(&self) -> &[T] {
        &self.cells
    }

    /// What each bin holds, taken out.
    pub fn into_cells(self) -> Vec<T> {
        self.cells
    }
}

impl Histogram<usize> {
    /// Counts `x`.
    pub fn count(&mut self, x: f64) {
        *self.at(x) += 1;
    }

    /// The density of each bin, `n_k / (total w_k)`: per unit of the axis, out of `total`
    /// values (the counted ones and any the caller left out).
    pub fn density(&self, total: usize) -> Vec<f64> {
        self.cells
            .iter()
            .enumerate()
            .map(|(k, &n)| n as f64 / (total as f64 * self.bins.width(k)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_bins_take_their_lower_edge_and_the_last_collects_the_rest() {
        let b = Bins::linear(1.0, 0.5, 4);
        let index: Vec<usize> = [0.0, 1.0, 1.49, 1.5, 2.9, 3.0, 1e9, f64::NAN]
            .iter()
            .map(|&x| b.index(x))
            .collect();
        assert_eq!(index, [0, 0, 0, 1, 3, 3, 3, 0]);
        assert_eq!((b.edge(0), b.edge(4)), (1.0, 3.0));
        assert_eq!((b.centre(0), b.centre(3)), (1.25, 2.75));
        assert_eq!(b.width(2), 0.5);
        // Wholly below 2.0: bins 0 and 1; below 2.0 less a little: bin 0 only.
        assert_eq!(
            (b.below(2.0), b.below(1.9), b.below(0.0), b.below(9.0)),
            (2, 1, 0, 4)
        );
    }

    #[test]
    fn log_bins_are_equal_in_log10() {
        let b = Bins::log10(2.0, 10.0, 30);
        // One decade above lo starts bin 10; a bit below, bin 9.
        assert_eq!(b.index(20.0 * (1.0 + 1e-12)), 10);
        assert_eq!(b.index(19.9), 9);
        assert_eq!(b.index(1.0), 0);
        assert!((b.edge(10) - 20.0).abs() < 1e-12);
        let centre = b.centre(10);
        assert!((centre - 20.0 * 10f64.powf(0.05)).abs() < 1e-12, "{centre}");
        assert!((b.width(0) - 2.0 * (10f64.powf(0.1) - 1.0)).abs() < 1e-12);
        // Bins up to 20: bin 10 holds it, so eleven of them; up to less than lo, one.
        assert_eq!(Bins::log10_up_to(2.0, 10.0, 20.0 * (1.0 + 1e-12)).len(), 11);
        assert_eq!(Bins::log10_up_to(2.0, 10.0, 19.9).len(), 10);
        assert_eq!(Bins::log10_up_to(2.0, 10.0, 0.0).len(), 1);
    }

    #[test]
    fn densities_integrate_to_the_share_counted() {
        // 800 values evenly on [0, 2), a quarter of them left out: the densities over
        // bins of width 0.25 are 75 / (800 * 0.25) = 0.375 each and integrate to 0.75.
        let mut h = Histogram::new(Bins::linear(0.0, 0.25, 8));
        for k in 0..800 {
            if k % 4 != 0 {
                h.count((k as f64 + 0.5) * 0.0025);
            }
        }
        let d = h.density(800);
        assert!(d.iter().all(|&v| (v - 0.375).abs() < 1e-12), "{d:?}");
        let integral: f64 = d.iter().map(|v| v * 0.25).sum();
        assert!((integral - 0.75).abs() < 1e-12);
    }

    #[test]
    fn a_histogram_holds_whatever_its_bins_sum() {
        let mut h: Histogram<(f64, u32)> = Histogram::new(Bins::linear(0.0, 1.0, 3));
        for x in [0.5, 0.7, 2.5, 7.0] {
            let cell = h.at(x);
            cell.0 += x;
            cell.1 += 1;
        }
        assert_eq!(h.cells(), [(1.2, 2), (0.0, 0), (9.5, 2)]);
        assert_eq!(h.into_cells().len(), 3);
    }
}
