//! The load that gives a target relative contact area ([`crate::conventions`], section 3).
//!
//! Validations state their load as a contact area at a given magnification, because
//! `p~0 = p0 / (E* g_bar(zeta))` changes with `zeta` at fixed `p0` (paper section 3.1). The
//! contact area `a_r(p0)` grows monotonically with `p0`, so `p0` is found by bracketing and
//! then regula falsi (Illinois variant) on `(ln p0, a_r)`, every solve warm-started from the
//! previous one. On a grid `a_r` moves in steps of `1/N^2`, so the search accepts
//! `|a_r - target| <= max(rel_tol min(target, 1 - target), 1.5 / N^2)`.
//!
//! The first guess is Persson's `a_r = erf(p0 / (sqrt2 Dp_tot))` with
//! `Dp_tot = E* g_bar / 2` (paper eq. pressureDistOri), inverted.

use serde::{Deserialize, Serialize};

use crate::engine::contact::{ContactProblem, ContactSolution, Model};
use crate::engine::solver::{SolveOptions, Solver, Start};
use crate::error::{check_open, Error, Result};

/// How closely the contact area must match its target.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AreaSearch {
    /// Relative tolerance on `min(a_r, 1 - a_r)`.
    pub rel_tol: f64,
    /// Largest number of solves.
    pub max_solves: usize,
}

impl Default for AreaSearch {
    fn default() -> Self {
        Self {
            rel_tol: 2e-3,
            max_solves: 60,
        }
    }
}

/// The relative tolerance of a contact area held over a step of magnification (a step
/// at fixed contact area): 1e-5 of it, or the search's floor of 1.5 grid points where that
/// is coarser. A step of the paper's size at fixed load changes `a_r` by some 2e-3 of it
/// (4096^2, a_r = 0.14, zeta 128 -> 129.5: 0.035% of A0), so a load set to the usual 2e-3
/// would leave such a step at fixed area indistinguishable from one at fixed load.
pub const HELD_AREA_REL_TOL: f64 = 1e-5;

impl AreaSearch {
    /// The search of a contact area held over a step ([`HELD_AREA_REL_TOL`]).
    pub fn held() -> Self {
        Self {
            rel_tol: HELD_AREA_REL_TOL,
            ..Self::default()
        }
    }
}

/// Persson's estimate of the load for contact area `a_r` on a surface of rms gradient
/// `g_bar`: `p0 = sqrt2 (E* g_bar / 2) erfinv(a_r)`.
pub fn persson_load_guess(a_r: f64, g_bar: f64, e_star: f64) -> f64 {
    std::f64::consts::SQRT_2 * 0.5 * e_star * g_bar * statrs::function::erf::erf_inv(a_r)
}

/// What to aim for: a contact area, and where to start looking for its load.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AreaTarget {
    /// Target relative contact area, in (0, 1).
    pub contact_area: f64,
    /// First load to try (see [`persson_load_guess`]).
    pub p0_guess: f64,
}

/// A solution at the load that gives `target` contact area, with the number of solves.
pub struct AreaSolution {
    /// The solution at the accepted load.
    pub solution: ContactSolution,
    /// Solves used by the search.
    pub solves: usize,
}

/// Finds `p0` such that the contact area on `heights` is `target.contact_area`, starting
/// from the load `target.p0_guess` (and from `start`'s fields).
///
/// # Errors
///
/// If the target area is outside (0, 1) or the first load is not positive
/// ([`Error::InvalidInput`]), a solve fails or is stopped (its error, [`Error::Stopped`]
/// passed on as it is), or the search ends without
/// bracketing the area or within its budget of solves ([`Error::LoadSearch`]).
pub fn solve_for_area(
    solver: &mut dyn Solver,
    model: &Model,
    heights: &[f64],
    target: AreaTarget,
    start: Start,
    opts: &SolveOptions,
    search: &AreaSearch,
) -> Result<AreaSolution> {
    let AreaTarget {
        contact_area: target,
        p0_guess,
    } = target;
    check_open("contact_area", target, 0.0, 1.0)?;
    crate::error::check_positive("p0_guess", p0_guess)?;
    let n2 = model.grid.points() as f64;
    let accept = (search.rel_tol * target.min(1.0 - target)).max(1.5 / n2);
    let solves = std::cell::Cell::new(0usize);
    let mut solve_at = |p0: f64, start: Start| -> Result<ContactSolution> {
        solves.set(solves.get() + 1);
        let problem = ContactProblem::new(model, heights, p0)?;
        solver.solve(&problem, start, opts)
    };
    let (lo, hi) = match bracket(&mut solve_at, p0_guess.ln(), target, accept, start)? {
        Bracket::Matched(solution) => {
            return Ok(AreaSolution {
                solution,
                solves: solves.get(),
            })
        }
        Bracket::Between(lo, hi) => (lo, hi),
    };
    let solution = illinois(&mut solve_at, lo, hi, target, accept, search.max_solves)?;
    Ok(AreaSolution {
        solution,
        solves: solves.get(),
    })
}

/// A solve at one load, as the search calls it: the load `p0` and where to start.
type SolveAt<'s> = dyn FnMut(f64, Start) -> Result<ContactSolution> + 's;

/// One point of the search: `x = ln p0`, its solution, and `f = a_r - target`.
struct Probe {
    x: f64,
    solution: ContactSolution,
    f: f64,
}

/// What the bracketing found: a load whose contact area is accepted, or two loads whose
/// contact areas lie on either side of the target.
enum Bracket {
    Matched(ContactSolution),
    Between(Probe, Probe),
}

/// Brackets the target in `x = ln p0`, `f = a_r - target`: from `x0`, steps of doubling
/// length (from 0.5) towards the target until `f` changes sign, each solve warm-started
/// from the last.
fn bracket(
    solve_at: &mut SolveAt,
    mut x0: f64,
    target: f64,
    accept: f64,
    start: Start,
) -> Result<Bracket> {
    let mut s0 = solve_at(x0.exp(), start)?;
    let mut f0 = s0.contact_area() - target;
    if f0.abs() <= accept {
        return Ok(Bracket::Matched(s0));
    }
    let mut step = if f0 < 0.0 { 0.5 } else { -0.5 };
    loop {
        let x1 = x0 + step;
        let s1 = solve_at(x1.exp(), Start::Warm(&s0))?;
        let f1 = s1.contact_area() - target;
        if f1.abs() <= accept {
            return Ok(Bracket::Matched(s1));
        }
        if f1.signum() != f0.signum() {
            let lo = Probe {
                x: x0,
                solution: s0,
                f: f0,
            };
            let hi = Probe {
                x: x1,
                solution: s1,
                f: f1,
            };
            return Ok(Bracket::Between(lo, hi));
        }
        x0 = x1;
        s0 = s1;
        f0 = f1;
        step *= 2.0;
        if step.abs() > 60.0 {
            return Err(Error::LoadSearch(format!(
                "no load gives contact area {target} (reached {:.4e} at p0 = {:.3e})",
                f1 + target,
                x1.exp()
            )));
        }
    }
}

/// Illinois regula falsi inside the bracket `[lo, hi]`, each solve warm-started from the
/// nearer end, within `max_solves` solves.
fn illinois(
    solve_at: &mut SolveAt,
    lo: Probe,
    hi: Probe,
    target: f64,
    accept: f64,
    max_solves: usize,
) -> Result<ContactSolution> {
    let Probe {
        x: mut x0,
        solution: mut s0,
        f: mut f0,
    } = lo;
    let Probe {
        x: mut x1,
        solution: mut s1,
        f: mut f1,
    } = hi;
    let mut side = 0i32;
    let mut count = 0usize;
    loop {
        count += 1;
        if count > max_solves {
            return Err(Error::LoadSearch(format!(
                "contact area {target} not matched within {max_solves} solves (bracket a_r in \
                 [{:.5}, {:.5}])",
                f0.min(f1) + target,
                f0.max(f1) + target
            )));
        }
        let mut x = (x0 * f1 - x1 * f0) / (f1 - f0);
        if !(x.is_finite()) || (x1 - x0).abs() < 1e-13 {
            x = 0.5 * (x0 + x1);
        }
        let warm = if (x - x0).abs() < (x - x1).abs() {
            &s0
        } else {
            &s1
        };
        let s = solve_at(x.exp(), Start::Warm(warm))?;
        let f = s.contact_area() - target;
        if f.abs() <= accept || (x1 - x0).abs() < 1e-12 {
            return Ok(s);
        }
        if f.signum() == f1.signum() {
            x1 = x;
            s1 = s;
            f1 = f;
            if side == 1 {
                f0 *= 0.5;
            }
            side = 1;
        } else {
            x0 = x;
            s0 = s;
            f0 = f;
            if side == -1 {
                f1 *= 0.5;
            }
            side = -1;
        }
    }
}
