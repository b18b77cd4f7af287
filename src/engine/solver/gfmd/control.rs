//! GFMD's step control (see "Step control" in the module docs): the momentum schedule
//! `beta`, and the step `tau`, which shrinks when the residual shows a mode that the step
//! makes unstable and grows back at every new low.
//!
//! The defaults are the values of the measurements in `docs/measured.md`
//! ("GFMD's dynamics": what each change bought), each a named constant of [`GfmdParams`]
//! that says where its value comes from.

use serde::{Deserialize, Serialize};

/// GFMD's constants: the step in units of the squared mode period (`1/omega^2`), and the
/// step control (see the module docs). The defaults are its associated constants, which
/// say where each value comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GfmdParams {
    /// First step `tau` of a cold solve ([`Self::TAU_COLD`]).
    pub tau: f64,
    /// First step of a warm solve (the contact set of a warm start has more isolated
    /// points, and stiffer modes, than a cold start meets early on; [`Self::TAU_WARM`]).
    pub tau_warm: f64,
    /// Steps without a new lowest residual before the step shrinks
    /// ([`Self::STALL_WINDOW`]).
    pub stall_window: usize,
    /// Steps in a row in which the residual alternately rises and falls before the step
    /// shrinks ([`Self::ZIGZAG_WINDOW`]).
    pub zigzag_window: usize,
    /// Steps in a row in which the residual rises (to above twice its low) before the
    /// step shrinks ([`Self::RISE_WINDOW`]).
    pub rise_window: usize,
    /// Largest damping factor `beta` (the schedule's limit, 1, is optimal only for
    /// problems without a smallest curvature; [`Self::BETA_MAX`]).
    pub beta_max: f64,
    /// Growth of the step, up to the first, at every new lowest residual
    /// ([`Self::REGROW`]).
    pub regrow: f64,
    /// Factor of a shrink ([`Self::SHRINK`]).
    pub shrink: f64,
    /// Smallest step, as a fraction of the first: below it the solve has stalled
    /// ([`Self::TAU_FLOOR`]).
    pub tau_floor: f64,
}

impl Default for GfmdParams {
    fn default() -> Self {
        Self {
            tau: Self::TAU_COLD,
            tau_warm: Self::TAU_WARM,
            stall_window: Self::STALL_WINDOW,
            zigzag_window: Self::ZIGZAG_WINDOW,
            rise_window: Self::RISE_WINDOW,
            beta_max: Self::BETA_MAX,
            regrow: Self::REGROW,
            shrink: Self::SHRINK,
            tau_floor: Self::TAU_FLOOR,
        }
    }
}

impl GfmdParams {
    /// First step of a cold solve, in units of the squared mode period: the best fixed
    /// step on the speed study's scenes (docs/measured.md: "the momentum schedule with a
    /// fixed step 0.3", cold 142 -> 36 iterations at 128^2).
    pub const TAU_COLD: f64 = 0.3;
    /// First step of a warm solve (docs/measured.md: "a warm step of 0.2", a 512^2 sweep
    /// segment from zeta = 20, 29.6 -> 18.7 iterations per shell).
    pub const TAU_WARM: f64 = 0.2;
    /// Steps without a new lowest residual before the step shrinks (docs/measured.md:
    /// "shrinking the step when the residual stalls", 256^2 cold 142 -> 67 iterations
    /// and no limit cycle left).
    pub const STALL_WINDOW: usize = 8;
    /// Steps in a row in which the residual alternately rises and falls before the step
    /// shrinks (docs/measured.md: "shrinking on a zigzag or a steady rise of the
    /// residual", 1024^2 cold 111 -> 77 iterations).
    pub const ZIGZAG_WINDOW: usize = 4;
    /// Steps in a row in which the residual rises, to above twice its low, before the
    /// step shrinks (the same measurement as [`Self::ZIGZAG_WINDOW`]).
    pub const RISE_WINDOW: usize = 3;
    /// Largest `beta` (docs/measured.md: the cap of 0.8 left a low load crawling; 0.95
    /// took a solve at `a_r = 2e-4`, where the rigid mode is soft, from over 1500 to 363
    /// iterations at tol 1e-8).
    pub const BETA_MAX: f64 = 0.95;
    /// Growth of the step at every new lowest residual, up to the first
    /// (docs/measured.md: "regrowing the step at every new low", no stalled solve left on the hard
    /// scenes).
    pub const REGROW: f64 = 1.02;
    /// Factor of a shrink: the value of the measurements of [`Self::STALL_WINDOW`]
    /// and [`Self::ZIGZAG_WINDOW`], not tuned alone.
    pub const SHRINK: f64 = 0.7;
    /// Smallest step, as a fraction of the first: a step shrunk a thousandfold means the
    /// residual cannot improve (a tolerance below its rounding floor). A stopping rule,
    /// not a tuned value.
    pub const TAU_FLOOR: f64 = 1e-3;

    /// The first step of a solve: [`Self::tau`] cold, [`Self::tau_warm`] warm, or, for a
    /// solver that ended a solve with step `last` (a sweep), one shrink above `last` if
    /// that is smaller.
    pub(super) fn first_step(&self, warm: bool, last: Option<f64>) -> f64 {
        let first = if warm { self.tau_warm } else { self.tau };
        last.map_or(first, |t| (t / self.shrink).min(first))
    }
}

/// The course of the residual over the last steps, as the step control reads it: whether
/// it rose at the last step, for how many steps in a row it has alternately risen and
/// fallen (a mode too stiff for the step flips sign every step), and for how many steps in
/// a row it has risen.
#[derive(Debug, Clone, Copy)]
struct Course {
    /// The last residual.
    last: f64,
    /// Whether the last step raised the residual; `None` before the first step and
    /// after a shrink.
    rose: Option<bool>,
    /// Steps in a row, up to the last, each of which moved the residual the other way
    /// than the step before it (the first step of a run counts one).
    alternating: usize,
    /// Steps in a row, up to the last, that raised the residual.
    rising: usize,
}

impl Course {
    fn new() -> Self {
        Self {
            last: f64::INFINITY,
            rose: None,
            alternating: 0,
            rising: 0,
        }
    }

    /// Records the residual of the next step.
    fn record(&mut self, residual: f64) {
        let rose = residual > self.last;
        self.alternating = if self.rose == Some(!rose) {
            self.alternating + 1
        } else {
            1
        };
        self.rising = if rose { self.rising + 1 } else { 0 };
        self.rose = Some(rose);
        self.last = residual;
    }

    /// Starts the runs afresh (the last residual stays the reference of the next step).
    fn forget_runs(&mut self) {
        self.rose = None;
        self.alternating = 0;
        self.rising = 0;
    }
}

/// The momentum schedule and the step control of one solve.
#[derive(Debug, Clone, Copy)]
pub(super) struct Momentum {
    params: GfmdParams,
    tau_first: f64,
    /// The step.
    pub(super) tau: f64,
    /// Steps since the last restart (`beta = k / (k + 3)`).
    k: usize,
    /// The lowest residual since the last shrink, and the steps since it was reached.
    best: f64,
    since_best: usize,
    course: Course,
}

impl Momentum {
    pub(super) fn new(params: GfmdParams, tau: f64) -> Self {
        Self {
            params,
            tau_first: tau,
            tau,
            k: 0,
            best: f64::INFINITY,
            since_best: 0,
            course: Course::new(),
        }
    }

    /// Damping of the next look-ahead.
    pub(super) fn beta(&self) -> f64 {
        let k = self.k as f64;
        (k / (k + 3.0)).min(self.params.beta_max)
    }

    /// Step 4: after a step with power `power` (force times step) from a state whose
    /// residual estimate is `residual`, the schedule of the next. Returns false when the
    /// step has shrunk below its floor (the residual cannot improve).
    pub(super) fn control(&mut self, power: f64, residual: f64) -> bool {
        let mut restart = power <= 0.0;
        self.course.record(residual);
        if residual < self.best {
            self.best = residual;
            self.since_best = 0;
            self.tau = (self.tau * self.params.regrow).min(self.tau_first);
        } else {
            self.since_best += 1;
        }
        if self.unstable(residual) {
            self.tau *= self.params.shrink;
            self.best = residual;
            self.since_best = 0;
            self.course.forget_runs();
            restart = true;
        }
        self.k = if restart { 0 } else { self.k + 1 };
        self.tau >= self.params.tau_floor * self.tau_first
    }

    /// Whether the residual, `residual` at the last step, shows a mode that the step
    /// makes unstable: it zigzags, or it rises step after step well above its low
    /// (a stiff mode may also grow without zigzagging), or it has reached no new low
    /// for a while (a limit cycle through the wall).
    fn unstable(&self, residual: f64) -> bool {
        let p = &self.params;
        let zigzag = self.course.alternating >= p.zigzag_window;
        let growing = self.course.rising >= p.rise_window && residual > 2.0 * self.best;
        zigzag || growing || self.since_best >= p.stall_window
    }

    /// Forgets the momentum (after the state was replaced).
    pub(super) fn restart(&mut self) {
        self.k = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The signed counter the course replaces: positive when the residual last rose, its
    /// magnitude the run of alternations.
    fn zigzag_counter(rises: &[bool]) -> Vec<u32> {
        let mut z = 0i32;
        rises
            .iter()
            .map(|&rose| {
                z = match (rose, z) {
                    (true, z) if z <= 0 => 1 - z,
                    (false, z) if z > 0 => -z - 1,
                    (true, _) => 1,
                    (false, _) => -1,
                };
                z.unsigned_abs()
            })
            .collect()
    }

    #[test]
    fn the_course_counts_alternations_as_the_signed_counter_did() {
        // Every sequence of eight rises and falls.
        for bits in 0u32..256 {
            let rises: Vec<bool> = (0..8).map(|k| bits >> k & 1 == 1).collect();
            let mut course = Course::new();
            course.last = 0.0;
            let counted: Vec<u32> = rises
                .iter()
                .map(|&rose| {
                    course.record(if rose {
                        course.last + 1.0
                    } else {
                        course.last - 1.0
                    });
                    course.alternating as u32
                })
                .collect();
            assert_eq!(counted, zigzag_counter(&rises), "{rises:?}");
        }
    }

    #[test]
    fn default_parameters_are_the_named_constants() {
        let p = GfmdParams::default();
        assert_eq!((p.tau, p.tau_warm, p.beta_max), (0.3, 0.2, 0.95));
        assert_eq!((p.stall_window, p.zigzag_window, p.rise_window), (8, 4, 3));
        assert_eq!((p.regrow, p.shrink, p.tau_floor), (1.02, 0.7, 1e-3));
    }
}
