//! One spectrum from the scans of one surface at several scales: each scan's power
//! spectrum over the band it resolves reliably, averaged where the bands overlap.
//!
//! **Samples.** A scan gives estimates of the isotropic `C(q)` (length^4, the convention
//! of [`crate::measured::psd`]) at wavevectors `q`, each with the number of independent
//! Fourier modes `n` it rests on ([`Sample`]): an areal scan one sample per mode of its
//! half spectrum ([`crate::measured::psd::scan_modes`]); a line scan one per bin of the
//! spectrum converted from its profiles ([`crate::measured::line::abel`]). What each
//! sample counts is set by the caller ([`crate::measured::scales`]).
//!
//! **Bins.** `BINS_PER_DECADE` log-spaced bins from the lowest `q` of the union of the
//! bands, `q_b = q_lo 10^(b / 10)` their lower edges. Scan `i` contributes only the samples
//! inside its band `[q_lo,i, q_hi,i]` ([`Band`]); in bin `b` its estimate is the weighted
//! mean of its samples there,
//!
//! `C_i(b) = sum_s n_s C_s / N_i(b)`,  `N_i(b) = sum_s n_s`,
//!
//! and the stitched spectrum is the mean of the scans' estimates weighted by the
//! independent modes each holds in the bin,
//!
//! `C(b) = sum_i N_i(b) C_i(b) / N(b)`,  `N(b) = sum_i N_i(b)`,
//!
//! at `q(b) = sum_i N_i(b) q_i(b) / N(b)` (the mean wavevector of its samples). A
//! periodogram ordinate is exponentially distributed (its standard deviation is its mean),
//! so `C(b)` has the standard error `C(b) / sqrt(N(b))`. A scan that holds many modes in
//! a bin (the larger scan, at its short wavelengths) outweighs one that holds a few (the
//! smaller scan, near its longest wavelengths), as the variance of each asks. A bin's mean
//! `C` lies above `C` at its mean `q` by the curvature of the spectrum over the bin: 3.7%
//! for `C ~ q^-3.6` over a tenth of a decade with modes spread as a 2D scan's (uniform in
//! `q^2`), 2.9% with samples uniform in `ln q`.
//!
//! **Gaps.** Bands that do not overlap leave a gap between the highest `q` reached below
//! and the next band's lowest ([`Gap`]); its bins hold no sample. Across a gap, and within
//! a band between bins, the spectrum is interpolated linearly in `ln C` against `ln q`
//! ([`Stitched::spectrum`]), and extended to the edges of the union with the slope of the
//! nearest segment: Persson's theory on the stitched spectrum leans on that interpolation
//! over a gap, and the check says so.
//!
//! **Theory.** Persson's theory takes shells ([`crate::measured::theory::Theory::new`]):
//! [`Stitched::shells`] lays the stitched `C(q)` on the lattice of a square of side
//! `L = 2 pi / q_lo` (the union's lowest `q`) in annuli `q_k = k 2 pi / L`, each holding
//! `2 pi k` modes (the continuum's count) of `|h~|^2 = C(q_k) (2 pi / L)^2`, over any band
//! inside the union, in grid units of a chosen length (lengths divided by it), as the
//! line scans' shells are laid ([`crate::measured::line::synthesis::shells`]).

use serde::{Deserialize, Serialize};

use super::line::abel::LogLog;
use crate::engine::spectrum::ShellSpectrum;
use crate::error::{Error, Result};
use crate::stats::{Bins, Histogram};

/// Log-spaced bins per decade of `q` of the stitched spectrum (the radial average's).
pub const BINS_PER_DECADE: f64 = 10.0;

/// A band of wavevectors, `lo <= q <= hi` (1 / length).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Band {
    /// The lowest `q`.
    pub lo: f64,
    /// The highest `q`.
    pub hi: f64,
}

impl Band {
    /// Whether `q` lies in the band (its edges within a relative 1e-9).
    pub fn holds(&self, q: f64) -> bool {
        q >= self.lo * (1.0 - 1e-9) && q <= self.hi * (1.0 + 1e-9)
    }
}

/// One estimate of `C(q)`, resting on `modes` independent Fourier modes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// `q` (1 / length).
    pub q: f64,
    /// `C(q)` (length^4).
    pub c: f64,
    /// Independent modes it rests on (its weight).
    pub modes: f64,
}

/// A scan's spectrum, or the stitched one, in one bin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Bin {
    /// The mean `q` of the bin's samples (1 / length).
    pub q: f64,
    /// `C(q)` (length^4).
    pub c: f64,
    /// Its standard error, `C / sqrt(modes)`.
    pub std_error: f64,
    /// Independent modes in the bin (the weight).
    pub modes: f64,
}

/// A stretch of wavevectors no scan resolves, between two bands.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Gap {
    /// The highest `q` reached by the bands below (1 / length).
    pub from: f64,
    /// The lowest `q` of the next band.
    pub to: f64,
}

/// The stitched spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stitched {
    /// The union of the bands: from the lowest `q` to the highest.
    pub band: Band,
    /// The stitched bins, increasing `q` (bins without a sample left out).
    pub bins: Vec<Bin>,
    /// Each scan's bins on the same grid (inside its band only).
    pub scans: Vec<Vec<Bin>>,
    /// The gaps between bands.
    pub gaps: Vec<Gap>,
}

/// The gaps that `bands` leave in their union, increasing.
pub fn gaps(bands: &[Band]) -> Vec<Gap> {
    let mut sorted = bands.to_vec();
    sorted.sort_by(|a, b| a.lo.total_cmp(&b.lo));
    let mut gaps = Vec::new();
    let Some(first) = sorted.first() else {
        return gaps;
    };
    let mut reach = first.hi;
    for b in &sorted[1..] {
        if b.lo > reach * (1.0 + 1e-9) {
            gaps.push(Gap {
                from: reach,
                to: b.lo,
            });
        }
        reach = reach.max(b.hi);
    }
    gaps
}

/// Per bin: the sums of `n q`, `n C` and `n`.
type Sums = (f64, f64, f64);

/// A bin of sums as a bin of means (`None` when it holds no sample).
fn mean(s: &Sums) -> Option<Bin> {
    let &(nq, nc, n) = s;
    (n > 0.0).then(|| Bin {
        q: nq / n,
        c: nc / n,
        std_error: nc / n / n.sqrt(),
        modes: n,
    })
}

/// Stitches the scans' samples, each scan `(band, samples)` (module docs).
///
/// # Errors
///
/// If there is no scan, a band is empty or not positive, or no sample lies in any band.
pub fn stitch(scans: &[(Band, Vec<Sample>)]) -> Result<Stitched> {
    for (band, _) in scans {
        if !(band.lo > 0.0 && band.lo.is_finite() && band.hi > band.lo && band.hi.is_finite()) {
            return Err(Error::invalid(
                "band",
                format!("[{}, {}]", band.lo, band.hi),
                "a band of wavevectors 0 < lo < hi",
            ));
        }
    }
    let Some(lo) = scans.iter().map(|s| s.0.lo).min_by(f64::total_cmp) else {
        return Err(Error::invalid("scales", "no scan", "at least one scan"));
    };
    let hi = scans.iter().map(|s| s.0.hi).fold(lo, f64::max);
    let bins = Bins::log10_up_to(lo, BINS_PER_DECADE, hi);
    let mut total = Histogram::<Sums>::new(bins);
    let per_scan: Vec<Vec<Bin>> = scans
        .iter()
        .map(|(band, samples)| {
            let mut own = Histogram::<Sums>::new(bins);
            for s in samples
                .iter()
                .filter(|s| band.holds(s.q) && s.c.is_finite())
            {
                let cell = own.at(s.q);
                cell.0 += s.modes * s.q;
                cell.1 += s.modes * s.c;
                cell.2 += s.modes;
            }
            for (k, cell) in own.cells().iter().enumerate() {
                let t = &mut total.at(bins.centre(k));
                t.0 += cell.0;
                t.1 += cell.1;
                t.2 += cell.2;
            }
            own.cells().iter().filter_map(mean).collect()
        })
        .collect();
    let stitched: Vec<Bin> = total.cells().iter().filter_map(mean).collect();
    if stitched.is_empty() {
        return Err(Error::invalid(
            "scales",
            "scans without a mode in their bands",
            "rough scans (a spectrum with power in the band each resolves)",
        ));
    }
    let bands: Vec<Band> = scans.iter().map(|s| s.0).collect();
    Ok(Stitched {
        band: Band { lo, hi },
        bins: stitched,
        scans: per_scan,
        gaps: gaps(&bands),
    })
}

impl Stitched {
    /// The stitched `C(q)` (length^4) inside the union (zero outside): linear in log-log
    /// between the bins' `(q, C)`, across gaps too, and extended to the union's edges with
    /// the slope of the nearest segment (module docs).
    pub fn spectrum(&self) -> impl Fn(f64) -> f64 + '_ {
        let nodes: Vec<(f64, f64)> = self
            .bins
            .iter()
            .filter(|b| b.c > 0.0)
            .map(|b| (b.q, b.c))
            .collect();
        let tail = match nodes.as_slice() {
            [.., a, b] => Some((b.1 / a.1).ln() / (b.0 / a.0).ln()),
            _ => Some(0.0),
        };
        let table = LogLog::new(&nodes, tail);
        let single = (nodes.len() == 1).then(|| nodes[0].1);
        move |q: f64| {
            if !self.band.holds(q) {
                0.0
            } else if let Some(c) = single {
                c
            } else {
                table.at(q)
            }
        }
    }

    /// The shells of the stitched spectrum over `band` (inside the union), in grid units
    /// of the length `unit` (module docs), for [`crate::measured::theory::Theory::new`].
    pub fn shells(&self, band: Band, unit: f64) -> ShellSpectrum {
        let c = self.spectrum();
        let q_lo = self.band.lo;
        let top = (band.hi / q_lo * (1.0 + 1e-9)).floor() as usize;
        let ks = (1..=top).filter(|&k| band.holds(q_lo * k as f64));
        crate::measured::theory::annuli(q_lo * unit, ks, |k| c(q_lo * k as f64), unit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn power_law(q: f64) -> f64 {
        q.powf(-3.6)
    }

    /// Samples of `C = q^-3.6` on a fine log grid over `band`, `modes` each.
    fn exact(band: Band, modes: f64) -> Vec<Sample> {
        (0..400)
            .map(|k| band.lo * (band.hi / band.lo).powf((k as f64 + 0.5) / 400.0))
            .map(|q| Sample {
                q,
                c: power_law(q),
                modes,
            })
            .collect()
    }

    #[test]
    fn overlapping_bands_average_by_modes_and_leave_no_gap() {
        let a = Band { lo: 1.0, hi: 20.0 };
        let b = Band {
            lo: 10.0,
            hi: 200.0,
        };
        // Scan b reads 10% high, with a quarter of a's modes per sample: in the overlap
        // the stitched spectrum is 2% high ((4 + 1.1) / 5).
        let high: Vec<Sample> = exact(b, 1.0)
            .into_iter()
            .map(|s| Sample { c: 1.1 * s.c, ..s })
            .collect();
        let s = stitch(&[(a, exact(a, 4.0)), (b, high)]).unwrap();
        assert!(s.gaps.is_empty());
        assert_eq!(s.band, Band { lo: 1.0, hi: 200.0 });
        for bin in &s.bins {
            let ratio = bin.c / power_law(bin.q);
            // Within a bin, C varies: the mean of q^-3.6 over the bin exceeds its value at
            // the mean q by 2.9% for bins a tenth of a decade wide (samples uniform in
            // ln q); the edges of bands cut bins, and the share moves.
            let want = if bin.q > 11.0 && bin.q < 19.0 {
                1.02
            } else if bin.q > 21.0 {
                1.1
            } else if bin.q < 9.0 {
                1.0
            } else {
                continue;
            };
            assert!((ratio / want - 1.029).abs() < 0.02, "q {}: {ratio}", bin.q);
        }
        assert_eq!(s.scans.len(), 2);
        assert!(s.scans[0].iter().all(|b| b.q <= 20.0));
    }

    #[test]
    fn bands_apart_leave_a_gap_that_the_spectrum_bridges_in_log_log() {
        let bands = [
            Band { lo: 1.0, hi: 10.0 },
            Band {
                lo: 100.0,
                hi: 1000.0,
            },
            Band { lo: 5.0, hi: 30.0 },
        ];
        let g = gaps(&bands);
        assert_eq!(
            g,
            vec![Gap {
                from: 30.0,
                to: 100.0
            }]
        );
        let s = stitch(&[
            (bands[0], exact(bands[0], 1.0)),
            (bands[1], exact(bands[1], 1.0)),
        ])
        .unwrap();
        assert_eq!(s.gaps.len(), 1);
        assert!(s.bins.iter().all(|b| b.q < 10.0 || b.q > 100.0));
        // A power law is bridged exactly (up to the bins' own few percent).
        let c = s.spectrum();
        assert!((c(30.0) / power_law(30.0) - 1.0).abs() < 0.05);
        assert_eq!(c(2000.0), 0.0);
    }

    #[test]
    fn the_shells_of_a_band_hold_its_rms_slope() {
        // On the lattice q_k = k lo: g^2 = 2 pi sum_k k^3 lo^4 C(k lo) over the band.
        let band = Band { lo: 1.0, hi: 100.0 };
        let s = stitch(&[(band, exact(band, 1.0))]).unwrap();
        let inner = Band { lo: 2.0, hi: 50.0 };
        let lattice = |b: Band| -> f64 {
            (1..=100)
                .map(|k| k as f64)
                .filter(|&q| b.holds(q))
                .map(|q| 2.0 * std::f64::consts::PI * q.powi(3) * power_law(q))
                .sum()
        };
        for b in [band, inner] {
            // Grid units of 0.01: slopes are dimensionless, unchanged. A bin's mean C
            // exceeds C at its mean q by 2.9% for q^-3.6 over a tenth of a decade
            // (samples uniform in ln q): the stitched slope^2 by as much.
            let g2 = s.shells(b, 0.01).rms_gradient(f64::INFINITY).powi(2);
            let ratio = g2 / lattice(b);
            assert!(
                (ratio - 1.029).abs() < 0.01,
                "{b:?}: {g2} vs {}",
                lattice(b)
            );
        }
    }
}
