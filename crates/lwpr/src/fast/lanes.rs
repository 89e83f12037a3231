//! Four `f64` lanes (`[f64; 4]`) and their operations, for the full-metric step above 4
//! dimensions (`fast/wide.rs`): written lane by lane, so that the compiler maps them onto AVX2
//! registers, with fused multiply-adds (`f64::mul_add`, correctly rounded on every CPU). With
//! `AVX` some take AVX2 intrinsics (`lanes_avx.rs`) for the same values.

#[cfg(target_arch = "x86_64")]
use crate::fast::lanes_avx;

/// Four lanes.
pub(crate) type V = [f64; 4];

#[inline(always)]
pub(crate) fn splat(x: f64) -> V {
    [x; 4]
}

#[inline(always)]
pub(crate) fn map2(a: V, b: V, f: impl Fn(f64, f64) -> f64) -> V {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])]
}

#[inline(always)]
pub(crate) fn mul(a: V, b: V) -> V {
    map2(a, b, |x, y| x * y)
}

#[inline(always)]
pub(crate) fn sub(a: V, b: V) -> V {
    map2(a, b, |x, y| x - y)
}

/// `a·b + c` with one rounding.
#[inline(always)]
pub(crate) fn fma(a: V, b: V, c: V) -> V {
    [
        a[0].mul_add(b[0], c[0]),
        a[1].mul_add(b[1], c[1]),
        a[2].mul_add(b[2], c[2]),
        a[3].mul_add(b[3], c[3]),
    ]
}

/// `(v₀ + v₁) + (v₂ + v₃)`; with `AVX` (set only where the CPU has AVX2) unpacked in
/// registers (the same value; the plain form makes the compiler keep the lanes of the sums
/// that feed it as two shuffled halves).
#[inline(always)]
pub(crate) fn hsum<const AVX: bool>(v: V) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if AVX {
        // SAFETY: `AVX` is set only where the CPU has AVX2.
        return unsafe { lanes_avx::hsum(v) };
    }
    (v[0] + v[1]) + (v[2] + v[3])
}

/// `max(0, max_i |v_i|)` as `numeric::max_abs(0.0, v)` (NaNs ignored; the same value); with
/// `AVX` four lanes in one register.
#[inline(always)]
pub(crate) fn max_abs0<const AVX: bool>(v: &[f64]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if AVX {
        // SAFETY: `AVX` is set only where the CPU has AVX2.
        return unsafe { lanes_avx::max_abs0(v) };
    }
    crate::numeric::max_abs(0.0, v)
}

/// `e^x` lane-wise for `x ∈ [−10, 10]` (the clipped `b = ln α`): the scheme of
/// [`crate::numeric::exp_fast`] with fused multiply-adds (within one unit in the last place of
/// `f64::exp`, tested).
#[inline(always)]
pub(crate) fn exp4(x: V) -> V {
    use crate::numeric::{EXP_C as C, EXP_SHIFT as SHIFT, LN2_HI, LN2_LO};
    // k = round(x / ln 2) (in t's low mantissa bits), r = x − k ln 2 (k·LN2_HI is exact).
    let t = fma(x, splat(std::f64::consts::LOG2_E), splat(SHIFT));
    let kf = sub(t, splat(SHIFT));
    let r = fma(kf, splat(-LN2_LO), fma(kf, splat(-LN2_HI), x));
    let (r2, c) = (mul(r, r), |i: usize| splat(C[i]));
    let r4 = mul(r2, r2);
    let r8 = mul(r4, r4);
    let (t0, t1, t2) = (fma(c(1), r, c(0)), fma(c(3), r, c(2)), fma(c(5), r, c(4)));
    let (t3, t4, t5) = (fma(c(7), r, c(6)), fma(c(9), r, c(8)), fma(c(11), r, c(10)));
    let (u0, u1, u2) = (fma(t1, r2, t0), fma(t3, r2, t2), fma(t5, r2, t4));
    let tail = fma(u2, r8, fma(u1, r4, u0));
    let p = fma(r2, tail, r);
    let scale = t.map(|v| {
        let k_bits = v.to_bits().wrapping_sub(SHIFT.to_bits());
        f64::from_bits(k_bits.wrapping_add(1023) << 52)
    });
    map2(p, scale, |p, s| (1.0 + p) * s)
}

/// Four elements from `s[i..]`, the lanes from `rem` on zero; with `AVX` (set only where the
/// CPU has AVX2, checked at run time) a partial vector is one masked load instead of a branch
/// per lane (the same values).
#[inline(always)]
pub(crate) fn load<const AVX: bool>(s: &[f64], i: usize, rem: usize) -> V {
    if rem >= 4 {
        s[i..i + 4].try_into().unwrap()
    } else if cfg!(target_arch = "x86_64") && AVX {
        let s = &s[i..i + rem];
        // SAFETY: `AVX` is set only where the CPU has AVX2; the mask enables the `rem` lanes
        // of `s` (masked lanes are not accessed).
        #[cfg(target_arch = "x86_64")]
        return unsafe { lanes_avx::load(s.as_ptr(), rem) };
        #[cfg(not(target_arch = "x86_64"))]
        unreachable!()
    } else {
        std::array::from_fn(|l| if l < rem { s[i + l] } else { 0.0 })
    }
}

/// Stores the first `min(rem, 4)` lanes of `v` at `s[i..]` (with `AVX`: as [`load`]).
#[inline(always)]
pub(crate) fn store<const AVX: bool>(s: &mut [f64], i: usize, rem: usize, v: V) {
    if rem >= 4 {
        s[i..i + 4].copy_from_slice(&v);
    } else if cfg!(target_arch = "x86_64") && AVX {
        let s = &mut s[i..i + rem];
        // SAFETY: as in `load`.
        #[cfg(target_arch = "x86_64")]
        unsafe {
            lanes_avx::store(s.as_mut_ptr(), rem, v)
        };
    } else {
        // Lane by lane (a loop of one store would become a call of `memcpy`).
        if rem > 0 {
            s[i] = v[0];
        }
        if rem > 1 {
            s[i + 1] = v[1];
        }
        if rem > 2 {
            s[i + 2] = v[2];
        }
    }
}
