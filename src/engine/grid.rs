//! The periodic grid, square or rectangular, and its wavevector tables
//! ([`crate::conventions`], section 2).
//!
//! A grid is `rows x cols` points with spacing `a` (the same along both axes), sides
//! `L_y = rows a` and `L_x = cols a`, stored row-major: the point `(i, j)` (row `i` along
//! y, column `j` along x) sits at index `i * cols + j`. A square grid has `rows = cols = n`
//! and side `L = n a`.
//!
//! Fourier space uses the *half spectrum* of a real field, laid out row-major as `rows`
//! rows (the y wavenumber, FFT order) by `m = cols/2 + 1` columns (the x wavenumber,
//! `0..=cols/2`): the mode `(ky, kx)` sits at index `ky * m + kx`. Its integer wavevector
//! is `(mx, my) = (kx, ky)` with `my = ky - rows` when `ky > rows/2`, and
//! `q = 2 pi (mx / L_x, my / L_y)`.
//!
//! The half spectrum stores each pair `(q, -q)` once. Sums over the full spectrum
//! (`sum_q`) are therefore weighted sums over the half spectrum with [`Grid::weight`]:
//! 1 on the column `kx = 0` (and on `kx = cols/2` when `cols` is even, the x-Nyquist
//! column), 2 elsewhere.
//!
//! Magnification works on integer shells. On a square grid the mode with integer
//! wavevector `(mx, my)` lies on the shell `k2 = mx^2 + my^2`, and `|q| <= zeta q_l` holds
//! exactly when `k2 <= (zeta L / lambda_l)^2`. Comparing integers keeps "which modes does
//! zeta include" free of rounding.
//!
//! On a rectangle the two axes have different wavenumber units, `2 pi / L_x` and
//! `2 pi / L_y`; both are whole multiples of `dq = 2 pi / (a lcm(rows, cols))`, the unit of
//! the common period `L_s = a lcm(rows, cols)`. With `g = gcd(rows, cols)`,
//! `q = dq (mx rows/g, my cols/g)`, so a shell of equal `|q|` is the integer
//! `k2 = (mx rows/g)^2 + (my cols/g)^2`, in units of `dq^2`: the same rule, which on a
//! square (`g = n`) is `mx^2 + my^2`, and the rule of the measured spectra
//! ([`crate::measured`]). A rectangle whose largest `k2` does not fit in 32 bits (large,
//! nearly coprime sides) has no shell table: its `|q|` is computed from the two axes'
//! units, and asking for its shells ([`Grid::k2`], [`Grid::k2_table`]) is a programming
//! error. Surfaces and magnification live on square grids; the free-boundary body, which
//! needs only the stiffness, on rectangles of any shape.

use crate::error::{Error, Result};

use crate::engine::tolerance::SHELL_SLACK;

/// Smallest side accepted: below this the FFT tables and the spectra are degenerate.
pub const MIN_N: usize = 4;
/// Largest side accepted (the paper's largest runs were 16384^2).
pub const MAX_N: usize = 32768;

/// A periodic `rows x cols` grid with its half-spectrum wavevector tables.
#[derive(Debug, Clone)]
pub struct Grid {
    rows: usize,
    cols: usize,
    spacing: f64,
    /// `lcm(rows, cols)`: the common period in points, `n` on a square grid.
    period: usize,
    /// Integer `|k|^2` of every half-spectrum mode, in units of `dq^2` (module docs);
    /// `None` on a rectangle whose shells do not fit in 32 bits.
    k2: Option<Vec<u32>>,
}

impl Grid {
    /// A square grid of `n x n` points with spacing `spacing` (grid units: `spacing = 1`).
    ///
    /// # Errors
    ///
    /// If `n` is outside `[MIN_N, MAX_N]` or `spacing` is not a finite number `> 0`.
    pub fn new(n: usize, spacing: f64) -> Result<Self> {
        if !(MIN_N..=MAX_N).contains(&n) {
            return Err(Error::invalid(
                "n",
                n,
                format!("an integer in [{MIN_N}, {MAX_N}]"),
            ));
        }
        Self::rectangle(n, n, spacing)
    }

    /// A grid of `rows x cols` points with spacing `spacing`.
    ///
    /// # Errors
    ///
    /// If `rows` or `cols` is outside `[MIN_N, MAX_N]`, or `spacing` is not a finite number
    /// `> 0`.
    pub fn rectangle(rows: usize, cols: usize, spacing: f64) -> Result<Self> {
        for (name, side) in [("rows", rows), ("cols", cols)] {
            if !(MIN_N..=MAX_N).contains(&side) {
                return Err(Error::invalid(
                    name,
                    side,
                    format!("an integer in [{MIN_N}, {MAX_N}]"),
                ));
            }
        }
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(Error::invalid(
                "spacing",
                spacing,
                "a finite number > 0".to_string(),
            ));
        }
        let g = gcd(rows, cols);
        let (sx, sy) = ((rows / g) as u64, (cols / g) as u64);
        let m = cols / 2 + 1;
        let (mx_max, my_max) = ((cols / 2) as u64, (rows / 2) as u64);
        let largest = (mx_max * sx).pow(2) + (my_max * sy).pow(2);
        let k2 = (largest <= u32::MAX as u64).then(|| {
            let mut k2 = vec![0u32; rows * m];
            for ky in 0..rows {
                let my = signed_index(ky, rows).unsigned_abs() * sy;
                for kx in 0..m {
                    let mx = kx as u64 * sx;
                    k2[ky * m + kx] = (mx * mx + my * my) as u32;
                }
            }
            k2
        });
        Ok(Self {
            rows,
            cols,
            spacing,
            period: rows / g * cols,
            k2,
        })
    }

    /// Points per side of a square grid.
    ///
    /// # Panics
    ///
    /// If the grid is not square: a rectangle's callers use [`Grid::rows`] and
    /// [`Grid::cols`].
    pub fn n(&self) -> usize {
        assert!(
            self.is_square(),
            "Grid::n on a {} x {} rectangle",
            self.rows,
            self.cols
        );
        self.rows
    }

    /// Points along y (rows).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Points along x (columns): the length of a row.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Whether `rows = cols`.
    pub fn is_square(&self) -> bool {
        self.rows == self.cols
    }

    /// Number of real-space points, `rows cols`.
    pub fn points(&self) -> usize {
        self.rows * self.cols
    }

    /// Grid spacing `a`.
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// Side length `L = n a` of a square grid; on a rectangle, the common period
    /// `L_s = a lcm(rows, cols)` of the shells (module docs).
    pub fn length(&self) -> f64 {
        self.period as f64 * self.spacing
    }

    /// Columns of the half spectrum, `m = cols/2 + 1`.
    pub fn half_cols(&self) -> usize {
        self.cols / 2 + 1
    }

    /// Number of half-spectrum modes, `rows (cols/2 + 1)`.
    pub fn modes(&self) -> usize {
        self.rows * self.half_cols()
    }

    /// The wavenumber unit of the shells, `2 pi / L_s` (`2 pi / L` on a square grid).
    pub fn dq(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.length()
    }

    /// Integer `|k|^2` of half-spectrum mode `s` (`mx^2 + my^2` on a square grid).
    ///
    /// # Panics
    ///
    /// On a rectangle without shells ([`Grid::has_shells`]).
    #[inline]
    pub fn k2(&self, s: usize) -> u32 {
        self.k2_table()[s]
    }

    /// Integer `|k|^2` of half-spectrum mode `s` in units of `dq^2` (module docs), computed
    /// from its wavevector in 64 bits: defined on every grid, also on a rectangle without a
    /// shell table, and equal to [`Grid::k2`] where that is defined.
    pub fn k2_wide(&self, s: usize) -> u64 {
        let g = gcd(self.rows, self.cols);
        let (sx, sy) = ((self.rows / g) as u64, (self.cols / g) as u64);
        let (mx, my) = self.wavevector(s);
        let (kx, ky) = (mx.unsigned_abs() * sx, my.unsigned_abs() * sy);
        kx * kx + ky * ky
    }

    /// The table of integer `|k|^2` over the half spectrum.
    ///
    /// # Panics
    ///
    /// On a rectangle without shells ([`Grid::has_shells`]).
    pub fn k2_table(&self) -> &[u32] {
        match &self.k2 {
            Some(k2) => k2,
            None => panic!(
                "the {} x {} grid's shells do not fit in 32 bits",
                self.rows, self.cols
            ),
        }
    }

    /// Whether the grid has integer shells: every square grid, and every rectangle whose
    /// largest shell fits in 32 bits (module docs).
    pub fn has_shells(&self) -> bool {
        self.k2.is_some()
    }

    /// `|q|` of half-spectrum mode `s`: `dq sqrt(k2)`, or on a rectangle without shells
    /// `2 pi sqrt((mx / L_x)^2 + (my / L_y)^2)`.
    #[inline]
    pub fn q(&self, s: usize) -> f64 {
        match &self.k2 {
            Some(k2) => self.dq() * (k2[s] as f64).sqrt(),
            None => {
                let (mx, my) = self.wavevector(s);
                let qx = mx as f64 / self.cols as f64;
                let qy = my as f64 / self.rows as f64;
                2.0 * std::f64::consts::PI * (qx * qx + qy * qy).sqrt() / self.spacing
            }
        }
    }

    /// Integer wavevector `(mx, my)` of half-spectrum mode `s`, in the units of each axis,
    /// `2 pi / L_x` and `2 pi / L_y`.
    pub fn wavevector(&self, s: usize) -> (i64, i64) {
        let m = self.half_cols();
        ((s % m) as i64, signed_index(s / m, self.rows))
    }

    /// Parseval weight of half-spectrum column `kx` (see the module docs).
    #[inline]
    pub fn weight(&self, kx: usize) -> f64 {
        if kx == 0 || (self.cols % 2 == 0 && kx == self.cols / 2) {
            1.0
        } else {
            2.0
        }
    }

    /// Parseval weight of half-spectrum mode `s`.
    #[inline]
    pub fn weight_of(&self, s: usize) -> f64 {
        self.weight(s % self.half_cols())
    }

    /// True for modes on a Nyquist row or column (`|mx| = cols/2` for even `cols`, or
    /// `|my| = rows/2` for even `rows`), which carry no roughness: a real field cannot hold
    /// a travelling wave there.
    pub fn is_nyquist(&self, s: usize) -> bool {
        let (mx, my) = self.wavevector(s);
        (self.cols % 2 == 0 && mx.unsigned_abs() as usize == self.cols / 2)
            || (self.rows % 2 == 0 && my.unsigned_abs() as usize == self.rows / 2)
    }

    /// Largest shell index `k2` included at magnification `zeta` for long-wavelength
    /// cutoff `lambda_l`: modes with `k2 <= shell_limit` have `|q| <= zeta q_l`.
    ///
    /// The relative slack [`SHELL_SLACK`] makes `zeta` values computed from a shell's own
    /// `|q|` include that shell.
    pub fn shell_limit(&self, zeta: f64, lambda_l: f64) -> u32 {
        u32::try_from(self.shell_limit_wide(zeta, lambda_l)).unwrap_or(u32::MAX)
    }

    /// [`Grid::shell_limit`] in 64 bits, for the shells of [`Grid::k2_wide`].
    pub fn shell_limit_wide(&self, zeta: f64, lambda_l: f64) -> u64 {
        let r = zeta * self.length() / lambda_l;
        let r2 = r * r * (1.0 + SHELL_SLACK);
        // `as` saturates: a limit beyond 64 bits includes every shell.
        r2.floor() as u64
    }

    /// Magnification at which the shell `k2` is resolved: `zeta = |q| / q_l`.
    pub fn zeta_of_shell(&self, k2: u32, lambda_l: f64) -> f64 {
        (k2 as f64).sqrt() * lambda_l / self.length()
    }

    /// Mean of a real field.
    pub fn mean(&self, field: &[f64]) -> f64 {
        crate::engine::field::sum(field) / self.points() as f64
    }
}

/// Greatest common divisor.
pub fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// FFT index `k` of a length-`n` transform as a signed wavenumber in `(-n/2, n/2]`.
#[inline]
pub fn signed_index(k: usize, n: usize) -> i64 {
    if k > n / 2 {
        k as i64 - n as i64
    } else {
        k as i64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_count_every_full_spectrum_mode_once() {
        for n in [4usize, 5, 8, 9, 16, 33] {
            let g = Grid::new(n, 1.0).unwrap();
            let total: f64 = (0..g.modes()).map(|s| g.weight_of(s)).sum();
            assert_eq!(total, (n * n) as f64, "n = {n}");
        }
    }

    #[test]
    fn shell_limit_includes_exact_radius() {
        let g = Grid::new(64, 1.0).unwrap();
        // lambda_l = 32: q_l = 2 pi / 32, i.e. k = 2; zeta = 2.5 reaches k = 5, k2 = 25.
        assert_eq!(g.shell_limit(2.5, 32.0), 25);
        assert_eq!(g.shell_limit(1.0, 32.0), 4);
        assert!((g.zeta_of_shell(25, 32.0) - 2.5).abs() < 1e-15);
    }

    #[test]
    fn rectangle_weights_count_every_full_spectrum_mode_once() {
        for (rows, cols) in [(6usize, 10usize), (12, 8), (5, 9), (7, 4), (9, 6)] {
            let g = Grid::rectangle(rows, cols, 1.0).unwrap();
            let total: f64 = (0..g.modes()).map(|s| g.weight_of(s)).sum();
            assert_eq!(total, (rows * cols) as f64, "{rows} x {cols}");
        }
    }

    #[test]
    fn rectangle_shells_are_exact_squares_of_q() {
        // |q|^2 = (2 pi)^2 [(mx / L_x)^2 + (my / L_y)^2] must equal dq^2 k2 for every mode,
        // and two modes share a shell exactly when their |q| agree.
        for (rows, cols, a) in [
            (6usize, 10usize, 1.0),
            (12, 8, 0.5),
            (5, 9, 2.0),
            (8, 8, 1.0),
        ] {
            let g = Grid::rectangle(rows, cols, a).unwrap();
            let two_pi = 2.0 * std::f64::consts::PI;
            for s in 0..g.modes() {
                let (mx, my) = g.wavevector(s);
                let qx = two_pi * mx as f64 / (cols as f64 * a);
                let qy = two_pi * my as f64 / (rows as f64 * a);
                let q = (qx * qx + qy * qy).sqrt();
                assert!(
                    (g.q(s) - q).abs() <= 1e-13 * q.max(1.0),
                    "{rows} x {cols}: mode {s}: {} vs {q}",
                    g.q(s)
                );
            }
        }
        // 6 x 10: lcm 30, q = dq (3 mx, 5 my). The modes (mx, my) = (5, 0) and (0, 3)
        // both have |q| = 15 dq; (1, 1) has k2 = 9 + 25.
        let g = Grid::rectangle(6, 10, 1.0).unwrap();
        assert_eq!(g.length(), 30.0);
        let at = |kx: usize, ky: usize| g.k2(ky * g.half_cols() + kx);
        assert_eq!(at(5, 0), 225);
        assert_eq!(at(0, 3), 225);
        assert_eq!(at(1, 1), 34);
        assert_eq!(at(1, 5), 34); // ky = 5 is my = -1
    }

    #[test]
    fn a_square_rectangle_is_the_square_grid() {
        for n in [4usize, 9, 16] {
            let a = Grid::new(n, 0.7).unwrap();
            let b = Grid::rectangle(n, n, 0.7).unwrap();
            assert_eq!(a.k2_table(), b.k2_table());
            assert_eq!(a.length().to_bits(), b.length().to_bits());
            assert_eq!(a.n(), n);
        }
    }

    #[test]
    fn nyquist_modes_of_a_rectangle_sit_on_each_axis_own_nyquist() {
        let g = Grid::rectangle(6, 9, 1.0).unwrap();
        let nyquist: Vec<(i64, i64)> = (0..g.modes())
            .filter(|&s| g.is_nyquist(s))
            .map(|s| g.wavevector(s))
            .collect();
        // cols = 9 is odd (no x-Nyquist); rows = 6 has my = 3 on every column 0..=4.
        assert_eq!(nyquist, (0..5).map(|mx| (mx, 3)).collect::<Vec<_>>());
    }

    #[test]
    #[should_panic(expected = "rectangle")]
    fn n_of_a_rectangle_panics() {
        let _ = Grid::rectangle(6, 10, 1.0).unwrap().n();
    }

    #[test]
    fn rejects_bad_sizes() {
        assert!(Grid::new(2, 1.0).is_err());
        assert!(Grid::new(16, 0.0).is_err());
        assert!(Grid::new(16, f64::NAN).is_err());
        assert!(Grid::rectangle(3, 16, 1.0).is_err());
        assert!(Grid::rectangle(16, MAX_N + 1, 1.0).is_err());
    }

    #[test]
    fn a_rectangle_whose_shells_overflow_has_exact_q_but_no_shells() {
        // 2042 x 2000: g = 2, the largest shell (1000 * 1021)^2 + (1021 * 1000)^2 > 2^32.
        let g = Grid::rectangle(2042, 2000, 0.5).unwrap();
        assert!(!g.has_shells());
        assert!(Grid::rectangle(2000, 2000, 0.5).unwrap().has_shells());
        let two_pi = 2.0 * std::f64::consts::PI;
        for s in [1usize, 1001, 5 * g.half_cols() + 17, g.modes() - 1] {
            let (mx, my) = g.wavevector(s);
            let q = two_pi * (mx as f64 / 1000.0).hypot(my as f64 / 1021.0);
            assert!((g.q(s) / q - 1.0).abs() < 1e-14, "mode {s}");
        }
        let err = std::panic::catch_unwind(|| g.k2(1));
        assert!(err.is_err(), "no shells to read");
        // The 64-bit shells are there: (1000 * 1021)^2 + (1021 * 1000)^2 at the corner.
        let corner = (g.rows() / 2) * g.half_cols() + g.half_cols() - 1;
        assert_eq!(g.k2_wide(corner), 2 * (1000u64 * 1021).pow(2));
    }

    #[test]
    fn wide_shells_are_the_table_where_it_exists() {
        for (rows, cols) in [(6usize, 10usize), (12, 8), (5, 9), (16, 16), (640, 480)] {
            let g = Grid::rectangle(rows, cols, 1.0).unwrap();
            for s in 0..g.modes() {
                assert_eq!(
                    g.k2_wide(s),
                    u64::from(g.k2(s)),
                    "{rows} x {cols}: mode {s}"
                );
            }
        }
    }
}
