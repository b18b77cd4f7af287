//! FIRE's schedule (see the module docs): the time step `dt` and the mixing `alpha`, which
//! grow while the force keeps pulling along the velocity and are reset when it turns
//! against it.
//!
//! The constants are [`FireParams`]' associated constants, each saying where its value
//! comes from: Bitzek et al.'s published values where they are used as published, and the
//! measurements on the speed study's scenes where they were tuned.

use serde::{Deserialize, Serialize};

/// FIRE's constants (Bitzek, Koskinen, Gähler, Moseler & Gumbsch, PRL 97, 170201 (2006),
/// who call them `Delta t`, `Delta t_max`, `N_min`, `f_inc`, `f_dec`, `alpha_start` and
/// `f_alpha`), with times in units of the inverse mode frequency of the mass-weighted
/// dynamics. The defaults are its associated constants.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FireParams {
    /// First time step ([`Self::DT_START`]).
    pub dt_start: f64,
    /// Largest time step ([`Self::DT_MAX`]).
    pub dt_max: f64,
    /// Steps along the force after a restart before `dt` may grow and `alpha` shrink
    /// ([`Self::N_DELAY`]).
    pub n_delay: usize,
    /// Growth of `dt` at a step along the force ([`Self::F_INC`]).
    pub f_inc: f64,
    /// Factor of `dt` at a restart ([`Self::F_DEC`]).
    pub f_dec: f64,
    /// Mixing after a restart ([`Self::ALPHA_START`]).
    pub alpha_start: f64,
    /// Factor of `alpha` at a step along the force ([`Self::F_ALPHA`]).
    pub f_alpha: f64,
    /// Smallest time step, as a fraction of the first ([`Self::DT_MIN`]).
    pub dt_min: f64,
    /// Steps without a new lowest residual after which the solve has stalled
    /// ([`Self::STALL_WINDOW`]).
    pub stall_window: usize,

    /// Step back at a restart, in time steps ([`Self::BACK`]).
    pub back: f64,
}

impl Default for FireParams {
    fn default() -> Self {
        Self {
            dt_start: Self::DT_START,
            dt_max: Self::DT_MAX,
            n_delay: Self::N_DELAY,
            f_inc: Self::F_INC,
            f_dec: Self::F_DEC,
            alpha_start: Self::ALPHA_START,
            f_alpha: Self::F_ALPHA,
            dt_min: Self::DT_MIN,
            stall_window: Self::STALL_WINDOW,

            back: Self::BACK,
        }
    }
}

impl FireParams {
    /// First time step (docs/measured.md: "FIRE", the tuning set; 0.3 took 3-9% more
    /// iterations).
    pub const DT_START: f64 = 0.6;
    /// Largest time step: below the stability limit of the stiffest constrained modes
    /// (the wall makes modes up to about 2.5 times as fast as the free ones). 1.5 and 0.7
    /// took 1.4 times the iterations at the lowest loads (docs/measured.md: "FIRE").
    pub const DT_MAX: f64 = 1.0;
    /// Bitzek et al.'s `N_min` is 5, which took 1.2 and 2.3 times the iterations (the
    /// tuning set, its lowest loads): mass weighting gives the free modes one frequency,
    /// so there is no slow mode to wait for.
    pub const N_DELAY: usize = 0;
    /// Bitzek et al.'s `f_inc` is 1.1, which took 1.1 times the iterations (docs/measured.md:
    /// "FIRE").
    pub const F_INC: f64 = 1.05;
    /// Bitzek et al.'s `f_dec` is 0.5: restarts come every few steps on this problem (the
    /// wall turns the motion), and halving `dt` at each kept it far below its stable size,
    /// 4.8 and 1.9 times the iterations (docs/measured.md: "FIRE").
    pub const F_DEC: f64 = 0.95;
    /// Bitzek et al.'s `alpha_start` is 0.1: strong mixing after a restart damps the
    /// oscillation of the modes the wall couples near the contact edges; 0.1 took 1.8
    /// and 1.6 times the iterations (docs/measured.md: "FIRE").
    pub const ALPHA_START: f64 = 0.9;
    /// Bitzek et al.'s `f_alpha` is 0.99: with mixing this strong, a slow decay keeps a
    /// soft mode (the rigid approach at the lowest loads) from gathering speed; 0.99
    /// took 1.2 and 18 times the iterations (docs/measured.md: "FIRE").
    pub const F_ALPHA: f64 = 0.7;
    /// Smallest time step, as a fraction of the first: FIRE 2.0's `Delta t_min`
    /// (Guénolé et al., Comput. Mater. Sci. 175, 109584 (2020)), so that a run of
    /// restarts cannot freeze the dynamics. Not tuned.
    pub const DT_MIN: f64 = 0.02;
    /// Steps without a new lowest residual estimate after which the residual cannot
    /// improve (a tolerance below its rounding floor). A converging solve reaches a new
    /// low every few steps, but at the lowest loads 100 steps without one occurred far
    /// from convergence. A stopping rule, not a tuned value.
    pub const STALL_WINDOW: usize = 300;
    /// FIRE 2.0's step back at a restart (Guénolé et al., half a step, 0.5) took 1.4 and
    /// 1.1 times the iterations here (docs/measured.md: "FIRE"): none.
    pub const BACK: f64 = 0.0;
}

/// What the schedule makes of one step: the time step, whether the velocity is kept
/// (`false` after a restart), and the mixing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Schedule {
    pub(super) dt: f64,
    pub(super) keep: bool,
    pub(super) alpha: f64,
    /// The time by which the position steps back along the dropped velocity at a
    /// restart (0 otherwise).
    pub(super) back: f64,
}

/// FIRE's schedule over one solve.
#[derive(Debug, Clone, Copy)]
pub(super) struct Control {
    params: FireParams,
    dt: f64,
    alpha: f64,
    /// Steps along the force since the last restart.
    along: usize,
    /// The lowest residual estimate so far, and the steps since it was reached.
    best: f64,
    since_best: usize,
}

impl Control {
    pub(super) fn new(params: FireParams) -> Self {
        Self {
            params,
            dt: params.dt_start,
            alpha: params.alpha_start,
            along: 0,
            best: f64::INFINITY,
            since_best: 0,
        }
    }

    /// The schedule of a step from a state with residual estimate `residual` whose force
    /// has power `power` against the velocity: along the force (`power > 0`), after
    /// `n_delay` such steps in a row, `dt` grows (up to `dt_max`) and `alpha` shrinks;
    /// against it (or at rest), the velocity is dropped, `dt` shrinks (down to `dt_min`)
    /// and `alpha` starts again. `None` once the residual has reached no new low for
    /// `stall_window` steps.
    pub(super) fn next(&mut self, power: f64, residual: f64) -> Option<Schedule> {
        let p = &self.params;
        if residual < self.best {
            self.best = residual;
            self.since_best = 0;
        } else {
            self.since_best += 1;
        }
        let keep = power > 0.0;
        let back = if keep { 0.0 } else { p.back * self.dt };
        if keep {
            self.along += 1;
            if self.along > p.n_delay {
                self.dt = (self.dt * p.f_inc).min(p.dt_max);
                self.alpha *= p.f_alpha;
            }
        } else {
            self.along = 0;
            self.dt = (self.dt * p.f_dec).max(p.dt_min * p.dt_start);
            self.alpha = p.alpha_start;
        }
        (self.since_best < p.stall_window).then_some(Schedule {
            dt: self.dt,
            keep,
            alpha: self.alpha,
            back,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_step_grows_after_the_delay_and_shrinks_at_a_restart() {
        let p = FireParams {
            n_delay: 5,
            back: 0.5,
            ..FireParams::default()
        };
        let mut c = Control::new(p);
        for k in 0..p.n_delay {
            // The residual falls at every step: no stall.
            assert_eq!(c.next(1.0, 1.0 / (k + 1) as f64).unwrap().dt, p.dt_start);
        }
        let grown = c.next(1.0, 0.01).unwrap();
        assert_eq!(grown.dt, p.dt_start * p.f_inc);
        assert_eq!(grown.alpha, p.alpha_start * p.f_alpha);
        assert_eq!(grown.back, 0.0);
        let mut residual = 0.01;
        for _ in 0..1000 {
            residual *= 0.99;
            c.next(1.0, residual);
        }
        assert_eq!(c.next(1.0, 0.0).unwrap().dt, p.dt_max, "capped");
        let restart = c.next(-1.0, 0.0).unwrap();
        assert_eq!(
            restart,
            Schedule {
                dt: p.dt_max * p.f_dec,
                keep: false,
                alpha: p.alpha_start,
                back: p.back * p.dt_max,
            }
        );
        assert!(
            !c.next(0.0, 0.0).unwrap().keep,
            "at rest counts as a restart"
        );
        for _ in 0..10_000 {
            c.next(-1.0, -1.0);
        }
        assert_eq!(
            c.next(-1.0, -2.0).unwrap().dt,
            p.dt_min * p.dt_start,
            "floor"
        );
    }

    #[test]
    fn a_residual_without_a_new_low_for_the_window_stalls() {
        let p = FireParams::default();
        let mut c = Control::new(p);
        assert!(c.next(1.0, 1.0).is_some());
        for k in 1..p.stall_window {
            assert!(c.next(1.0, 1.0).is_some(), "step {k}");
        }
        assert!(c.next(1.0, 1.0).is_none());
        let mut c = Control::new(p);
        for k in 0..10 * p.stall_window {
            assert!(c.next(1.0, 1.0 / (k + 1) as f64).is_some());
        }
    }

    #[test]
    fn default_parameters_are_the_named_constants() {
        let p = FireParams::default();
        assert_eq!((p.n_delay, p.f_inc, p.f_dec), (0, 1.05, 0.95));
        assert_eq!((p.alpha_start, p.f_alpha, p.back), (0.9, 0.7, 0.0));
        assert_eq!((p.dt_start, p.dt_max, p.dt_min), (0.6, 1.0, 0.02));
        assert_eq!(p.stall_window, 300);
    }
}
