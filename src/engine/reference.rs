//! Closed-form contact solutions that the solvers are tested against.
//!
//! Pure, documented functions; each is itself tested.

/// Westergaard's solution for a one-dimensional sinusoid `h(x) = h0 cos(2 pi x / lambda)`
/// pressed onto an elastic half-space of modulus `E*` at mean pressure `p0`
/// (Westergaard, J. Appl. Mech. 6, 49 (1939); Johnson, *Contact Mechanics*, section 13.2).
///
/// With `p* = pi E* h0 / lambda`, the pressure that brings the sinusoid into full contact:
///
/// * partial contact, `p0 < p*`: contact over `|x| < a` (per period) with
///   `sin^2(pi a / lambda) = p0 / p*`, and
///   `p(x) = (2 p0 / sin^2 psi) cos(pi x / lambda) sqrt(sin^2 psi - sin^2(pi x / lambda))`,
///   `psi = pi a / lambda`; the peak pressure is `p(0) = 2 sqrt(p0 p*)`;
/// * full contact, `p0 >= p*`: `p(x) = p0 + p* cos(2 pi x / lambda)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Westergaard {
    /// Amplitude `h0`.
    pub h0: f64,
    /// Wavelength `lambda`.
    pub lambda: f64,
    /// Effective modulus `E*`.
    pub e_star: f64,
}

impl Westergaard {
    /// `p* = pi E* h0 / lambda`.
    pub fn full_contact_pressure(&self) -> f64 {
        std::f64::consts::PI * self.e_star * self.h0 / self.lambda
    }

    /// Contact fraction `2 a / lambda = (2/pi) asin(sqrt(p0/p*))`, 1 at full contact.
    pub fn contact_fraction(&self, p0: f64) -> f64 {
        let ratio = p0 / self.full_contact_pressure();
        if ratio >= 1.0 {
            1.0
        } else {
            2.0 / std::f64::consts::PI * ratio.sqrt().asin()
        }
    }

    /// Peak pressure: `2 sqrt(p0 p*)` in partial contact, `p0 + p*` in full contact.
    pub fn peak_pressure(&self, p0: f64) -> f64 {
        let ps = self.full_contact_pressure();
        if p0 >= ps {
            p0 + ps
        } else {
            2.0 * (p0 * ps).sqrt()
        }
    }

    /// Pressure at `x` (the sinusoid's crest at `x = 0`).
    pub fn pressure(&self, p0: f64, x: f64) -> f64 {
        use std::f64::consts::PI;
        let ps = self.full_contact_pressure();
        if p0 >= ps {
            return p0 + ps * (2.0 * PI * x / self.lambda).cos();
        }
        let s2 = p0 / ps;
        let phase = PI * x / self.lambda;
        let d = s2 - phase.sin().powi(2);
        if d <= 0.0 {
            return 0.0;
        }
        // |cos| covers the contact centred on the next crest (x near lambda) too.
        2.0 * p0 / s2 * phase.cos().abs() * d.sqrt()
    }
}

/// Hertz's solution for a rigid sphere of radius `R` (a paraboloid, `h(r) = -r^2 / (2R)`)
/// pressed with force `F` onto an elastic half-space of modulus `E*` with a free surface
/// (Hertz, J. reine angew. Math. 92, 156 (1882); Johnson, *Contact Mechanics*, section 4.2):
/// contact radius `a = (3 F R / (4 E*))^(1/3)`, pressure
/// `p(r) = p_max sqrt(1 - r^2/a^2)`, `p_max = 3 F / (2 pi a^2)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Radius of the sphere.
    pub radius: f64,
    /// Effective modulus `E*`.
    pub e_star: f64,
}

impl Hertz {
    /// Contact radius under force `force`.
    pub fn contact_radius(&self, force: f64) -> f64 {
        (0.75 * force * self.radius / self.e_star).cbrt()
    }

    /// The force that gives contact radius `a`.
    pub fn force_for_radius(&self, a: f64) -> f64 {
        4.0 * self.e_star * a.powi(3) / (3.0 * self.radius)
    }

    /// Peak pressure under force `force`.
    pub fn peak_pressure(&self, force: f64) -> f64 {
        let a = self.contact_radius(force);
        1.5 * force / (std::f64::consts::PI * a * a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn westergaard_pressure_averages_to_load_and_peaks_where_stated() {
        let w = Westergaard {
            h0: 0.3,
            lambda: 10.0,
            e_star: 2.0,
        };
        for ratio in [0.01, 0.2, 0.7, 1.0, 1.5] {
            let p0 = ratio * w.full_contact_pressure();
            let m = 200_000;
            let mean: f64 = (0..m)
                .map(|k| w.pressure(p0, (k as f64 + 0.5) / m as f64 * w.lambda))
                .sum::<f64>()
                / m as f64;
            assert!(
                (mean - p0).abs() < 1e-4 * p0,
                "ratio {ratio}: mean {mean} vs {p0}"
            );
            assert!((w.pressure(p0, 0.0) - w.peak_pressure(p0)).abs() < 1e-12 * p0.max(1.0));
            let area = (0..m)
                .filter(|&k| w.pressure(p0, (k as f64 + 0.5) / m as f64 * w.lambda) > 0.0)
                .count() as f64
                / m as f64;
            assert!((area - w.contact_fraction(p0)).abs() < 1e-4);
        }
    }
    #[test]
    fn hertz_radius_and_force_are_inverse_and_the_pressure_integrates_to_the_force() {
        let h = Hertz {
            radius: 1000.0,
            e_star: 2.0,
        };
        let f = h.force_for_radius(45.0);
        assert!((h.contact_radius(f) - 45.0).abs() < 1e-12);
        // integral of p_max sqrt(1 - r^2/a^2) 2 pi r dr = (2/3) pi a^2 p_max = F.
        let a = h.contact_radius(f);
        let integral = 2.0 / 3.0 * std::f64::consts::PI * a * a * h.peak_pressure(f);
        assert!((integral / f - 1.0).abs() < 1e-14);
    }
}
