//! `sin q` and `cos q` of the joint angles, four at a time (issue 31: the C library's `sincos`,
//! once per joint, was a fifth of a `sarcos7` CRBA call).
//!
//! `q = n π/2 + (y₀ + y₁)` with `n` the nearest integer to `2q/π` and `π/2` in three parts
//! (Cody and Waite with fused multiply-adds: `q − n π/2₁` is exact, the other two parts carried
//! into the tail `y₁`), then fdlibm's kernels `sin(y₀ + y₁)` and `cos(y₀ + y₁)` on `|y₀| ≤ π/4`
//! (minimax polynomials of degree 13 and 14, evaluated by Estrin's scheme), swapped and signed
//! by `n mod 4`. One generic text ([`kernel`]) runs on four AVX2 lanes ([`avx2`]) or on one
//! `f64`; every step is an IEEE operation with one rounding (`mul_add` is a fused multiply-add
//! in both, in software where the CPU has none), so every copy gives the same bits on every
//! CPU. Beyond `|q| ≤ 10⁶` rad (and for a non-finite `q`) the standard library's `sin_cos` is
//! used. Distance to the standard library (glibc): at most 1 unit in the last place (tests).

#[cfg(target_arch = "x86_64")]
mod avx2;

use std::ops::{Add, Mul, Neg, Sub};

/// `1.5 · 2⁵²`: `(x + TOINT) − TOINT` rounds `|x| < 2⁵¹` to the nearest integer (ties to even).
const TOINT: f64 = 1.5 / f64::EPSILON;
/// `2/π`.
const INV_PIO2: f64 = f64::from_bits(0x3FE4_5F30_6DC9_C883);
/// `π/2 = PIO2_1 + PIO2_2 + PIO2_3 + O(10⁻⁴⁹)`, each part the nearest double to the rest.
const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5444_2D18);
const PIO2_2: f64 = f64::from_bits(0x3C91_A626_3314_5C07);
const PIO2_3: f64 = f64::from_bits(0xB91F_1976_B7ED_8FBC);
/// Largest `|q|` reduced here (`n < 2²⁰`; the reduction error `n · 10⁻⁴⁹` stays far below
/// the closest a double comes to a multiple of `π/2`, ≈ `2⁻⁶²`).
const MAX_ANGLE: f64 = 1.0e6;

/// `sin(y₀+y₁) ≈ y₀ + y₀³ (S₀ + S₁ z + … + S₅ z⁵)`, `z = y₀²`: fdlibm's `__kernel_sin`.
const S: [f64; 6] = [
    f64::from_bits(0xBFC5_5555_5555_5549),
    f64::from_bits(0x3F81_1111_1110_F8A6),
    f64::from_bits(0xBF2A_01A0_19C1_61D5),
    f64::from_bits(0x3EC7_1DE3_57B1_FE7D),
    f64::from_bits(0xBE5A_E5E6_8A2B_9CEB),
    f64::from_bits(0x3DE5_D93A_5ACF_D57C),
];
/// `cos(y₀+y₁) ≈ 1 − z/2 + z² (C₀ + C₁ z + … + C₅ z⁵)`: fdlibm's `__kernel_cos`.
const C: [f64; 6] = [
    f64::from_bits(0x3FA5_5555_5555_554C),
    f64::from_bits(0xBF56_C16C_16C1_5177),
    f64::from_bits(0x3EFA_01A0_19CB_1590),
    f64::from_bits(0xBE92_7E4F_809C_52AD),
    f64::from_bits(0x3E21_EE9E_BDB4_B1C4),
    f64::from_bits(0xBDA8_FAE9_BE88_38D4),
];

/// `(sin q, cos q)`, the bits of [`sin_cos_slices`].
pub fn sin_cos(q: f64) -> (f64, f64) {
    let (mut s, mut c) = ([0.0; 4], [0.0; 4]);
    sin_cos_slices(&[q], &mut s, &mut c);
    (s[0], c[0])
}

/// `sin[i] = sin q_i`, `cos[i] = cos q_i`, four angles at a time; `sin` and `cos` hold at
/// least `q.len()` rounded up to a multiple of 4 (the padding is overwritten). With AVX2 and
/// FMA where the CPU has them.
#[inline]
pub fn sin_cos_slices(q: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    let len = q.len().next_multiple_of(4);
    let (sin, cos) = (&mut sin[..len], &mut cos[..len]);
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU supports AVX2 and FMA (checked above); the lengths are checked.
        return unsafe { avx2::sin_cos_slices(q, sin, cos) };
    }
    for ((&x, s), c) in q.iter().zip(sin).zip(cos) {
        (*s, *c) = sin_cos_f64(x);
    }
}

/// One angle with the `f64` copy of [`kernel`], or the standard library's beyond `MAX_ANGLE`.
#[inline]
fn sin_cos_f64(q: f64) -> (f64, f64) {
    if q.abs() <= MAX_ANGLE {
        kernel(q)
    } else {
        q.sin_cos()
    }
}

/// What [`kernel`] needs of its lanes: the arithmetic (IEEE, one rounding each), a fused
/// multiply-add and the quadrant's swap and signs.
trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    fn splat(x: f64) -> Self;
    /// `self · a + b` with one rounding.
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// `(sin, cos)` in quadrant `n mod 4`, `n` in the low bits of `big`: `(s, c)`, `(c, −s)`,
    /// `(−s, −c)`, `(−c, s)`.
    fn quadrant(big: Self, s: Self, c: Self) -> (Self, Self);
}

impl Lanes for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        f64::mul_add(self, a, b)
    }
    #[inline(always)]
    fn quadrant(big: Self, s: Self, c: Self) -> (Self, Self) {
        let n = big.to_bits();
        let (a, b) = if n & 1 == 0 { (s, c) } else { (c, s) };
        (
            f64::from_bits(a.to_bits() ^ ((n & 2) << 62)),
            f64::from_bits(b.to_bits() ^ (((n + 1) & 2) << 62)),
        )
    }
}

/// `(sin q, cos q)` for `|q| ≤ MAX_ANGLE`, lane by lane, without branches.
#[inline(always)]
fn kernel<L: Lanes>(q: L) -> (L, L) {
    let k = L::splat;
    // n = round(2q/π); `big` holds n mod 2⁵¹ in its low bits.
    let big = q.mul_add(k(INV_PIO2), k(TOINT));
    let n = big - k(TOINT);
    // y₀ + y₁ = q − n π/2: `q − n PIO2_1` is exact (a multiple of 2⁻⁵³ below 1 for n ≠ 0),
    // `n PIO2_2` is split exactly into `hi + lo` and the subtraction of `hi` carried (2Sum).
    let r = (-n).mul_add(k(PIO2_1), q);
    let hi = n * k(PIO2_2);
    let lo = n.mul_add(k(PIO2_2), -hi) + n * k(PIO2_3);
    let y0 = r - hi;
    let back = y0 - r;
    let y1 = ((r - (y0 - back)) + (-hi - back)) - lo;
    // sin(y₀+y₁) = y₀ + y₀³ P(z) + y₁ (1 − z/2) and cos(y₀+y₁) = (1 − z/2) + z² Q(z) − y₀ y₁,
    // z = y₀², the rounding of 1 − z/2 carried (fdlibm's `__kernel_sin`, `__kernel_cos`).
    let z = y0 * y0;
    let z2 = z * z;
    let hz = k(0.5) * z;
    let sin_tail = (-hz).mul_add(y1, y1);
    let sin = (z * y0).mul_add(estrin(&S, z, z2), sin_tail) + y0;
    let one_hz = k(1.0) - hz;
    let cos_tail = (-y0).mul_add(y1, (k(1.0) - one_hz) - hz);
    let cos = one_hz + z2.mul_add(estrin(&C, z, z2), cos_tail);
    L::quadrant(big, sin, cos)
}

/// `c₀ + c₁ z + … + c₅ z⁵` as `(c₀ + c₁ z) + z² (c₂ + c₃ z) + z⁴ (c₄ + c₅ z)` (Estrin: three
/// multiply-adds deep instead of Horner's five), `z2 = z²`.
#[inline(always)]
fn estrin<L: Lanes>(c: &[f64; 6], z: L, z2: L) -> L {
    let k = L::splat;
    let low = z.mul_add(k(c[1]), k(c[0]));
    let mid = z.mul_add(k(c[3]), k(c[2]));
    let high = z.mul_add(k(c[5]), k(c[4]));
    (z2 * z2).mul_add(high, z2.mul_add(mid, low))
}

#[cfg(test)]
mod tests;
