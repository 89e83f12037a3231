//! The update of one RF of a 2-D model with every dimension a constant: kernel and regression
//! on two inputs each, a full metric, one output per RF and two PLS directions (the most two
//! regression inputs allow). Steps (a)–(d) and (f) of [`crate::rf_update::update_rf`], with the
//! same expressions in the same order — so the same bits, checked by a test against the general
//! path — on the RF's state viewed as fixed-size arrays, without the general path's scratch
//! buffers, run-time lengths and per-element bounds checks (a fifth fewer instructions per RF
//! update; the lwpr README's fifth round has the figures).
//!
//! Written out term by term where the general code sums in a particular order: a dot product
//! of two ([`crate::simd::dot`]) is `(0 + a₀b₀) + a₁b₁`, a row of `M·D` starts from `0`, and so
//! on; adding `0.0` is kept because it is not an identity for `−0.0`.

use crate::metric::MetricAcc;
use crate::params::Params;
use crate::rf::{Pls, Rf, SubModel};
use crate::scratch::Scratch;

/// Whether [`update_rf_2d`] applies to RF `i` of a model whose kernel and regression inputs
/// are both 2-D (the caller's constants): a full metric, one output, two directions.
#[inline(always)]
pub(crate) fn applies(p: &Params, sub: &SubModel, i: usize) -> bool {
    let rf = &sub.rfs[i];
    !p.cfg.diag_only && rf.outs.len() == 1 && rf.outs[0].n_reg == 2
}

/// The first `N` elements of an RF's state as an array (the state is never shorter).
#[inline(always)]
pub(crate) fn arr<const N: usize>(v: &mut [f64]) -> &mut [f64; N] {
    v.first_chunk_mut()
        .expect("RF state shorter than its dimensions")
}

/// `simd::dot` of two 2-vectors, in its order.
#[inline(always)]
fn dot2(a: &[f64], b: [f64; 2]) -> f64 {
    let mut r = 0.0;
    r += a[0] * b[0];
    r += a[1] * b[1];
    r
}

/// [`crate::rf_update::update_rf`] for RF `i` when [`applies`] holds: the sample is `ws.xk`,
/// `ws.xr` and the output `y`; adds `w·ŷ` to `ws.yacc[0]` when the RF is trustworthy and
/// returns whether it is.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn update_rf_2d(
    p: &Params,
    sub: &mut SubModel,
    i: usize,
    w: f64,
    dwdq: f64,
    ddwdqdq: f64,
    y: f64,
    ws: &mut Scratch,
) -> bool {
    let SubModel {
        rfs,
        centers,
        ms,
        ds,
        ..
    } = sub;
    let Rf {
        alpha,
        b,
        hm,
        mean_x,
        var_x,
        trustworthy,
        outs,
        ..
    } = &mut rfs[i];
    let out = &mut outs[0];
    let x: [f64; 2] = *arr(&mut ws.xr);
    // (a) The input means, with ω = sum_w[0]·λ[0] before this update.
    let omega = out.sum_w[0] * out.lambda[0];
    let (mean_x, var_x) = (arr::<2>(mean_x), arr::<2>(var_x));
    let inv = 1.0 / (omega + w);
    let mut xmz = [0.0; 2];
    for k in 0..2 {
        let m = (omega * mean_x[k] + w * x[k]) * inv;
        mean_x[k] = m;
        let d = x[k] - m;
        xmz[k] = d;
        var_x[k] = (omega * var_x[k] + w * d * d) * inv;
    }
    // n_data and λ as before this update (forgetting is the last step).
    let n_data = *arr::<2>(&mut out.n_data);
    let lambda = *arr::<2>(&mut out.lambda);
    if n_data[0] > 4.0 {
        *trustworthy = true;
    }
    // (a, output) and (b): the PLS step; the cost terms of (d).
    let (yp, e_cv, e, s) = regression(out, omega, y, w, xmz, n_data, lambda);
    let acc = if p.cfg.update_d {
        crate::metric_2d::output_terms(out, w, s, e_cv, e, p.cfg.meta, n_data, lambda)
    } else {
        MetricAcc::default()
    };
    // (f) Forgetting (two directions cannot grow a third in two inputs).
    let (tau, fin) = (p.cfg.tau_lambda, p.cfg.final_lambda);
    let (nd, lam) = (arr::<2>(&mut out.n_data), arr::<2>(&mut out.lambda));
    for j in 0..2 {
        nd[j] = nd[j] * lam[j] + 1.0;
        lam[j] = tau * lam[j] + fin * (1.0 - tau);
    }
    out.slope_stale = true;
    let trusted = *trustworthy;
    if trusted {
        ws.yacc[0] += w * yp;
    }
    if acc.n == 0 {
        return trusted;
    }
    // (d) The metric step at dx = x − c.
    let (xk, c) = (*arr::<2>(&mut ws.xk), arr::<2>(&mut centers[i * 2..]));
    let dx = [xk[0] - c[0], xk[1] - c[1]];
    let st = crate::metric_2d::MetricState {
        m: arr(&mut ms[i * 4..]),
        d: arr(&mut ds[i * 4..]),
        alpha: arr(alpha),
        b: arr(b),
        hm: arr(hm),
    };
    crate::metric_2d::step_2d(p, st, acc, dx, dwdq, ddwdqdq);
    trusted
}

/// `pls::update_regression::<2>` with `x̃ = xmz`: returns the prediction `ŷ`, the leave-one-out
/// residual of the last trusted direction, the residual `e` and the new projections `s`.
#[inline(always)]
fn regression(
    out: &mut Pls,
    omega: f64,
    y: f64,
    w: f64,
    xmz: [f64; 2],
    n_data: [f64; 2],
    lambda: [f64; 2],
) -> (f64, f64, f64, [f64; 2]) {
    out.beta0 = (omega * out.beta0 + w * y) / (omega + w);
    let ymz = y - out.beta0;
    let Pls {
        u,
        p,
        sxy,
        ssx,
        beta,
        ss_s2,
        ss_yres,
        sum_w,
        sum_e_cv2,
        ssp,
        sum_e2,
        beta0,
        ..
    } = out;
    let (u, p, sxy, ssx) = (arr::<4>(u), arr::<4>(p), arr::<4>(sxy), arr::<4>(ssx));
    let (beta, ss_s2, ss_yres) = (arr::<2>(beta), arr::<2>(ss_s2), arr::<2>(ss_yres));
    let (sum_w, sum_e_cv2) = (arr::<2>(sum_w), arr::<2>(sum_e_cv2));
    // Projections with the old directions, keeping the residual inputs.
    let s0 = dot2(&u[0..2], xmz);
    let x1 = [xmz[0] - p[0] * s0, xmz[1] - p[1] * s0];
    let s = [s0, dot2(&u[2..4], x1)];
    let xres = [xmz, x1];
    let mut e_cv = [0.0; 2];
    let mut yres = 0.0;
    for j in 0..2 {
        yres += beta[j] * s[j];
        sum_w[j] = sum_w[j] * lambda[j] + w;
        e_cv[j] = ymz - yres;
    }
    let mut ws2 = 0.0;
    for j in 0..2 {
        let lam = lambda[j];
        let lam_slow = 0.9 + 0.1 * lam;
        let t = if j == 0 { ymz } else { e_cv[0] };
        let (wt, wsj) = (w * t, w * s[j]);
        let xj = xres[j];
        let mut norm2 = 0.0;
        for k in 0..2 {
            let v = sxy[2 * j + k] * lam_slow + wt * xj[k];
            sxy[2 * j + k] = v;
            norm2 += v * v;
        }
        if norm2 > 1e-24 {
            let inv = 1.0 / norm2.sqrt();
            for k in 0..2 {
                u[2 * j + k] = sxy[2 * j + k] * inv;
            }
        }
        ss_s2[j] = lam * ss_s2[j] + s[j] * wsj;
        ss_yres[j] = lam * ss_yres[j] + t * wsj;
        let inv_s2 = 1.0 / ss_s2[j];
        beta[j] = ss_yres[j] * inv_s2;
        for k in 0..2 {
            let v = lam * ssx[2 * j + k] + wsj * xj[k];
            ssx[2 * j + k] = v;
            p[2 * j + k] = v * inv_s2;
        }
        ws2 += wsj * wsj * inv_s2;
    }
    *ssp = lambda[1] * *ssp + ws2;
    // The new projections (`pls::project`).
    let n0 = dot2(&u[0..2], xmz);
    let xu = [xmz[0] - p[0] * n0, xmz[1] - p[1] * n0];
    let sn = [n0, dot2(&u[2..4], xu)];
    // Both directions predict once the second has seen enough data (`Pls::n_pred`).
    let np = if n_data[1] > 4.0 { 2 } else { 1 };
    let ypred: f64 = (0..np).map(|j| beta[j] * sn[j]).sum();
    let e_cv_r = e_cv[np - 1];
    let e = ymz - ypred;
    if n_data[0] * (1.0 - lambda[0]) > 0.1 {
        *sum_e2 = *sum_e2 * lambda[1] + w * e * e;
        for j in 0..2 {
            sum_e_cv2[j] = sum_e_cv2[j] * lambda[j] + w * e_cv[j] * e_cv[j];
        }
    }
    (ypred + *beta0, e_cv_r, e, sn)
}
