//! The fused passes of a CG iteration ([`FusedPass`]): what each convolution of an
//! iteration generates row by row as the forward transforms read it, and the sums it takes
//! row by row as the inverse transforms write the result.

use super::sums::{contact_sums, GapSums, Step, View};
use crate::engine::fft::FusedPass;

/// Step 1 with preconditioning, the pass of `z = K g`: the masked gap generated with its
/// sums, and `[sum_Ic z, sum_Ic g z]` over the result.
pub(super) struct Precondition<'a> {
    pub(super) view: View<'a>,
    pub(super) n: usize,
}

impl FusedPass for Precondition<'_> {
    type Generated = GapSums;
    type Consumed = [f64; 2];

    #[inline(always)]
    fn generate(&self, i: usize, row: &mut [f64], _: &mut [f64], _: &[f64]) -> GapSums {
        let n = self.n;
        self.view.gap_sums_into(i * n..(i + 1) * n, Some(row))
    }

    #[inline(always)]
    fn consume(&self, i: usize, z: &[f64], _: &[f64]) -> [f64; 2] {
        let (p, u, h) = self.view.row(i, self.n);
        let frame = self.view.frame;
        let (mut sz, mut gz) = (0.0, 0.0);
        for (((&zk, &pk), &uk), &hk) in z.iter().zip(p).zip(u).zip(h) {
            let zm = if pk > 0.0 { zk } else { 0.0 };
            sz += zm;
            gz += frame.gap(uk, hk) * zm;
        }
        [sz, gz]
    }
}

/// Step 2, the pass of `r = K^-1 t`: the search direction `t = (z - zbar) + beta t` on
/// `Ic`, 0 elsewhere, generated (and kept in the side field `t`; `z` is read from the
/// output's old values, without preconditioning the gap takes its place), and
/// `[sum_Ic r, sum t, sum g t, sum r t]` over the result.
pub(super) struct Direction<'a> {
    pub(super) view: View<'a>,
    pub(super) n: usize,
    pub(super) precond: bool,
    pub(super) zbar: f64,
    pub(super) beta: f64,
}

impl FusedPass for Direction<'_> {
    type Generated = ();
    type Consumed = [f64; 4];

    #[inline(always)]
    fn generate(&self, i: usize, row: &mut [f64], t: &mut [f64], z: &[f64]) {
        let (p, u, h) = self.view.row(i, self.n);
        let frame = self.view.frame;
        let (zbar, beta) = (self.zbar, self.beta);
        if self.precond {
            for (((x, tk), &zk), &pk) in row.iter_mut().zip(t.iter_mut()).zip(z).zip(p) {
                let d = zk - zbar + beta * *tk;
                *tk = if pk > 0.0 { d } else { 0.0 };
                *x = *tk;
            }
        } else {
            for ((((x, tk), &pk), &uk), &hk) in
                row.iter_mut().zip(t.iter_mut()).zip(p).zip(u).zip(h)
            {
                let d = frame.gap(uk, hk) + beta * *tk;
                *tk = if pk > 0.0 { d } else { 0.0 };
                *x = *tk;
            }
        }
    }

    #[inline(always)]
    fn consume(&self, i: usize, r: &[f64], t: &[f64]) -> [f64; 4] {
        let (p, u, h) = self.view.row(i, self.n);
        let frame = self.view.frame;
        let (mut sr, mut st, mut gt, mut rt) = (0.0, 0.0, 0.0, 0.0);
        // t = 0 outside contact: only the sum of r needs a mask.
        for ((((&rk, &tk), &pk), &uk), &hk) in r.iter().zip(t).zip(p).zip(u).zip(h) {
            sr += if pk > 0.0 { rk } else { 0.0 };
            st += tk;
            gt += frame.gap(uk, hk) * tk;
            rt += rk * tk;
        }
        [sr, st, gt, rt]
    }
}

/// Step 4 fused into the pass of `u = K^-1 p`: the new pressure generated (and kept in
/// the side field `p`; the old displacement is read from the output's old values) with
/// `[sum p, points clipped, points entered]`, and [`contact_sums`] over the new `u`.
pub(super) struct Update<'a> {
    pub(super) step: Step,
    pub(super) t: &'a [f64],
    pub(super) h: &'a [f64],
    pub(super) n: usize,
}

impl FusedPass for Update<'_> {
    type Generated = [f64; 3];
    type Consumed = [f64; 3];

    fn generate(&self, i: usize, row: &mut [f64], pr: &mut [f64], ur: &[f64]) -> [f64; 3] {
        let rg = i * self.n..(i + 1) * self.n;
        let mut acc = [0.0; 3];
        for ((((x, pk), &uk), &tk), &hk) in row
            .iter_mut()
            .zip(pr.iter_mut())
            .zip(ur)
            .zip(&self.t[rg.clone()])
            .zip(&self.h[rg])
        {
            let (q, clip, enter) = self.step.point(*pk, uk, hk, tk);
            *pk = q;
            *x = q;
            acc[0] += q;
            acc[1] += clip;
            acc[2] += enter;
        }
        acc
    }

    fn consume(&self, i: usize, u: &[f64], p: &[f64]) -> [f64; 3] {
        let n = self.n;
        contact_sums(u, p, &self.h[i * n..(i + 1) * n])
    }
}

/// The pass of an exact `u = K^-1 p`: the load scale applied to the stored pressure (kept
/// in the side field `p`) as it is generated, and [`contact_sums`] over the new `u`.
pub(super) struct Rescale<'a> {
    pub(super) scale: f64,
    pub(super) h: &'a [f64],
    pub(super) n: usize,
}

impl FusedPass for Rescale<'_> {
    type Generated = ();
    type Consumed = [f64; 3];

    fn generate(&self, _: usize, row: &mut [f64], p: &mut [f64], _: &[f64]) {
        for (x, pj) in row.iter_mut().zip(p.iter_mut()) {
            *pj *= self.scale;
            *x = *pj;
        }
    }

    fn consume(&self, i: usize, u: &[f64], p: &[f64]) -> [f64; 3] {
        let n = self.n;
        contact_sums(u, p, &self.h[i * n..(i + 1) * n])
    }
}
