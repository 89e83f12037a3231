//! The activation pass of an update: the distance `q` of every RF to the input, the RFs to
//! update, and the two nearest (for the add and prune tests).
//!
//! In 2-D with a full metric (the cross test's shape), [`for_each_q`] computes the distances
//! of four RFs at a time on AVX2. One at a time, loads and loop overhead dominate the dozen
//! arithmetic operations of an RF; here four RFs share each instruction: their centres and
//! metrics are loaded in place (no copies) and transposed into one lane per RF. Every lane
//! performs the operations of [`crate::scratch::quad`] in the same order, so each `q` has the
//! same bits.

use crate::params::{Params, W_UPDATE};
use crate::scratch::quad_full_n;

/// Calls `f(i, q_i)` for every RF `i` in order, with `q_i = ‖M_i (x − c_i)‖²` as
/// [`crate::scratch::quad`] computes it (bit for bit). `centers` holds 2 values per RF,
/// `ms` the 4 of each RF's row-major `M` (upper-triangular); `x` is the kernel input.
/// `AVX` may be set only where the CPU has AVX2 (checked at run time by the caller).
#[inline(always)]
pub(crate) fn for_each_q<const AVX: bool>(
    centers: &[f64],
    ms: &[f64],
    x: &[f64],
    mut f: impl FnMut(usize, f64),
) {
    let n = centers.len() / 2;
    let (centers, ms, x) = (&centers[..2 * n], &ms[..4 * n], &x[..2]);
    let mut i = 0;
    #[cfg(target_arch = "x86_64")]
    if AVX {
        while i + 4 <= n {
            // SAFETY: callers set `AVX` only after the run-time check that the CPU has AVX2
            // (`simd::has_avx2`: the update's AVX2 entry point, the unit test); the slices
            // hold the 8 centre and 16 metric values read.
            let q = unsafe { block4(&centers[2 * i..2 * i + 8], &ms[4 * i..4 * i + 16], x) };
            #[cfg(test)]
            crate::tests::activation::BLOCKS.with(|b| b.set(b.get() + 1));
            for (j, &qj) in q.iter().enumerate() {
                f(i + j, qj);
            }
            i += 4;
        }
    }
    while i < n {
        let q = quad_full_n::<2>(&centers[2 * i..], &ms[4 * i..], x, f64::INFINITY);
        f(i, q);
        i += 1;
    }
}

/// `q` of four consecutive RFs (`c`: 8 values, `m`: 16). Lanes hold the RFs in the order
/// 0, 2, 1, 3 (what the unpacking gives) until the final permutation.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn block4(c: &[f64], m: &[f64], x: &[f64]) -> [f64; 4] {
    use std::arch::x86_64::*;
    debug_assert!(c.len() >= 8 && m.len() >= 16 && x.len() >= 2);
    // Centres [c0x c0y c1x c1y], [c2x c2y c3x c3y] → [c0x c2x c1x c3x], [c0y c2y c1y c3y].
    let (ca, cb) = (
        _mm256_loadu_pd(c.as_ptr()),
        _mm256_loadu_pd(c.as_ptr().add(4)),
    );
    let (cx, cy) = (_mm256_unpacklo_pd(ca, cb), _mm256_unpackhi_pd(ca, cb));
    // Metrics [m00 m01 m10 m11] per RF → m00, m01, m11 of RFs 0, 2, 1, 3.
    let r0 = _mm256_loadu_pd(m.as_ptr());
    let r1 = _mm256_loadu_pd(m.as_ptr().add(4));
    let r2 = _mm256_loadu_pd(m.as_ptr().add(8));
    let r3 = _mm256_loadu_pd(m.as_ptr().add(12));
    let (lo02, lo13) = (_mm256_unpacklo_pd(r0, r2), _mm256_unpacklo_pd(r1, r3));
    let (hi02, hi13) = (_mm256_unpackhi_pd(r0, r2), _mm256_unpackhi_pd(r1, r3));
    let m00 = _mm256_permute2f128_pd::<0x20>(lo02, lo13);
    let m01 = _mm256_permute2f128_pd::<0x20>(hi02, hi13);
    let m11 = _mm256_permute2f128_pd::<0x31>(hi02, hi13);
    // The operations of `quad_full_n::<2>`, in its order.
    let dx0 = _mm256_sub_pd(_mm256_set1_pd(x[0]), cx);
    let dx1 = _mm256_sub_pd(_mm256_set1_pd(x[1]), cy);
    let zero = _mm256_setzero_pd();
    let v0 = _mm256_add_pd(zero, _mm256_mul_pd(m00, dx0));
    let v0 = _mm256_add_pd(v0, _mm256_mul_pd(m01, dx1));
    let q = _mm256_add_pd(zero, _mm256_mul_pd(v0, v0));
    let v1 = _mm256_add_pd(zero, _mm256_mul_pd(m11, dx1));
    let q = _mm256_add_pd(q, _mm256_mul_pd(v1, v1));
    // Lanes 0, 2, 1, 3 → RFs 0, 1, 2, 3.
    let q = _mm256_permute4x64_pd::<0b11_01_10_00>(q);
    let mut out = [0.0; 4];
    _mm256_storeu_pd(out.as_mut_ptr(), q);
    out
}

/// The activation pass's state: the two RFs of smallest `q` (largest activation) so far, with
/// their activations where already computed (`q < qb`), for the add/prune tests.
pub(crate) struct Top2 {
    pub q1: f64,
    pub i1: usize,
    pub w1: Option<f64>,
    pub q2: f64,
    pub i2: usize,
    pub w2: Option<f64>,
}

impl Top2 {
    pub fn new() -> Top2 {
        Top2 {
            q1: f64::INFINITY,
            i1: usize::MAX,
            w1: None,
            q2: f64::INFINITY,
            i2: usize::MAX,
            w2: None,
        }
    }

    /// The nearest RF's activation, 0 when there is none (taken from the pass when it
    /// computed it, else from the kernel).
    #[inline(always)]
    pub fn w_max(&self, p: &Params) -> f64 {
        Self::w(p, self.i1, self.q1, self.w1)
    }

    /// The second-nearest RF's activation, 0 when there is none.
    #[inline(always)]
    pub fn w_sec(&self, p: &Params) -> f64 {
        Self::w(p, self.i2, self.q2, self.w2)
    }

    /// The activation of RF `i` at distance `q`, `w` if the pass computed it; 0 for no RF.
    #[inline(always)]
    fn w(p: &Params, i: usize, q: f64, w: Option<f64>) -> f64 {
        if i < usize::MAX {
            w.unwrap_or_else(|| p.kernel(q).0)
        } else {
            0.0
        }
    }

    /// Visits RF `i` at distance `q`: queues it for the update if its activation exceeds
    /// `W_UPDATE` (`q < qb` first, so that far RFs cost no exponential), and keeps the two
    /// nearest.
    #[inline(always)]
    pub fn visit(
        &mut self,
        p: &Params,
        qb: f64,
        i: usize,
        q: f64,
        active: &mut Vec<(usize, f64, f64, f64)>,
    ) {
        let mut wq = None;
        if q < qb {
            let (w, dw, ddw) = p.kernel(q);
            if w > W_UPDATE {
                active.push((i, w, dw, ddw));
            }
            wq = Some(w);
        }
        if q < self.q2 {
            if q < self.q1 {
                (self.q2, self.i2, self.w2) = (self.q1, self.i1, self.w1);
                (self.q1, self.i1, self.w1) = (q, i, wq);
            } else {
                (self.q2, self.i2, self.w2) = (q, i, wq);
            }
        }
    }
}
