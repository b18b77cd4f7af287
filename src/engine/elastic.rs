//! The elastic half-space: its Green's function and its elastic energy ([`crate::conventions`], section 2).
//!
//! In the small-slope, frictionless approximation the surface displacement `u` and the
//! normal stress `p` are related mode by mode (paper section 2.1, refs Campana & Müser):
//!
//! ```text
//!     p~(q) = (q E* / 2) u~(q)        q != 0,
//! ```
//!
//! and `u~(0)` (the rigid shift) is free, fixed by the load: `p~(0) = p0`. The elastic
//! energy per unit area is the quadratic form of that stiffness,
//!
//! ```text
//!     E_el = (E*/4) sum_q q |u~(q)|^2  =  (1/2) mean[(p - p0) u],
//! ```
//!
//! the second form holding in real space because `p - p0` has no `q = 0` part (paper
//! eq. elasticEnergy_u). The per-mode energy `E_exa(q) = (E*/4) q |u~(q)|^2` is what the
//! single-mode validations compare with Persson's `E_P(q)`.

use rayon::prelude::*;
use rustfft::num_complex::Complex64;

use crate::engine::grid::Grid;
use crate::error::{check_positive, Result};

/// An elastic half-space with effective modulus `E*`, on a grid.
#[derive(Debug, Clone)]
pub struct HalfSpace {
    e_star: f64,
    /// `q E*/2` for every half-spectrum mode (0 at `q = 0`).
    stiffness: Vec<f64>,
}

impl HalfSpace {
    /// The half-space of modulus `e_star` on `grid`.
    ///
    /// # Errors
    ///
    /// If `e_star` is not positive and finite.
    pub fn new(grid: &Grid, e_star: f64) -> Result<Self> {
        check_positive("e_star", e_star)?;
        let stiffness = (0..grid.modes())
            .map(|s| 0.5 * e_star * grid.q(s))
            .collect::<Vec<f64>>();
        Ok(Self { e_star, stiffness })
    }

    /// A half-space of modulus `e_star` whose stiffness over the half spectrum is `table`
    /// (0 at `q = 0`), e.g. the free-boundary one of [`crate::engine::boussinesq`].
    ///
    /// # Errors
    ///
    /// If `e_star` is not positive and finite.
    pub fn with_stiffness(e_star: f64, table: Vec<f64>) -> Result<Self> {
        check_positive("e_star", e_star)?;
        Ok(Self {
            e_star,
            stiffness: table,
        })
    }

    /// Effective modulus `E*`.
    pub fn e_star(&self) -> f64 {
        self.e_star
    }

    /// The table of `q E*/2` over the half spectrum.
    pub fn stiffness(&self) -> &[f64] {
        &self.stiffness
    }

    /// `2 / (q E*)` over the half spectrum (0 at `q = 0`: the rigid shift is free), computed
    /// from the stiffness rather than stored (a table costs 4 bytes per grid point).
    pub fn compliance(&self) -> impl Iterator<Item = f64> + '_ {
        self.stiffness
            .iter()
            .map(|&k| if k > 0.0 { 1.0 / k } else { 0.0 })
    }

    /// Stress from displacement, `p~ = (q E*/2) u~`, with `p~(0) = p0`.
    pub fn pressure_from_displacement(&self, u: &[Complex64], p0: f64, p: &mut [Complex64]) {
        p.par_iter_mut()
            .zip(u.par_iter())
            .zip(self.stiffness.par_iter())
            .for_each(|((pi, ui), k)| *pi = ui * *k);
        p[0] = Complex64::new(p0, 0.0);
    }

    /// Elastic energy per unit area from the displacement spectrum,
    /// `(E*/4) sum_q q |u~(q)|^2`.
    pub fn energy_fourier(&self, grid: &Grid, u: &[Complex64]) -> f64 {
        u.iter()
            .zip(&self.stiffness)
            .enumerate()
            .map(|(s, (ui, k))| grid.weight_of(s) * 0.5 * k * ui.norm_sqr())
            .sum()
    }

    /// Per-mode energies `E_exa(q) = (E*/4) q |u~(q)|^2` over the half spectrum, each
    /// already multiplied by its Parseval weight (so they sum to the total).
    pub fn mode_energies(&self, grid: &Grid, u: &[Complex64]) -> Vec<f64> {
        u.iter()
            .zip(&self.stiffness)
            .enumerate()
            .map(|(s, (ui, k))| grid.weight_of(s) * 0.5 * k * ui.norm_sqr())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::fft::Fft2;
    use crate::engine::surface::{Surface, SurfaceModel};

    /// Elastic energy per unit area in real space, `(1/2) mean[(p - p0) u]`, where `p0` is
    /// the mean of `p`.
    fn energy_real(p: &[f64], u: &[f64]) -> f64 {
        let p0 = crate::engine::field::mean(p);
        0.5 * crate::engine::field::sum_zip(p, u, |pi, ui| (pi - p0) * ui) / p.len() as f64
    }

    #[test]
    fn energy_in_real_space_equals_energy_in_fourier_space() {
        let s = Surface::generate(&SurfaceModel::new(64, 0.7, 32.0, 4.0, 11)).unwrap();
        let grid = s.grid();
        let fft = Fft2::new(grid);
        let hs = HalfSpace::new(grid, 2.5).unwrap();
        // Any displacement will do: take the surface itself, full contact.
        let u_spec = s.modes().to_vec();
        let mut p_spec = fft.new_spectrum();
        hs.pressure_from_displacement(&u_spec, 0.3, &mut p_spec);
        let mut u = vec![0.0; grid.points()];
        let mut p = vec![0.0; grid.points()];
        let mut work = Vec::new();
        fft.inverse(&u_spec, &mut u, &mut work);
        fft.inverse(&p_spec, &mut p, &mut work);
        let ef = hs.energy_fourier(grid, &u_spec);
        let er = energy_real(&p, &u);
        assert!((ef - er).abs() < 1e-13 * ef, "{ef} vs {er}");
        let modes: f64 = hs.mode_energies(grid, &u_spec).iter().sum();
        assert!((modes - ef).abs() < 1e-13 * ef);
        // Full contact: E = (E*/4) sum q |h~|^2.
        let direct: f64 = s
            .shells()
            .shells
            .iter()
            .map(|sh| sh.full_contact_energy(2.5))
            .sum();
        assert!((direct - ef).abs() < 1e-12 * ef);
    }
}
