//! The RF updates of the 2-D cross test's shape — kernel and regression on two inputs, full
//! metric, one output per sub-model, two PLS directions — taken three (or two) RFs at a time:
//! each step of `update_rf` (`update/rf.rs`) (means, PLS, cost terms, metric step, guard and
//! blend) is taken for every RF of the group before the next step. The means, the PLS step, the
//! cost terms, forgetting and the metric step are the 2-D code `update_rf` calls; the trust
//! test, the guard's sum and the blend are written out here, as there. The results are those
//! of the RFs updated one after the other, bit for bit (each RF's arithmetic is its own; the
//! blend adds in the RFs' order; tested in `tests/group.rs`).
//!
//! Why: a 2-D RF update is ≈ 1,000 instructions of mostly serial arithmetic (divisions, square
//! roots, `exp`), longer than the CPU's reorder window, so one RF's steps barely overlapped the
//! next one's. Interleaved by steps, neighbouring steps belong to different RFs and are
//! independent. Measured (fingerprint, 2-D cross, seed 0, 20 epochs, 16 interleaved runs): the
//! update about 9 % faster when the machine is quiet (median ratios 0.904–0.913), about 1 %
//! when a neighbour shares the core; 2.3 % fewer instructions (`docs/history/lwpr-speed.md`,
//! ninth round).

use crate::fast::plane_metric::{step_2d, MetricState};
use crate::fast::plane_pls::{arr, regression_2d_core};
use crate::params::Params;
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::update::metric::MetricAcc;
use crate::update::regression::{update_input_means, RegOut};
use crate::update::rf::{after_regression, start_blend, update_one, RfOutcome};
use crate::update::Stages;

/// `Stages::update_active` with groups: the RFs of `ws.active` in groups of three or two
/// where they can be ([`update_groups`]), the others one at a time by `update_one`.
#[inline(always)]
pub(crate) fn update_active_grouped<S: Stages>(
    p: &Params,
    sub: &mut SubModel,
    o0: usize,
    ws: &mut Scratch,
) -> f64 {
    let mut sum_w = start_blend(p, ws);
    let mut a = 0;
    while a < ws.active.len() {
        a = update_groups(p, sub, a, o0, ws, &mut sum_w);
        if a == ws.active.len() {
            break;
        }
        update_one::<S>(p, sub, a, o0, ws, &mut sum_w);
        a += 1;
    }
    sum_w
}

/// Updates the active RFs `ws.active[a..]` of `sub` from `a` on in groups of three (two when
/// two or four are left), as long as the next group's RFs all have two PLS directions; adds
/// the weights of the RFs that entered the blend to `sum_w` and the ids of diverged RFs to
/// `ws.diverged`. Returns the index of the first RF not updated (the caller updates it alone
/// and calls again).
#[inline(always)]
pub(crate) fn update_groups(
    p: &Params,
    sub: &mut SubModel,
    mut a: usize,
    o0: usize,
    ws: &mut Scratch,
    sum_w: &mut f64,
) -> usize {
    loop {
        // The group's size, decided once (four left: two pairs, not three and one alone).
        let g = match ws.active.len() - a {
            0 | 1 => return a,
            2 | 4 => 2,
            _ => 3,
        };
        let done = if g == 2 {
            group::<2>(p, sub, a, o0, ws, sum_w)
        } else {
            group::<3>(p, sub, a, o0, ws, sum_w)
        };
        if !done {
            return a;
        }
        a += g;
    }
}

/// [`update_group_2d`] on `ws.active[a..a + G]` with its bookkeeping; false (nothing done)
/// when one of these RFs has more or fewer than two directions.
#[inline(always)]
fn group<const G: usize>(
    p: &Params,
    sub: &mut SubModel,
    a: usize,
    o0: usize,
    ws: &mut Scratch,
    sum_w: &mut f64,
) -> bool {
    let act: [_; G] = ws.active[a..a + G]
        .try_into()
        .expect("a group within the active RFs");
    if act.iter().any(|x| sub.rfs[x.0].outs[0].n_reg != 2) {
        return false;
    }
    let r = update_group_2d::<G>(p, sub, act, o0, ws);
    for l in 0..G {
        if r[l].blended {
            *sum_w += act[l].1;
        }
        if !r[l].finite {
            ws.diverged.push(sub.rfs[act[l].0].id);
        }
    }
    true
}

/// Updates the RFs `act[l]` (index, w, dw/dq, d²w/dq², distinct indices) of `sub`, each with
/// two directions, as `update_rf` (`update/rf.rs`) would one after the other, their steps
/// interleaved; adds the predictions of those trustworthy and finite to the blend (`ws.yacc`)
/// in order.
#[inline(always)]
fn update_group_2d<const L: usize>(
    p: &Params,
    sub: &mut SubModel,
    act: [(usize, f64, f64, f64); L],
    o0: usize,
    ws: &mut Scratch,
) -> [RfOutcome; L] {
    let ii = act.map(|a| a.0);
    let w = act.map(|a| a.1);
    let (dwdq, ddwdqdq) = (act.map(|a| a.2), act.map(|a| a.3));
    let y = ws.yn[o0];
    let xr = *arr::<2>(&mut ws.xr);
    let xk = *arr::<2>(&mut ws.xk);
    let SubModel {
        rfs,
        centers,
        ms,
        ds,
        ..
    } = sub;
    let Ok(mut rf) = rfs.get_disjoint_mut(ii) else {
        unreachable!("the active RFs are distinct")
    };
    // (a) Means, and the trust test (`n_data > 2·nr`, as `update_rf`).
    let mut omega = [0.0; L];
    let mut xmz = [[0.0; 2]; L];
    for l in 0..L {
        omega[l] = rf[l].outs[0].sum_w[0] * rf[l].outs[0].lambda[0];
        update_input_means(2, rf[l], omega[l], &xr, w[l], &mut xmz[l]);
        if rf[l].outs[0].n_data[0] > 2.0 * 2.0 {
            rf[l].trustworthy = true;
        }
    }
    // (b) The PLS step.
    let mut reg = [RegOut::default(); L];
    let mut sn = [[0.0; 2]; L];
    for l in 0..L {
        (reg[l], sn[l]) = regression_2d_core(&mut rf[l].outs[0], omega[l], y, w[l], xmz[l]);
    }
    // The cost terms of (d), (e) the growth test and (f) forgetting (`output_step`).
    let mut acc = [MetricAcc::default(); L];
    let mut ps = [[0.0; 2]; L];
    for l in 0..L {
        let out = &mut rf[l].outs[0];
        if after_regression::<2>(p, out, 2, w[l], &sn[l], &mut ps[l], &reg[l], &mut acc[l]) {
            ws.pls.skipped += 1;
        }
    }
    // (d) The metric steps.
    for l in 0..L {
        if acc[l].n == 0 {
            continue;
        }
        let i = ii[l];
        let c = &centers[i * 2..i * 2 + 2];
        let dx = [xk[0] - c[0], xk[1] - c[1]];
        let r = &mut *rf[l];
        let st = MetricState {
            m: arr(&mut ms[i * 4..i * 4 + 4]),
            d: arr(&mut ds[i * 4..i * 4 + 4]),
            alpha: arr(&mut r.alpha),
            b: arr(&mut r.b),
            hm: arr(&mut r.hm),
        };
        step_2d(p, st, acc[l], dx, dwdq[l], ddwdqdq[l]);
    }
    let trusted = rf.each_mut().map(|r| r.trustworthy);
    // Guards and the blend, in the RFs' order.
    let mut outc = [RfOutcome {
        blended: false,
        finite: true,
    }; L];
    for l in 0..L {
        let chk = 0.0 + (reg[l].yp + reg[l].chk);
        let finite = if acc[l].n == 0 {
            chk.is_finite()
        } else {
            (chk + sub.trace_d(p, ii[l])).is_finite()
        };
        let blended = trusted[l] && finite;
        if blended {
            ws.yacc[0] += w[l] * reg[l].yp;
        }
        outc[l] = RfOutcome { blended, finite };
    }
    outc
}
