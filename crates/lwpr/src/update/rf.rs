//! Step 3 of an update for the active receptive fields (`docs/lwpr.md`, "One update"): for
//! each, (a) the weighted means, then per output (b) the PLS regression, the metric's cost
//! terms, (e) the growth test and (f) forgetting, then (c) its prediction into the blend and
//! (d) the distance metric; and the numerical guard's test of its state. Inlined into the
//! update (a function of its own per RF was tried: more instructions, no faster).

use crate::params::Params;
use crate::pls::Pls;
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::update::metric::{output_terms, MetricAcc};
use crate::update::metric_step::reference_step;
use crate::update::regression::{
    check_grow, forget, update_input_means, update_regression, PlsScratch, RegOut,
};
use crate::update::stages::{dims, FullStep, Stages};

/// Step 3 for every RF in `ws.active`, one after the other ([`Stages::update_active`]).
#[inline(always)]
pub(crate) fn update_active<S: Stages>(
    p: &Params,
    sub: &mut SubModel,
    o0: usize,
    ws: &mut Scratch,
) -> f64 {
    let mut sum_w = start_blend(p, ws);
    let (nk, ml) = (dims::<S>(p).0, p.mlen());
    for a in 0..ws.active.len() {
        crate::update::prefetch::ahead(sub, nk, ml, &ws.active, a);
        update_one::<S>(p, sub, a, o0, ws, &mut sum_w);
    }
    sum_w
}

/// Clears the blend (`ws.yacc`), the diverged RFs and the leverage guard's count for the
/// update of a sub-model; returns the blend's initial `Σ w`, 0.
#[inline(always)]
pub(crate) fn start_blend(p: &Params, ws: &mut Scratch) -> f64 {
    ws.yacc[..p.n_local_out()].iter_mut().for_each(|v| *v = 0.0);
    ws.diverged.clear();
    ws.pls.skipped = 0;
    0.0
}

/// Updates the active RF `ws.active[a]`, adds its weight to `sum_w` when it entered the blend
/// and queues its id in `ws.diverged` when its state stopped being finite.
#[inline(always)]
pub(crate) fn update_one<S: Stages>(
    p: &Params,
    sub: &mut SubModel,
    a: usize,
    o0: usize,
    ws: &mut Scratch,
    sum_w: &mut f64,
) {
    let (i, w, dwdq, ddwdqdq) = ws.active[a];
    let r = update_rf::<S>(p, sub, i, w, dwdq, ddwdqdq, o0, ws);
    if r.blended {
        *sum_w += w;
    }
    if !r.finite {
        ws.diverged.push(sub.rfs[i].id);
    }
}

/// What [`update_rf`] reports about the RF it updated.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RfOutcome {
    /// Its prediction entered the update's blend (`ws.yacc`): it is trustworthy and `finite`.
    pub blended: bool,
    /// Its predictions at the sample, its regression (`β`, `p`, `u`) and its metric are
    /// finite; when not, its state has diverged and the update removes it.
    pub finite: bool,
}

/// Updates RF `i` of `sub` at activation `w` (kernel derivatives `dwdq`, `ddwdqdq`) with the
/// sample in `ws` (outputs `o0..` of `ws.yn`); adds `w·ŷ_k` to `ws.yacc` when the RF is
/// trustworthy and its state stayed finite.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn update_rf<S: Stages>(
    p: &Params,
    sub: &mut SubModel,
    i: usize,
    w: f64,
    dwdq: f64,
    ddwdqdq: f64,
    o0: usize,
    ws: &mut Scratch,
) -> RfOutcome {
    let (nk, nr) = dims::<S>(p);
    let (ml, ny) = (p.mlen(), p.n_local_out());
    let y = &ws.yn[o0..o0 + ny];
    let rf = &mut sub.rfs[i];
    // (a) The inputs' means (each output's `β₀` in its PLS step, with the same `ω`).
    let omega = rf.outs[0].sum_w[0] * rf.outs[0].lambda[0];
    update_input_means(nr, rf, omega, &ws.xr, w, &mut ws.pls.xmz);
    if rf.outs[0].n_data[0] > 2.0 * nr as f64 {
        rf.trustworthy = true;
    }
    let mut acc = MetricAcc::default();
    // Numerical guard: the sum of the RF's predictions at the sample, of the PLS steps' results
    // and (below) of the diagonal of `D` is finite iff all are.
    let mut chk = 0.0;
    for (o, out) in rf.outs.iter_mut().enumerate() {
        // (b), the cost terms of (d), (e) and (f).
        let (yp, pls_chk) = S::output_step(p, out, nr, omega, y[o], w, &mut acc, &mut ws.pls);
        // Its prediction at the sample may be finite while an untrusted direction is not.
        chk += yp + pls_chk;
        ws.rf_yp[o] = yp;
    }
    let trusted = rf.trustworthy;
    if acc.n == 0 {
        return blend(ws, ny, w, trusted, chk.is_finite());
    }
    // (d) The distance metric.
    let c = &sub.centers[i * nk..(i + 1) * nk];
    for k in 0..nk {
        ws.met.dx[k] = ws.xk[k] - c[k];
    }
    let s = FullStep {
        m: &mut sub.ms[i * ml..(i + 1) * ml],
        d: &mut sub.ds[i * ml..(i + 1) * ml],
        alpha: &mut rf.alpha,
        b: &mut rf.b,
        hm: &mut rf.hm,
        acc,
        dwdq,
        ddwdqdq,
    };
    if !p.cfg.diag_only {
        S::full_metric_step(nk, p, s, &mut ws.met);
    } else {
        reference_step(nk, p, s, &mut ws.met);
    }
    sub.sync_head(p, i);
    // A non-finite element of `M` (or an overflow of `D = MᵀM`) shows on the diagonal of `D`,
    // a sum of squares of `M`'s column.
    let finite = (chk + sub.trace_d(p, i)).is_finite();
    // (c) Its prediction into the blend.
    blend(ws, ny, w, trusted, finite)
}

/// Adds the updated RF's `w·ŷ_k` (in `ws.rf_yp`) to the update's blend when it is trustworthy
/// and its state stayed finite (a diverged RF, removed by the caller, stays out of it).
#[inline(always)]
fn blend(ws: &mut Scratch, ny: usize, w: f64, trusted: bool, finite: bool) -> RfOutcome {
    let blended = trusted && finite;
    if blended {
        for (acc, &yp) in ws.yacc[..ny].iter_mut().zip(&ws.rf_yp[..ny]) {
            *acc += w * yp;
        }
    }
    RfOutcome { blended, finite }
}

/// The reference's [`Stages::output_step`]: (b) the PLS regression over the output's current
/// number of directions, then [`after_pls`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn output_step(
    p: &Params,
    out: &mut Pls,
    nr: usize,
    omega: f64,
    y: f64,
    w: f64,
    acc: &mut MetricAcc,
    ws: &mut PlsScratch,
) -> (f64, f64) {
    let r = update_regression::<0>(out, nr, omega, y, w, ws);
    after_pls::<0>(p, out, nr, w, &r, acc, ws)
}

/// What follows the PLS step `r` of one output ([`after_regression`] on the new projections
/// in `ws.s`), counting a skip of the leverage guard in `ws.skipped`; returns the RF's
/// prediction for that output and the PLS step's guard sum ([`RegOut::chk`]). `R > 0`: the
/// output's number of directions as a constant.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn after_pls<const R: usize>(
    p: &Params,
    out: &mut Pls,
    nr: usize,
    w: f64,
    r: &RegOut,
    acc: &mut MetricAcc,
    ws: &mut PlsScratch,
) -> (f64, f64) {
    let (sv, ps) = (&ws.s, &mut ws.ps);
    if after_regression::<R>(p, out, nr, w, sv, ps, r, acc) {
        ws.skipped += 1;
    }
    (r.yp, r.chk)
}

/// What follows an output's PLS step `r` (new projections `s`, scratch `ps`): the metric's
/// cost terms into `acc` when `update_d`, (e) the growth test and (f) forgetting; true when
/// the leverage guard skipped the cost terms ([`output_terms`]).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn after_regression<const R: usize>(
    p: &Params,
    out: &mut Pls,
    nr: usize,
    w: f64,
    s: &[f64],
    ps: &mut [f64],
    r: &RegOut,
    acc: &mut MetricAcc,
) -> bool {
    let skipped =
        p.cfg.update_d && output_terms::<R>(out, nr, w, s, ps, r.e_cv, r.e, p.cfg.meta, acc);
    check_grow(out, p);
    // Over the directions as they are now (one may have just been added).
    forget(out, p.cfg.tau_lambda, p.cfg.final_lambda);
    // The slope is recomputed when a prediction needs it (`Pls::refresh_slope`).
    out.slope_stale = true;
    skipped
}
