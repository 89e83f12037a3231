//! Steps (a)–(d) and (f) of an update for one active receptive field (`shared/LWPR.md`,
//! "One update"). Inlined into the update (a function of its own per RF was tried: more
//! instructions, no faster).

use crate::metric::{self, MetricAcc};
use crate::metric_call::FullStep;
use crate::params::Params;
use crate::pls;
use crate::rf::SubModel;
use crate::scratch::Scratch;

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
/// trustworthy and its state stayed finite. `NK`, `NR` > 0 fix the dimensions; `AVX` is set
/// only by the update's AVX2 entry point (after the CPU check).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn update_rf<const NK: usize, const NR: usize, const AVX: bool>(
    p: &Params,
    sub: &mut SubModel,
    i: usize,
    w: f64,
    dwdq: f64,
    ddwdqdq: f64,
    o0: usize,
    ws: &mut Scratch,
) -> RfOutcome {
    let nk = if NK > 0 { NK } else { p.nk() };
    let nr = if NR > 0 { NR } else { p.nr() };
    let (ml, ny) = (p.mlen(), p.n_local_out());
    let diag = p.cfg.diag_only;
    let y = &ws.yn[o0..o0 + ny];
    let rf = &mut sub.rfs[i];
    let omega = rf.outs[0].sum_w[0] * rf.outs[0].lambda[0];
    pls::update_input_means(nr, rf, omega, &ws.xr, w, &mut ws.pls.xmz);
    if rf.outs[0].n_data[0] > 2.0 * nr as f64 {
        rf.trustworthy = true;
    }
    let mut acc = MetricAcc::default();
    // Numerical guard: the sum of the RF's predictions at the sample, of the PLS steps' results
    // and (below) of the diagonal of `D` is finite iff all are.
    let mut chk = 0.0;
    for (o, out) in rf.outs.iter_mut().enumerate() {
        // Two directions (the usual count at small dimensions) as a constant, so that the
        // loops over them unroll (the arithmetic is the same).
        let (yp, pls_chk) = if NR > 0 && out.n_reg == 2 && !force_dynamic() {
            output_step::<2>(p, out, nr, omega, y[o], w, &mut acc, &mut ws.pls)
        } else {
            output_step::<0>(p, out, nr, omega, y[o], w, &mut acc, &mut ws.pls)
        };
        // Its prediction at the sample may be finite while an untrusted direction is not.
        chk += yp + pls_chk;
        ws.rf_yp[o] = yp;
    }
    let trusted = rf.trustworthy;
    if acc.n == 0 {
        return blend(ws, ny, w, trusted, chk.is_finite());
    }
    let c = &sub.centers[i * nk..(i + 1) * nk];
    for k in 0..nk {
        ws.met.dx[k] = ws.xk[k] - c[k];
    }
    let (m, d) = (
        &mut sub.ms[i * ml..(i + 1) * ml],
        &mut sub.ds[i * ml..(i + 1) * ml],
    );
    let (alpha, b, hm) = (&mut rf.alpha, &mut rf.b, &mut rf.hm);
    if !diag {
        let s = FullStep {
            m,
            d,
            alpha,
            b,
            hm,
            acc,
            dwdq,
            ddwdqdq,
        };
        crate::metric_call::full_step_call::<NK, AVX>(nk, p, s, &mut ws.met);
    } else {
        let (meta, pen) = (p.cfg.meta, p.penalty_n);
        metric::derivatives(nk, diag, meta, m, d, dwdq, ddwdqdq, pen, &mut ws.met);
        metric::step(nk, p, m, d, alpha, b, hm, acc, &mut ws.met);
    }
    // A non-finite element of `M` (or an overflow of `D = MᵀM`) shows on the diagonal of `D`,
    // a sum of squares of `M`'s column.
    let finite = (chk + sub.trace_d(p, i)).is_finite();
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

/// Tests can switch the constant-direction path off (per thread), to compare it with the
/// general one, and count the times it was taken; always `false` outside tests.
#[cfg(test)]
fn force_dynamic() -> bool {
    use crate::tests::const_r::{FAST_PATH_TAKEN, FORCE_DYNAMIC};
    let off = FORCE_DYNAMIC.with(|f| f.get());
    if !off {
        FAST_PATH_TAKEN.with(|n| n.set(n.get() + 1));
    }
    off
}

#[cfg(not(test))]
#[inline(always)]
fn force_dynamic() -> bool {
    false
}

/// Tests can switch the 2-D metric step, the 2-D activation pass and the 2-D plain prediction
/// off too (the same switch, not counted); always `false` outside tests.
#[cfg(test)]
pub(crate) fn general_only() -> bool {
    crate::tests::const_r::FORCE_DYNAMIC.with(|f| f.get())
}

#[cfg(not(test))]
#[inline(always)]
pub(crate) fn general_only() -> bool {
    false
}

/// Steps (b), the metric's output terms, (e) and (f) of one output's PLS model `out` (`R` > 0:
/// its number of directions, as a constant); returns the RF's prediction for that output and
/// the PLS step's guard sum ([`pls::RegOut::chk`]).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn output_step<const R: usize>(
    p: &Params,
    out: &mut crate::rf::Pls,
    nr: usize,
    omega: f64,
    y: f64,
    w: f64,
    acc: &mut MetricAcc,
    ws: &mut pls::PlsScratch,
) -> (f64, f64) {
    // Two directions in two inputs: the PLS step on fixed-size arrays (the same arithmetic).
    let r = if R == 2 && nr == 2 {
        crate::rf_update_2d::regression_2d(out, omega, y, w, ws)
    } else {
        pls::update_regression::<R>(out, nr, omega, y, w, ws)
    };
    let (sv, ps) = (&ws.s, &mut ws.ps);
    if after_regression::<R>(p, out, nr, w, sv, ps, &r, acc) {
        ws.skipped += 1;
    }
    (r.yp, r.chk)
}

/// What follows an output's PLS step `r` (new projections `s`, scratch `ps`): the metric's
/// cost terms into `acc` when `update_d`, (e) the growth test and (f) forgetting; true when
/// the leverage guard skipped the cost terms ([`metric::output_terms`]).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn after_regression<const R: usize>(
    p: &Params,
    out: &mut crate::rf::Pls,
    nr: usize,
    w: f64,
    s: &[f64],
    ps: &mut [f64],
    r: &pls::RegOut,
    acc: &mut MetricAcc,
) -> bool {
    let skipped = p.cfg.update_d
        && metric::output_terms::<R>(out, nr, w, s, ps, r.e_cv, r.e, p.cfg.meta, acc);
    out.check_grow(p);
    // Over the directions as they are now (one may have just been added).
    pls::forget(out, p.cfg.tau_lambda, p.cfg.final_lambda);
    // The slope is recomputed when a prediction needs it (`Pls::refresh_slope`).
    out.slope_stale = true;
    skipped
}
