//! Persson's theory on the spectrum of one surface (Python's `theory`): its modes grouped
//! into shells of equal `|q|` give the pressure broadening `Dp^2` shell by shell (paper eq.
//! broadening), from which the contact area, the pressure distribution and the elastic
//! energy follow at every magnification, in the original theory or with a correction
//! factor `S(a_r) = gamma + (1 - gamma) a_r^2` (eq. gamma). See [`crate::persson`].

use crate::engine::surface::Surface;
use crate::error::Result;
use crate::persson::{Broadening, Correction, Prediction};

/// Persson's theory at one load on one surface's spectrum.
pub struct Theory {
    /// The prediction shell by shell.
    pub prediction: Prediction,
    /// The magnification of the finest shell (at least 1).
    pub zeta_max: f64,
}

/// The theory at mean pressure `p0` on the spectrum of `surface`, original (`correction`
/// `None`) or corrected, for the effective modulus `e_star`.
///
/// # Errors
///
/// If `e_star` or `p0` is out of range for the theory.
pub fn theory(
    surface: &Surface,
    p0: f64,
    correction: Option<Correction>,
    e_star: f64,
) -> Result<Theory> {
    let broadening = Broadening::new(&surface.shells(), e_star)?;
    let prediction = match correction {
        None => Prediction::original(&broadening, p0)?,
        Some(c) => Prediction::corrected(&broadening, p0, c)?,
    };
    Ok(Theory {
        prediction,
        zeta_max: surface.zeta_max().max(1.0),
    })
}
