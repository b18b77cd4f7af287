//! Persson's theory checked on a measured surface: the user's own height maps, read and
//! checked ([`scan`]), their missing points refused or filled ([`fill`]), their units
//! ([`units`]), statistics and spectrum ([`psd`]), the contact problem along a load curve
//! ([`body`]), Persson's predictions ([`theory`]), the re-entry share over magnification
//! ([`reentry`]), spikes and outliers found before the solves ([`spikes`]), the words
//! where the theory does not apply ([`warnings`]), the check
//! ([`check`]: its [`options`], its [`curves`], its [`findings`] and how they are drawn from
//! the measurements, `conclude`) and its page ([`mod@page`], its [`figures`]); line scans,
//! by way of the isotropic surface they imply ([`mod@line`]); one surface measured at
//! several scales, its scans' spectra stitched into one ([`stitch`]) and each areal scan
//! set against Persson on its band and on the whole surface ([`scales`]). The load curves and the
//! re-entry climb run on the engine's sweeps ([`crate::engine::load_curve`],
//! [`crate::engine::climb`]).

pub mod body;
pub mod check;
mod conclude;
pub mod curves;
pub mod cutoff;
pub mod figures;
pub mod fill;
pub mod findings;
pub mod line;
pub mod options;
pub mod page;
pub mod pixel;
pub mod psd;
pub mod reentry;
mod resolved;
pub mod scales;
pub mod scan;
pub mod spikes;
pub mod stitch;
pub mod theory;
pub mod units;
pub mod warnings;
