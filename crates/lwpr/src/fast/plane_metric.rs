//! The full-metric step (d) of a 2-D kernel (a compile-time constant): the fused step of
//! `fast/fused.rs` at `nk = 2` on fixed-size arrays, with the same expressions in the same order
//! (the same bits; a test checks whole models against the reference); `max |M|` and `D = MᵀM`
//! by the general code.
//!
//! `M` is upper-triangular and row-major: its free elements are `M₀₀`, `M₀₁` (row 0, indices
//! 0 and 1) and `M₁₁` (row 1, index 3). The rows' updates are independent (each reads only its
//! own row of `M`, `D` before the step and `M (x − c)` before the step), so they are written as
//! one pass over the three elements.

use crate::numeric::max_abs;
use crate::params::Params;
use crate::update::metric::MetricAcc;
use crate::update::metric_step::mtm;

/// One RF's metric state (`2 × 2` row-major; `M`, `α`, `b`, `hm` use the upper triangle).
pub(crate) struct MetricState<'a> {
    pub m: &'a mut [f64; 4],
    pub d: &'a mut [f64; 4],
    pub alpha: &'a mut [f64; 4],
    pub b: &'a mut [f64; 4],
    pub hm: &'a mut [f64; 4],
}

/// Indices of the free elements, their rows `n` and columns `n + j`.
const K: [usize; 3] = [0, 1, 3];
const ROW: [usize; 3] = [0, 0, 1];
const COL: [usize; 3] = [0, 1, 1];

/// The step on `st` with the output sums `acc` (non-empty), `dx = x − c` and the
/// kernel derivatives `dwdq`, `ddwdqdq` at the sample; then `D = MᵀM`.
#[inline(always)]
pub(crate) fn step_2d(
    p: &Params,
    st: MetricState,
    acc: MetricAcc,
    dx: [f64; 2],
    dwdq: f64,
    ddwdqdq: f64,
) {
    let MetricState { m, d, alpha, b, hm } = st;
    // `α = e^b` by `f64::exp` below, as `full_step` does at this size.
    debug_assert!(crate::update::metric_step::libm_exp(2));
    let (meta, rate, pen) = (p.cfg.meta, p.cfg.meta_rate, p.penalty_n);
    let inv_n = 1.0 / acc.n as f64;
    let (ca, cb, cc) = (acc.a * inv_n, acc.b * inv_n, acc.c * inv_n);
    // max |M| over the free elements (rows 0 and 1 from the diagonal), as `full_step`.
    let max_m = max_abs(max_abs(0.0, &m[0..2]), &m[3..4]);
    let thr = 0.1 * max_m;
    // M (x − c) and the rows of M·D (penalty gradient), from the state before the step.
    let mut mdx0 = 0.0;
    mdx0 += m[0] * dx[0];
    mdx0 += m[1] * dx[1];
    let mdx = [mdx0, 0.0 + m[3] * dx[1]];
    let md = [
        0.0 + m[0] * d[0] + m[1] * d[2],
        0.0 + m[0] * d[1] + m[1] * d[3],
        0.0 + m[3] * d[3],
    ];
    let ddiag = [d[0], d[3]];
    let ss = [
        [m[0], m[1]].iter().map(|v| v * v).sum::<f64>(),
        [m[3]].iter().map(|v| v * v).sum::<f64>(),
    ];
    let pen4 = 4.0 * pen;
    let mut g = [0.0; 3];
    if meta {
        let mut gg = [0.0; 3];
        for e in 0..3 {
            let (k, n, col) = (K[e], ROW[e], COL[e]);
            let x = dx[col];
            let mdx_n = mdx[n];
            let dj2 = md[e] * pen4;
            let dwdm = 2.0 * x * mdx_n * dwdq;
            let dqdm = 2.0 * x * mdx_n;
            let ddw = ddwdqdq * dqdm * dqdm + 2.0 * dwdq * x * x;
            let mv = m[k];
            let ddj2 = 4.0 * pen * (ddiag[col] + ss[n] + mv * mv);
            g[e] = ca * dj2 + cb * dwdm;
            gg[e] = ca * ddj2 + cb * ddw + cc * dwdm * dwdm;
            let aux = (rate * g[e] * hm[k]).clamp(-0.1, 0.1);
            b[k] = (b[k] - aux).clamp(-10.0, 10.0);
        }
        for e in 0..3 {
            alpha[K[e]] = b[K[e]].exp();
        }
        for e in 0..3 {
            let (k, a) = (K[e], alpha[K[e]]);
            hm[k] = hm[k] * (1.0 - a * gg[e]).max(0.0) - a * g[e];
        }
    } else {
        for e in 0..3 {
            let (n, col) = (ROW[e], COL[e]);
            let dj2 = md[e] * pen4;
            let dwdm = 2.0 * dx[col] * mdx[n] * dwdq;
            g[e] = ca * dj2 + cb * dwdm;
        }
    }
    // The step, halving the rate instead where it would exceed a tenth of max |M|.
    for e in 0..3 {
        let k = K[e];
        let dm = alpha[k] * g[e];
        let halve = dm > thr;
        alpha[k] = if halve { alpha[k] * 0.5 } else { alpha[k] };
        m[k] = if halve { m[k] } else { m[k] - dm };
    }
    mtm(2, m, d);
}
