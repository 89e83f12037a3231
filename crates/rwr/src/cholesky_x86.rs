//! The x86-64 kernels of the blocked Cholesky factorisation (`cholesky.rs`): the updates from
//! the finished columns to a panel, eight blocks of rows at a time, each block held in a
//! register through all finished columns (AVX-512: blocks of eight rows; AVX2: of four). Each
//! entry gets `a − x·l` per finished column in column order, a separate IEEE multiply and
//! subtract (never fused): the right-looking factorisation's bits (tested in `cholesky.rs`).

use crate::simd::{mask4, unroll};
use std::arch::x86_64::*;

/// Blocks updated together (independent chains, one register each).
const GROUP: usize = 8;

/// Blocks of one group: first row, column and rows (1..=8 on AVX-512, 1..=4 on AVX2); unused
/// slots repeat block 0.
struct Blocks {
    row: [usize; GROUP],
    col: [usize; GROUP],
    len: [usize; GROUP],
    n: usize,
}

/// The mask of the first `len` of eight lanes.
#[inline(always)]
fn mask8(len: usize) -> __mmask8 {
    ((1u16 << len) - 1) as u8
}

/// Applies the updates from the finished columns `0..c0` to the rows `c..p` of the columns
/// `c0 ≤ c < c1` of the column-major `p × p` matrix `m`.
///
/// # Safety
/// The CPU must support AVX-512F.
#[target_feature(enable = "avx512f")]
pub(crate) unsafe fn panel_avx512(m: &mut [f64], p: usize, c0: usize, c1: usize) {
    in_groups(m, p, c0, c1, 8, group);
}

/// [`panel_avx512`] on AVX2 registers: blocks of four rows.
///
/// # Safety
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn panel_avx2(m: &mut [f64], p: usize, c0: usize, c1: usize) {
    // The unmasked reads of the finished columns reach at most 3 rows past a column's end, into
    // the next column: inside `m` while a finished column is not the last (`c0 < p`) and the
    // matrix has at least 3 rows (the last read is at `(p − 2) p + p + 2 < p²`).
    assert!(p >= 3, "panel_avx2 needs at least 3 rows, got {p}");
    in_groups(m, p, c0, c1, 4, group_avx2);
}

/// A kernel for one group of blocks through the finished columns `0..c0` (`m`, `p`, `c0`).
type GroupKernel = unsafe fn(&mut [f64], usize, usize, &Blocks);

/// Splits the panel's columns into blocks of `rows` rows and runs `group` on each [`GROUP`] of
/// them (the last one padded with block 0).
///
/// # Safety
/// `group` must be safe to call on this CPU.
#[inline(always)]
unsafe fn in_groups(
    m: &mut [f64],
    p: usize,
    c0: usize,
    c1: usize,
    rows: usize,
    group: GroupKernel,
) {
    assert!(c0 < c1 && c1 <= p && m.len() == p * p);
    let mut b = Blocks {
        row: [0; GROUP],
        col: [0; GROUP],
        len: [0; GROUP],
        n: 0,
    };
    for c in c0..c1 {
        for i0 in (c..p).step_by(rows) {
            (b.row[b.n], b.col[b.n], b.len[b.n]) = (i0, c, (p - i0).min(rows));
            b.n += 1;
            if b.n == GROUP {
                group(m, p, c0, &b);
                b.n = 0;
            }
        }
    }
    if b.n > 0 {
        for g in b.n..GROUP {
            (b.row[g], b.col[g], b.len[g]) = (b.row[0], b.col[0], b.len[0]);
        }
        group(m, p, c0, &b);
    }
}

/// [`group`] on AVX2 registers (blocks of at most four rows). The panel's entries are loaded
/// and stored masked; the finished columns are read whole (the lanes past a block's rows are
/// computed and dropped).
#[target_feature(enable = "avx2")]
unsafe fn group_avx2(m: &mut [f64], p: usize, c0: usize, b: &Blocks) {
    debug_assert!(c0 < p);
    let base = m.as_mut_ptr();
    let mut acc = [_mm256_setzero_pd(); GROUP];
    unroll!(g => {
        let k = mask4(b.len[g]);
        acc[g] = _mm256_maskload_pd(base.add(b.col[g] * p + b.row[g]), k);
    });
    for j in 0..c0 {
        let lj = base.add(j * p);
        unroll!(g => {
            let l = _mm256_set1_pd(*lj.add(b.col[g]));
            let x = _mm256_loadu_pd(lj.add(b.row[g]));
            acc[g] = _mm256_sub_pd(acc[g], _mm256_mul_pd(x, l));
        });
    }
    unroll!(g => {
        if g < b.n {
            let k = mask4(b.len[g]);
            _mm256_maskstore_pd(base.add(b.col[g] * p + b.row[g]), k, acc[g]);
        }
    });
}

/// One group of blocks through the finished columns `0..c0`. Every read and write stays in
/// `m`: a block's rows lie in `0..p` (masked lanes are neither read nor written), its column
/// below `p`.
#[target_feature(enable = "avx512f")]
unsafe fn group(m: &mut [f64], p: usize, c0: usize, b: &Blocks) {
    let base = m.as_mut_ptr();
    let mut acc = [_mm512_setzero_pd(); GROUP];
    let mut k = [0u8; GROUP];
    unroll!(g => {
        k[g] = mask8(b.len[g]);
        acc[g] = _mm512_maskz_loadu_pd(k[g], base.add(b.col[g] * p + b.row[g]));
    });
    for j in 0..c0 {
        let lj = base.add(j * p);
        unroll!(g => {
            let l = _mm512_set1_pd(*lj.add(b.col[g]));
            let x = _mm512_maskz_loadu_pd(k[g], lj.add(b.row[g]));
            acc[g] = _mm512_sub_pd(acc[g], _mm512_mul_pd(x, l));
        });
    }
    unroll!(g => {
        if g < b.n {
            _mm512_mask_storeu_pd(base.add(b.col[g] * p + b.row[g]), k[g], acc[g]);
        }
    });
}
