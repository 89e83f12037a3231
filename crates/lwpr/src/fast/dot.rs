//! [`crate::numeric::dot`] in one AVX2 register, for the rows of a full metric's distance
//! (`distance::quad`) above 4 dimensions.
//!
//! The compiler vectorises `numeric::dot` as two 2-lane halves (lanes 0, 2 and 1, 3, so that
//! its final `(l₀ + l₁) + (l₂ + l₃)` is one vector addition), with two shuffles per term
//! group; here the four partial sums stay in one 256-bit register and are unpacked once at
//! the end. Each lane performs the same multiplications and additions in the same order, so
//! the value has the same bits (tested in `tests/dot.rs`).

/// `numeric::dot(a, b)`, bit for bit.
///
/// # Safety
/// The CPU must support AVX2 (callers check it at run time: `fast::has_avx2`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) unsafe fn dot_avx2(a: &[f64], b: &[f64]) -> f64 {
    use std::arch::x86_64::*;
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let ((ca, ra), (cb, rb)) = (a.as_chunks::<4>(), b.as_chunks::<4>());
    // l_j = (…(0 + a_j b_j) + a_{j+4} b_{j+4}) + …, lane j.
    let mut l = _mm256_setzero_pd();
    for (x, y) in ca.iter().zip(cb) {
        // SAFETY: `x` and `y` are arrays of 4 `f64`.
        let (x, y) = unsafe { (_mm256_loadu_pd(x.as_ptr()), _mm256_loadu_pd(y.as_ptr())) };
        l = _mm256_add_pd(l, _mm256_mul_pd(x, y));
    }
    // [l₀ l₁], [l₂ l₃] → [l₀ l₂] + [l₁ l₃] = [l₀ + l₁, l₂ + l₃].
    let (lo, hi) = (_mm256_castpd256_pd128(l), _mm256_extractf128_pd::<1>(l));
    let s = _mm_add_pd(_mm_unpacklo_pd(lo, hi), _mm_unpackhi_pd(lo, hi));
    let mut r = _mm_cvtsd_f64(s) + _mm_cvtsd_f64(_mm_unpackhi_pd(s, s));
    for (x, y) in ra.iter().zip(rb) {
        r += x * y;
    }
    r
}
