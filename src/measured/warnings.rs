//! A word when a scan lies outside what Persson's theory (or the check) assumes: each
//! [`Limit`] names a statistic of the surface or the curve, its threshold and why it
//! matters, and the check reports a [`Warning`] with the scan's number beside the
//! threshold wherever one is crossed. The list is written once, [`LIMITS`]; the page, the
//! JSON and the list in `docs/check-surface.md` come from it.

use serde::{Deserialize, Serialize};

/// On which side of its threshold a statistic warns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Above the threshold.
    Above,
    /// Below the threshold.
    Below,
    /// Its magnitude above the threshold.
    MagnitudeAbove,
}

/// One statistic with its threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// Its key in the JSON (`warnings[].name`).
    pub name: &'static str,
    /// The statistic, in words.
    pub statistic: &'static str,
    /// The threshold.
    pub threshold: f64,
    /// Which side warns.
    pub side: Side,
    /// What crossing it means.
    pub meaning: &'static str,
}

impl Limit {
    /// Whether `value` crosses the threshold.
    pub fn crossed(&self, value: f64) -> bool {
        match self.side {
            Side::Above => value > self.threshold,
            Side::Below => value < self.threshold,
            Side::MagnitudeAbove => value.abs() > self.threshold,
        }
    }

    /// The comparison in words: `above 0.5`, `below 0.5`, `beyond ±1`.
    pub fn condition(&self) -> String {
        match self.side {
            Side::Above => format!("above {}", self.threshold),
            Side::Below => format!("below {}", self.threshold),
            Side::MagnitudeAbove => format!("beyond ±{}", self.threshold),
        }
    }

    /// The warning for `value`, if it crosses the threshold.
    pub fn check(&self, value: f64) -> Option<Warning> {
        (value.is_finite() && self.crossed(value)).then(|| Warning {
            name: self.name.to_string(),
            value,
            threshold: self.threshold,
            message: format!(
                "{} is {} ({}): {}",
                self.statistic,
                super::units::eng(value),
                self.condition(),
                self.meaning
            ),
        })
    }
}

/// The spectrum's anisotropy, `sqrt(l_min / l_max)` of the slope tensor.
pub const ANISOTROPY: Limit = Limit {
    name: "anisotropy",
    statistic: "the spectral isotropy sqrt(l_min / l_max) of the slope tensor",
    threshold: 0.5,
    side: Side::Below,
    meaning: "the spectrum is strongly anisotropic (stripes, scan lines, a lay); Persson's \
              theory assumes an isotropic one",
};

/// The log-log slope of `C(q)` over the highest octave.
pub const NOISE_FLOOR: Limit = Limit {
    name: "noise_floor",
    statistic: "the log-log slope of C(q) over the highest octave below the Nyquist \
                wavevector",
    threshold: -1.0,
    side: Side::Above,
    meaning: "the spectrum flattens at high q, as an instrument's noise floor does (a \
              self-affine surface falls as q^-2(1+H), slope -2 to -4); the slopes, and \
              with them the contact area, are then the noise's",
};

/// The skewness of the heights.
pub const SKEWNESS: Limit = Limit {
    name: "skewness",
    statistic: "the skewness of the heights",
    threshold: 1.0,
    side: Side::MagnitudeAbove,
    meaning: "the heights are far from Gaussian (particles, pits, terraces); Persson's \
              theory takes Gaussian heights",
};

/// The excess kurtosis of the heights.
pub const KURTOSIS: Limit = Limit {
    name: "kurtosis",
    statistic: "the excess kurtosis of the heights",
    threshold: 2.0,
    side: Side::MagnitudeAbove,
    meaning: "the height distribution's tails are far from Gaussian (isolated spikes or \
              steps); Persson's theory takes Gaussian heights",
};

/// The rms slope from finite differences.
pub const RMS_SLOPE: Limit = Limit {
    name: "rms_slope",
    statistic: "the rms slope",
    threshold: 0.5,
    side: Side::Above,
    meaning: "beyond the small-slope regime that the half-space model and Persson's \
              theory assume",
};

/// The smallest simulated contact area at the default loads.
pub const AREA_LOW: Limit = Limit {
    name: "contact_area_low",
    statistic: "the smallest simulated contact area at the default loads",
    threshold: 0.005,
    side: Side::Below,
    meaning: "below the range the default loads aim for (about 1% to 30%): a few points \
              carry the load, and the grid resolves the contact patches poorly",
};

/// The largest simulated contact area at the default loads.
pub const AREA_HIGH: Limit = Limit {
    name: "contact_area_high",
    statistic: "the largest simulated contact area at the default loads",
    threshold: 0.45,
    side: Side::Above,
    meaning: "above the range the default loads aim for (about 1% to 30%): the scan is \
              far from Persson's low-load regime there",
};

/// The mean pressure in contact, `p0 / a_r`, in units of `E*`.
pub const CONTACT_PRESSURE: Limit = Limit {
    name: "contact_pressure",
    statistic: "the largest mean pressure in contact p0 / a_r, in units of E*",
    threshold: 0.2,
    side: Side::Above,
    meaning: "far past the yield of any material (hardness stays below about 0.2 E* even \
              for diamond): a real contact is plastic at these loads",
};

/// The fewest grid points in contact at any load: below a few hundred, the contact area
/// moves in steps of one point in `rows * cols` and its patches are a few pixels wide.
pub const RESOLUTION: Limit = Limit {
    name: "resolution",
    statistic: "the fewest grid points in contact at any load (a_r times the scan's points)",
    threshold: 200.0,
    side: Side::Below,
    meaning: "the contact area moves in steps of one point and its patches are a few \
              pixels wide: the grid resolves the contact poorly at these loads; measure a \
              larger scan, or read the higher loads",
};

/// Every limit, in the order the page lists them.
pub const LIMITS: [Limit; 9] = [
    ANISOTROPY,
    NOISE_FLOOR,
    SKEWNESS,
    KURTOSIS,
    RMS_SLOPE,
    AREA_LOW,
    AREA_HIGH,
    CONTACT_PRESSURE,
    RESOLUTION,
];

/// A crossed threshold: the statistic's key, its value, the threshold, and the word.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// The [`Limit`]'s name.
    pub name: String,
    /// The scan's value (the mean over scans).
    pub value: f64,
    /// The threshold.
    pub threshold: f64,
    /// What it means, with both numbers.
    pub message: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_limit_warns_on_its_side_only_and_says_its_numbers() {
        let names: Vec<&str> = LIMITS.iter().map(|l| l.name).collect();
        let mut unique = names.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "{names:?}");
        assert!(ANISOTROPY.check(0.3).is_some() && ANISOTROPY.check(0.7).is_none());
        assert!(SKEWNESS.check(-2.0).is_some() && SKEWNESS.check(0.5).is_none());
        assert!(RMS_SLOPE.check(0.8).is_some() && RMS_SLOPE.check(0.2).is_none());
        assert!(RMS_SLOPE.check(f64::NAN).is_none());
        assert!(RESOLUTION.check(58.0).is_some() && RESOLUTION.check(655.0).is_none());
        let w = NOISE_FLOOR.check(-0.25).unwrap();
        assert_eq!((w.value, w.threshold), (-0.25, -1.0));
        assert!(
            w.message.contains("-250e-3") && w.message.contains("above -1"),
            "{}",
            w.message
        );
    }
}
