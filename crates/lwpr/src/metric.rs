//! Distance-metric learning, step (d): gradient descent on the leave-one-out cost
//! `J = (1/W) Σ w (y − ŷ)² / (1 − w sᵀP s)² + (γ/n) Σ D_ij²` with respect to the upper-triangular
//! `M` (`D = MᵀM`), with optional IDBD meta learning of the per-element rates.
//!
//! With several outputs per RF (shared mode) the cost is the mean over outputs of their
//! leave-one-out costs plus one penalty; each output's transient multiplier `T` scales its own
//! term, so with one output this is exactly the reference step.

use crate::params::Params;
use crate::rf::Pls;

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
pub(crate) fn derivatives(
    diag: bool,
    meta: bool,
    m: &[f64],
    d: &[f64],
    dwdq: f64,
    ddwdqdq: f64,
    pen: f64,
    ws: &mut MetricScratch,
) {
    let nk = ws.dx.len();
    let dx = &ws.dx;
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
    for n in 0..nk {
        ws.mdx[n] = (n..nk).map(|i| m[n * nk + i] * dx[i]).sum();
    }
    for n in 0..nk {
        let mrow = &m[n * nk + n..(n + 1) * nk];
        let ss: f64 = if meta {
            mrow.iter().map(|v| v * v).sum()
        } else {
            0.0
        };
        for mm in n..nk {
            let k = n * nk + mm;
            let dqdm = 2.0 * dx[mm] * ws.mdx[n];
            ws.dwdm[k] = dqdm * dwdq;
            let drow = &d[mm * nk + n..(mm + 1) * nk];
            let sum: f64 = drow.iter().zip(mrow).map(|(a, b)| a * b).sum();
            ws.dj2[k] = 4.0 * pen * sum;
            if meta {
                ws.ddw[k] = ddwdqdq * dqdm * dqdm + 2.0 * dwdq * dx[mm] * dx[mm];
                ws.ddj2[k] = 4.0 * pen * (d[mm * nk + mm] + ss + m[k] * m[k]);
            }
        }
    }
}

/// One output's part of the metric gradient (the `∂J1/∂w` terms) from its PLS state after the
/// regression step, with `s` the new projections, `e_cv` and `e` from that step. Updates the
/// memory traces `H`, `r`. Does nothing while `n_data[0]·(1 − λ[0]) ≤ 0.1`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn output_terms(
    pls: &mut Pls,
    nr: usize,
    w: f64,
    s: &[f64],
    e_cv: f64,
    e: f64,
    meta: bool,
    acc: &mut MetricAcc,
) {
    let r = pls.n_reg;
    let l0 = 1.0 - pls.lambda[0];
    let ok = |j: usize| pls.n_data[j] * l0 > 0.1;
    if !ok(0) {
        return;
    }
    let mut h = 0.0;
    for j in 0..r {
        if ok(j) {
            h += s[j] * s[j] / pls.ss_s2[j];
        }
    }
    h *= w;
    let big_w = pls.sum_w[0];
    let big_e = if r == 1 || pls.n_data[r - 1] > 2.0 * nr as f64 {
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
            let ps = s[j] / pls.ss_s2[j];
            let pse = e * ps;
            dj1 -= 2.0 * pse * pls.h_tr[j] + 2.0 * ps * ps * pls.r_tr[j];
            spse += s[j] * pse;
        }
    }
    dj1 /= big_w;
    if meta {
        let mut ddj1 = 2.0 * (e * e * h / w - e_cv2 / big_w) + big_e / (big_w * big_w);
        for j in 0..r {
            if ok(j) {
                let ps = s[j] / pls.ss_s2[j];
                ddj1 += 4.0 * (e * ps / big_w + ps * spse) * pls.h_tr[j];
            }
        }
        acc.c += t * ddj1 / big_w;
    }
    acc.a += t * w / big_w;
    acc.b += t * dj1;
    acc.n += 1;
    for j in 0..r {
        if ok(j) {
            let lam = pls.lambda[j];
            pls.h_tr[j] = lam * pls.h_tr[j] + (w / (1.0 - h)) * s[j] * e_cv * t;
            pls.r_tr[j] = lam * pls.r_tr[j] + (w * w * e_cv2 / (1.0 - h)) * s[j] * s[j] * t;
        }
    }
}

/// The gradient step on `M` (and the meta step on `α`), then `D = MᵀM`.
/// Expects [`derivatives`] in `ws` and a non-empty `acc`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn step(
    p: &Params,
    m: &mut [f64],
    d: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
    acc: MetricAcc,
    ws: &mut MetricScratch,
) {
    let nk = p.nk();
    let diag = p.cfg.diag_only;
    let inv_n = 1.0 / acc.n as f64;
    let (ca, cb, cc) = (acc.a * inv_n, acc.b * inv_n, acc.c * inv_n);
    let meta = p.cfg.meta;
    let rate = p.cfg.meta_rate;
    // The free elements: diagonal (k = n) or upper triangle (k = n·nk + m, m ≥ n).
    let idx = |n: usize, mm: usize| if diag { n } else { n * nk + mm };
    let mut max_m: f64 = 0.0;
    for n in 0..nk {
        for mm in if diag { n..n + 1 } else { n..nk } {
            max_m = max_m.max(m[idx(n, mm)].abs());
        }
    }
    for n in 0..nk {
        for mm in if diag { n..n + 1 } else { n..nk } {
            let k = idx(n, mm);
            let g = ca * ws.dj2[k] + cb * ws.dwdm[k];
            if meta {
                let gg = ca * ws.ddj2[k] + cb * ws.ddw[k] + cc * ws.dwdm[k] * ws.dwdm[k];
                let aux = (rate * g * hm[k]).clamp(-0.1, 0.1);
                b[k] = (b[k] - aux).clamp(-10.0, 10.0);
                alpha[k] = b[k].exp();
                hm[k] = hm[k] * (1.0 - alpha[k] * gg).max(0.0) - alpha[k] * g;
            }
            let dm = alpha[k] * g;
            if dm > 0.1 * max_m {
                alpha[k] *= 0.5;
            } else {
                m[k] -= dm;
            }
        }
    }
    if diag {
        for n in 0..nk {
            d[n] = m[n] * m[n];
        }
    } else {
        for i in 0..nk {
            for j in i..nk {
                let v: f64 = (0..=i).map(|k| m[k * nk + i] * m[k * nk + j]).sum();
                d[i * nk + j] = v;
                d[j * nk + i] = v;
            }
        }
    }
}
