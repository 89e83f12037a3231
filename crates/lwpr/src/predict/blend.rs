//! The prediction itself: per sub-model, the activation-weighted blend of the trustworthy RFs'
//! local linear models, `ŷ = Σ w ŷ_k / Σ w` over `w > cutoff`, with the confidence bound or the
//! Jacobian on request (`docs/lwpr.md`, "Prediction"). Generic over the [`Stages`] that
//! compute a plain prediction's sums (the fast dispatch, `fast/mod.rs`, chooses them).

use crate::distance::quad;
use crate::numeric::dot;
use crate::params::Params;
use crate::pls::{project, Pls};
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::update::stages::{dims, Stages};
use crate::LwprError;

/// How much support a prediction had.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Support {
    /// The smallest, over sub-models, total activation `Σ w` of the RFs that predicted.
    pub sum_w: f64,
}

/// What a prediction computes besides `ŷ`.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Want {
    /// `ŷ` alone.
    Plain,
    /// And the confidence bounds (into `ws.conf`).
    Conf,
    /// And the Jacobian (into `ws.jac`).
    Jac,
}

/// Predicts at `x` into `ws.y` (and `ws.conf` or `ws.jac`, `ws.support`). With `strict`, fails
/// with [`LwprError::NoActiveRf`] at the first sub-model without support; else such outputs
/// are 0. `PLAIN`: `want` is [`Want::Plain`] (a copy of its own, without the other branches).
#[inline(always)]
pub(crate) fn predict_core<S: Stages, const PLAIN: bool>(
    p: &Params,
    subs: &mut [SubModel],
    ws: &mut Scratch,
    x: &[f64],
    want: Want,
    strict: bool,
) -> Result<Support, LwprError> {
    let want = if PLAIN { Want::Plain } else { want };
    ws.load_x(p, x);
    let ny = p.n_local_out();
    let mut min_sw = f64::INFINITY;
    if want == Want::Jac {
        ws.jac.iter_mut().for_each(|v| *v = 0.0);
    }
    for (s, sub) in subs.iter_mut().enumerate() {
        let o0 = s * ny;
        for o in o0..o0 + ny {
            ws.yacc[o] = 0.0;
            ws.wyy[o] = 0.0;
            ws.wconf[o] = 0.0;
        }
        if want == Want::Jac {
            ws.dwdx.iter_mut().for_each(|v| *v = 0.0);
        }
        let sum_w = if PLAIN {
            S::plain_sums(p, sub, o0, ws)
        } else {
            sub_sums::<S>(p, sub, o0, ws, want)
        };
        if sum_w <= 0.0 && strict {
            return Err(LwprError::NoActiveRf { output: o0 });
        }
        min_sw = min_sw.min(sum_w);
        finish(p, ws, o0, sum_w, want);
        check_finite_outputs(&ws.y[o0..o0 + ny], o0)?;
    }
    Ok(Support { sum_w: min_sw })
}

/// [`LwprError::PredictionOverflow`] at the first non-finite value of `y` (outputs `o0..`).
#[inline(always)]
pub(crate) fn check_finite_outputs(y: &[f64], o0: usize) -> Result<(), LwprError> {
    match y.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(k) => Err(LwprError::PredictionOverflow {
            output: o0 + k,
            value: y[k],
        }),
    }
}

/// The sums over the RFs of sub-model `sub` that predict at the input in `ws` (trustworthy,
/// `w > cutoff`): `Σ w ŷ_k` into `ws.yacc`, `Σ w ŷ_k²` into `ws.wyy`, with `Conf` `Σ w σ²_k`
/// into `ws.wconf`, with `Jac` the parts of the Jacobian into `ws.jac` and `ws.dwdx`; returns
/// `Σ w`.
#[inline(always)]
pub(crate) fn sub_sums<S: Stages>(
    p: &Params,
    sub: &mut SubModel,
    o0: usize,
    ws: &mut Scratch,
    want: Want,
) -> f64 {
    let (nk, nr) = dims::<S>(p);
    let (ml, diag, cutoff, qb) = (p.mlen(), p.cfg.diag_only, p.cfg.cutoff, ws.qb_cutoff);
    let SubModel {
        rfs,
        centers,
        ms,
        ds,
        heads,
    } = sub;
    let kern = if diag { &*ds } else { &*ms };
    let mut sum_w = 0.0;
    let rf_chunks = centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
    // Where the model keeps heads, the RFs they put beyond `qb` are not measured (same sums).
    let mut heads = if S::HEADS {
        heads.walk(S::AVX, p, &ws.xk[..nk])
    } else {
        None
    };
    for (i, (rf, (c, md))) in rfs.iter_mut().zip(rf_chunks).enumerate() {
        // Every RF's bound in turn (the walk computes a block's at its first RF).
        if heads.as_mut().is_some_and(|h| h.beyond(i, qb)) {
            continue;
        }
        if !rf.trustworthy {
            continue;
        }
        let q = quad(S::AVX, diag, c, md, &ws.xk[..nk], &mut ws.met.dx, qb);
        if q >= qb {
            continue;
        }
        let (w, dwdq, _) = p.kernel(q);
        if w <= cutoff {
            continue;
        }
        sum_w += w;
        let xc = &mut ws.pls.xmz[..nr];
        let (xr, mean_x) = (&ws.xr[..nr], &rf.mean_x[..nr]);
        for k in 0..nr {
            xc[k] = xr[k] - mean_x[k];
        }
        if want == Want::Jac {
            activation_gradient(diag, nk, dwdq, &ds[i * ml..(i + 1) * ml], c, ws);
        }
        if want != Want::Conf {
            for pls in rf.outs.iter_mut() {
                pls.refresh_slope(nr);
            }
        }
        for (lo, pls) in rf.outs.iter().enumerate() {
            rf_output(p, pls, nr, o0 + lo, w, ws, want);
        }
    }
    sum_w
}

/// `∂w/∂x_K = 2 (dw/dq) D (x − c)` of one RF (metric `dd`, centre `c`) into `ws.ddx`, and
/// added to `ws.dwdx`.
#[inline(always)]
fn activation_gradient(diag: bool, nk: usize, dwdq: f64, dd: &[f64], c: &[f64], ws: &mut Scratch) {
    for k in 0..nk {
        let dxk = ws.xk[k] - c[k];
        ws.ddx[k] = if diag { 2.0 * dwdq * dd[k] * dxk } else { 0.0 };
    }
    if !diag {
        for k in 0..nk {
            ws.met.dx[k] = ws.xk[k] - c[k];
        }
        for k in 0..nk {
            let row = &dd[k * nk..(k + 1) * nk];
            ws.ddx[k] = 2.0 * dwdq * dot(row, &ws.met.dx);
        }
    }
    for k in 0..nk {
        ws.dwdx[k] += ws.ddx[k];
    }
}

/// One RF's local model `pls` of output `o` at `x̃ = ws.pls.xmz` (activation `w`): its
/// prediction `ŷ_k` into the sums, with `Conf` its variance term, with `Jac` its parts of the
/// Jacobian.
#[inline(always)]
fn rf_output(p: &Params, pls: &Pls, nr: usize, o: usize, w: f64, ws: &mut Scratch, want: Want) {
    let xc = &ws.pls.xmz[..nr];
    let yk = if want == Want::Conf {
        let np = pls.n_pred(nr).max(1);
        let (xu, sv) = (&mut ws.pls.xu, &mut ws.pls.s);
        project(&pls.u, &pls.p, nr, np, xc, xu, sv);
        let mut yk = pls.beta0;
        let mut ss = 0.0;
        for j in 0..np {
            yk += pls.beta[j] * sv[j];
            ss += sv[j] * sv[j] / pls.ss_s2[j];
        }
        let gamma = pls.sum_e_cv2[np - 1] / (pls.sum_w[np - 1] - pls.ssp);
        ws.wconf[o] += w * gamma * (1.0 + w * ss);
        yk
    } else {
        pls.beta0 + dot(&pls.slope[..nr], xc)
    };
    ws.yacc[o] += w * yk;
    ws.wyy[o] += w * yk * yk;
    if want == Want::Jac {
        let n_in = p.n_in;
        let row = &mut ws.jac[o * n_in..(o + 1) * n_in];
        for (k, &d) in p.rdims.iter().enumerate() {
            row[d] += w * pls.slope[k];
        }
        for (k, &d) in p.kdims.iter().enumerate() {
            row[d] += yk * ws.ddx[k];
        }
    }
}

/// The outputs `o0..` of a sub-model from its sums (`Σ w = sum_w`): `ŷ`, the support, with
/// `Conf` the bound, with `Jac` the Jacobian, in user units; 0 (and support 0) without
/// support.
#[inline(always)]
fn finish(p: &Params, ws: &mut Scratch, o0: usize, sum_w: f64, want: Want) {
    let (n_in, ny) = (p.n_in, p.n_local_out());
    if sum_w <= 0.0 {
        for o in o0..o0 + ny {
            ws.y[o] = 0.0;
            ws.support[o] = 0.0;
        }
        return;
    }
    for o in o0..o0 + ny {
        ws.support[o] = sum_w;
        let yn = ws.yacc[o] / sum_w;
        let no = p.norm_out[o];
        ws.y[o] = yn * no;
        if want == Want::Conf {
            let r = ws.wconf[o] + ws.wyy[o] - ws.yacc[o] * yn;
            ws.conf[o] = r.abs().sqrt() / sum_w * no;
        }
        if want == Want::Jac {
            let row = &mut ws.jac[o * n_in..(o + 1) * n_in];
            for (k, &d) in p.kdims.iter().enumerate() {
                row[d] -= yn * ws.dwdx[k];
            }
            for (d, v) in row.iter_mut().enumerate() {
                *v *= no / (sum_w * p.norm_in[d]);
            }
        }
    }
}
