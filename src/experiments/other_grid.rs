//! The headline's surface on another grid, declared once.
//!
//! A study that runs the headline's scene on grids of its own (the re-entry tolerance
//! study's grids, the total energy's finer resolutions) and each job of such a study name
//! the grid by the same three keys, the Hurst exponent staying the headline's:
//!
//! ```toml
//! n = 256          # points per side
//! lambda_l = 128   # long-wavelength cutoff (grid units), at most n
//! lambda_s = 4     # short-wavelength cutoff, at least 2 grid spacings
//! ```
//!
//! `other_grid!` declares a struct with these fields followed by its own, with serde
//! derives that refuse unknown keys, and gives it the scene on that grid ([`Base`] at the
//! headline's Hurst exponent) and the grid in words. The fields are written into the
//! struct, not flattened, for the reason [`super::scene`] gives; their order is the order
//! in which a job serialises, and so part of its key.
//!
//! [`Base`]: super::scene::Base

/// Declares a struct on another grid: the fields `n`, `lambda_l` and `lambda_s` followed by
/// its own, with serde derives that refuse unknown keys, `base(hurst, seeds, tol)` (the
/// scene on this grid) and `grid_label()` (the grid in words).
macro_rules! other_grid {
    ($($item:tt)*) => {
        $crate::experiments::scene::fields_first! {
            [
                /// Points per side.
                n: usize,
                /// Long-wavelength cutoff (grid units).
                lambda_l: f64,
                /// Short-wavelength cutoff (grid units).
                lambda_s: f64,
            ]
            impl {
                /// The scene on this grid: the surface model of Hurst exponent `hurst` over
                /// `seeds`, solved to `tol`.
                pub fn base<'a>(
                    &self,
                    hurst: f64,
                    seeds: &'a [u64],
                    tol: f64,
                ) -> $crate::experiments::scene::Base<'a> {
                    let (n, lambda_l, lambda_s) = (self.n, self.lambda_l, self.lambda_s);
                    $crate::experiments::scene::Base::new(n, hurst, lambda_l, lambda_s, seeds, tol)
                }

                /// The grid in words: `"256^2, lambda_l = 128, lambda_s = 4"`.
                pub fn grid_label(&self) -> String {
                    format!(
                        "{}^2, lambda_l = {}, lambda_s = {}",
                        self.n, self.lambda_l, self.lambda_s
                    )
                }
            }
            $($item)*
        }
    };
}
pub(crate) use other_grid;
