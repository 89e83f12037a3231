//! AVX2 forms of some lane operations of `lanes.rs` (the same values): masked loads and
//! stores of a row's partial last vector, the horizontal sum, `max |v|`.

use std::arch::x86_64::*;

/// Four lanes (`lanes::V`; not imported, so that `lanes.rs` and this file form no circle).
type V = [f64; 4];

/// Lane masks: the first `k` lanes enabled (the sign bit set).
static MASKS: [[i64; 4]; 5] = [
    [0, 0, 0, 0],
    [-1, 0, 0, 0],
    [-1, -1, 0, 0],
    [-1, -1, -1, 0],
    [-1, -1, -1, -1],
];

/// The first `k` of the four values at `p`, the others zero.
///
/// # Safety
/// AVX2; `p` valid for reading `k ≤ 4` values (masked lanes are not accessed).
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) unsafe fn load(p: *const f64, k: usize) -> V {
    let mut out = [0.0; 4];
    // SAFETY: the caller's contract; `MASKS[k]` holds 4 `i64`.
    unsafe {
        let m = _mm256_loadu_si256(MASKS[k].as_ptr().cast());
        _mm256_storeu_pd(out.as_mut_ptr(), _mm256_maskload_pd(p, m));
    }
    out
}

/// Writes the first `k` lanes of `v` to `p`.
///
/// # Safety
/// AVX2; `p` valid for writing `k ≤ 4` values.
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) unsafe fn store(p: *mut f64, k: usize, v: V) {
    // SAFETY: the caller's contract; `MASKS[k]` holds 4 `i64`.
    unsafe {
        let m = _mm256_loadu_si256(MASKS[k].as_ptr().cast());
        _mm256_maskstore_pd(p, m, _mm256_loadu_pd(v.as_ptr()));
    }
}

/// `(v₀ + v₁) + (v₂ + v₃)`: `[v₀ v₂] + [v₁ v₃]`, then the two halves.
///
/// # Safety
/// AVX2.
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) unsafe fn hsum(v: V) -> f64 {
    // SAFETY: `v` holds 4 `f64`.
    let v = unsafe { _mm256_loadu_pd(v.as_ptr()) };
    let (lo, hi) = (_mm256_castpd256_pd128(v), _mm256_extractf128_pd::<1>(v));
    let s = _mm_add_pd(_mm_unpacklo_pd(lo, hi), _mm_unpackhi_pd(lo, hi));
    _mm_cvtsd_f64(s) + _mm_cvtsd_f64(_mm_unpackhi_pd(s, s))
}

/// `numeric::max_abs(0.0, v)`. `vmaxpd(x, l)` returns its second operand `l` when `x` is NaN,
/// as `f64::max` ignores a NaN; `l` starts at 0 and only takes values of `|v_i|` that are not
/// NaN, and every `|v_i|` is `+0` or more, so the maximum and its sign are those of the fold.
///
/// # Safety
/// AVX2.
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) unsafe fn max_abs0(v: &[f64]) -> f64 {
    let (chunks, rest) = v.as_chunks::<4>();
    let sign = _mm256_set1_pd(-0.0);
    let mut l = _mm256_setzero_pd();
    for c in chunks {
        // SAFETY: `c` holds 4 `f64`.
        let x = _mm256_andnot_pd(sign, unsafe { _mm256_loadu_pd(c.as_ptr()) });
        l = _mm256_max_pd(x, l);
    }
    let mut lanes = [0.0; 4];
    // SAFETY: `lanes` holds 4 `f64`.
    unsafe { _mm256_storeu_pd(lanes.as_mut_ptr(), l) };
    let mut r = lanes[0].max(lanes[1]).max(lanes[2].max(lanes[3]));
    for &x in rest {
        r = r.max(x.abs());
    }
    r
}
