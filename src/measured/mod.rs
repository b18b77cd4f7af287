//! Persson's theory checked on a measured surface: the user's own height maps, read and
//! checked ([`scan`]), their statistics and spectrum ([`psd`]).

pub mod body;
pub mod check;
pub mod page;
pub mod psd;
pub mod scan;
pub mod theory;
