//! The sums one CG iteration takes over its fields, row by row as the transforms read and
//! write them: the gap's sums, the direction's, the update's, the update of one point, and
//! a view of the fields with the frame they are read in.

use crate::engine::contact::{gap, Residual};
use crate::engine::field::fold_chunks;

/// How the stored fields read: the true pressure is `scale p` and the gap
/// `g = (scale u - h) - gbar`, the load scale applied lazily and `gbar` the rigid shift.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub(super) scale: f64,
    pub(super) gbar: f64,
}

impl Frame {
    /// The true pressure of the stored `p`.
    #[inline]
    pub(super) fn pressure(&self, p: f64) -> f64 {
        self.scale * p
    }

    /// The gap ([`gap`]) of the stored displacement `u` over the height `h`.
    #[inline]
    pub(super) fn gap(&self, u: f64, h: f64) -> f64 {
        gap(self.scale * u, h) - self.gbar
    }
}

/// Sums over the gap: `sum_Ic g^2`, `sum_Ic p |g|`, `sum_Ic p`, and the largest
/// penetration `max(-g)` (0 when nothing penetrates).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct GapSums {
    pub(super) gg: f64,
    pub(super) pg: f64,
    pub(super) sp: f64,
    pub(super) pen: f64,
}

impl GapSums {
    /// The residual estimate the iteration watches: the complementarity and penetration
    /// components of the [`Residual`].
    pub(super) fn estimate(&self, ell: f64) -> f64 {
        Residual::complementarity_of(self.pg, self.sp, ell)
            .max(Residual::penetration_of(self.pen, ell))
    }

    pub(super) fn add(self, o: Self) -> Self {
        Self {
            gg: self.gg + o.gg,
            pg: self.pg + o.pg,
            sp: self.sp + o.sp,
            pen: self.pen.max(o.pen),
        }
    }
}

/// What step 1 ([`super::Solve::gap`]) found.
#[derive(Debug, Clone, Copy)]
pub struct Gap {
    /// The gap's sums.
    pub(super) sums: GapSums,
    /// `sum_Ic z` (0 without preconditioning).
    pub(super) sz: f64,
    /// `G = sum_Ic g z` (`sum_Ic g^2` without preconditioning).
    pub(super) rho: f64,
    /// The residual estimate, [`GapSums::estimate`].
    pub(super) estimate: f64,
}

/// The sums of step 2 ([`super::Solve::direction`]) that the step length needs.
#[derive(Debug, Clone, Copy)]
pub(super) struct Direction {
    /// `sum_Ic r`.
    pub(super) sum_r: f64,
    /// `sum_Ic t`.
    pub(super) sum_t: f64,
    /// `sum_Ic g t`.
    pub(super) gt: f64,
    /// `sum_Ic r t`.
    pub(super) rt: f64,
}

/// The sums of step 4 ([`super::Solve::update`]), over the new pressure.
#[derive(Debug, Clone, Copy)]
pub(super) struct Update {
    /// `sum p` of the stored pressure.
    pub(super) sum_p: f64,
    /// Points clipped to `p = 0`, and points that entered contact.
    pub(super) clipped: f64,
    pub(super) entered: f64,
    /// `sum_Ic u`, `sum_Ic h` and `|Ic|` of the new contact set (`u` of the stored
    /// pressure).
    pub(super) su: f64,
    pub(super) sh: f64,
    pub(super) cnt: f64,
}

impl Update {
    /// The update from its sums over the pressure (`sum p`, points clipped, points
    /// entered) and over the new contact set (`sum_Ic u`, `sum_Ic h`, `|Ic|`).
    pub(super) fn new([sum_p, clipped, entered]: [f64; 3], [su, sh, cnt]: [f64; 3]) -> Self {
        Self {
            sum_p,
            clipped,
            entered,
            su,
            sh,
            cnt,
        }
    }
}

/// The update of one point (step 4), read in the frame of the fields.
#[derive(Clone, Copy)]
pub(super) struct Step {
    pub(super) frame: Frame,
    pub(super) tau: f64,
    /// Pressure per unit penetration given to points entering contact.
    pub(super) admit: f64,
}

impl Step {
    /// The new pressure of a point with stored pressure `p` and displacement `u`, height
    /// `h` and search direction `t`, and whether it was clipped and whether it entered
    /// (as 0 or 1).
    #[inline]
    pub(super) fn point(&self, p: f64, u: f64, h: f64, t: f64) -> (f64, f64, f64) {
        let p_true = self.frame.pressure(p);
        let g = self.frame.gap(u, h);
        let stepped = p_true - self.tau * t;
        let was_in = p_true > 0.0;
        let q = if was_in {
            stepped.max(0.0)
        } else if g < 0.0 {
            -self.admit * g
        } else {
            0.0
        };
        (
            q,
            f64::from(u8::from(was_in && stepped <= 0.0)),
            f64::from(u8::from(!was_in && g < 0.0)),
        )
    }
}

/// `sum_Ic u`, `sum_Ic h` and `|Ic|` over one row, `Ic = {p > 0}`: what the rigid shift
/// `gbar = mean_Ic (u - h)` needs once `u = K^-1 p` has been recomputed.
pub(super) fn contact_sums(u: &[f64], p: &[f64], h: &[f64]) -> [f64; 3] {
    let mut acc = [0.0; 3];
    for ((&uk, &pk), &hk) in u.iter().zip(p).zip(h) {
        let w = if pk > 0.0 { 1.0 } else { 0.0 };
        acc[0] += w * uk;
        acc[1] += w * hk;
        acc[2] += w;
    }
    acc
}

/// The fields of the iteration with the heights, read in their [`Frame`].
#[derive(Clone, Copy)]
pub(super) struct View<'a> {
    pub(super) p: &'a [f64],
    pub(super) u: &'a [f64],
    pub(super) h: &'a [f64],
    pub(super) frame: Frame,
}

impl<'a> View<'a> {
    pub(super) fn new(p: &'a [f64], u: &'a [f64], h: &'a [f64], frame: Frame) -> Self {
        Self { p, u, h, frame }
    }

    /// Row `i` (of length `n`) of `p`, `u` and `h`.
    #[inline]
    pub(super) fn row(&self, i: usize, n: usize) -> (&[f64], &[f64], &[f64]) {
        let r = i * n..(i + 1) * n;
        (&self.p[r.clone()], &self.u[r.clone()], &self.h[r])
    }

    /// Gap sums over a range; the masked gap (`g` in contact, 0 outside) goes to `out`
    /// when given.
    pub(super) fn gap_sums_into(
        &self,
        range: std::ops::Range<usize>,
        out: Option<&mut [f64]>,
    ) -> GapSums {
        let frame = self.frame;
        let (p, u, h) = (
            &self.p[range.clone()],
            &self.u[range.clone()],
            &self.h[range],
        );
        let mut acc = [0.0f64; 3];
        let mut pen = f64::NEG_INFINITY;
        let mut step = |pk: f64, uk: f64, hk: f64| -> f64 {
            let g = frame.gap(uk, hk);
            let pk = frame.pressure(pk);
            let contact = pk > 0.0;
            let gm = if contact { g } else { 0.0 };
            acc[0] += gm * gm;
            // p = 0 outside contact: these need no mask.
            acc[1] += pk * g.abs();
            acc[2] += pk;
            // Penetration anywhere, contact points included, as in the full residual:
            // with a smaller estimate the full residual is evaluated too early, fails, and
            // costs a refresh and an evaluation for nothing.
            pen = pen.max(-g);
            gm
        };
        match out {
            Some(o) => {
                for (((ok, &pk), &uk), &hk) in o.iter_mut().zip(p).zip(u).zip(h) {
                    *ok = step(pk, uk, hk);
                }
            }
            None => {
                for ((&pk, &uk), &hk) in p.iter().zip(u).zip(h) {
                    step(pk, uk, hk);
                }
            }
        }
        GapSums {
            gg: acc[0],
            pg: acc[1],
            sp: acc[2],
            pen: pen.max(0.0),
        }
    }

    /// Gap sums over the whole grid.
    pub(super) fn gap_sums(&self) -> GapSums {
        let n2 = self.p.len();
        fold_chunks(
            n2,
            GapSums::default(),
            #[inline(always)]
            |rg| self.gap_sums_into(rg, None),
            GapSums::add,
        )
    }
}
