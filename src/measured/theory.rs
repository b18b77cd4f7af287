//! Persson's predictions for a measured surface, on the scan's own spectrum: the contact
//! area (original theory, eq. pressureDistOri's `a_r = erf(p0 / (sqrt2 Dp_tot))`, and the
//! corrected one with `S(a_r)`, eq. gamma), the pressure distribution (the mirror
//! Gaussian) and the elastic energy (eqs. elasticEnergy_h_tot and
//! elasticEnergy_h_tot_wS), all at full resolution ([`crate::persson`]). The default
//! loads are chosen from the original theory's inverse.
//!
//! Units: pressures in units of `E*`; the spectrum's shells are in grid units (lengths
//! divided by the pixel size), so an energy per unit area from them is multiplied by the
//! pixel size to be in `E*` times the scan's length unit.

use serde::{Deserialize, Serialize};
use statrs::function::erf::erf_inv;

use crate::engine::spectrum::{Shell, ShellSpectrum};
use crate::error::{Error, Result};
use crate::persson::{Broadening, Correction, Prediction, PressureDistribution};

/// Persson's predictions at one load.
#[derive(Debug, Clone)]
pub struct Predicted {
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// Contact area, original theory.
    pub contact_area: f64,
    /// Contact area, corrected theory.
    pub contact_area_corrected: f64,
    /// Elastic energy per unit area, original theory (grid units).
    pub energy: f64,
    /// Elastic energy per unit area, corrected theory (grid units).
    pub energy_corrected: f64,
    /// The pressure distribution of the original theory.
    pub distribution: PressureDistribution,
    /// The pressure distribution of the corrected theory.
    pub distribution_corrected: PressureDistribution,
}

/// The contact modulus of the check (pressures in its units).
pub const E_STAR: f64 = 1.0;

/// Persson's theory on one scan's spectrum.
#[derive(Debug, Clone)]
pub struct Theory {
    broadening: Broadening,
}

impl Theory {
    /// The theory on `shells`.
    pub fn new(shells: &ShellSpectrum) -> Result<Self> {
        if shells.shells.is_empty() {
            return Err(Error::invalid(
                "heights",
                "a flat surface",
                "a rough surface (a spectrum with power)",
            ));
        }
        Ok(Self {
            broadening: Broadening::new(shells, E_STAR)?,
        })
    }

    /// The predictions at load `p0`.
    pub fn at(&self, p0: f64) -> Result<Predicted> {
        let original = Prediction::original(&self.broadening, p0)?;
        let corrected = Prediction::corrected(&self.broadening, p0, Correction::default())?;
        let full = f64::INFINITY;
        Ok(Predicted {
            p0,
            contact_area: original.contact_area(full),
            contact_area_corrected: corrected.contact_area(full),
            energy: original.elastic_energy(full),
            energy_corrected: corrected.elastic_energy(full),
            distribution: original.pressure_distribution(full),
            distribution_corrected: corrected.pressure_distribution(full),
        })
    }

    /// The original theory's contact area at load `p0` with the modes up to
    /// magnification `zeta` resolved, `erf(p0 / (sqrt2 Dp_tot(zeta)))`.
    pub fn contact_area_at(&self, p0: f64, zeta: f64) -> Result<f64> {
        Ok(Prediction::original(&self.broadening, p0)?.contact_area(zeta))
    }

    /// The load at which the original theory predicts contact area `a_r`,
    /// `p0 = sqrt2 Dp_tot erf^-1(a_r)`.
    pub fn load_for_area(&self, a_r: f64) -> f64 {
        std::f64::consts::SQRT_2 * self.broadening.total(f64::INFINITY).sqrt() * erf_inv(a_r)
    }
}

/// The default loads' target areas (original theory): eight, log-spaced from 0.7% to 22%,
/// so that the measured areas span about 1% to 30% (at low load a surface's contact area
/// is some 1.4 times the original theory's, the paper's contact-area law).
pub fn default_areas() -> Vec<f64> {
    let (lo, hi, k) = (0.007f64, 0.22f64, 8);
    (0..k)
        .map(|i| lo * (hi / lo).powf(i as f64 / (k - 1) as f64))
        .collect()
}

/// Checks loads given: at least one, each `p0/E*` in `(0, 10)`.
pub fn check_loads(loads: &[f64]) -> Result<()> {
    if loads.is_empty() {
        return Err(Error::invalid("loads", "[]", "at least one load p0/E*"));
    }
    for &p in loads {
        if !(p.is_finite() && p > 0.0 && p < 10.0) {
            return Err(Error::invalid(
                "loads",
                p,
                "nominal pressures p0/E* in (0, 10) (the small-slope model's range)",
            ));
        }
    }
    Ok(())
}

/// A load curve's loads, increasing: the given ones (checked, each once) or the defaults.
pub fn loads(theory: &Theory, given: Option<&[f64]>) -> Result<Vec<f64>> {
    let mut loads = match given {
        Some(l) => l.to_vec(),
        None => default_areas()
            .into_iter()
            .map(|a| theory.load_for_area(a))
            .collect(),
    };
    check_loads(&loads)?;
    crate::error::check_once("loads", &loads)?;
    loads.sort_by(f64::total_cmp);
    Ok(loads)
}

/// One load of the curve as the page and the JSON state it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TheoryPoint {
    /// The load, `p0 / E*`.
    pub p0: f64,
    /// Original theory.
    pub a_r_persson: f64,
    /// Corrected theory.
    pub a_r_persson_corrected: f64,
}

/// The shells of an isotropic spectrum on the lattice of annuli `k` of width `dq` (grid
/// units of the length `unit`): annulus `k` holds `2 pi k` modes at `|q| = k dq`, each of
/// power `C dq^2 / unit^4`, with `c(k)` the spectrum `C` (length^4) at its physical
/// wavevector; empty annuli are left out. Line scans' converted spectra and stitched
/// spectra reach [`Theory::new`] this way.
pub fn annuli(
    dq: f64,
    ks: impl Iterator<Item = usize>,
    c: impl Fn(usize) -> f64,
    unit: f64,
) -> ShellSpectrum {
    let two_pi = 2.0 * std::f64::consts::PI;
    let shells = ks
        .filter_map(|k| {
            let modes = two_pi * k as f64;
            let h2 = modes * c(k) / unit.powi(4) * dq * dq;
            let q = dq * k as f64;
            (h2 > 0.0).then_some(Shell {
                k2: u32::try_from(k * k).unwrap_or(u32::MAX),
                q,
                zeta: k as f64,
                modes: modes.round() as u32,
                h2,
                q2h2: q * q * h2,
            })
        })
        .collect();
    ShellSpectrum { q_l: dq, shells }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::surface::{Surface, SurfaceModel};

    #[test]
    fn the_default_loads_give_the_targeted_areas() {
        let s = Surface::generate(&SurfaceModel::new(64, 0.8, 64.0, 4.0, 1)).unwrap();
        let theory = Theory::new(&s.shells()).unwrap();
        let loads = loads(&theory, None).unwrap();
        assert_eq!(loads.len(), 8);
        for (p0, a) in loads.iter().zip(default_areas()) {
            let got = theory.at(*p0).unwrap().contact_area;
            assert!((got / a - 1.0).abs() < 1e-9, "{got} vs {a}");
        }
        // Unit rms gradient: Dp_tot = 1/2, so p0 = erf^-1(a) / sqrt2.
        assert!((loads[0] - erf_inv(0.007) / std::f64::consts::SQRT_2).abs() < 1e-12);
    }

    #[test]
    fn loads_out_of_range_are_refused_by_name() {
        let s = Surface::generate(&SurfaceModel::new(32, 0.8, 32.0, 4.0, 1)).unwrap();
        let theory = Theory::new(&s.shells()).unwrap();
        let twice = vec![0.2, 0.1, 0.2];
        for bad in [vec![], vec![0.1, -0.2], vec![f64::NAN], vec![20.0], twice] {
            let e = loads(&theory, Some(&bad)).unwrap_err().to_string();
            assert!(e.contains("loads"), "{e}");
        }
        assert_eq!(loads(&theory, Some(&[0.2, 0.1])).unwrap(), vec![0.1, 0.2]);
    }
}
