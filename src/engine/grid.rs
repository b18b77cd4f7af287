//! The periodic square grid and its wavevector tables ([`crate::conventions`], section 2).
//!
//! A grid is `n x n` points with spacing `a`, side `L = n a`, stored row-major: the point
//! `(i, j)` (row `i` along y, column `j` along x) sits at index `i * n + j`.
//!
//! Fourier space uses the *half spectrum* of a real field, laid out row-major as
//! `n` rows (the y wavenumber, FFT order) by `m = n/2 + 1` columns (the x wavenumber,
//! `0..=n/2`): the mode `(ky, kx)` sits at index `ky * m + kx`. Its integer wavevector is
//! `(mx, my) = (kx, ky)` with `my = ky - n` when `ky > n/2`, and `q = 2 pi (mx, my) / L`.
//!
//! The half spectrum stores each pair `(q, -q)` once. Sums over the full spectrum
//! (`sum_q`) are therefore weighted sums over the half spectrum with [`Grid::weight`]:
//! 1 on the column `kx = 0` (and on `kx = n/2` when `n` is even, the x-Nyquist column), 2
//! elsewhere.
//!
//! Magnification works on integer shells: the mode with integer wavevector `(mx, my)` lies
//! on the shell `k2 = mx^2 + my^2`, and `|q| <= zeta q_l` holds exactly when
//! `k2 <= (zeta L / lambda_l)^2`. Comparing integers keeps "which modes does zeta include"
//! free of rounding.

use crate::error::{Error, Result};

/// Relative slack on `|k|^2` when deciding whether a shell is resolved at a magnification:
/// a `zeta` computed from a shell's own `|q|` includes that shell despite rounding. Every
/// "is this shell resolved at zeta" decision (grid, surfaces, the spectrum's cutoffs,
/// theory) uses it, and the sweep of a measured map's modes, which compares magnifications
/// (`zeta`, not `|k|^2`) with it.
pub const SHELL_SLACK: f64 = 1e-9;

/// Smallest grid accepted: below this the FFT tables and the spectra are degenerate.
pub const MIN_N: usize = 4;
/// Largest grid accepted (the paper's largest runs were 16384^2).
pub const MAX_N: usize = 32768;

/// A periodic `n x n` grid with its half-spectrum wavevector tables.
#[derive(Debug, Clone)]
pub struct Grid {
    n: usize,
    spacing: f64,
    /// Integer `|k|^2 = mx^2 + my^2` of every half-spectrum mode.
    k2: Vec<u32>,
}

impl Grid {
    /// A grid of `n x n` points with spacing `spacing` (grid units: `spacing = 1`).
    pub fn new(n: usize, spacing: f64) -> Result<Self> {
        if !(MIN_N..=MAX_N).contains(&n) {
            return Err(Error::invalid(
                "n",
                n,
                format!("an integer in [{MIN_N}, {MAX_N}]"),
            ));
        }
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(Error::invalid(
                "spacing",
                spacing,
                "a finite number > 0".to_string(),
            ));
        }
        let m = n / 2 + 1;
        let mut k2 = vec![0u32; n * m];
        for ky in 0..n {
            let my = signed_index(ky, n);
            for kx in 0..m {
                k2[ky * m + kx] = (kx as i64 * kx as i64 + my * my) as u32;
            }
        }
        Ok(Self { n, spacing, k2 })
    }

    /// Points per side.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Number of real-space points, `n^2`.
    pub fn points(&self) -> usize {
        self.n * self.n
    }

    /// Grid spacing `a`.
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// Side length `L = n a`.
    pub fn length(&self) -> f64 {
        self.n as f64 * self.spacing
    }

    /// Columns of the half spectrum, `m = n/2 + 1`.
    pub fn half_cols(&self) -> usize {
        self.n / 2 + 1
    }

    /// Number of half-spectrum modes, `n * (n/2 + 1)`.
    pub fn modes(&self) -> usize {
        self.n * self.half_cols()
    }

    /// The wavenumber unit `2 pi / L`.
    pub fn dq(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.length()
    }

    /// Integer `mx^2 + my^2` of half-spectrum mode `s`.
    #[inline]
    pub fn k2(&self, s: usize) -> u32 {
        self.k2[s]
    }

    /// The table of integer `mx^2 + my^2` over the half spectrum.
    pub fn k2_table(&self) -> &[u32] {
        &self.k2
    }

    /// `|q|` of half-spectrum mode `s`.
    #[inline]
    pub fn q(&self, s: usize) -> f64 {
        self.dq() * (self.k2[s] as f64).sqrt()
    }

    /// Integer wavevector `(mx, my)` of half-spectrum mode `s`.
    pub fn wavevector(&self, s: usize) -> (i64, i64) {
        let m = self.half_cols();
        ((s % m) as i64, signed_index(s / m, self.n))
    }

    /// Parseval weight of half-spectrum column `kx` (see the module docs).
    #[inline]
    pub fn weight(&self, kx: usize) -> f64 {
        if kx == 0 || (self.n % 2 == 0 && kx == self.n / 2) {
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

    /// True for modes on a Nyquist row or column (`|mx| = n/2` or `|my| = n/2`, even `n`),
    /// which carry no roughness: a real field cannot hold a travelling wave there.
    pub fn is_nyquist(&self, s: usize) -> bool {
        if self.n % 2 != 0 {
            return false;
        }
        let (mx, my) = self.wavevector(s);
        mx.unsigned_abs() as usize == self.n / 2 || my.unsigned_abs() as usize == self.n / 2
    }

    /// Largest shell index `k2` included at magnification `zeta` for long-wavelength
    /// cutoff `lambda_l`: modes with `k2 <= shell_limit` have `|q| <= zeta q_l`.
    ///
    /// The relative slack [`SHELL_SLACK`] makes `zeta` values computed from a shell's own
    /// `|q|` include that shell.
    pub fn shell_limit(&self, zeta: f64, lambda_l: f64) -> u32 {
        let r = zeta * self.length() / lambda_l;
        let r2 = r * r * (1.0 + SHELL_SLACK);
        if r2 >= u32::MAX as f64 {
            u32::MAX
        } else {
            r2.floor() as u32
        }
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
    fn rejects_bad_sizes() {
        assert!(Grid::new(2, 1.0).is_err());
        assert!(Grid::new(16, 0.0).is_err());
        assert!(Grid::new(16, f64::NAN).is_err());
    }
}
