//! The free-boundary elastic half-space: the surface displacement under a uniformly loaded
//! pixel, and the stiffness it gives on a doubled, zero-padded grid.
//!
//! A measured height map is not periodic: its images must not press on it. The surface
//! displacement of a frictionless half-space under a pressure `p(r')` is Boussinesq's
//! solution (Johnson, *Contact Mechanics*, 1985, eq. 3.20),
//!
//! ```text
//!     u(r) = 1/(pi E*) integral p(r') / |r - r'| d^2 r',
//! ```
//!
//! whose Fourier transform, `u~ = 2 p~ / (q E*)`, is the periodic kernel of
//! [`crate::engine::elastic`]. For a pressure that is uniform on each pixel of side `a`,
//! the integral over one pixel has a closed form (Love, Phil. Trans. R. Soc. A 228, 377
//! (1929); Johnson eq. 3.25): with `F(s, t) = s asinh(t / |s|) + t asinh(s / |t|)`, an
//! antiderivative of `1 / sqrt(s^2 + t^2)` in `s` and `t`,
//!
//! ```text
//!     G(x, y) = 1/(pi E*) [F(x+h, y+h) - F(x-h, y+h) - F(x+h, y-h) + F(x-h, y-h)],  h = a/2,
//! ```
//!
//! the displacement at `(x, y)` under a unit pressure on the pixel centred at the origin;
//! at the centre `G(0, 0) = 4 a ln(1 + sqrt 2) / (pi E*)`, and far away
//! `G -> a^2 / (pi E* r)`.
//!
//! On a grid of `M_y x M_x = 2R x 2C` points whose pressure vanishes outside an `R x C`
//! window, the sum `u(r) = sum_r' G(r - r') p(r')` over the window needs `G` at distances
//! below `R` pixels along y and `C` along x only, so the periodic convolution on the
//! doubled grid with `G` sampled at the signed distances `(j - M_x [j >= C]) a` along x and
//! `(i - M_y [i >= R]) a` along y is exactly the free-boundary sum: no image reaches the
//! window along either axis (Hockney's method; Liu, Wang & Liu, Wear 243, 101 (2000), for
//! contact mechanics). In the crate's Fourier convention (`f~ = M^-2 sum f e^(-i q.r)`,
//! `M^2 = M_y M_x` points) the convolution is `u~(q) = M^2 G~(q) p~(q)`, so the stiffness
//! of the padded half-space is `K(q) = 1 / (M^2 G~(q))`, mode by mode, in place of the
//! periodic `q E* / 2`. The `q = 0` mode is the rigid shift, free in a contact problem at
//! given load: its stiffness is 0, as in the periodic case. A square window (`R = C`) is
//! the square doubled grid `M = 2N`.

use crate::engine::fft::Fft2;
use crate::engine::grid::Grid;
use crate::error::{check_positive, Error, Result};

/// `s asinh(t / |s|)`, with its limit 0 at `s = 0`.
fn term(s: f64, t: f64) -> f64 {
    if s == 0.0 {
        0.0
    } else {
        s * (t / s.abs()).asinh()
    }
}

/// `F(s, t) = s asinh(t/|s|) + t asinh(s/|t|)`: `d^2 F / ds dt = 1 / sqrt(s^2 + t^2)`.
fn antiderivative(s: f64, t: f64) -> f64 {
    term(s, t) + term(t, s)
}

/// The surface displacement at `(x, y)` under a unit pressure uniform on the square pixel
/// of side `a` centred at the origin, on a half-space of contact modulus `e_star`.
pub fn pixel_displacement(x: f64, y: f64, a: f64, e_star: f64) -> f64 {
    let h = 0.5 * a;
    let f = antiderivative;
    (f(x + h, y + h) - f(x - h, y + h) - f(x + h, y - h) + f(x - h, y - h))
        / (std::f64::consts::PI * e_star)
}

/// The response field of a unit pressure on pixel `(0, 0)` of a doubled grid of
/// `rows x cols` points (`2R x 2C`, spacing `a`): `G` at the signed distances of the
/// periodic layout (row `i` at `y = (i - rows [i >= rows/2]) a`, column `j` at
/// `x = (j - cols [j >= cols/2]) a`), row-major.
pub fn padded_response(rows: usize, cols: usize, a: f64, e_star: f64) -> Vec<f64> {
    let signed = |i: usize, m: usize| {
        let k = crate::engine::grid::signed_index(i, m);
        k as f64 * a
    };
    let mut g = vec![0.0; rows * cols];
    for (i, row) in g.chunks_mut(cols).enumerate() {
        let y = signed(i, rows);
        for (j, v) in row.iter_mut().enumerate() {
            *v = pixel_displacement(signed(j, cols), y, a, e_star);
        }
    }
    g
}

/// The stiffness `K(q) = 1 / (M^2 G~(q))` of the free-boundary half-space over the half
/// spectrum of the doubled grid `padded` (0 at `q = 0`, the free rigid shift), for the
/// window of `padded.rows() / 2 x padded.cols() / 2` points.
///
/// # Errors
///
/// If `e_star` is not positive, a side of `padded` is odd, or the sampled response is not
/// positive definite (it is for every grid tried; the check guards the division).
pub fn padded_stiffness(padded: &Grid, fft: &Fft2, e_star: f64) -> Result<Vec<f64>> {
    check_positive("e_star", e_star)?;
    let (rows, cols) = (padded.rows(), padded.cols());
    for (name, side) in [("padded grid rows", rows), ("padded grid cols", cols)] {
        if side % 2 != 0 {
            return Err(Error::invalid(
                name,
                side,
                "an even number of points (twice the window)",
            ));
        }
    }
    let response = padded_response(rows, cols, padded.spacing(), e_star);
    let mut spec = fft.new_spectrum();
    fft.forward(&response, &mut spec);
    let scale = (rows * cols) as f64;
    let mut table = Vec::with_capacity(spec.len());
    for (s, g) in spec.iter().enumerate() {
        if s == 0 {
            table.push(0.0);
            continue;
        }
        let g = scale * g.re;
        if !(g > 0.0 && g.is_finite()) {
            return Err(Error::invalid(
                "free-boundary kernel",
                format!("M^2 G~ = {g:e} at mode {s}"),
                "a positive response at every wavevector",
            ));
        }
        table.push(1.0 / g);
    }
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pixel_response_has_its_closed_form_centre_and_far_field() {
        let (a, e) = (1.0, 2.0);
        let centre = 4.0 * a * (1.0 + 2f64.sqrt()).ln() / (std::f64::consts::PI * e);
        assert!((pixel_displacement(0.0, 0.0, a, e) - centre).abs() < 1e-15);
        for r in [50.0f64, 200.0] {
            let far = a * a / (std::f64::consts::PI * e * r);
            let (x, y) = (0.6 * r, 0.8 * r);
            let g = pixel_displacement(x, y, a, e);
            assert!((g / far - 1.0).abs() < 1e-4, "r = {r}: {g} vs {far}");
        }
        // Symmetric in x and y and in their signs.
        let g = pixel_displacement(1.7, -0.4, a, e);
        for (x, y) in [(-1.7, -0.4), (1.7, 0.4), (-0.4, 1.7), (0.4, -1.7)] {
            assert!((pixel_displacement(x, y, a, e) - g).abs() < 1e-15);
        }
    }

    #[test]
    fn the_pixel_response_is_the_integral_of_one_over_r() {
        // Midpoint quadrature of 1/(pi E* r) over the pixel, seen from a point one and a
        // half pixels away (no singularity inside).
        let (x, y, a) = (1.5, 0.5, 1.0);
        let k = 400;
        let d = a / k as f64;
        let mut sum = 0.0;
        for i in 0..k {
            for j in 0..k {
                let xs = -0.5 * a + (i as f64 + 0.5) * d;
                let ys = -0.5 * a + (j as f64 + 0.5) * d;
                sum += d * d / ((x - xs).powi(2) + (y - ys).powi(2)).sqrt();
            }
        }
        let quadrature = sum / std::f64::consts::PI;
        let g = pixel_displacement(x, y, a, 1.0);
        assert!((g / quadrature - 1.0).abs() < 1e-6, "{g} vs {quadrature}");
    }

    #[test]
    fn the_padded_convolution_is_the_free_boundary_sum() {
        // A pressure on an R x C window of a 2R x 2C grid: the FFT convolution with the
        // padded stiffness's inverse equals the direct sum over the window, with no image,
        // on a square window and on rectangles either way round.
        let e = 1.0;
        for (r, c) in [(6usize, 6usize), (4, 7), (7, 4)] {
            let (rows, cols) = (2 * r, 2 * c);
            let grid = Grid::rectangle(rows, cols, 1.0).unwrap();
            let fft = Fft2::new(&grid);
            let table = padded_stiffness(&grid, &fft, e).unwrap();
            let mut p = vec![0.0; rows * cols];
            for i in 0..r {
                for j in 0..c {
                    p[i * cols + j] = 1.0 + ((i * 7 + j * 3) % 5) as f64;
                }
            }
            let mut spec = fft.new_spectrum();
            fft.forward(&p, &mut spec);
            for (s, v) in spec.iter_mut().enumerate() {
                *v = if s == 0 {
                    num_complex_zero()
                } else {
                    *v / table[s]
                };
            }
            let mut u = vec![0.0; rows * cols];
            fft.inverse(&spec, &mut u, &mut Vec::new());
            // The FFT result lacks the q = 0 part (the free rigid shift): compare differences.
            let direct = |i: usize, j: usize| -> f64 {
                let mut sum = 0.0;
                for k in 0..r {
                    for l in 0..c {
                        let (dx, dy) = (j as f64 - l as f64, i as f64 - k as f64);
                        sum += pixel_displacement(dx, dy, 1.0, e) * p[k * cols + l];
                    }
                }
                sum
            };
            let (u0, d0) = (u[0], direct(0, 0));
            for i in 0..r {
                for j in 0..c {
                    let du = u[i * cols + j] - u0;
                    let dd = direct(i, j) - d0;
                    assert!(
                        (du - dd).abs() < 1e-12 * d0,
                        "{r} x {c}: ({i}, {j}): {du} vs {dd}"
                    );
                }
            }
        }
    }

    #[test]
    fn an_odd_padded_side_is_refused_naming_it() {
        let grid = Grid::rectangle(12, 9, 1.0).unwrap();
        let fft = Fft2::new(&grid);
        let e = padded_stiffness(&grid, &fft, 1.0).unwrap_err().to_string();
        assert!(e.contains("padded grid cols"), "{e}");
    }

    fn num_complex_zero() -> rustfft::num_complex::Complex64 {
        rustfft::num_complex::Complex64::new(0.0, 0.0)
    }

    #[test]
    fn the_padded_stiffness_is_positive_and_near_the_periodic_one_between_the_extremes() {
        // Between the box's own scale and the pixel's, the padded kernel is close to the
        // periodic q E*/2.
        let grid = Grid::new(64, 1.0).unwrap();
        let fft = Fft2::new(&grid);
        let table = padded_stiffness(&grid, &fft, 1.0).unwrap();
        assert!(table[1..].iter().all(|&k| k > 0.0));
        let s = grid.half_cols() * 3; // the mode (kx, ky) = (0, 3)
        let periodic = 0.5 * grid.q(s);
        assert!(
            (table[s] / periodic - 1.0).abs() < 0.1,
            "{} vs {periodic}",
            table[s]
        );
    }
}
