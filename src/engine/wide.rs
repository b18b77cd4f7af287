//! Hot loops compiled for the processor they run on: [`wide`] runs a closure compiled with
//! AVX2 where the processor has it (checked at run time; the standard library caches the
//! answer), and as the portable baseline (SSE2 on x86-64) elsewhere.
//!
//! The element-wise passes of the solvers (a solver iteration's fills, residual sums and
//! updates, the FFT's column gather and scatter and kernel product) are short arithmetic
//! over rows of the grid; the baseline does them two values at a time, AVX2 four, with
//! blends instead of and/or sequences for `max` and the wall's conditions. The numbers do
//! not change: the compiler may not reorder or fuse floating-point operations (no fast-math,
//! no contraction), so each value is computed by the same operations in the same order;
//! wider registers only compute more of them at once. Sums stay in their order (the
//! compiler does not vectorise a floating-point sum it may not reassociate).
//!
//! A closure is compiled into the AVX2 function only where it is inlined there: the helpers
//! that call [`wide`] mark their own closure `#[inline(always)]`, and a caller whose loop
//! body is hot marks the closure it hands them the same way.
//!
//! Measured (`docs/measured.md`, the element-wise loops): the reduced `total_energy` scene with four realizations,
//! one thread, GFMD in 0.81 and CG in 0.93 of the baseline's time, the same job results.

/// Runs `f`, compiled with AVX2 when the processor has it. The closure, and what it calls
/// inline, is compiled for both; call it around a loop body, not around a parallel loop
/// (the tasks a parallel loop spawns are compiled once, for the baseline).
#[inline(always)]
pub fn wide<R, F: FnOnce() -> R>(f: F) -> R {
    #[cfg(target_arch = "x86_64")]
    if has_avx2() {
        // SAFETY: the processor has AVX2 (checked at run time).
        return unsafe { with_avx2(f) };
    }
    f()
}

/// Whether the processor has AVX2.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn has_avx2() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
}

/// `f`, inlined into a function compiled with AVX2.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn with_avx2<R, F: FnOnce() -> R>(f: F) -> R {
    f()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The loops of a GFMD step in miniature: a look-ahead with the wall, a force and its
    /// power summed in order, over values that hit every branch.
    #[inline(always)]
    fn step(u: &[f64], v: &[f64], h: &[f64], s: &[f64], out: &mut [f64]) -> f64 {
        let mut power = 0.0;
        for ((((o, &ui), &vi), &hi), &si) in out.iter_mut().zip(u).zip(v).zip(h).zip(s) {
            let y = (ui + 0.7 * vi).max(hi);
            let f = if y <= hi { (-si).max(0.0) } else { -si };
            *o = (y + 0.3 * f).max(hi);
            power += f * (*o - ui);
        }
        power
    }

    #[test]
    fn the_wide_and_the_baseline_build_give_the_same_bits() {
        let n = 4099;
        let x = |k: usize, a: f64| ((k as f64) * a).sin();
        let u: Vec<f64> = (0..n).map(|k| x(k, 0.37)).collect();
        let v: Vec<f64> = (0..n).map(|k| 1e-3 * x(k, 1.3)).collect();
        let h: Vec<f64> = (0..n).map(|k| x(k, 0.11) - 0.2).collect();
        let s: Vec<f64> = (0..n).map(|k| x(k, 2.9) * 1e-2).collect();
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        let pa = wide(
            #[inline(always)]
            || step(&u, &v, &h, &s, &mut a),
        );
        let pb = step(&u, &v, &h, &s, &mut b);
        assert_eq!(pa.to_bits(), pb.to_bits());
        assert!(a.iter().zip(&b).all(|(p, q)| p.to_bits() == q.to_bits()));
    }
}
