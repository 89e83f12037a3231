//! Floating-point primitives with a fixed order of operations — a dot product, `max |v|` and
//! a branch-free exponential — written so that the compiler can vectorise them (their results
//! do not depend on the instruction set: without fast-math the compiler never reorders
//! floating-point operations).

/// `max(acc, max_i |v_i|)` with `f64::max` (NaNs ignored). The maximum is exact and
/// order-independent, so four independent lanes give the same value as a sequential fold.
#[inline(always)]
pub(crate) fn max_abs(acc: f64, v: &[f64]) -> f64 {
    let mut l = [acc; 4];
    let (chunks, rest) = v.as_chunks::<4>();
    for c in chunks {
        for j in 0..4 {
            l[j] = l[j].max(c[j].abs());
        }
    }
    for &x in rest {
        l[0] = l[0].max(x.abs());
    }
    l[0].max(l[1]).max(l[2].max(l[3]))
}

/// 1.5·2^52: adding it rounds to an integer, which then sits in the low mantissa bits.
pub(crate) const EXP_SHIFT: f64 = 6_755_399_441_055_744.0;
/// `ln 2 = LN2_HI + LN2_LO` (fdlibm's split): `LN2_HI` has 32 significant bits, so `k·LN2_HI`
/// is exact for `|k| < 2^21`.
pub(crate) const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
/// See [`LN2_HI`].
pub(crate) const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
/// `1/i!` for `i = 2..=13`: `e^r = 1 + r + r²·Σ EXP_C[i−2]·r^{i−2}`.
pub(crate) const EXP_C: [f64; 12] = [
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5_040.0,
    1.0 / 40_320.0,
    1.0 / 362_880.0,
    1.0 / 3_628_800.0,
    1.0 / 39_916_800.0,
    1.0 / 479_001_600.0,
    1.0 / 6_227_020_800.0,
];

/// `e^x` for finite `x` in `[-700, 700]`, branch-free so that loops over it vectorise:
/// `x = k ln 2 + r` with `|r| ≤ ln 2 / 2` (Cody–Waite split of `ln 2`), `e^r` by its Taylor
/// polynomial of degree 13 (truncation error < 1e-17 relative) evaluated by Estrin's scheme,
/// scaled by `2^k` through the exponent bits. Within one unit in the last place of `f64::exp`
/// (tested); `exp_fast(0) = 1` exactly.
#[inline(always)]
pub(crate) fn exp_fast(x: f64) -> f64 {
    const SHIFT: f64 = EXP_SHIFT;
    const C: [f64; 12] = EXP_C;
    let t = x * std::f64::consts::LOG2_E + SHIFT;
    let kf = t - SHIFT;
    let r = (x - kf * LN2_HI) - kf * LN2_LO;
    // e^r = 1 + (r + r²·Σ_{i=2..13} r^{i−2} / i!), the sum by Estrin's scheme (a shallow
    // dependency tree, so that a scalar call has a short latency too).
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let (t0, t1) = (C[0] + C[1] * r, C[2] + C[3] * r);
    let (t2, t3) = (C[4] + C[5] * r, C[6] + C[7] * r);
    let (t4, t5) = (C[8] + C[9] * r, C[10] + C[11] * r);
    let (u0, u1, u2) = (t0 + t1 * r2, t2 + t3 * r2, t4 + t5 * r2);
    let tail = (u0 + u1 * r4) + u2 * r8;
    let p = 1.0 + (r + r2 * tail);
    // 2^k: k + 1023 in the exponent field (t's low bits hold k offset by SHIFT's mantissa).
    let k_bits = t.to_bits().wrapping_sub(SHIFT.to_bits());
    p * f64::from_bits(k_bits.wrapping_add(1023) << 52)
}

/// `Σ a_i b_i` over `min(len)` terms: the terms of whole groups of four in four interleaved
/// partial sums (term `i` into lane `i mod 4`), combined as `(l₀ + l₁) + (l₂ + l₃)`, then the
/// last `len mod 4` terms in order. The additions do not form one serial chain and vectorise;
/// the order is fixed, so the value is the same on every CPU.
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut l = [0.0; 4];
    // Fixed-size chunks: no division by a run-time chunk size (`chunks_exact` zipped is not
    // always inlined into the AVX2 entry points, and then divides).
    let ((ca, ra), (cb, rb)) = (a.as_chunks::<4>(), b.as_chunks::<4>());
    for (x, y) in ca.iter().zip(cb) {
        for j in 0..4 {
            l[j] += x[j] * y[j];
        }
    }
    let mut r = (l[0] + l[1]) + (l[2] + l[3]);
    for (x, y) in ra.iter().zip(rb) {
        r += x * y;
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_fast_is_accurate() {
        assert_eq!(exp_fast(0.0), 1.0);
        let mut worst: f64 = 0.0;
        let n = 200_000;
        for i in 0..=n {
            let x = -30.0 + 60.0 * i as f64 / n as f64;
            let (a, b) = (exp_fast(x), x.exp());
            worst = worst.max(((a - b) / b).abs());
        }
        for &x in &[-700.0, -300.5, -10.0, 10.0, 300.25, 700.0, 1e-300, -1e-17] {
            let (a, b) = (exp_fast(x), f64::exp(x));
            worst = worst.max(((a - b) / b).abs());
        }
        assert!(worst < 3e-16, "relative error {worst:e}");
    }

    #[test]
    fn dot_matches_sequential_sum() {
        let v: Vec<f64> = (0..23).map(|i| (i as f64 * 0.37).sin()).collect();
        let w: Vec<f64> = (0..23).map(|i| (i as f64 * 0.11).cos()).collect();
        for len in 0..v.len() {
            let s: f64 = v[..len].iter().zip(&w).map(|(a, b)| a * b).sum();
            assert!((dot(&v[..len], &w[..len]) - s).abs() < 1e-14);
        }
    }

    #[test]
    fn max_abs_matches_fold() {
        let v: Vec<f64> = (0..23)
            .map(|i| ((i * 37 % 11) as f64 - 5.3) * 1.7)
            .collect();
        for len in 0..v.len() {
            let f = v[..len].iter().fold(0.25, |a: f64, x| a.max(x.abs()));
            assert_eq!(max_abs(0.25, &v[..len]), f);
        }
    }
}
