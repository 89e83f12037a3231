//! The full-metric step (d) for kernels of more than 4 dimensions: the maths of
//! `full_step` (`fast/fused.rs`) four lanes at a time with fused multiply-adds, on the
//! RF's state in place.
//!
//! `M·D` and `D = MᵀM` are sums of whole rows of `D` and `M` scaled by one element each, read
//! four columns at a time straight from the row-major storage and accumulated in registers
//! (a vector that runs past a row's end holds the next row's first elements: those lanes are
//! computed and dropped; the last row comes from a padded copy). The element-wise step runs
//! over each row of the upper triangle from the diagonal, four columns at a time, the last
//! vector partial. The results differ from `full_step` in the last bits (one rounding per
//! multiply-add, other summation orders); they are the same on every CPU, because
//! `f64::mul_add` is correctly rounded with or without hardware FMA (the baseline copy is
//! slow, the AVX2+FMA copy is the one that runs).
//!
//! Measured on the 21-D cross (`d = 21`, meta learning): about 2× faster per step than
//! `full_step`, 25k instead of 44k instructions (a version on padded copies of the state, at
//! 21k, was only 10–15 % faster: the copies in and out cost as much as the arithmetic).
//!
//! Without hardware FMA (x86-64 CPUs without AVX2 and FMA, which then also use the baseline
//! code everywhere else) `f64::mul_add` is a library call and this step is about 10× slower
//! than on AVX2+FMA (65 µs against 2.6 µs at 21-D, measured by forcing the baseline copy):
//! the price of the same bits on every CPU.

use crate::fast::lanes::{exp4, fma, hsum, load, map2, max_abs0, mul, splat, store, sub, V};
use crate::params::Params;
use crate::update::metric::{MetricAcc, MetricScratch};

/// The smallest kernel dimension whose full-metric steps the fast path takes here.
pub(crate) const MIN_DIMS: usize = 5;

/// The length of the wide step's scratch in `MetricScratch::wide` for `nk` kernel dimensions
/// and `mlen` metric elements: [`wide_len`] for full metrics of [`MIN_DIMS`] or more, else 0.
pub(crate) fn scratch_len(nk: usize, mlen: usize) -> usize {
    if mlen == nk * nk && nk >= MIN_DIMS {
        wide_len(nk)
    } else {
        0
    }
}

/// `Σ_t s_t · row_t[c0..c1]` over the terms `(s_t, row_t)` in order (`c1 − c0 ≤ 8` vectors,
/// accumulated in registers).
#[inline(always)]
fn combine<'a>(terms: impl Iterator<Item = (f64, &'a [V])>, c0: usize, c1: usize) -> [V; 8] {
    let mut a = [splat(0.0); 8];
    for (s, row) in terms {
        let s = splat(s);
        for (acc, x) in a.iter_mut().zip(&row[c0..c1]) {
            *acc = fma(s, *x, *acc);
        }
    }
    a
}

/// Row `r` of the row-major `nk × nk` matrix `a` as `q` vectors (`4q ≥ nk` columns): in place
/// when the elements after the row reach that far (the lanes from `nk` on then hold the next
/// row and must not be used), else (the last row) the padded copy `last`.
#[inline(always)]
fn row_vectors<'a>(a: &'a [f64], nk: usize, q: usize, r: usize, last: &'a [V]) -> &'a [V] {
    let rest = a[r * nk..].as_chunks::<4>().0;
    if rest.len() >= q {
        &rest[..q]
    } else {
        &last[..q]
    }
}

/// `nk` rounded up to a multiple of 4.
#[inline(always)]
fn padded(nk: usize) -> usize {
    (nk + 3) & !3
}

/// The row stride of the scratch blocks of [`wide_step`]: a vector more than the padded row,
/// so that a vector starting at any column of a row stays in it.
fn stride(nk: usize) -> usize {
    padded(nk) + 4
}

/// The scratch of [`wide_step`] for `nk` kernel dimensions: two blocks of `nk` rows (`M·D`,
/// then `G`; `G₂`), the padded last rows of `M` and `D`, `x − c` and the diagonal of `D`.
pub(crate) fn wide_len(nk: usize) -> usize {
    let s = stride(nk);
    2 * nk * s + 2 * padded(nk) + 2 * s
}

/// The full-metric step (d) of one RF for `nk > 4`, with the arguments of `full_step`
/// (`fast/fused.rs`, there: what each is); `NK > 0` fixes `nk` at compile
/// time; `AVX` (set only where the CPU has AVX2 and FMA) takes masked loads and stores for
/// the partial vectors (the same results). Uses `ws.dx`, `ws.mdx`, `ws.row` and `ws.wide`.
///
/// `M·D` and `D = MᵀM` combine rows of `D` and `M` read in place four columns at a time (the
/// last row from a padded copy); the element-wise step runs over each row of the upper
/// triangle in place, four columns at a time from the diagonal, the last vector partial.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn wide_step<const NK: usize, const AVX: bool>(
    nk: usize,
    p: &Params,
    m: &mut [f64],
    d: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
    acc: MetricAcc,
    dwdq: f64,
    ddwdqdq: f64,
    ws: &mut MetricScratch,
) {
    let nk = if NK > 0 { NK } else { nk };
    let (nkp, nn, s) = (padded(nk), nk * nk, stride(nk));
    let q = nkp / 4;
    let (m, d, alpha, b, hm) = (
        &mut m[..nn],
        &mut d[..nn],
        &mut alpha[..nn],
        &mut b[..nn],
        &mut hm[..nn],
    );
    let wide = &mut ws.wide[..wide_len(nk)];
    let (gb, rest) = wide.split_at_mut(nk * s);
    let (ggb, rest) = rest.split_at_mut(nk * s);
    let (m_last, rest) = rest.split_at_mut(nkp);
    let (d_last, rest) = rest.split_at_mut(nkp);
    let (dxp, ddp) = rest.split_at_mut(s);
    // The lanes past `nk` are read (and multiplied by zeros): they must be finite.
    dxp[..nk].copy_from_slice(&ws.dx[..nk]);
    dxp[nk..].fill(0.0);
    for j in 0..nk {
        ddp[j] = d[j * nk + j];
    }
    ddp[nk..].fill(0.0);
    d_last[..nk].copy_from_slice(&d[nn - nk..]);

    // max |M| (exact in any order; the lower triangle is zero).
    let max_m = max_abs0::<AVX>(m);

    // Row n of M·D (the penalty gradient, from the unchanged M and D) into the first block,
    // in column blocks of up to 8 vectors held in registers.
    {
        let d_last = d_last.as_chunks::<4>().0;
        for n in 0..nk {
            let mrow = &m[n * nk..(n + 1) * nk];
            for c0 in (0..q).step_by(8) {
                let c1 = (c0 + 8).min(q);
                let terms = (n..nk).map(|i| (mrow[i], row_vectors(d, nk, q, i, d_last)));
                let a = combine(terms, c0, c1);
                gb[n * s + 4 * c0..n * s + 4 * c1].copy_from_slice(a[..c1 - c0].as_flattened());
            }
        }
    }

    let inv_n = 1.0 / acc.n as f64;
    let (ca, cb, cc) = (acc.a * inv_n, acc.b * inv_n, acc.c * inv_n);
    let (meta, rate) = (p.cfg.meta, p.cfg.meta_rate);
    let pen = p.penalty_n;
    let thr = 0.1 * max_m;
    // Three passes over the rows of the upper triangle (columns n..nk of row n, four at a
    // time), each over independent vectors, so that the long dependency chains (the
    // exponential above all) of neighbouring vectors overlap.
    // (1) M (x − c) and Σ_j M_nj² of each row (before the step).
    let (mdx, ss) = (&mut ws.mdx[..nk], &mut ws.row[..nk]);
    for n in 0..nk {
        let (mut a, mut sq) = (splat(0.0), splat(0.0));
        let mr = &m[n * nk..(n + 1) * nk];
        for c in (n..nk).step_by(4) {
            let mv = load::<AVX>(mr, c, nk - c);
            a = fma(mv, load::<AVX>(dxp, c, 4), a);
            sq = fma(mv, mv, sq);
        }
        (mdx[n], ss[n]) = (hsum::<AVX>(a), hsum::<AVX>(sq));
    }
    // (2) The gradient G (over M·D) and, with meta, the curvature G₂ (second block) and the
    // new b = ln α.
    for n in 0..nk {
        let (mdx, ss) = (splat(mdx[n]), splat(ss[n]));
        // Row n of M, h, b (from column 0) and of both scratch blocks: per-row slices let
        // the compiler drop the bounds checks of the vectors below.
        let r = n * nk..(n + 1) * nk;
        let (mr, hr, br) = (&m[r.clone()], &hm[r.clone()], &mut b[r]);
        let (gr, ggr) = (&mut gb[n * s..(n + 1) * s], &mut ggb[n * s..(n + 1) * s]);
        for c in (n..nk).step_by(4) {
            let rem = nk - c;
            let x = load::<AVX>(dxp, c, 4);
            let dqdm = mul(mul(splat(2.0), x), mdx);
            let dwdm = mul(dqdm, splat(dwdq));
            let dj2 = mul(load::<AVX>(gr, c, 4), splat(4.0 * pen));
            let g = fma(splat(ca), dj2, mul(splat(cb), dwdm));
            store::<AVX>(gr, c, 4, g);
            if meta {
                let mv = load::<AVX>(mr, c, rem);
                let ddw = fma(
                    mul(splat(ddwdqdq), dqdm),
                    dqdm,
                    mul(mul(splat(2.0 * dwdq), x), x),
                );
                let dd_ss = map2(load::<AVX>(ddp, c, 4), ss, |a, b| a + b);
                let ddj2 = mul(splat(4.0 * pen), fma(mv, mv, dd_ss));
                let gg = fma(
                    mul(splat(cc), dwdm),
                    dwdm,
                    fma(splat(ca), ddj2, mul(splat(cb), ddw)),
                );
                store::<AVX>(ggr, c, 4, gg);
                let aux =
                    mul(mul(splat(rate), g), load::<AVX>(hr, c, rem)).map(|v| v.clamp(-0.1, 0.1));
                let bn = sub(load::<AVX>(br, c, rem), aux).map(|v| v.clamp(-10.0, 10.0));
                store::<AVX>(br, c, rem, bn);
            }
        }
    }
    // (3) With meta, α = e^b and the IDBD memory h ← h·max(0, 1 − α G₂) − α G; then the step
    // on M, halving α instead where it would exceed a tenth of max |M|.
    for n in 0..nk {
        let r = n * nk..(n + 1) * nk;
        let (mr, ar, br, hr) = (
            &mut m[r.clone()],
            &mut alpha[r.clone()],
            &b[r.clone()],
            &mut hm[r],
        );
        let (gr, ggr) = (&gb[n * s..(n + 1) * s], &ggb[n * s..(n + 1) * s]);
        for c in (n..nk).step_by(4) {
            let rem = nk - c;
            let (g, mv) = (load::<AVX>(gr, c, 4), load::<AVX>(mr, c, rem));
            let a = if meta {
                let an = exp4(load::<AVX>(br, c, rem));
                let keep = fma(sub(splat(0.0), an), load::<AVX>(ggr, c, 4), splat(1.0))
                    .map(|v| v.max(0.0));
                let hn = fma(load::<AVX>(hr, c, rem), keep, sub(splat(0.0), mul(an, g)));
                store::<AVX>(hr, c, rem, hn);
                an
            } else {
                load::<AVX>(ar, c, rem)
            };
            let dm = mul(a, g);
            let an = map2(dm, a, |dm, a| if dm > thr { a * 0.5 } else { a });
            store::<AVX>(ar, c, rem, an);
            store::<AVX>(
                mr,
                c,
                rem,
                map2(dm, mv, |dm, m| if dm > thr { m } else { m - dm }),
            );
        }
    }

    // D = MᵀM from the new M: row i = Σ_{k ≤ i} M_ki · (row k of M), whole rows (below the
    // diagonal the extra terms are exact zeros, so D comes out symmetric).
    m_last[..nk].copy_from_slice(&m[nn - nk..]);
    let m_last = m_last.as_chunks::<4>().0;
    for i in 0..nk {
        for c0 in (0..q).step_by(8) {
            let c1 = (c0 + 8).min(q);
            let terms = (0..i + 1).map(|k| (m[k * nk + i], row_vectors(m, nk, q, k, m_last)));
            let a = combine(terms, c0, c1);
            let (j0, j1) = (4 * c0, (4 * c1).min(nk));
            d[i * nk + j0..i * nk + j1].copy_from_slice(&a.as_flattened()[..j1 - j0]);
        }
    }
}
