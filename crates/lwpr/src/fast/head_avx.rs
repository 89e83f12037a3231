//! The AVX2 form of the heads' block sums (`head/bound.rs`, `Heads::bounds`): the same
//! operations in the same order per lane, so the same values, eight RFs in one register.

use std::arch::x86_64::*;

/// Per lane `l`, `Σ_{j<n} d[j][l]·t·t` (`d` the upper halves of single-precision numbers)
/// with `t = max(|x[j] − c[j][l]| − e[j], 0)` (a NaN `t` as 0), summed in order of
/// `j`.
///
/// # Safety
/// AVX2; `n ≤ c.len()`.
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) unsafe fn sums(
    c: &[[f32; 8]],
    d: &[[u16; 8]],
    x: &[f32],
    e: &[f32],
    n: usize,
) -> [f32; 8] {
    let (c, d, x, e) = (&c[..n], &d[..n], &x[..n], &e[..n]);
    let sign = _mm256_set1_ps(-0.0);
    let zero = _mm256_setzero_ps();
    let mut s = zero;
    for j in 0..n {
        // SAFETY: each row holds 8 values.
        let (cj, dj) = unsafe {
            let dj = _mm256_cvtepu16_epi32(_mm_loadu_si128(d[j].as_ptr().cast()));
            (
                _mm256_loadu_ps(c[j].as_ptr()),
                _mm256_castsi256_ps(_mm256_slli_epi32::<16>(dj)),
            )
        };
        let t = _mm256_andnot_ps(sign, _mm256_sub_ps(_mm256_set1_ps(x[j]), cj));
        let t = _mm256_sub_ps(t, _mm256_set1_ps(e[j]));
        // `t > 0 ? t : 0`; the comparison is false for NaN.
        let t = _mm256_and_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(t, zero), t);
        s = _mm256_add_ps(s, _mm256_mul_ps(_mm256_mul_ps(dj, t), t));
    }
    let mut out = [0.0; 8];
    // SAFETY: `out` holds 8 values.
    unsafe { _mm256_storeu_ps(out.as_mut_ptr(), s) };
    out
}
