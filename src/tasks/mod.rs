//! The tasks a user asks for, one function each, called by both front ends: the command
//! line (`src/commands/`) and the Python package (`python/`). What a task computes, how it
//! checks its input and what it reports is written here once, so that `persson-check solve`
//! and `persson_check.solve` cannot drift apart; a front end only reads its arguments,
//! shows progress and writes or returns the result.
//!
//! | task | here | command line | Python |
//! |---|---|---|---|
//! | a self-affine surface | [`surface::generate`] | `surface` | `surface` |
//! | heights handed over as a field | [`surface::from_heights`] | `solve --heights` | `solve`, `sweep`, `theory` |
//! | one contact problem and its summary | [`solve::SolveArgs`] (checked, settled, run), [`solve::SolveSummary`] | `solve` (`summary.json`) | `solve`, `Solution.summary()` |
//! | a magnification sweep | [`solve::SolveArgs`], [`sweep::steps`], [`sweep::with_run`] | | `sweep` |
//! | Persson's theory on a surface's spectrum | [`theory::theory`] | | `theory` |
//! | the validations, their plan and merge | [`validations`] | `validate [--plan] [--merge]` | `validate`, `plan`, `merge` |
//! | Persson checked on measured height maps | [`check::check_surface`] | `check-surface` | `check_surface` |
//! | one surface measured at several scales | [`scales::check_scales`] | `check-surface --scales` | `check_surface(..., scales=True)` |
//! | the parsers: solver names, the load, ranges | [`parse`] | flags | keywords |
//! | stored job results recomputed and compared | [`audit::audit`] | `audit` | |
//!
//! # Defaults and checks, once
//!
//! A task's defaults are written once, in the library ([`SolveOptions::DEFAULT_TOL`],
//! [`SolveOptions::DEFAULT_MAX_ITER`], [`SolverKind::default`]); a front end leaves a value
//! it was not given as `None` (Python's wrappers show the defaults, read from the native
//! module). A request checks the values given once, before any work.
//!
//! # Names in messages
//!
//! Errors name the parameter as the user wrote it: the command line as a flag
//! (`invalid --p0 = -1: must be a finite number > 0`), Python as a keyword (`invalid p0 =
//! -1: ...`). A task takes a [`Spelling`] ([`Flags`] or [`Keywords`]) and names its
//! parameters through it; everything else in a message is the same in both.

pub mod audit;
pub mod check;
pub mod parse;
pub mod scales;
pub mod solve;
pub mod surface;
pub mod sweep;
pub mod theory;
pub mod validations;

use std::path::Path;

/// The solvers by name and their options (with the defaults of `tol` and `max_iter`), for
/// a front end that names them.
pub use crate::engine::solver::{SolveOptions, SolverKind};

use crate::error::{Error, Result};

/// How a front end writes a parameter in its messages.
pub trait Spelling {
    /// The parameter the library calls `key` (`contact_area`) as the user writes it.
    fn name(&self, key: &str) -> String;

    /// `key` given the value `value`, as the user would write it (`--p0 P`, `p0=P`).
    fn given(&self, key: &str, value: &str) -> String;

    /// `e` with the parameter it names written as the user writes it (other errors are
    /// returned unchanged).
    fn rename(&self, e: Error) -> Error {
        match &e {
            Error::InvalidInput { field, .. } => {
                let name = self.name(field);
                e.with_field(&name)
            }
            _ => e,
        }
    }
}

/// Python's spelling: a keyword is the library's name (`contact_area`), given as `p0=P`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Keywords;

impl Spelling for Keywords {
    fn name(&self, key: &str) -> String {
        key.to_string()
    }

    fn given(&self, key: &str, value: &str) -> String {
        format!("{key}={value}")
    }
}

/// The command line's spelling: `contact_area` is the flag `--contact-area`, given as
/// `--contact-area A`; `renamed` lists the keys read from another flag or scene key
/// (`solve --heights` reads `lambda_l` from `--file-lambda-l`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Flags<'a> {
    /// `(key, name)` pairs that replace the rule `--key-with-dashes`.
    pub renamed: &'a [(&'a str, &'a str)],
}

impl Spelling for Flags<'_> {
    fn name(&self, key: &str) -> String {
        match self.renamed.iter().find(|(k, _)| *k == key) {
            Some((_, name)) => name.to_string(),
            None => format!("--{}", key.replace('_', "-")),
        }
    }

    fn given(&self, key: &str, value: &str) -> String {
        format!("{} {value}", self.name(key))
    }
}

/// Checks, before any work, that `out` can become a folder (it is one, or does not exist
/// yet).
///
/// # Errors
///
/// If `out` exists and is not a folder.
pub fn check_out_dir(out: &Path, s: &dyn Spelling) -> Result<()> {
    if out.exists() && !out.is_dir() {
        return Err(Error::invalid(
            &s.name("out"),
            out.display(),
            "a folder (this path exists and is not one)",
        ));
    }
    Ok(())
}

/// Checks, before any work, that `out` can become a file (it is one, or does not exist
/// yet).
///
/// # Errors
///
/// If `out` is a folder.
pub fn check_out_file(out: &Path, s: &dyn Spelling) -> Result<()> {
    if out.is_dir() {
        return Err(Error::invalid(
            &s.name("out"),
            out.display(),
            "a file (this path is a folder)",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_and_keywords_name_a_parameter_as_the_user_writes_it() {
        let flags = Flags {
            renamed: &[("lambda_l", "--file-lambda-l")],
        };
        assert_eq!(flags.name("contact_area"), "--contact-area");
        assert_eq!(flags.name("lambda_l"), "--file-lambda-l");
        assert_eq!(flags.given("p0", "P"), "--p0 P");
        assert_eq!(Keywords.name("contact_area"), "contact_area");
        assert_eq!(Keywords.given("p0", "P"), "p0=P");
        let e = flags.rename(Error::invalid("max_iter", 0, ">= 1"));
        assert_eq!(e.to_string(), "invalid --max-iter = 0: must be >= 1");
        let e = Keywords.rename(Error::invalid("max_iter", 0, ">= 1"));
        assert_eq!(e.to_string(), "invalid max_iter = 0: must be >= 1");
    }
}
