//! Power spectra: the self-affine model spectrum and a realization's own shell spectrum.
//!
//! The model ([`crate::conventions`], section 3; paper section 2): an isotropic spectrum
//! `C(q) ~ q^(-2(1+H))` for `q_l <= q <= q_s`, zero outside, with an optional roll-off
//! plateau `C(q) = C(q_l)` for `q_r <= q < q_l`. `q_l = 2 pi / lambda_l`,
//! `q_s = 2 pi / lambda_s`.
//!
//! A realization is compared with Persson's theory on its own discrete modes, grouped in
//! shells of equal integer `|k|^2` ([`ShellSpectrum`]): the shell broadening of paper
//! eq. (broadening), `Dp^2 = sum (q E*/2)^2 |h~(q)|^2`, is a sum over exactly the modes that
//! raising the magnification adds.

use serde::{Deserialize, Serialize};

use crate::engine::grid::Grid;
use crate::error::{check_open, Error, Result};

/// Self-affine isotropic spectrum with cutoffs (lengths in grid units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SelfAffine {
    /// Hurst exponent `H`, in (0, 1).
    pub hurst: f64,
    /// Long-wavelength cutoff `lambda_l` (the roll-off wavelength when there is no plateau).
    pub lambda_l: f64,
    /// Short-wavelength cutoff `lambda_s`, at least two grid spacings.
    pub lambda_s: f64,
    /// Optional roll-off: the plateau extends from `lambda_l` up to `lambda_r`.
    #[serde(default)]
    pub lambda_r: Option<f64>,
}

impl SelfAffine {
    /// Checks the parameters against the grid ([`crate::conventions`], section 3).
    ///
    /// # Errors
    ///
    /// If `hurst` is outside (0, 1), `lambda_s` is below two grid spacings, `lambda_l` is
    /// outside `(lambda_s, L]`, or `lambda_r` outside `(lambda_l, L]`; the error names the
    /// parameter.
    pub fn validate(&self, grid: &Grid) -> Result<()> {
        check_open("hurst", self.hurst, 0.0, 1.0)?;
        let a = grid.spacing();
        let l = grid.length();
        if !(self.lambda_s.is_finite() && self.lambda_s >= 2.0 * a) {
            return Err(Error::invalid(
                "lambda_s",
                self.lambda_s,
                format!(">= 2 grid spacings ({})", 2.0 * a),
            ));
        }
        if !(self.lambda_l.is_finite() && self.lambda_l > self.lambda_s && self.lambda_l <= l) {
            return Err(Error::invalid(
                "lambda_l",
                self.lambda_l,
                format!("in (lambda_s = {}, L = {l}]", self.lambda_s),
            ));
        }
        if let Some(r) = self.lambda_r {
            if !(r.is_finite() && r > self.lambda_l && r <= l) {
                return Err(Error::invalid(
                    "lambda_r",
                    r,
                    format!("in (lambda_l = {}, L = {l}]", self.lambda_l),
                ));
            }
        }
        Ok(())
    }

    /// `q_l = 2 pi / lambda_l`.
    pub fn q_l(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.lambda_l
    }

    /// `q_s = 2 pi / lambda_s`.
    pub fn q_s(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.lambda_s
    }

    /// Largest magnification, `zeta_max = lambda_l / lambda_s`.
    pub fn zeta_max(&self) -> f64 {
        self.lambda_l / self.lambda_s
    }

    /// `C(q)` up to a constant factor, with `C(q_l) = 1`, as a function of the integer
    /// shell `k2` of `grid` (exact cutoffs, see [`crate::engine::grid`]).
    pub fn shape_on_shell(&self, grid: &Grid, k2: u32) -> f64 {
        if k2 == 0 {
            return 0.0;
        }
        let l = grid.length();
        let k2 = k2 as f64;
        let kl2 = (l / self.lambda_l).powi(2);
        let ks2 = (l / self.lambda_s).powi(2);
        let slack = crate::engine::tolerance::SHELL_SLACK;
        if k2 > ks2 * (1.0 + slack) {
            return 0.0;
        }
        if k2 >= kl2 * (1.0 - slack) {
            // (q / q_l)^(-2(1+H)) = (k2 / kl2)^(-(1+H))
            return (k2 / kl2).powf(-(1.0 + self.hurst));
        }
        match self.lambda_r {
            Some(r) if k2 >= (l / r).powi(2) * (1.0 - slack) => 1.0,
            _ => 0.0,
        }
    }
}

/// One shell of equal integer `|k|^2` of a realization's spectrum. Sums run over the full
/// spectrum (both `q` and `-q`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Shell {
    /// Integer `mx^2 + my^2`.
    pub k2: u32,
    /// `|q|` of the shell.
    pub q: f64,
    /// Magnification at which the shell is resolved, `|q| / q_l`.
    pub zeta: f64,
    /// Number of full-spectrum modes on the shell with non-zero amplitude.
    pub modes: u32,
    /// `sum |h~(q)|^2` over the shell.
    pub h2: f64,
    /// `sum q^2 |h~(q)|^2` over the shell (its contribution to `g_bar^2`).
    pub q2h2: f64,
}

impl Shell {
    /// The shell's full-contact pressure broadening `(E*/2)^2 q^2 sum |h~|^2`
    /// (paper eq. broadening).
    pub fn broadening(&self, e_star: f64) -> f64 {
        0.25 * e_star * e_star * self.q2h2
    }

    /// The shell's full-contact elastic energy per unit area `(E*/4) q sum |h~|^2`.
    pub fn full_contact_energy(&self, e_star: f64) -> f64 {
        0.25 * e_star * self.q * self.h2
    }
}

/// A realization's spectrum grouped into shells of increasing `|q|` (non-zero shells only).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShellSpectrum {
    /// `q_l = 2 pi / lambda_l` of the realization.
    pub q_l: f64,
    /// Shells in increasing `k2`.
    pub shells: Vec<Shell>,
}

impl ShellSpectrum {
    /// Groups the half-spectrum amplitudes `modes` of `grid` into shells.
    pub fn from_modes(
        grid: &Grid,
        modes: &[rustfft::num_complex::Complex64],
        lambda_l: f64,
    ) -> Self {
        use std::collections::BTreeMap;
        let mut acc: BTreeMap<u32, (u32, f64)> = BTreeMap::new();
        for (s, h) in modes.iter().enumerate() {
            let k2 = grid.k2(s);
            let a2 = h.norm_sqr();
            if k2 == 0 || a2 == 0.0 {
                continue;
            }
            let w = grid.weight_of(s);
            let e = acc.entry(k2).or_insert((0, 0.0));
            e.0 += w as u32;
            e.1 += w * a2;
        }
        let q_l = 2.0 * std::f64::consts::PI / lambda_l;
        let dq = grid.dq();
        let shells = acc
            .into_iter()
            .map(|(k2, (count, h2))| {
                let q = dq * (k2 as f64).sqrt();
                Shell {
                    k2,
                    q,
                    zeta: q / q_l,
                    modes: count,
                    h2,
                    q2h2: q * q * h2,
                }
            })
            .collect();
        Self { q_l, shells }
    }

    /// Shells resolved at magnification `zeta` (`|q| <= zeta q_l`, with the same slack as
    /// [`Grid::shell_limit`]).
    pub fn up_to(&self, zeta: f64) -> &[Shell] {
        let limit = zeta * zeta * (1.0 + crate::engine::tolerance::SHELL_SLACK);
        let end = self.shells.partition_point(|s| s.zeta * s.zeta <= limit);
        &self.shells[..end]
    }

    /// Rms gradient `g_bar(zeta) = sqrt(sum_{|q| <= zeta q_l} q^2 |h~|^2)`.
    pub fn rms_gradient(&self, zeta: f64) -> f64 {
        self.up_to(zeta).iter().map(|s| s.q2h2).sum::<f64>().sqrt()
    }

    /// Rms height over the modes resolved at `zeta`.
    pub fn rms_height(&self, zeta: f64) -> f64 {
        self.up_to(zeta).iter().map(|s| s.h2).sum::<f64>().sqrt()
    }
}
