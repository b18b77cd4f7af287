//! Rigid rough surfaces: generated self-affine realizations and measured height maps.
//!
//! Generation ([`crate::conventions`], section 3): `h~(q) = sqrt(C(q)) xi(q)` with `xi` complex Gaussian,
//! `E|xi|^2 = 1` (or a random phase, `|xi| = 1`), Hermitian so that `h` is real, Nyquist
//! rows and the `q = 0` mode empty, and an overall factor that sets the rms gradient
//! `g_bar^2 = sum_q q^2 |h~(q)|^2` at full resolution (1 by default: pressures are then in
//! units of `E* g_bar`).
//!
//! Reproducibility: the random number of the mode `(mx, my)` is read from the ChaCha8
//! stream of the seed at a word position fixed by `(mx, my)` alone (a counter-based
//! draw). A seed therefore gives the same bits on every platform and thread count, and the
//! same mode amplitudes on every grid that holds the mode: a realization refined to a finer
//! grid (lengths doubled in grid units) keeps its long-wavelength modes.
//!
//! Magnification: the surface at `zeta` keeps exactly the modes with `|q| <= zeta q_l` of
//! the same realization; raising `zeta` only adds modes.

use rand::Rng;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::engine::spectrum::{SelfAffine, ShellSpectrum};
use crate::error::{check_positive, Error, Result};

/// How the random amplitudes `xi(q)` are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Amplitudes {
    /// Complex Gaussian, `E|xi|^2 = 1` (the paper's colored noise).
    #[default]
    Gaussian,
    /// Random phase with unit modulus: the realization's spectrum equals `C(q)` exactly.
    RandomPhase,
}

fn one() -> f64 {
    1.0
}

/// The self-affine surface model, declared once: the `[surface]` table of a scene file
/// ([`crate::engine::scene`]), the surface of every validation's scene
/// ([`crate::experiments::scene::Base`]), the command line's surface flags and Python's
/// `surface`. With a seed it is one realization ([`Surface::generate`]); without one, the
/// seed comes from elsewhere (a flag, a scene's list of seeds).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceModel {
    /// Points per side.
    pub n: usize,
    /// Hurst exponent, in (0, 1).
    pub hurst: f64,
    /// Long-wavelength cutoff (grid units), at most `n`.
    pub lambda_l: f64,
    /// Short-wavelength cutoff (grid units), at least 2.
    pub lambda_s: f64,
    /// Optional roll-off wavelength: a plateau from `lambda_r` down to `lambda_l`.
    #[serde(default)]
    pub lambda_r: Option<f64>,
    /// How the amplitudes are drawn.
    #[serde(default)]
    pub amplitudes: Amplitudes,
    /// The rms gradient at full resolution.
    #[serde(default = "one")]
    pub rms_gradient: f64,
    /// The seed of the realization.
    #[serde(default)]
    pub seed: Option<u64>,
}

impl SurfaceModel {
    /// Realization `seed` of a Gaussian self-affine surface with `g_bar = 1` and no
    /// roll-off, grid spacing 1.
    pub fn new(n: usize, hurst: f64, lambda_l: f64, lambda_s: f64, seed: u64) -> Self {
        Self {
            n,
            hurst,
            lambda_l,
            lambda_s,
            lambda_r: None,
            amplitudes: Amplitudes::Gaussian,
            rms_gradient: 1.0,
            seed: Some(seed),
        }
    }

    /// The same model, realization `seed`.
    pub fn seeded(self, seed: u64) -> Self {
        Self {
            seed: Some(seed),
            ..self
        }
    }

    /// The model spectrum.
    pub fn spectrum(&self) -> SelfAffine {
        SelfAffine {
            hurst: self.hurst,
            lambda_l: self.lambda_l,
            lambda_s: self.lambda_s,
            lambda_r: self.lambda_r,
        }
    }

    /// Checks the grid and the spectrum against the grid; errors name the field.
    pub fn validate_spectrum(&self) -> Result<()> {
        let grid = Grid::new(self.n, 1.0)?;
        self.spectrum().validate(&grid)
    }

    /// Checks every range (grid size, spectrum, normalisation); errors name the field.
    pub fn validate(&self) -> Result<()> {
        self.validate_spectrum()?;
        check_positive("rms_gradient", self.rms_gradient)
    }

    /// `zeta_max = lambda_l / lambda_s`.
    pub fn zeta_max(&self) -> f64 {
        self.lambda_l / self.lambda_s
    }
}

/// A rigid surface: its grid, its full-resolution half spectrum and its `lambda_l`.
#[derive(Debug, Clone)]
pub struct Surface {
    grid: Grid,
    lambda_l: f64,
    modes: Vec<Complex64>,
}

impl Surface {
    /// Generates the realization of `model` (its seed).
    ///
    /// # Errors
    ///
    /// A range of the model out of bounds, or no seed, named by its field.
    pub fn generate(model: &SurfaceModel) -> Result<Self> {
        let grid = Grid::new(model.n, 1.0)?;
        let spectrum = model.spectrum();
        spectrum.validate(&grid)?;
        check_positive("rms_gradient", model.rms_gradient)?;
        let seed = model
            .seed
            .ok_or_else(|| Error::invalid("seed", "missing", "given"))?;
        let modes = draw_modes(&grid, seed, model.amplitudes, |k2| {
            spectrum.shape_on_shell(&grid, k2)
        });
        let mut surface = Self {
            grid,
            lambda_l: spectrum.lambda_l,
            modes,
        };
        let g = surface.rms_gradient(f64::INFINITY);
        if g > 0.0 {
            let f = model.rms_gradient / g;
            surface.modes.iter_mut().for_each(|h| *h *= f);
        }
        Ok(surface)
    }

    /// A realization of a tabulated isotropic spectrum on an `n x n` grid (grid units):
    /// `power(q)` is the expected `|h~(q)|^2` of one mode at `|q| = 2 pi |k| / n` (zero
    /// where the spectrum is empty), drawn as [`Surface::generate`] draws (the same seed,
    /// the same `xi` per wavevector) but with no rescaling of the rms gradient;
    /// `lambda_l = n`.
    ///
    /// # Errors
    /// `n` outside the grid's range, or a `power` that is negative or not finite.
    pub fn generate_tabulated(
        n: usize,
        power: &dyn Fn(f64) -> f64,
        seed: u64,
        amplitudes: Amplitudes,
    ) -> Result<Self> {
        let grid = Grid::new(n, 1.0)?;
        let dq = grid.dq();
        let mut bad = None;
        let modes = draw_modes(&grid, seed, amplitudes, |k2| {
            let q = dq * f64::from(k2).sqrt();
            let c = power(q);
            if !(c.is_finite() && c >= 0.0) {
                bad.get_or_insert((q, c));
                return 0.0;
            }
            c
        });
        if let Some((q, c)) = bad {
            return Err(Error::invalid(
                "power",
                format!("{c} at q = {q}"),
                "a finite power >= 0 at every wavevector",
            ));
        }
        Ok(Self {
            lambda_l: grid.length(),
            grid,
            modes,
        })
    }

    /// A surface from measured heights on `grid` (row-major, `n x n`). `lambda_l` sets the
    /// magnification scale; it defaults to the box size `L`.
    ///
    /// # Errors
    ///
    /// If `grid` is not square (a surface's shells and `lambda_l` are the square grid's),
    /// `heights` is not `n x n` finite values, or `lambda_l` is outside `(0, L]`.
    pub fn from_heights(grid: Grid, heights: &[f64], lambda_l: Option<f64>) -> Result<Self> {
        if !grid.is_square() {
            return Err(Error::invalid(
                "grid",
                format!("{} x {}", grid.rows(), grid.cols()),
                "a square n x n grid (a surface is periodic on a square)",
            ));
        }
        if heights.len() != grid.points() {
            return Err(Error::invalid(
                "heights",
                format!("{} values", heights.len()),
                format!("n^2 = {} values", grid.points()),
            ));
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            let n = grid.n();
            return Err(Error::invalid(
                "heights",
                format!("{} at row {}, column {}", heights[i], i / n, i % n),
                "finite numbers (no NaN or infinity)",
            ));
        }
        let lambda_l = lambda_l.unwrap_or(grid.length());
        if !(lambda_l.is_finite() && lambda_l > 0.0 && lambda_l <= grid.length()) {
            return Err(Error::invalid(
                "lambda_l",
                lambda_l,
                format!("in (0, L = {}]", grid.length()),
            ));
        }
        let fft = Fft2::new(&grid);
        let mut modes = fft.new_spectrum();
        fft.forward(heights, &mut modes);
        Ok(Self {
            grid,
            lambda_l,
            modes,
        })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The long-wavelength cutoff that defines `zeta = |q| / q_l`.
    pub fn lambda_l(&self) -> f64 {
        self.lambda_l
    }

    /// `q_l = 2 pi / lambda_l`.
    pub fn q_l(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.lambda_l
    }

    /// Full-resolution half spectrum `h~(q)`.
    pub fn modes(&self) -> &[Complex64] {
        &self.modes
    }

    /// Modes below this power (relative to the total) are rounding, not roughness: a
    /// height map read from a file has `1e-17`-sized amplitudes on every mode.
    const NEGLIGIBLE: f64 = 1e-24;

    /// The `|h~|^2` below which a mode counts as empty.
    fn floor(&self) -> f64 {
        let total: f64 = self.modes.iter().skip(1).map(|h| h.norm_sqr()).sum();
        total * Self::NEGLIGIBLE
    }

    /// Magnification of the shortest wavelength present (`max |q| / q_l` over non-empty
    /// modes).
    pub fn zeta_max(&self) -> f64 {
        let floor = self.floor();
        let k2 = self
            .modes
            .iter()
            .enumerate()
            .filter(|(_, h)| h.norm_sqr() > floor)
            .map(|(s, _)| self.grid.k2(s))
            .max()
            .unwrap_or(0);
        self.grid.zeta_of_shell(k2, self.lambda_l)
    }

    /// The half spectrum at magnification `zeta`: modes with `|q| <= zeta q_l`, others zero.
    pub fn modes_at(&self, zeta: f64, out: &mut [Complex64]) {
        let limit = self.grid.shell_limit(zeta, self.lambda_l);
        let k2 = self.grid.k2_table();
        out.par_iter_mut()
            .zip(self.modes.par_iter())
            .zip(k2.par_iter())
            .for_each(|((o, h), &k)| {
                *o = if k <= limit {
                    *h
                } else {
                    Complex64::new(0.0, 0.0)
                };
            });
    }

    /// Heights at magnification `zeta` (`f64::INFINITY` for full resolution).
    pub fn heights_at(&self, zeta: f64, fft: &Fft2) -> Vec<f64> {
        let mut spec = fft.new_spectrum();
        self.modes_at(zeta, &mut spec);
        let mut h = vec![0.0; self.grid.points()];
        fft.inverse_in_place(&mut spec, &mut h);
        h
    }

    /// The realization's shell spectrum (for Persson's theory and the statistics).
    pub fn shells(&self) -> ShellSpectrum {
        ShellSpectrum::from_modes(&self.grid, &self.modes, self.lambda_l)
    }

    /// Rms gradient at magnification `zeta`, `sqrt(sum_{|q| <= zeta q_l} q^2 |h~|^2)`.
    pub fn rms_gradient(&self, zeta: f64) -> f64 {
        let limit = self.grid.shell_limit(zeta, self.lambda_l);
        let dq2 = self.grid.dq().powi(2);
        self.modes
            .iter()
            .enumerate()
            .filter(|(s, _)| self.grid.k2(*s) <= limit)
            .map(|(s, h)| self.grid.weight_of(s) * dq2 * self.grid.k2(s) as f64 * h.norm_sqr())
            .sum::<f64>()
            .sqrt()
    }

    /// Distinct shells `k2` holding roughness, in increasing order: the magnification steps
    /// of a sweep that adds every shell one at a time.
    pub fn shell_sequence(&self) -> Vec<u32> {
        let floor = self.floor();
        let mut k2: Vec<u32> = self
            .modes
            .iter()
            .enumerate()
            .filter(|(s, h)| h.norm_sqr() > floor && self.grid.k2(*s) > 0)
            .map(|(s, _)| self.grid.k2(s))
            .collect();
        k2.sort_unstable();
        k2.dedup();
        k2
    }
}

/// The half spectrum of one realization on `grid`: `h~(q) = sqrt(shape(k2)) xi(q)` on the
/// half plane (Nyquist rows and `q = 0` empty), the column `kx = 0` made Hermitian.
fn draw_modes(
    grid: &Grid,
    seed: u64,
    amplitudes: Amplitudes,
    mut shape: impl FnMut(u32) -> f64,
) -> Vec<Complex64> {
    let m = grid.half_cols();
    let mut modes = vec![Complex64::new(0.0, 0.0); grid.modes()];
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for (s, h) in modes.iter_mut().enumerate() {
        let (mx, my) = grid.wavevector(s);
        // The half plane mx > 0, or mx = 0 and my > 0; the other half follows by symmetry.
        if grid.is_nyquist(s) || (mx == 0 && my <= 0) {
            continue;
        }
        let c = shape(grid.k2(s));
        if c == 0.0 {
            continue;
        }
        *h = c.sqrt() * draw(&mut rng, mode_id(mx, my), amplitudes);
    }
    // Column kx = 0: h~(0, -my) = conj h~(0, my).
    let n = grid.n();
    for ky in (n / 2 + 1)..n {
        modes[ky * m] = modes[(n - ky) * m].conj();
    }
    modes
}

/// A unique index of the half-plane wavevector `(mx, my)`, independent of the grid size:
/// Cantor pairing of `mx` with the zig-zag code of `my`.
fn mode_id(mx: i64, my: i64) -> u64 {
    let z = if my >= 0 {
        2 * my as u64
    } else {
        (-2 * my - 1) as u64
    };
    let x = mx as u64;
    (x + z) * (x + z + 1) / 2 + z
}

/// The amplitude `xi` of the mode with index `id`: four 32-bit words of the stream, at a
/// position fixed by `id`, through Box-Muller.
fn draw(rng: &mut ChaCha8Rng, id: u64, kind: Amplitudes) -> Complex64 {
    rng.set_word_pos(4 * id as u128);
    let u1 = unit_open(rng.next_u64());
    let u2 = unit_open(rng.next_u64());
    let phase = 2.0 * std::f64::consts::PI * u2;
    match kind {
        Amplitudes::Gaussian => {
            // |xi|^2 is exponential with mean 1: |xi| = sqrt(-ln u1).
            Complex64::from_polar((-u1.ln()).sqrt(), phase)
        }
        Amplitudes::RandomPhase => Complex64::from_polar(1.0, phase),
    }
}

/// A uniform number in (0, 1] from 53 random bits.
fn unit_open(bits: u64) -> f64 {
    ((bits >> 11) as f64 + 1.0) * (1.0 / (1u64 << 53) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::tolerance::SHELL_SLACK;

    fn params(n: usize, seed: u64) -> SurfaceModel {
        SurfaceModel::new(n, 0.8, n as f64 / 2.0, 4.0, seed)
    }

    #[test]
    fn heights_are_real_with_unit_rms_gradient() {
        let s = Surface::generate(&params(64, 1)).unwrap();
        assert!((s.rms_gradient(f64::INFINITY) - 1.0).abs() < 1e-12);
        // A real field round-trips through the real transform unchanged.
        let fft = Fft2::new(s.grid());
        let h = s.heights_at(f64::INFINITY, &fft);
        let mut back = fft.new_spectrum();
        fft.forward(&h, &mut back);
        for (a, b) in back.iter().zip(s.modes()) {
            assert!((a - b).norm() < 1e-14);
        }
        // Finite-difference gradient approaches g_bar (the spectrum stops at lambda_s = 4).
        let n = 64;
        let mut g2 = 0.0;
        for i in 0..n {
            for j in 0..n {
                let dx = (h[i * n + (j + 1) % n] - h[i * n + (j + n - 1) % n]) / 2.0;
                let dy = (h[((i + 1) % n) * n + j] - h[((i + n - 1) % n) * n + j]) / 2.0;
                g2 += dx * dx + dy * dy;
            }
        }
        let g = (g2 / (n * n) as f64).sqrt();
        assert!(g > 0.6 && g < 1.0, "finite-difference gradient {g}");
    }

    #[test]
    fn a_tabulated_spectrum_draws_the_modes_of_the_model_one() {
        // The self-affine shape given as a table of |q| draws the same realization as the
        // model, up to the overall factor that sets g_bar; with random phases every mode's
        // |h~|^2 is the table's value exactly.
        let mut p = params(32, 7);
        p.amplitudes = Amplitudes::RandomPhase;
        let model = Surface::generate(&p).unwrap();
        let grid = Grid::new(32, 1.0).unwrap();
        let (q_l, q_s) = (p.spectrum().q_l(), p.spectrum().q_s());
        let power = |q: f64| {
            if q >= q_l * (1.0 - SHELL_SLACK) && q <= q_s * (1.0 + SHELL_SLACK) {
                3.0 * (q / q_l).powf(-2.0 * (1.0 + p.hurst))
            } else {
                0.0
            }
        };
        let table = Surface::generate_tabulated(32, &power, 7, Amplitudes::RandomPhase).unwrap();
        let first = table.modes().iter().position(|h| h.norm() > 0.0).unwrap();
        let f = model.modes()[first].norm() / table.modes()[first].norm();
        for (s, (a, b)) in model.modes().iter().zip(table.modes()).enumerate() {
            assert!((a - b * f).norm() < 1e-12, "mode {s}: {a} vs {b}");
            if b.norm() > 0.0 {
                assert!((b.norm_sqr() / power(grid.q(s)) - 1.0).abs() < 1e-12);
            }
        }
        let e = Surface::generate_tabulated(32, &|_| f64::NAN, 7, Amplitudes::RandomPhase)
            .unwrap_err()
            .to_string();
        assert!(e.contains("power"), "{e}");
    }

    #[test]
    fn magnification_only_adds_modes() {
        let s = Surface::generate(&params(64, 2)).unwrap();
        let mut a = vec![Complex64::new(0.0, 0.0); s.grid().modes()];
        let mut b = a.clone();
        s.modes_at(3.0, &mut a);
        s.modes_at(5.5, &mut b);
        for (x, y) in a.iter().zip(&b) {
            if x.norm_sqr() > 0.0 {
                assert_eq!(x, y);
            }
        }
        assert!(s.rms_gradient(3.0) < s.rms_gradient(5.5));
        assert_eq!(s.rms_gradient(0.5), 0.0);
    }

    #[test]
    fn seed_fixes_the_modes_across_grid_sizes() {
        // Same physical surface at twice the resolution: lambda in grid units doubles and
        // the normalisation is the same set of modes, so common modes agree.
        let coarse = Surface::generate(&SurfaceModel::new(32, 0.8, 16.0, 4.0, 5)).unwrap();
        let fine = Surface::generate(&SurfaceModel::new(64, 0.8, 32.0, 8.0, 5)).unwrap();
        let (gc, gf) = (coarse.grid(), fine.grid());
        let mut matched = 0;
        for s in 0..gc.modes() {
            let h = coarse.modes()[s];
            if h.norm_sqr() == 0.0 {
                continue;
            }
            let (mx, my) = gc.wavevector(s);
            let ky = if my < 0 {
                (64 + my) as usize
            } else {
                my as usize
            };
            let t = ky * gf.half_cols() + mx as usize;
            // Heights scale with length: h~ doubles when all lengths double at fixed g_bar.
            assert!((fine.modes()[t] - 2.0 * h).norm() < 1e-12 * h.norm().max(1e-300));
            matched += 1;
        }
        assert!(matched > 50);
    }

    #[test]
    fn shells_partition_the_gradient() {
        let s = Surface::generate(&params(48, 3)).unwrap();
        let shells = s.shells();
        let total: f64 = shells.shells.iter().map(|x| x.q2h2).sum();
        assert!((total - 1.0).abs() < 1e-12);
        for zeta in [1.0, 2.0, 3.7, 6.0] {
            assert!((shells.rms_gradient(zeta) - s.rms_gradient(zeta)).abs() < 1e-12);
        }
        assert_eq!(s.shell_sequence().len(), shells.shells.len());
    }

    #[test]
    fn rejects_non_finite_heights() {
        let g = Grid::new(8, 1.0).unwrap();
        let mut h = vec![0.0; 64];
        h[10] = f64::NAN;
        let e = Surface::from_heights(g, &h, None).unwrap_err().to_string();
        assert!(e.contains("row 1, column 2"), "{e}");
    }
}
