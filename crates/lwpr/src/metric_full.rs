//! The distance-metric step (d) for a full metric `D = MᵀM` in one pass per row of `M`:
//! the derivatives of [`crate::metric::derivatives`] and the step of [`crate::metric::step`]
//! fused, with the same expressions in the same order (bit-identical results, checked by a
//! test), so that each row of `M` is read and written once instead of once per quantity.
//! The cubic-cost products `M·D` and `MᵀM` run on padded rows (stride a multiple of 4).

use crate::metric::{Coef, MetricAcc, MetricScratch};
use crate::params::Params;
use crate::simd::{dot, max_abs};

/// The row stride of the padded buffers: `nk` rounded up to a multiple of 4.
#[inline(always)]
pub(crate) fn padded(nk: usize) -> usize {
    (nk + 3) & !3
}

/// `y ← 0 + Σ_t coefs[t]·x_t` where `x_t = src[t·stride..][..y.len()]`, adding the terms to
/// each element in the order `t = 0, 1, …` (so exactly as zeroing `y` and then `y += c·x` row
/// after row), four rows per pass over `y` to cut loop overhead and loads/stores of `y`.
/// `coefs` must not be empty.
#[inline(always)]
pub(crate) fn set_rows(y: &mut [f64], coefs: &[f64], src: &[f64], stride: usize) {
    let len = y.len();
    let mut t = 0;
    let mut first = true;
    while t + 4 <= coefs.len() {
        let (c0, c1, c2, c3) = (coefs[t], coefs[t + 1], coefs[t + 2], coefs[t + 3]);
        let x0 = &src[t * stride..][..len];
        let x1 = &src[(t + 1) * stride..][..len];
        let x2 = &src[(t + 2) * stride..][..len];
        let x3 = &src[(t + 3) * stride..][..len];
        if first {
            for j in 0..len {
                y[j] = (((0.0 + c0 * x0[j]) + c1 * x1[j]) + c2 * x2[j]) + c3 * x3[j];
            }
            first = false;
        } else {
            for j in 0..len {
                y[j] = (((y[j] + c0 * x0[j]) + c1 * x1[j]) + c2 * x2[j]) + c3 * x3[j];
            }
        }
        t += 4;
    }
    while t < coefs.len() {
        let c = coefs[t];
        let x = &src[t * stride..][..len];
        if first {
            for j in 0..len {
                y[j] = 0.0 + c * x[j];
            }
            first = false;
        } else {
            for j in 0..len {
                y[j] += c * x[j];
            }
        }
        t += 1;
    }
}

/// Copies the `nk × nk` row-major `src` into `dst` with row stride `padded(nk)`. The padding
/// columns are not written: they are zero from allocation and nothing else writes them (the
/// padded buffers hold only copies made here, except `pad_b` which is written whole).
#[inline(always)]
pub(crate) fn pad_rows(nk: usize, src: &[f64], dst: &mut [f64]) {
    let nkp = padded(nk);
    for r in 0..nk {
        let d = &mut dst[r * nkp..(r + 1) * nkp];
        d[..nk].copy_from_slice(&src[r * nk..(r + 1) * nk]);
        debug_assert!(d[nk..].iter().all(|&v| v == 0.0));
    }
}

/// The full-metric step (d) of one RF: with `ws.dx = x − c` and the kernel derivatives
/// `dwdq`, `ddwdqdq` at the sample, the output sums `acc` (non-empty) and `pen = γ/n`, updates
/// `M` (upper-triangular, row-major), `α`, `b = ln α`, the IDBD memory `hm`, then `D = MᵀM`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn full_step(
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
    let nn = nk * nk;
    let (m, d, alpha, b, hm) = (
        &mut m[..nn],
        &mut d[..nn],
        &mut alpha[..nn],
        &mut b[..nn],
        &mut hm[..nn],
    );
    let meta = p.cfg.meta;
    let pen = p.penalty_n;
    let inv_n = 1.0 / acc.n as f64;
    let mut max_m: f64 = 0.0;
    for n in 0..nk {
        max_m = max_abs(max_m, &m[n * nk + n..(n + 1) * nk]);
    }
    let c = Coef {
        a: acc.a * inv_n,
        b: acc.b * inv_n,
        c: acc.c * inv_n,
        meta,
        rate: p.cfg.meta_rate,
        max_m,
        libm_exp: crate::metric::libm_exp(nk),
    };
    let thr = 0.1 * c.max_m;
    let dx = &ws.dx[..nk];
    for n in 0..nk {
        ws.mdx[n] = dot(&m[n * nk + n..(n + 1) * nk], &dx[n..]);
    }
    let nkp = padded(nk);
    // Up to 4 dimensions (constants in the update's small-input copies) the plain loops unroll
    // completely and padding would only add work.
    let small = nk <= 4;
    if !small {
        pad_rows(nk, d, &mut ws.pad_a);
    }
    let ddiag = &mut ws.pad_b[..nk];
    for (o, &v) in ddiag.iter_mut().zip(d.iter().step_by(nk + 1)) {
        *o = v;
    }
    let pen4 = 4.0 * pen;
    for n in 0..nk {
        let k0 = n * nk + n;
        let len = nk - n;
        // Row n of M·D (penalty gradient), from the unchanged D and row n of M.
        if small {
            let row = &mut ws.row[n..nk];
            row.iter_mut().for_each(|v| *v = 0.0);
            for i in n..nk {
                let a = m[n * nk + i];
                for (o, &dv) in row.iter_mut().zip(&d[i * nk + n..(i + 1) * nk]) {
                    *o += a * dv;
                }
            }
        } else {
            let a0 = n & !3;
            set_rows(
                &mut ws.row[a0..nkp],
                &m[k0..(n + 1) * nk],
                &ws.pad_a[n * nkp + a0..],
                nkp,
            );
        }
        let md = &ws.row[n..nk];
        let mdx_n = ws.mdx[n];
        let dxr = &dx[n..];
        let g = &mut ws.dwdm[..len];
        let gg = &mut ws.ddw[..len];
        let (mrow, arow, brow, hrow) = (
            &mut m[k0..k0 + len],
            &mut alpha[k0..k0 + len],
            &mut b[k0..k0 + len],
            &mut hm[k0..k0 + len],
        );
        if meta {
            let ss: f64 = mrow.iter().map(|v| v * v).sum();
            let dd = &ws.pad_b[n..nk];
            for j in 0..len {
                let x = dxr[j];
                let dj2 = md[j] * pen4;
                let dwdm = 2.0 * x * mdx_n * dwdq;
                let dqdm = 2.0 * x * mdx_n;
                let ddw = ddwdqdq * dqdm * dqdm + 2.0 * dwdq * x * x;
                let mv = mrow[j];
                let ddj2 = 4.0 * pen * (dd[j] + ss + mv * mv);
                let gj = c.a * dj2 + c.b * dwdm;
                g[j] = gj;
                gg[j] = c.a * ddj2 + c.b * ddw + c.c * dwdm * dwdm;
                let aux = (c.rate * gj * hrow[j]).clamp(-0.1, 0.1);
                brow[j] = (brow[j] - aux).clamp(-10.0, 10.0);
            }
            crate::metric::exp_into(c.libm_exp, &brow[..len], &mut arow[..len]);
            for j in 0..len {
                let a = arow[j];
                hrow[j] = hrow[j] * (1.0 - a * gg[j]).max(0.0) - a * g[j];
            }
        } else {
            for j in 0..len {
                let dj2 = md[j] * pen4;
                let dwdm = 2.0 * dxr[j] * mdx_n * dwdq;
                g[j] = c.a * dj2 + c.b * dwdm;
            }
        }
        for j in 0..len {
            let dm = arow[j] * g[j];
            let halve = dm > thr;
            arow[j] = if halve { arow[j] * 0.5 } else { arow[j] };
            mrow[j] = if halve { mrow[j] } else { mrow[j] - dm };
        }
    }
    mtm(nk, m, d, &mut ws.pad_a, &mut ws.pad_b, &mut ws.row);
}

/// `D = MᵀM` for the upper-triangular `M` (row-major, `nk × nk`): row `i` of `D` as
/// `Σ_{k≤i} M_ki · (row k of M)` (each element sums the same terms in the same order as
/// `Σ_{k≤i} M_ki M_kj`), on padded rows from the multiple of 4 at or below `i` so every vector
/// operation is whole; the upper triangle is then copied out and mirrored.
#[inline(always)]
pub(crate) fn mtm(
    nk: usize,
    m: &[f64],
    d: &mut [f64],
    mp: &mut [f64],
    dp: &mut [f64],
    col: &mut [f64],
) {
    let nkp = padded(nk);
    let (m, d) = (&m[..nk * nk], &mut d[..nk * nk]);
    if nk <= 4 {
        for i in 0..nk {
            for j in i..nk {
                let mut v = 0.0;
                for k in 0..=i {
                    v += m[k * nk + i] * m[k * nk + j];
                }
                d[i * nk + j] = v;
                d[j * nk + i] = v;
            }
        }
        return;
    }
    pad_rows(nk, m, mp);
    for i in 0..nk {
        let a0 = i & !3;
        // Column i of M down to the diagonal (`..i + 1`: a `..=i` index is not inlined).
        let col = &mut col[..i + 1];
        for (c, &v) in col.iter_mut().zip(m[i..].iter().step_by(nk)) {
            *c = v;
        }
        set_rows(&mut dp[i * nkp + a0..(i + 1) * nkp], col, &mp[a0..], nkp);
    }
    for i in 0..nk {
        let src = &dp[i * nkp + i..i * nkp + nk];
        d[i * nk + i..(i + 1) * nk].copy_from_slice(src);
        // Column i below the diagonal.
        for j in i + 1..nk {
            d[j * nk + i] = src[j - i];
        }
    }
}
