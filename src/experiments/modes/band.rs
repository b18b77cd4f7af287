//! Bands of modes around a target wavenumber, and the elastic energy they hold,
//! eq. (elasticEnergy_u_q) summed over a band.

use crate::engine::contact::{ContactSolution, Model};
use crate::engine::grid::Grid;
use crate::engine::surface::Surface;
use crate::error::{Error, Result};

/// A band of modes around a target wavenumber: the half-spectrum indices with
/// `|q/q_t - 1| <= half_width`, and their full-contact energy.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Target magnification `zeta_t = q_t / q_l`.
    pub zeta_t: f64,
    /// Half-spectrum indices of the band's modes.
    pub modes: Vec<usize>,
    /// Full-contact energy of the band, `(E*/4) sum_band q |h~(q)|^2` (full spectrum).
    pub nominal: f64,
    /// Magnification of the band's first mode (`min |q| / q_l`).
    pub zeta_lo: f64,
    /// Magnification of the band's last mode (`max |q| / q_l`).
    pub zeta_hi: f64,
}

impl Band {
    /// The band of `surface` around `zeta_t` with relative half-width `half_width`, on a
    /// half-space of modulus `e_star`. Errors name `zeta_t` when the band holds no mode
    /// with roughness.
    pub fn new(surface: &Surface, zeta_t: f64, half_width: f64, e_star: f64) -> Result<Self> {
        let grid: &Grid = surface.grid();
        let q_t = zeta_t * surface.q_l();
        let mut modes = Vec::new();
        let (mut nominal, mut lo, mut hi) = (0.0, f64::INFINITY, 0.0f64);
        for s in 0..grid.modes() {
            let q = grid.q(s);
            if grid.k2(s) == 0 || (q / q_t - 1.0).abs() > half_width {
                continue;
            }
            modes.push(s);
            let h2 = surface.modes()[s].norm_sqr();
            nominal += grid.weight_of(s) * 0.25 * e_star * q * h2;
            lo = lo.min(q / surface.q_l());
            hi = hi.max(q / surface.q_l());
        }
        if nominal <= 0.0 || !nominal.is_finite() {
            return Err(Error::invalid(
                "targets",
                zeta_t,
                format!("a magnification whose band (|q/q_t - 1| <= {half_width}) holds roughness"),
            ));
        }
        Ok(Self {
            zeta_t,
            modes,
            nominal,
            zeta_lo: lo,
            zeta_hi: hi,
        })
    }

    /// The band's share of the per-mode energies `energies` (weighted, as from
    /// [`HalfSpace::mode_energies`](crate::engine::elastic::HalfSpace::mode_energies)).
    pub fn energy(&self, energies: &[f64]) -> f64 {
        self.modes.iter().map(|&s| energies[s]).sum()
    }
}

/// The elastic energy `E_exa` of every band in `bands` for `solution`, eq.
/// (elasticEnergy_u_q) summed over each band.
pub fn band_energies(model: &Model, solution: &ContactSolution, bands: &[Band]) -> Vec<f64> {
    let u = solution.displacement_spectrum(model);
    let energies = model.halfspace.mode_energies(&model.grid, &u);
    bands.iter().map(|b| b.energy(&energies)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::surface::SurfaceModel;

    #[test]
    fn band_energy_is_the_full_contact_energy_of_its_shells() {
        let surface = Surface::generate(&SurfaceModel::new(64, 0.5, 32.0, 4.0, 5)).unwrap();
        let band = Band::new(&surface, 4.0, 0.15, 2.0).unwrap();
        let shells: f64 = surface
            .shells()
            .shells
            .iter()
            .filter(|s| (s.zeta / 4.0 - 1.0).abs() <= 0.15)
            .map(|s| s.full_contact_energy(2.0))
            .sum();
        assert!((band.nominal - shells).abs() < 1e-12 * shells);
        let e = Band::new(&surface, 40.0, 0.1, 1.0).unwrap_err().to_string();
        assert!(e.contains("targets"), "{e}");
    }
}
