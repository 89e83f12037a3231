//! The distance-metric step (d) for a full metric `D = MᵀM` in one pass per row of `M`: the
//! derivatives (`update/metric_derivatives.rs`) and the step (`update/metric_step.rs`) fused,
//! with the same expressions in the same order (bit-identical results, checked by a test), so
//! that each row of `M` is read and written once instead of once per quantity.
//!
//! Used for kernels of up to 4 dimensions; above, `fast/wide.rs` does the same step four lanes
//! at a time and is tested against this one.

use crate::numeric::{dot, max_abs};
use crate::params::Params;
use crate::update::metric::{MetricAcc, MetricScratch};
use crate::update::metric_step::{exp_into, libm_exp, mtm, Coef};

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
        libm_exp: libm_exp(nk),
    };
    let thr = 0.1 * c.max_m;
    let dx = &ws.dx[..nk];
    for n in 0..nk {
        ws.mdx[n] = dot(&m[n * nk + n..(n + 1) * nk], &dx[n..]);
    }
    let ddiag = &mut ws.ddiag[..nk];
    for (o, &v) in ddiag.iter_mut().zip(d.iter().step_by(nk + 1)) {
        *o = v;
    }
    let pen4 = 4.0 * pen;
    for n in 0..nk {
        let k0 = n * nk + n;
        let len = nk - n;
        // Row n of M·D (penalty gradient), from the unchanged D and row n of M.
        let row = &mut ws.row[n..nk];
        row.iter_mut().for_each(|v| *v = 0.0);
        for i in n..nk {
            let a = m[n * nk + i];
            for (o, &dv) in row.iter_mut().zip(&d[i * nk + n..(i + 1) * nk]) {
                *o += a * dv;
            }
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
            let dd = &ws.ddiag[n..nk];
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
            exp_into(c.libm_exp, &brow[..len], &mut arow[..len]);
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
    mtm(nk, m, d);
}
