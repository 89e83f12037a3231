//! The full-metric step (d) for kernels of more than 4 dimensions: the maths of
//! [`crate::metric_full::full_step`] on padded copies of one RF's metric state, four lanes at a
//! time with fused multiply-adds.
//!
//! `M` is upper-triangular; its rows are copied into rows of stride `nkp` (a multiple of 4,
//! zero padding), so every vector operation is whole: `M·D` and `D = MᵀM` accumulate whole
//! rows in registers, the element-wise step runs from the multiple of 4 at or below the
//! diagonal with the lanes outside the upper triangle masked. The results differ from
//! `full_step` in the last bits (one rounding per multiply-add, other summation orders); they
//! are the same on every CPU, because `f64::mul_add` is correctly rounded with or without
//! hardware FMA (the baseline copy is slow, the AVX2+FMA copy is the one that runs).

use crate::metric::{MetricAcc, MetricScratch};
use crate::metric_full::padded;
use crate::params::Params;

/// Four lanes.
type V = [f64; 4];

#[inline(always)]
fn splat(x: f64) -> V {
    [x; 4]
}

#[inline(always)]
fn map2(a: V, b: V, f: impl Fn(f64, f64) -> f64) -> V {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])]
}

#[inline(always)]
fn mul(a: V, b: V) -> V {
    map2(a, b, |x, y| x * y)
}

#[inline(always)]
fn sub(a: V, b: V) -> V {
    map2(a, b, |x, y| x - y)
}

/// `a·b + c` with one rounding.
#[inline(always)]
fn fma(a: V, b: V, c: V) -> V {
    [
        a[0].mul_add(b[0], c[0]),
        a[1].mul_add(b[1], c[1]),
        a[2].mul_add(b[2], c[2]),
        a[3].mul_add(b[3], c[3]),
    ]
}

/// `(v₀ + v₁) + (v₂ + v₃)`.
#[inline(always)]
fn hsum(v: V) -> f64 {
    (v[0] + v[1]) + (v[2] + v[3])
}

/// `e^x` lane-wise for `x ∈ [−10, 10]` (the clipped `b = ln α`): the scheme of
/// [`crate::simd::exp_fast`] with fused multiply-adds (within one unit in the last place of
/// `f64::exp`, tested).
#[inline(always)]
pub(crate) fn exp4(x: V) -> V {
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
    const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
    const C: [f64; 12] = [
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
    // k = round(x / ln 2) (in t's low mantissa bits), r = x − k ln 2 (k·LN2_HI is exact).
    let t = fma(x, splat(std::f64::consts::LOG2_E), splat(SHIFT));
    let kf = sub(t, splat(SHIFT));
    let r = fma(kf, splat(-LN2_LO), fma(kf, splat(-LN2_HI), x));
    let (r2, c) = (mul(r, r), |i: usize| splat(C[i]));
    let (r4, r8) = (mul(r2, r2), mul(mul(r2, r2), mul(r2, r2)));
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

/// The scratch of [`wide_step`] for `nk` kernel dimensions (0 when the step is not used): six
/// padded `nk × nkp` blocks (`M`, `D`, `α`, `b`, IDBD memory, `M·D`) and two padded vectors
/// (`x − c`, diagonal of `D`).
pub(crate) fn wide_len(nk: usize) -> usize {
    let nkp = padded(nk);
    6 * nk * nkp + 2 * nkp
}

/// The full-metric step (d) of one RF for `nk > 4`, with the arguments of
/// [`crate::metric_full::full_step`] (there: what each is); `NK > 0` fixes `nk` at compile
/// time. Uses `ws.dx` and `ws.wide`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn wide_step<const NK: usize>(
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
    let (nkp, nn) = (padded(nk), nk * nk);
    let q = nkp / 4;
    let blk = nk * nkp;
    let (m, d, alpha, b, hm) = (
        &mut m[..nn],
        &mut d[..nn],
        &mut alpha[..nn],
        &mut b[..nn],
        &mut hm[..nn],
    );
    let wide = &mut ws.wide[..wide_len(nk)];
    let (pm, rest) = wide.split_at_mut(blk);
    let (pd, rest) = rest.split_at_mut(blk);
    let (pa, rest) = rest.split_at_mut(blk);
    let (pb, rest) = rest.split_at_mut(blk);
    let (ph, rest) = rest.split_at_mut(blk);
    let (pmd, rest) = rest.split_at_mut(blk);
    let (dxp, ddp) = rest.split_at_mut(nkp);
    // Copy the state in (the padding columns stay zero: nothing writes them).
    for r in 0..nk {
        let (src, dst) = (r * nk..(r + 1) * nk, r * nkp..r * nkp + nk);
        pm[dst.clone()].copy_from_slice(&m[src.clone()]);
        pd[dst.clone()].copy_from_slice(&d[src.clone()]);
        pa[dst.clone()].copy_from_slice(&alpha[src.clone()]);
        pb[dst.clone()].copy_from_slice(&b[src.clone()]);
        ph[dst].copy_from_slice(&hm[src]);
        ddp[r] = d[r * nk + r];
    }
    dxp[..nk].copy_from_slice(&ws.dx[..nk]);
    let (pm4, pd4) = (pm.as_chunks_mut::<4>().0, pd.as_chunks_mut::<4>().0);
    let (pa4, pb4) = (pa.as_chunks_mut::<4>().0, pb.as_chunks_mut::<4>().0);
    let (ph4, pmd4) = (ph.as_chunks_mut::<4>().0, pmd.as_chunks_mut::<4>().0);
    let (dx4, dd4) = (dxp.as_chunks::<4>().0, ddp.as_chunks::<4>().0);

    // max |M| (exact in any order; the lower triangle and the padding are zero).
    let mut mx = splat(0.0);
    for v in pm4.iter() {
        mx = map2(mx, *v, |a, x| a.max(x.abs()));
    }
    let max_m = mx[0].max(mx[1]).max(mx[2].max(mx[3]));
    // Row n of M·D (the penalty gradient, from the unchanged M and D), in column blocks of
    // up to 8 vectors held in registers.
    for n in 0..nk {
        let mrow = pm4[n * q..(n + 1) * q].as_flattened();
        for c0 in (0..q).step_by(8) {
            let c1 = (c0 + 8).min(q);
            let terms = mrow[n..nk].iter().zip(pd4[n * q..].chunks_exact(q));
            let a = combine(terms.map(|(&m, row)| (m, row)), c0, c1);
            pmd4[n * q + c0..n * q + c1].copy_from_slice(&a[..c1 - c0]);
        }
    }

    let inv_n = 1.0 / acc.n as f64;
    let (ca, cb, cc) = (acc.a * inv_n, acc.b * inv_n, acc.c * inv_n);
    let (meta, rate) = (p.cfg.meta, p.cfg.meta_rate);
    let pen = p.penalty_n;
    let thr = 0.1 * max_m;
    for n in 0..nk {
        let rows = n * q..(n + 1) * q;
        let (mrow, grow, ggrow) = (
            &mut pm4[rows.clone()],
            &mut pmd4[rows.clone()],
            &mut pd4[rows.clone()],
        );
        let (arow, brow, hrow) = (
            &mut pa4[rows.clone()],
            &mut pb4[rows.clone()],
            &mut ph4[rows],
        );
        // The vectors from the one holding the diagonal; its lanes below the diagonal are
        // computed too and restored at the end (padding lanes stay zero in `M` by themselves:
        // there `x − c`, `M·D` and hence the gradient are zero).
        let v0 = n / 4;
        let saved = (mrow[v0], arow[v0], brow[v0], hrow[v0]);
        // M (x − c) and Σ_j M_nj² of row n (before its step).
        let (mut mdx, mut ss) = (splat(0.0), splat(0.0));
        for (v, x) in mrow.iter().zip(dx4) {
            mdx = fma(*v, *x, mdx);
            ss = fma(*v, *v, ss);
        }
        let (mdx, ss) = (hsum(mdx), hsum(ss));
        // The gradient G (over M·D) and, with meta, the curvature G₂ (over the D block, no
        // longer needed) and the new b = ln α.
        for v in v0..q {
            let x = dx4[v];
            let dqdm = mul(mul(splat(2.0), x), splat(mdx));
            let dwdm = mul(dqdm, splat(dwdq));
            let dj2 = mul(grow[v], splat(4.0 * pen));
            let g = fma(splat(ca), dj2, mul(splat(cb), dwdm));
            grow[v] = g;
            if meta {
                let mv = mrow[v];
                let ddw = fma(
                    mul(splat(ddwdqdq), dqdm),
                    dqdm,
                    mul(mul(splat(2.0 * dwdq), x), x),
                );
                let dd_ss = map2(dd4[v], splat(ss), |a, b| a + b);
                let ddj2 = mul(splat(4.0 * pen), fma(mv, mv, dd_ss));
                ggrow[v] = fma(
                    mul(splat(cc), dwdm),
                    dwdm,
                    fma(splat(ca), ddj2, mul(splat(cb), ddw)),
                );
                let aux = mul(mul(splat(rate), g), hrow[v]).map(|v| v.clamp(-0.1, 0.1));
                brow[v] = sub(brow[v], aux).map(|v| v.clamp(-10.0, 10.0));
            }
        }
        // With meta, α = e^b and the IDBD memory h ← h·max(0, 1 − α G₂) − α G; then the step
        // on M, halving α instead where it would exceed a tenth of max |M|.
        for v in v0..q {
            let (g, mv) = (grow[v], mrow[v]);
            let a = if meta {
                let an = exp4(brow[v]);
                let keep = fma(sub(splat(0.0), an), ggrow[v], splat(1.0)).map(|v| v.max(0.0));
                hrow[v] = fma(hrow[v], keep, sub(splat(0.0), mul(an, g)));
                an
            } else {
                arow[v]
            };
            let dm = mul(a, g);
            arow[v] = map2(dm, a, |dm, a| if dm > thr { a * 0.5 } else { a });
            mrow[v] = map2(dm, mv, |dm, m| if dm > thr { m } else { m - dm });
        }
        for l in 0..n % 4 {
            mrow[v0][l] = saved.0[l];
            arow[v0][l] = saved.1[l];
            brow[v0][l] = saved.2[l];
            hrow[v0][l] = saved.3[l];
        }
    }

    // D = MᵀM from the new M: row i = Σ_{k ≤ i} M_ki · (row k of M), whole rows (below the
    // diagonal the extra terms are exact zeros, so D comes out symmetric).
    for i in 0..nk {
        for c0 in (0..q).step_by(8) {
            let c1 = (c0 + 8).min(q);
            let rows = pm4[..(i + 1) * q].chunks_exact(q);
            let a = combine(rows.map(|row| (row.as_flattened()[i], row)), c0, c1);
            let flat = a.as_flattened();
            let (j0, j1) = (4 * c0, (4 * c1).min(nk));
            d[i * nk + j0..i * nk + j1].copy_from_slice(&flat[..j1 - j0]);
        }
    }
    // Copy the state out.
    let (pm, pa, pb, ph) = (
        pm4.as_flattened(),
        pa4.as_flattened(),
        pb4.as_flattened(),
        ph4.as_flattened(),
    );
    for r in 0..nk {
        let (dst, src) = (r * nk..(r + 1) * nk, r * nkp..r * nkp + nk);
        m[dst.clone()].copy_from_slice(&pm[src.clone()]);
        alpha[dst.clone()].copy_from_slice(&pa[src.clone()]);
        b[dst.clone()].copy_from_slice(&pb[src.clone()]);
        hm[dst].copy_from_slice(&ph[src]);
    }
}
