//! The x86-64 kernels of [`crate::stats::Stats::flush`]: [`GROUP`] blocks of [`LANES`] rows
//! held in vector registers through all held samples (AVX-512: one register per block, the whole
//! group at once; AVX2: two, half the group at a time). Each lane gets the portable kernel's operations in its
//! order — separate IEEE multiplies and adds, never fused — so the same bits (tested in
//! `held.rs`).

use crate::held::{Group, Held, Kernel, GROUP, LANES, PAD};
use crate::simd::{mask4, unroll};
use std::arch::x86_64::*;

/// Blocks per pass of the AVX2 kernels: half a group, so that the accumulators (two registers
/// per block) and the operands fit the 16 AVX2 registers. With the whole group at once, 16
/// accumulators spilled on every held sample (`gram_avx2` was 18 % of a sarcos7 training run
/// on an AMD EPYC without AVX-512). The passes read the held samples twice, from the L1 cache.
const PASS: usize = GROUP / 2;

/// The accumulators of one pass: block `b + g` in registers `2g` (rows 0–3) and `2g + 1` (4–7).
type Acc = [__m256d; 2 * PASS];

/// [`crate::simd::unroll`] over the [`PASS`] blocks of a pass.
macro_rules! unroll_pass {
    ($g:ident => $body:block) => {{
        unroll!(@ $g $body 0 1 2 3)
    }};
}

/// The mask of half `k` (rows `4k..4k + 4`) of a block with `len` rows.
#[inline(always)]
unsafe fn mask(len: usize, k: usize) -> __m256i {
    mask4(len.saturating_sub(4 * k).min(4))
}

/// Multiplies every accumulator by `f` (a held sample's rescaling; nothing when 1).
#[inline(always)]
unsafe fn rescale(acc: &mut Acc, f: f64) {
    if f != 1.0 {
        let f = _mm256_set1_pd(f);
        unroll_pass!(g => {
            acc[2 * g] = _mm256_mul_pd(acc[2 * g], f);
            acc[2 * g + 1] = _mm256_mul_pd(acc[2 * g + 1], f);
        });
    }
}

/// The entries of the pass's blocks `b..b + PASS` (zeros past a block's rows). `t` is checked
/// against `m` by the caller.
#[inline(always)]
unsafe fn load(t: &Group, m: &[f64], b: usize) -> Acc {
    let mut acc = [_mm256_setzero_pd(); 2 * PASS];
    unroll_pass!(g => {
        let ptr = m.as_ptr().add(t.off[b + g]);
        if t.len[b + g] == LANES {
            acc[2 * g] = _mm256_loadu_pd(ptr);
            acc[2 * g + 1] = _mm256_loadu_pd(ptr.add(4));
        } else {
            acc[2 * g] = _mm256_maskload_pd(ptr, mask(t.len[b + g], 0));
            acc[2 * g + 1] = _mm256_maskload_pd(ptr.add(4), mask(t.len[b + g], 1));
        }
    });
    acc
}

/// Stores the pass's blocks among the group's first `t.n` back into `m`.
#[inline(always)]
unsafe fn store(t: &Group, acc: &Acc, m: &mut [f64], b: usize) {
    unroll_pass!(g => {
        let ptr = m.as_mut_ptr().add(t.off[b + g]);
        if b + g < t.n && t.len[b + g] == LANES {
            _mm256_storeu_pd(ptr, acc[2 * g]);
            _mm256_storeu_pd(ptr.add(4), acc[2 * g + 1]);
        } else if b + g < t.n {
            _mm256_maskstore_pd(ptr, mask(t.len[b + g], 0), acc[2 * g]);
            _mm256_maskstore_pd(ptr.add(4), mask(t.len[b + g], 1), acc[2 * g + 1]);
        }
    });
}

/// Checks what the kernels' unchecked reads rely on: every block lies in `m`, reads `φ` rows
/// `row..row + LANES` within a held sample's `p + PAD` values, and its column is a `φ` index
/// (`G`) or a `u` index (`C`, `cols = d`); the held vectors have their lengths.
fn check(t: &Group, h: &Held, p: usize, cols: usize, d: usize, m: &[f64]) {
    for g in 0..GROUP {
        assert!(t.len[g] >= 1 && t.len[g] <= LANES && t.off[g] + t.len[g] <= m.len());
        assert!(t.row[g] + LANES <= p + PAD && t.col[g] < cols);
    }
    let n = h.len();
    assert!(h.phi.len() == n * (p + PAD) && h.w.len() == n && h.u.len() == n * d);
}

/// [`crate::held`]'s `gram_group` on AVX registers, [`PASS`] blocks at a time.
#[inline(always)]
unsafe fn gram_body(t: &Group, h: &Held, p: usize, d: usize, m: &mut [f64]) {
    check(t, h, p, p, d, m);
    for b in (0..t.n).step_by(PASS) {
        let mut acc = load(t, m, b);
        for s in 0..h.len() {
            let phi = h.phi.as_ptr().add(s * (p + PAD));
            let w = *h.w.get_unchecked(s);
            rescale(&mut acc, *h.scale.get_unchecked(s));
            unroll_pass!(g => {
                let wj = _mm256_set1_pd(w * *phi.add(t.col[b + g]));
                let x = phi.add(t.row[b + g]);
                acc[2 * g] = _mm256_add_pd(acc[2 * g], _mm256_mul_pd(wj, _mm256_loadu_pd(x)));
                let x = _mm256_loadu_pd(x.add(4));
                acc[2 * g + 1] = _mm256_add_pd(acc[2 * g + 1], _mm256_mul_pd(wj, x));
            });
        }
        store(t, &acc, m, b);
    }
}

/// [`crate::held`]'s `cross_group` on AVX registers: `(w φ_i) u_k`, the product `w φ_i` first;
/// [`PASS`] blocks at a time.
#[inline(always)]
unsafe fn cross_body(t: &Group, h: &Held, p: usize, d: usize, m: &mut [f64]) {
    check(t, h, p, d, d, m);
    for b in (0..t.n).step_by(PASS) {
        let mut acc = load(t, m, b);
        for s in 0..h.len() {
            let phi = h.phi.as_ptr().add(s * (p + PAD));
            let w = _mm256_set1_pd(*h.w.get_unchecked(s));
            let u = h.u.as_ptr().add(s * d);
            rescale(&mut acc, *h.scale.get_unchecked(s));
            unroll_pass!(g => {
                let uk = _mm256_set1_pd(*u.add(t.col[b + g]));
                let x = phi.add(t.row[b + g]);
                let wx = _mm256_mul_pd(w, _mm256_loadu_pd(x));
                acc[2 * g] = _mm256_add_pd(acc[2 * g], _mm256_mul_pd(wx, uk));
                let wx = _mm256_mul_pd(w, _mm256_loadu_pd(x.add(4)));
                acc[2 * g + 1] = _mm256_add_pd(acc[2 * g + 1], _mm256_mul_pd(wx, uk));
            });
        }
        store(t, &acc, m, b);
    }
}

/// The accumulators of one group in AVX-512 registers (block `g` in register `g`).
type Acc512 = [__m512d; GROUP];

/// The mask of the first `len` of eight lanes.
#[inline(always)]
fn mask8(len: usize) -> __mmask8 {
    ((1u16 << len) - 1) as u8
}

/// [`load`] on AVX-512 registers.
#[inline(always)]
unsafe fn load512(t: &Group, m: &[f64]) -> Acc512 {
    let mut acc = [_mm512_setzero_pd(); GROUP];
    unroll!(g => {
        acc[g] = _mm512_maskz_loadu_pd(mask8(t.len[g]), m.as_ptr().add(t.off[g]));
    });
    acc
}

/// [`store`] on AVX-512 registers.
#[inline(always)]
unsafe fn store512(t: &Group, acc: &Acc512, m: &mut [f64]) {
    unroll!(g => {
        if g < t.n {
            _mm512_mask_storeu_pd(m.as_mut_ptr().add(t.off[g]), mask8(t.len[g]), acc[g]);
        }
    });
}

/// [`gram_body`] on AVX-512 registers.
#[target_feature(enable = "avx512f")]
unsafe fn gram_avx512(t: &Group, h: &Held, p: usize, d: usize, m: &mut [f64]) {
    check(t, h, p, p, d, m);
    let mut acc = load512(t, m);
    for s in 0..h.len() {
        let phi = h.phi.as_ptr().add(s * (p + PAD));
        let w = *h.w.get_unchecked(s);
        let f = *h.scale.get_unchecked(s);
        if f != 1.0 {
            let f = _mm512_set1_pd(f);
            unroll!(g => {
                acc[g] = _mm512_mul_pd(acc[g], f);
            });
        }
        unroll!(g => {
            let wj = _mm512_set1_pd(w * *phi.add(t.col[g]));
            let x = _mm512_loadu_pd(phi.add(t.row[g]));
            acc[g] = _mm512_add_pd(acc[g], _mm512_mul_pd(wj, x));
        });
    }
    store512(t, &acc, m);
}

/// [`cross_body`] on AVX-512 registers.
#[target_feature(enable = "avx512f")]
unsafe fn cross_avx512(t: &Group, h: &Held, p: usize, d: usize, m: &mut [f64]) {
    check(t, h, p, d, d, m);
    let mut acc = load512(t, m);
    for s in 0..h.len() {
        let phi = h.phi.as_ptr().add(s * (p + PAD));
        let w = _mm512_set1_pd(*h.w.get_unchecked(s));
        let u = h.u.as_ptr().add(s * d);
        let f = *h.scale.get_unchecked(s);
        if f != 1.0 {
            let f = _mm512_set1_pd(f);
            unroll!(g => {
                acc[g] = _mm512_mul_pd(acc[g], f);
            });
        }
        unroll!(g => {
            let uk = _mm512_set1_pd(*u.add(t.col[g]));
            let wx = _mm512_mul_pd(w, _mm512_loadu_pd(phi.add(t.row[g])));
            acc[g] = _mm512_add_pd(acc[g], _mm512_mul_pd(wx, uk));
        });
    }
    store512(t, &acc, m);
}

#[target_feature(enable = "avx2")]
unsafe fn gram_avx2(t: &Group, h: &Held, p: usize, d: usize, m: &mut [f64]) {
    gram_body(t, h, p, d, m)
}

#[target_feature(enable = "avx2")]
unsafe fn cross_avx2(t: &Group, h: &Held, p: usize, d: usize, m: &mut [f64]) {
    cross_body(t, h, p, d, m)
}

/// The kernels for `G` and `C` for this CPU (which must support AVX2): AVX-512 where it has
/// it, else AVX2.
pub(crate) fn kernels() -> (Kernel, Kernel) {
    if crate::simd::avx512() {
        // SAFETY: the CPU supports AVX-512F (checked just above).
        (
            |t, h, p, d, m| unsafe { gram_avx512(t, h, p, d, m) },
            |t, h, p, d, m| unsafe { cross_avx512(t, h, p, d, m) },
        )
    } else {
        kernels_avx2()
    }
}

/// The AVX2 kernels (also where the CPU has AVX-512, for the tests).
pub(crate) fn kernels_avx2() -> (Kernel, Kernel) {
    assert!(crate::simd::avx2());
    // SAFETY: the CPU supports AVX2 (asserted just above).
    (
        |t, h, p, d, m| unsafe { gram_avx2(t, h, p, d, m) },
        |t, h, p, d, m| unsafe { cross_avx2(t, h, p, d, m) },
    )
}
