//! The crate's error type.
//!
//! Every message names what was wrong, where, and what is allowed, so that a user can fix
//! the input without reading the code. Non-convergence carries the residual reached: a
//! solver never hands back an unconverged field as if it were a result.

use std::fmt::Display;
use std::path::PathBuf;

/// Result with the crate's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

/// Everything that can go wrong in this crate.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter outside its allowed range.
    #[error("invalid {field} = {value}: must be {allowed}")]
    InvalidInput {
        /// The parameter's name as the user writes it.
        field: String,
        /// The offending value, as text.
        value: String,
        /// The allowed range, in words.
        allowed: String,
    },
    /// A file that could not be used (scene, `.npy`, checkpoint).
    #[error("{path}: {message}")]
    BadFile {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// A solver stopped before reaching its tolerance.
    #[error(
        "{solver} did not converge ({reason}): residual {residual:.3e} > tolerance {tol:.1e} after {iterations} iterations"
    )]
    NotConverged {
        /// Solver name.
        solver: &'static str,
        /// Why it stopped.
        reason: Termination,
        /// Iterations spent.
        iterations: usize,
        /// Residual reached (solver-independent definition, see `contact::Residual`).
        residual: f64,
        /// Requested tolerance.
        tol: f64,
        /// Points in contact (`p > 0`) in the state the residual was taken from, for a
        /// contact solver (`None` elsewhere).
        contact_points: Option<usize>,
    },
    /// A NaN or infinity appeared in a solver's state.
    #[error("{solver}: non-finite value in {what} at iteration {iteration}")]
    NonFinite {
        /// Solver name.
        solver: &'static str,
        /// The quantity that went non-finite.
        what: &'static str,
        /// Iteration where it was detected.
        iteration: usize,
    },
    /// The contact set of a solve emptied: no point carries the load, so the load cannot be
    /// restored by scaling the pressure.
    #[error(
        "{solver}: the contact set emptied at iteration {iteration} (p0 = {p0:.3e}): no point is left to carry the load. \
         Start the solve cold rather than from a distant solution, or raise p0 or refine the grid so that the contact spans more than a few points"
    )]
    LostContact {
        /// Solver name.
        solver: &'static str,
        /// Iteration where the last point left contact.
        iteration: usize,
        /// The mean pressure of the problem.
        p0: f64,
    },
    /// A solve stopped from outside (its monitor answered stop): cancelled, or over its
    /// time budget. Not a failure of the method: the solver is left ready for its next
    /// solve, and the stop passes through sweeps and load searches to their callers.
    #[error(
        "{solver} stopped ({reason}) at iteration {iteration}, residual estimate {residual:.3e}"
    )]
    Stopped {
        /// Solver name.
        solver: &'static str,
        /// Why it was stopped.
        reason: StopReason,
        /// The last progress the monitor saw: its iteration...
        iteration: usize,
        /// ...and the method's residual estimate there.
        residual: f64,
    },
    /// Root finding on the load failed (for example, a target contact area not reachable).
    #[error("load search: {0}")]
    LoadSearch(String),
    /// An I/O failure, with the path involved.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
}

/// Why an iterative solve stopped (after argmin's termination reasons).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// The residual fell below the tolerance.
    Converged,
    /// The iteration budget ran out before the residual reached the tolerance.
    BudgetExhausted,
    /// The residual stopped improving at its rounding floor, above the tolerance.
    Stalled,
    /// A NaN or an infinity appeared in the solver's state.
    NonFinite,
    /// No point was left in contact to carry the load.
    LostContact,
    /// Stopped from outside: cancelled (Ctrl-C in Python) ([`StopReason::Cancelled`]).
    Cancelled,
    /// Stopped from outside: over its time budget ([`StopReason::OutOfTime`]).
    OutOfTime,
}

/// Why a solve was stopped from outside: what a monitor answers when it asks a running
/// solve to stop (`ControlFlow::Break(reason)`, see `engine::solver::executor`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The caller cancelled it (Ctrl-C in Python, a closed sweep).
    Cancelled,
    /// Its time budget ran out.
    OutOfTime,
}

impl From<StopReason> for Termination {
    fn from(reason: StopReason) -> Self {
        match reason {
            StopReason::Cancelled => Termination::Cancelled,
            StopReason::OutOfTime => Termination::OutOfTime,
        }
    }
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        Termination::from(*self).fmt(f)
    }
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Termination::Converged => "converged",
            Termination::BudgetExhausted => "iteration budget exhausted",
            Termination::Stalled => "stalled at the rounding floor",
            Termination::NonFinite => "non-finite value",
            Termination::LostContact => "contact set emptied",
            Termination::Cancelled => "cancelled",
            Termination::OutOfTime => "over its time budget",
        })
    }
}

impl Error {
    /// Why the solve behind this error stopped, for errors that come from an iterative
    /// solve ([`Error::NotConverged`], [`Error::NonFinite`], [`Error::LostContact`],
    /// [`Error::Stopped`]).
    pub fn termination(&self) -> Option<Termination> {
        match self {
            Error::NotConverged { reason, .. } => Some(*reason),
            Error::Stopped { reason, .. } => Some((*reason).into()),
            Error::NonFinite { .. } => Some(Termination::NonFinite),
            Error::LostContact { .. } => Some(Termination::LostContact),
            _ => None,
        }
    }

    /// Why the solve behind this error was stopped from outside, for an
    /// [`Error::Stopped`].
    pub fn stopped(&self) -> Option<StopReason> {
        match self {
            Error::Stopped { reason, .. } => Some(*reason),
            _ => None,
        }
    }

    /// An [`Error::InvalidInput`] for `field = value`, allowed `allowed`.
    pub fn invalid(field: &str, value: impl Display, allowed: impl Into<String>) -> Self {
        Error::InvalidInput {
            field: field.to_string(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// An [`Error::BadFile`] for `path`.
    pub fn bad_file(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Error::BadFile {
            path: path.into(),
            message: message.into(),
        }
    }

    /// The same error with an [`Error::InvalidInput`]'s field renamed to `field` (for
    /// example to the command-line flag or the scene key the value came from); other
    /// errors are returned unchanged.
    pub fn with_field(self, field: &str) -> Self {
        match self {
            Error::InvalidInput { value, allowed, .. } => Error::InvalidInput {
                field: field.to_string(),
                value,
                allowed,
            },
            other => other,
        }
    }

    /// The same error with an [`Error::InvalidInput`]'s field placed inside the table
    /// `table` (`hurst` becomes `reference.hurst`); other errors are returned unchanged.
    pub fn within(self, table: &str) -> Self {
        match self {
            Error::InvalidInput {
                field,
                value,
                allowed,
            } => Error::InvalidInput {
                field: format!("{table}.{field}"),
                value,
                allowed,
            },
            other => other,
        }
    }

    /// An [`Error::Io`] for `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// Checks `lo < value < hi` (open interval); names the field on failure.
pub fn check_open(field: &str, value: f64, lo: f64, hi: f64) -> Result<()> {
    if value.is_finite() && value > lo && value < hi {
        Ok(())
    } else {
        Err(Error::invalid(field, value, format!("in ({lo}, {hi})")))
    }
}

/// Checks that `name` can prefix a statistic's key: letters, digits and '_', not empty.
pub fn check_key_name(field: &str, name: &str) -> Result<()> {
    let ok = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            name,
            "letters, digits and '_', not empty",
        ))
    }
}

/// Checks that a list of realization seeds is not empty and names each seed once: a
/// repeated seed would count one realization twice and shrink the error bar for nothing.
pub fn check_seeds(seeds: &[u64]) -> Result<()> {
    if seeds.is_empty() {
        return Err(Error::invalid("seeds", "[]", "at least one seed"));
    }
    for (k, s) in seeds.iter().enumerate() {
        if seeds[..k].contains(s) {
            return Err(Error::invalid(
                "seeds",
                format!("{seeds:?}"),
                format!("distinct seeds ({s} appears twice)"),
            ));
        }
    }
    Ok(())
}

/// Checks that a list of values (loads, contact areas, parameters of a study) names each
/// value once: a repeated one would be run and counted twice.
///
/// # Errors
///
/// If a value appears twice; the error names `field` and the value.
pub fn check_once(field: &str, values: &[f64]) -> Result<()> {
    match (1..values.len()).find(|&k| values[..k].contains(&values[k])) {
        Some(k) => Err(Error::invalid(
            field,
            format!("{values:?}"),
            format!("each value once ({} appears twice)", values[k]),
        )),
        None => Ok(()),
    }
}

/// Checks `value > 0` and finite; names the field on failure.
pub fn check_positive(field: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, value, "a finite number > 0"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_errors_name_why_they_stopped() {
        let e = Error::NotConverged {
            solver: "cg",
            reason: Termination::Stalled,
            iterations: 12,
            residual: 3e-13,
            tol: 1e-14,
            contact_points: Some(3),
        };
        assert_eq!(e.termination(), Some(Termination::Stalled));
        assert!(
            e.to_string().contains("stalled at the rounding floor"),
            "{e}"
        );
        let e = Error::NonFinite {
            solver: "gfmd",
            what: "stress",
            iteration: 4,
        };
        assert_eq!(e.termination(), Some(Termination::NonFinite));
        let e = Error::LostContact {
            solver: "cg",
            iteration: 9,
            p0: 1e-5,
        };
        assert_eq!(e.termination(), Some(Termination::LostContact));
        let text = e.to_string();
        assert!(text.contains("contact set emptied at iteration 9"), "{e}");
        assert!(!text.contains("non-finite"), "{e}");
        assert_eq!(Error::invalid("n", 3, "> 4").termination(), None);
        let e = Error::Stopped {
            solver: "fire",
            reason: StopReason::OutOfTime,
            iteration: 7,
            residual: 2e-3,
        };
        assert_eq!(e.termination(), Some(Termination::OutOfTime));
        assert_eq!(e.stopped(), Some(StopReason::OutOfTime));
        assert!(
            e.to_string()
                .contains("stopped (over its time budget) at iteration 7"),
            "{e}"
        );
        assert_eq!(Error::invalid("n", 3, "> 4").stopped(), None);
    }
}
