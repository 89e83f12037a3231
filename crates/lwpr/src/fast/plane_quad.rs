//! The distances of a 2-D full-metric kernel (the cross test's shape), four RFs at a time on
//! AVX2, for the update's activation pass and for plain predictions.
//!
//! One at a time, loads and loop overhead dominate the dozen arithmetic operations of an RF;
//! here four RFs share each instruction: their centres and metrics are loaded in place (no
//! copies) and transposed into one lane per RF. Every lane performs the operations of
//! `distance::quad` in the same order, so each `q` has the same bits.

use crate::distance::quad_full_n;
use crate::numeric::dot;
use crate::params::Params;
use crate::rf::SubModel;
use crate::scratch::Scratch;

/// Calls `f(i, q_i)` for every RF `i` in order, with `q_i = ‖M_i (x − c_i)‖²` as
/// [`crate::distance::quad`] computes it (bit for bit). `centers` holds 2 values per RF,
/// `ms` the 4 of each RF's row-major `M` (upper-triangular); `x` is the kernel input.
/// `AVX` may be set only where the CPU has AVX2 (checked at run time by the caller). Returns
/// how many RFs were computed four at a time (on AVX2; the others one at a time).
#[inline(always)]
pub(crate) fn for_each_q<const AVX: bool>(
    centers: &[f64],
    ms: &[f64],
    x: &[f64],
    mut f: impl FnMut(usize, f64),
) -> usize {
    let n = centers.len() / 2;
    let (centers, ms, x) = (&centers[..2 * n], &ms[..4 * n], &x[..2]);
    let mut i = 0;
    #[cfg(target_arch = "x86_64")]
    if AVX {
        while i + 4 <= n {
            // SAFETY: callers set `AVX` only after the run-time check that the CPU has AVX2
            // (`fast::has_avx2`: the AVX2 entry points, the unit test); the slices
            // hold the 8 centre and 16 metric values read.
            let q = unsafe { block4(&centers[2 * i..2 * i + 8], &ms[4 * i..4 * i + 16], x) };
            for (j, &qj) in q.iter().enumerate() {
                f(i + j, qj);
            }
            i += 4;
        }
    }
    let blocks = i;
    while i < n {
        let q = quad_full_n::<2>(&centers[2 * i..], &ms[4 * i..], x, f64::INFINITY);
        f(i, q);
        i += 1;
    }
    blocks
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

/// The sums of a plain prediction over a 2-D full-metric sub-model (`Stages::plain_sums`):
/// the RFs that predict first, their distances four at a time (the same bits), then `Σ w ŷ_k`
/// as `predict/blend.rs` sums it (a plain prediction needs no `Σ w ŷ_k²`); returns `Σ w`.
#[inline(always)]
pub(crate) fn plain_sums_2d<const AVX: bool>(
    p: &Params,
    sub: &mut SubModel,
    o0: usize,
    ws: &mut Scratch,
    nr: usize,
) -> f64 {
    let (cutoff, qb) = (p.cfg.cutoff, ws.qb_cutoff);
    let SubModel {
        rfs, centers, ms, ..
    } = sub;
    let mut sum_w = 0.0;
    ws.active.clear();
    let active = &mut ws.active;
    let xk = [ws.xk[0], ws.xk[1]];
    for_each_q::<AVX>(centers, ms, &xk, |i, q| {
        // The distance first: most RFs are far, and it is already in a register.
        if q < qb && rfs[i].trustworthy {
            let w = p.kernel(q).0;
            if w > cutoff {
                active.push((i, w, 0.0, 0.0));
            }
        }
    });
    for a in 0..ws.active.len() {
        let (i, w, _, _) = ws.active[a];
        let rf = &mut rfs[i];
        sum_w += w;
        let xc = &mut ws.pls.xmz[..nr];
        let (xr, mean_x) = (&ws.xr[..nr], &rf.mean_x[..nr]);
        for k in 0..nr {
            xc[k] = xr[k] - mean_x[k];
        }
        for (lo, pls) in rf.outs.iter_mut().enumerate() {
            pls.refresh_slope(nr);
            let yk = pls.beta0 + dot(&pls.slope[..nr], xc);
            ws.yacc[o0 + lo] += w * yk;
        }
    }
    sum_w
}
