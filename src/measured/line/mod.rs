//! Line scans: Persson's theory checked on the profiles of a stylus profilometer (or any
//! one-dimensional trace), by way of the isotropic surface they imply.
//!
//! A contact area needs a surface; a profile gives only its spectrum along one direction.
//! Under isotropy that is enough: the profiles' spectrum ([`spectrum`]) is converted to
//! the surface's by the Abel transform ([`abel`]), Persson's theory is evaluated on the
//! converted spectrum, and the contact is simulated on isotropic 2D surfaces synthesized
//! with it (random phases, several seeds: [`synthesis`]), never on the measured profile.
//! Which inputs are line scans ([`profiles`]), and a profile at non-uniform positions (an
//! x-y export) resampled onto even spacing ([`resample`]); the check and its warnings
//! ([`check`]); its page ([`page`]).

pub mod abel;
pub mod check;
pub mod page;
pub mod profiles;
pub mod resample;
pub mod spectrum;
pub mod synthesis;
