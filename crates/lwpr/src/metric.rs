//! Distance-metric learning, step (d): gradient descent on the leave-one-out cost
//! `J = (1/W) Σ w (y − ŷ)² / (1 − w sᵀP s)² + (γ/n) Σ D_ij²` with respect to the upper-triangular
//! `M` (`D = MᵀM`), with optional IDBD meta learning of the per-element rates.
//!
//! With several outputs per RF (shared mode) the cost is the mean over outputs of their
//! leave-one-out costs plus one penalty; each output's transient multiplier `T` scales its own
//! term, so with one output this is exactly the reference step.

use crate::params::Params;
use crate::rf::Pls;
use crate::simd::{dot, exp_fast, max_abs};

/// Derivative buffers, one entry per metric element.
#[derive(Clone, Debug, Default)]
pub(crate) struct MetricScratch {
    /// `x − c` (kernel dims).
    pub dx: Vec<f64>,
    /// `M (x − c)`.
    pub mdx: Vec<f64>,
    /// `∂w/∂M`.
    pub dwdm: Vec<f64>,
    /// `∂J2/∂M` of the penalty, then reused for the total gradient.
    pub dj2: Vec<f64>,
    /// `∂²w/∂M²` (element-wise).
    pub ddw: Vec<f64>,
    /// `∂²J2/∂M²` (element-wise).
    pub ddj2: Vec<f64>,
    /// The diagonal of `D` (full metrics).
    pub ddiag: Vec<f64>,
    /// One row (`nk`).
    pub row: Vec<f64>,
    /// Scratch of the full-metric step above 4 dimensions
    /// ([`super::metric_wide::wide_step`]).
    pub wide: Vec<f64>,
}

impl MetricScratch {
    /// Buffers for `nk` kernel dimensions and `mlen` metric elements.
    pub fn new(nk: usize, mlen: usize) -> MetricScratch {
        MetricScratch {
            dx: vec![0.0; nk],
            mdx: vec![0.0; nk],
            dwdm: vec![0.0; mlen],
            dj2: vec![0.0; mlen],
            ddw: vec![0.0; mlen],
            ddj2: vec![0.0; mlen],
            ddiag: vec![0.0; nk],
            row: vec![0.0; nk],
            wide: if mlen == nk * nk && nk > 4 {
                vec![0.0; super::metric_wide::wide_len(nk)]
            } else {
                Vec::new()
            },
        }
    }
}

/// Sums over outputs of `T·w/W`, `T·∂J1/∂w`, `T·∂²J1/∂w²` and their count.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct MetricAcc {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub n: usize,
}

/// First and second derivatives of `w` and of the penalty `J2 = (γ/n) Σ D_ij²` with respect to
/// each free element of `M`, at `dx = x − c` (`pen` = γ/n). Second derivatives only with `meta`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn derivatives(
    nk: usize,
    diag: bool,
    meta: bool,
    m: &[f64],
    d: &[f64],
    dwdq: f64,
    ddwdqdq: f64,
    pen: f64,
    ws: &mut MetricScratch,
) {
    let dx = &ws.dx[..nk];
    if diag {
        for n in 0..nk {
            let aux = 2.0 * m[n];
            let dqdm = dx[n] * dx[n] * aux;
            ws.dwdm[n] = dqdm * dwdq;
            ws.dj2[n] = 2.0 * pen * d[n] * aux;
            if meta {
                ws.ddw[n] = ddwdqdq * dqdm * dqdm + 2.0 * dwdq * dx[n] * dx[n];
                ws.ddj2[n] = 2.0 * pen * (2.0 * d[n] + aux * aux);
            }
        }
        return;
    }
    let (m, d) = (&m[..nk * nk], &d[..nk * nk]);
    let dx = &dx[..nk];
    for n in 0..nk {
        let mrow = &m[n * nk + n..(n + 1) * nk];
        ws.mdx[n] = dot(mrow, &dx[n..]);
    }
    // ∂J2/∂M_nm = 4 pen Σ_{i≥n} M_ni D_im (m ≥ n): row n of M·D, accumulated over the rows i
    // of D (the same terms in the same order as a dot product).
    let pen4 = 4.0 * pen;
    for n in 0..nk {
        let row = &mut ws.row[n..nk];
        row.iter_mut().for_each(|v| *v = 0.0);
        for i in n..nk {
            let a = m[n * nk + i];
            for (o, &dv) in row.iter_mut().zip(&d[i * nk + n..(i + 1) * nk]) {
                *o += a * dv;
            }
        }
        let dst = &mut ws.dj2[n * nk + n..(n + 1) * nk];
        for (o, &v) in dst.iter_mut().zip(&ws.row[n..nk]) {
            *o = v * pen4;
        }
    }
    for n in 0..nk {
        let k0 = n * nk + n;
        let len = nk - n;
        let mdx_n = ws.mdx[n];
        let dxr = &dx[n..];
        let dwdm = &mut ws.dwdm[k0..k0 + len];
        for (o, &x) in dwdm.iter_mut().zip(dxr) {
            *o = 2.0 * x * mdx_n * dwdq;
        }
        if meta {
            let mrow = &m[k0..k0 + len];
            let ss: f64 = mrow.iter().map(|v| v * v).sum();
            let ddw = &mut ws.ddw[k0..k0 + len];
            for (o, &x) in ddw.iter_mut().zip(dxr) {
                let dqdm = 2.0 * x * mdx_n;
                *o = ddwdqdq * dqdm * dqdm + 2.0 * dwdq * x * x;
            }
            let ddj2 = &mut ws.ddj2[k0..k0 + len];
            for (j, (o, &mv)) in ddj2.iter_mut().zip(mrow).enumerate() {
                let mm = n + j;
                *o = 4.0 * pen * (d[mm * nk + mm] + ss + mv * mv);
            }
        }
    }
}

/// One output's part of the metric gradient (the `∂J1/∂w` terms) from its PLS state after the
/// regression step, with `s` the new projections, `e_cv` and `e` from that step (`ps`: scratch
/// of the same length). Updates the memory traces `H`, `r`. Does nothing while
/// `n_data[0]·(1 − λ[0]) ≤ 0.1`. Returns whether the guard below skipped the terms.
///
/// A numerical guard the reference library lacks: when the sample's leverage
/// `h = w Σ_j s_j²/SSs2_j` is not below 1 (or is NaN), the leave-one-out factor `1/(1 − h)` is
/// undefined and this output adds nothing (its traces are not updated either). A true leverage
/// lies in `[0, 1)`; `h ≥ 1` arises because `s` comes from the projections just updated while
/// `SSs2` was summed with the old ones, or when `SSs2` has decayed to nothing under fast
/// forgetting (the division then gives `±∞` and the RF's state turns NaN).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn output_terms<const R: usize>(
    pls: &mut Pls,
    nr: usize,
    w: f64,
    s: &[f64],
    ps: &mut [f64],
    e_cv: f64,
    e: f64,
    meta: bool,
    acc: &mut MetricAcc,
) -> bool {
    let r = if R > 0 { R } else { pls.n_reg };
    let (n_data, ss_s2, lambda) = (&pls.n_data[..r], &pls.ss_s2[..r], &pls.lambda[..r]);
    let (h_tr, r_tr) = (&mut pls.h_tr[..r], &mut pls.r_tr[..r]);
    let (s, ps) = (&s[..r], &mut ps[..r]);
    let l0 = 1.0 - lambda[0];
    let ok = |j: usize| n_data[j] * l0 > 0.1;
    if !ok(0) {
        return false;
    }
    let mut h = 0.0;
    for j in 0..r {
        if ok(j) {
            h += s[j] * s[j] / ss_s2[j];
        }
    }
    h *= w;
    let big_w = pls.sum_w[0];
    let big_e = if r == 1 || n_data[r - 1] > 2.0 * nr as f64 {
        pls.sum_e_cv2[r - 1]
    } else {
        pls.sum_e_cv2[r - 2]
    };
    let t = (pls.sum_e2 / (big_e + 1e-10)).powi(4).min(1.0);
    let e_cv2 = e_cv * e_cv;
    let mut dj1 = -big_e / big_w + e_cv2;
    let mut spse = 0.0;
    for j in 0..r {
        if ok(j) {
            // `s_j / SSs2_j`, kept for the second-derivative sum.
            ps[j] = s[j] / ss_s2[j];
            let pse = e * ps[j];
            dj1 -= 2.0 * pse * h_tr[j] + 2.0 * ps[j] * ps[j] * r_tr[j];
            spse += s[j] * pse;
        }
    }
    dj1 /= big_w;
    // The leverage guard (see above; false for a NaN `h` too), tested here so that the terms
    // before it need not wait.
    let leverage_ok = h < 1.0;
    if !leverage_ok {
        return true;
    }
    if meta {
        let mut ddj1 = 2.0 * (e * e * h / w - e_cv2 / big_w) + big_e / (big_w * big_w);
        for j in 0..r {
            if ok(j) {
                ddj1 += 4.0 * (e * ps[j] / big_w + ps[j] * spse) * h_tr[j];
            }
        }
        acc.c += t * ddj1 / big_w;
    }
    acc.a += t * w / big_w;
    acc.b += t * dj1;
    acc.n += 1;
    let (fh, fr) = (w / (1.0 - h), w * w * e_cv2 / (1.0 - h));
    for j in 0..r {
        if ok(j) {
            let lam = lambda[j];
            h_tr[j] = lam * h_tr[j] + fh * s[j] * e_cv * t;
            r_tr[j] = lam * r_tr[j] + fr * s[j] * s[j] * t;
        }
    }
    false
}

/// The gradient step on `M` (and the meta step on `α`), then `D = MᵀM`.
/// Expects [`derivatives`] in `ws` and a non-empty `acc`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn step(
    nk: usize,
    p: &Params,
    m: &mut [f64],
    d: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
    acc: MetricAcc,
    ws: &mut MetricScratch,
) {
    let diag = p.cfg.diag_only;
    let inv_n = 1.0 / acc.n as f64;
    let c = Coef {
        a: acc.a * inv_n,
        b: acc.b * inv_n,
        c: acc.c * inv_n,
        meta: p.cfg.meta,
        rate: p.cfg.meta_rate,
        max_m: 0.0,
        libm_exp: libm_exp(nk),
    };
    if diag {
        let c = Coef {
            max_m: max_abs(0.0, &m[..nk]),
            ..c
        };
        let r = 0..nk;
        let g = &mut ws.dj2[r.clone()];
        step_row(
            &c,
            g,
            &ws.dwdm[r.clone()],
            &ws.ddw[r.clone()],
            &ws.ddj2[r.clone()],
            &mut m[r.clone()],
            &mut alpha[r.clone()],
            &mut b[r.clone()],
            &mut hm[r],
        );
        for n in 0..nk {
            d[n] = m[n] * m[n];
        }
        return;
    }
    // The free elements: the upper triangle, row n = k ∈ n·nk + (n..nk).
    let mut max_m: f64 = 0.0;
    for n in 0..nk {
        max_m = max_abs(max_m, &m[n * nk + n..(n + 1) * nk]);
    }
    let c = Coef { max_m, ..c };
    for n in 0..nk {
        let r = n * nk + n..(n + 1) * nk;
        step_row(
            &c,
            &mut ws.dj2[r.clone()],
            &ws.dwdm[r.clone()],
            &ws.ddw[r.clone()],
            &ws.ddj2[r.clone()],
            &mut m[r.clone()],
            &mut alpha[r.clone()],
            &mut b[r.clone()],
            &mut hm[r],
        );
    }
    super::metric_full::mtm(nk, m, d);
}

/// Coefficients of one metric step: the output-averaged `T·w/W`, `T·∂J1/∂w`, `T·∂²J1/∂w²`,
/// meta learning on/off and its rate, and `max |M|` before the step.
pub(crate) struct Coef {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub meta: bool,
    pub rate: f64,
    pub max_m: f64,
    /// `α = e^b` by `f64::exp` (small metrics, scalar code: lower latency) instead of the
    /// vectorisable [`crate::simd::exp_fast`]; see [`libm_exp`].
    pub libm_exp: bool,
}

/// Whether the metric step of an `nk`-dimensional kernel takes `α = e^b` from `f64::exp`
/// (up to 4 dimensions, where the loops are short and scalar) or from
/// [`crate::simd::exp_fast`] (vectorised loops). Both are within 1 ulp of `e^b`.
#[inline(always)]
pub(crate) fn libm_exp(nk: usize) -> bool {
    nk <= 4
}

/// `α = e^b` element-wise, by `f64::exp` if `libm` else by [`exp_fast`] (see [`libm_exp`]).
#[inline(always)]
pub(crate) fn exp_into(libm: bool, b: &[f64], alpha: &mut [f64]) {
    if libm {
        for (a, v) in alpha.iter_mut().zip(b) {
            *a = v.exp();
        }
    } else {
        for (a, v) in alpha.iter_mut().zip(b) {
            *a = exp_fast(*v);
        }
    }
}

/// The step on a contiguous run of free elements of `M`: on entry `g` holds `∂J2/∂M`, on exit
/// the total gradient `T·∂J/∂M`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn step_row(
    c: &Coef,
    g: &mut [f64],
    dwdm: &[f64],
    ddw: &[f64],
    ddj2: &[f64],
    m: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
) {
    let len = g.len();
    let (dwdm, ddw, ddj2) = (&dwdm[..len], &ddw[..len], &ddj2[..len]);
    let (m, alpha, b, hm) = (
        &mut m[..len],
        &mut alpha[..len],
        &mut b[..len],
        &mut hm[..len],
    );
    for k in 0..len {
        g[k] = c.a * g[k] + c.b * dwdm[k];
    }
    if c.meta {
        for k in 0..len {
            let aux = (c.rate * g[k] * hm[k]).clamp(-0.1, 0.1);
            b[k] = (b[k] - aux).clamp(-10.0, 10.0);
        }
        exp_into(c.libm_exp, &b[..len], &mut alpha[..len]);
        for k in 0..len {
            let gg = c.a * ddj2[k] + c.b * ddw[k] + c.c * dwdm[k] * dwdm[k];
            hm[k] = hm[k] * (1.0 - alpha[k] * gg).max(0.0) - alpha[k] * g[k];
        }
    }
    let thr = 0.1 * c.max_m;
    for k in 0..len {
        let dm = alpha[k] * g[k];
        let halve = dm > thr;
        alpha[k] = if halve { alpha[k] * 0.5 } else { alpha[k] };
        m[k] = if halve { m[k] } else { m[k] - dm };
    }
}
