//! The four lanes of [`super::kernel`] in one AVX2 register.

use super::{kernel, sin_cos_f64, Lanes, MAX_ANGLE};
use std::arch::x86_64::*;
use std::ops::{Add, Mul, Neg, Sub};

/// Four `f64` lanes. Only built inside functions compiled with AVX2 and FMA.
#[derive(Clone, Copy)]
struct F64x4(__m256d);

// SAFETY (every `unsafe` block below): the intrinsics need AVX2 and FMA, which the only
// caller, `sin_cos_slices`, is compiled with; they are inlined into it.
impl Add for F64x4 {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self(unsafe { _mm256_add_pd(self.0, o.0) })
    }
}

impl Sub for F64x4 {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self(unsafe { _mm256_sub_pd(self.0, o.0) })
    }
}

impl Mul for F64x4 {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Self(unsafe { _mm256_mul_pd(self.0, o.0) })
    }
}

impl Neg for F64x4 {
    type Output = Self;
    /// The sign bit flipped, as `-x` on an `f64`.
    #[inline(always)]
    fn neg(self) -> Self {
        Self(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
    }
}

impl Lanes for F64x4 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Self(unsafe { _mm256_set1_pd(x) })
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        Self(unsafe { _mm256_fmadd_pd(self.0, a.0, b.0) })
    }
    /// [`f64`]'s `quadrant` on each lane: the swap a blend on bit 0 of `n`, the signs bit 1 of
    /// `n` and of `n + 1` moved to the sign bit.
    #[inline(always)]
    fn quadrant(big: Self, s: Self, c: Self) -> (Self, Self) {
        unsafe {
            let n = _mm256_castpd_si256(big.0);
            let one = _mm256_set1_epi64x(1);
            let two = _mm256_set1_epi64x(2);
            let odd = _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(n, one), one));
            let (a, b) = (
                _mm256_blendv_pd(s.0, c.0, odd),
                _mm256_blendv_pd(c.0, s.0, odd),
            );
            let sin_sign = _mm256_slli_epi64::<62>(_mm256_and_si256(n, two));
            let cos_sign = _mm256_slli_epi64::<62>(_mm256_and_si256(_mm256_add_epi64(n, one), two));
            (
                Self(_mm256_xor_pd(a, _mm256_castsi256_pd(sin_sign))),
                Self(_mm256_xor_pd(b, _mm256_castsi256_pd(cos_sign))),
            )
        }
    }
}

/// Lane masks: the first `k` lanes enabled (the sign bit set).
static MASKS: [[i64; 4]; 5] = [
    [0, 0, 0, 0],
    [-1, 0, 0, 0],
    [-1, -1, 0, 0],
    [-1, -1, -1, 0],
    [-1, -1, -1, -1],
];

/// [`super::sin_cos_slices`]: `sin` and `cos` of length `q.len()` rounded up to 4.
///
/// # Safety
/// AVX2 and FMA.
#[target_feature(enable = "avx2,fma")]
pub(super) unsafe fn sin_cos_slices(q: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    assert!(sin.len() >= q.len().next_multiple_of(4) && cos.len() >= sin.len());
    let abs = _mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX));
    let max = _mm256_set1_pd(MAX_ANGLE);
    let chunks = sin.chunks_exact_mut(4).zip(cos.chunks_exact_mut(4));
    for (i, (s4, c4)) in chunks.take(q.len().div_ceil(4)).enumerate() {
        let k = (q.len() - 4 * i).min(4);
        // SAFETY: lanes `4i .. 4i + k` of `q` exist; `s4` and `c4` hold 4 values.
        unsafe {
            let mask = _mm256_loadu_si256(MASKS[k].as_ptr().cast());
            let x = _mm256_maskload_pd(q.as_ptr().add(4 * i), mask);
            let (s, c) = kernel(F64x4(x));
            _mm256_storeu_pd(s4.as_mut_ptr(), s.0);
            _mm256_storeu_pd(c4.as_mut_ptr(), c.0);
            // Lanes beyond `MAX_ANGLE` or not finite (the comparison is false for NaN).
            let in_range = _mm256_cmp_pd::<_CMP_LE_OQ>(_mm256_and_pd(x, abs), max);
            if _mm256_movemask_pd(in_range) != 0b1111 {
                for j in 0..k {
                    (s4[j], c4[j]) = sin_cos_f64(q[4 * i + j]);
                }
            }
        }
    }
}
