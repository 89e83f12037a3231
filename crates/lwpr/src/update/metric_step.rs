//! Step (d): the gradient step on the metric's factor `M` — with optional IDBD meta learning
//! of the per-element rates `α` — and then `D = MᵀM` (`docs/lwpr.md`, "The distance metric").
//! [`reference_step`] is the whole step (d) of one RF after its outputs' cost terms.

use crate::numeric::{exp_fast, max_abs};
use crate::params::Params;
use crate::update::metric::{MetricAcc, MetricScratch};
use crate::update::metric_derivatives::derivatives;
use crate::update::stages::FullStep;

/// The metric step of one RF as the reference computes it: the derivatives
/// ([`derivatives`]) at `ws.dx = x − c`, then the step ([`step`]), for a diagonal or a full
/// metric. (The fast full-metric steps, `fast/`, compute the same, see there.)
#[inline(always)]
pub(crate) fn reference_step(nk: usize, p: &Params, s: FullStep<'_>, ws: &mut MetricScratch) {
    let FullStep {
        m,
        d,
        alpha,
        b,
        hm,
        acc,
        dwdq,
        ddwdqdq,
    } = s;
    let (diag, meta, pen) = (p.cfg.diag_only, p.cfg.meta, p.penalty_n);
    derivatives(nk, diag, meta, m, d, dwdq, ddwdqdq, pen, ws);
    step(nk, p, m, d, alpha, b, hm, acc, ws);
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
    mtm(nk, m, d);
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
    /// vectorisable [`crate::numeric::exp_fast`]; see [`libm_exp`].
    pub libm_exp: bool,
}

/// Whether the metric step of an `nk`-dimensional kernel takes `α = e^b` from `f64::exp`
/// (up to 4 dimensions, where the loops are short and scalar) or from
/// [`crate::numeric::exp_fast`] (vectorised loops). Both are within 1 ulp of `e^b`.
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

/// `D = MᵀM` for the upper-triangular `M` (row-major, `nk × nk`): `D_ij = Σ_{k≤i} M_ki M_kj`
/// for `j ≥ i`, mirrored below the diagonal.
#[inline(always)]
pub(crate) fn mtm(nk: usize, m: &[f64], d: &mut [f64]) {
    let (m, d) = (&m[..nk * nk], &mut d[..nk * nk]);
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
}
