//! The update of one sub-model (`shared/LWPR.md`, "One update"): the activation pass, the
//! update of every active RF (steps 1–4), the removal of RFs whose state diverged, and step 5,
//! adding or pruning an RF.

use crate::activation::Top2;
use crate::config::PruneRule;
use crate::params::Params;
use crate::partition::{RfEvent, RfId};
use crate::rf::SubModel;
use crate::scratch::{quad, Scratch};

/// What the update of one sub-model did.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SubOutcome {
    /// Largest activation of an existing RF.
    pub max_w: f64,
    /// An RF was added.
    pub added: bool,
    /// An RF was pruned.
    pub pruned: bool,
    /// Outputs of RFs whose metric terms the leverage guard skipped.
    pub metric_skipped: usize,
    /// RFs removed because their state stopped being finite.
    pub removed: usize,
}

/// Which sub-model is updated, and where its changes to the partition go.
pub(crate) struct SubCtx<'a> {
    /// Index of the sub-model (for its [`RfEvent`]s).
    pub s: usize,
    /// Its first output in `ws.yn` (its outputs are `o0..o0 + p.n_local_out()`).
    pub o0: usize,
    /// The model's queue of RF events.
    pub events: &'a mut Vec<RfEvent>,
    /// The model's next RF id.
    pub next_id: &'a mut u64,
}

/// Updates sub-model `sub` with the sample in `ws`.
///
/// The same code is compiled twice, once for the baseline target and once with AVX2 enabled
/// (chosen at run time); vector instructions do the same IEEE operations in the same order,
/// so both give bit-identical results.
pub(crate) fn update_sub(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::has_avx2() {
        // SAFETY: the CPU supports AVX2 (checked at run time).
        return unsafe { update_sub_avx2(p, sub, ws, cx) };
    }
    update_sub_dims::<false>(p, sub, ws, cx)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn update_sub_avx2(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    update_sub_dims::<true>(p, sub, ws, cx)
}

/// Small input spaces get their own copy of the update with the dimensions as constants, so
/// that the loops over them unroll (the arithmetic is the same).
#[inline(always)]
fn update_sub_dims<const AVX: bool>(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    match (p.nk(), p.nr()) {
        (1, 1) => update_sub_impl::<1, 1, AVX>(p, sub, ws, cx),
        (2, 2) => update_sub_impl::<2, 2, AVX>(p, sub, ws, cx),
        // The shapes of the learned controllers' models (crate `osrl-learn`): the forward model
        // (kernel on `(q, q̇)`, regression on `(q, q̇, u)`) and the gravity model (kernel on `q`,
        // regression on `(q, q̇, q̈)`) of the 7-DOF and the 3-DOF arms.
        (14, 21) => update_sub_impl::<14, 21, AVX>(p, sub, ws, cx),
        (7, 21) => update_sub_impl::<7, 21, AVX>(p, sub, ws, cx),
        (6, 9) => update_sub_impl::<6, 9, AVX>(p, sub, ws, cx),
        (3, 9) => update_sub_impl::<3, 9, AVX>(p, sub, ws, cx),
        // 21 inputs: the robot inverse-dynamics benchmark `[q, q̇, q̈]` and the 21-D cross.
        (21, 21) => update_sub_impl::<21, 21, AVX>(p, sub, ws, cx),
        _ => update_sub_impl::<0, 0, AVX>(p, sub, ws, cx),
    }
}

/// The update of one sub-model; `NK`, `NR` > 0 fix the kernel and regression dimensions at
/// compile time (0: taken from `p`).
#[inline(always)]
fn update_sub_impl<const NK: usize, const NR: usize, const AVX: bool>(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    let ny = p.n_local_out();
    // The RFs to update (into `ws.active`) and the two nearest.
    let top = activations::<NK, AVX>(p, sub, ws);
    // Steps 1–4 for each of them, and the prediction before learning.
    let sum_w = update_active::<NK, NR, AVX>(p, sub, cx.o0, ws);
    for o in 0..ny {
        ws.last_yp[cx.o0 + o] = if sum_w > 0.0 {
            ws.yacc[o] / sum_w
        } else {
            f64::NAN
        };
    }
    let w_max = top.w_max(p);
    let mut out = SubOutcome {
        max_w: w_max,
        metric_skipped: ws.pls.skipped,
        ..SubOutcome::default()
    };
    if !ws.diverged.is_empty() {
        // The indices of the two nearest RFs are stale now: no step 5 in this update.
        out.removed = remove_diverged(p, sub, ws, cx);
    } else if w_max <= p.cfg.w_gen {
        add(p, sub, ws, cx, &top, w_max);
        out.added = true;
    } else {
        out.pruned = prune(p, sub, cx, &top);
    }
    out
}

/// The activation pass: queues in `ws.active` every RF whose activation exceeds the update
/// threshold, with the kernel's derivatives, and returns the two nearest RFs.
#[inline(always)]
fn activations<const NK: usize, const AVX: bool>(
    p: &Params,
    sub: &SubModel,
    ws: &mut Scratch,
) -> Top2 {
    let nk = if NK > 0 { NK } else { p.nk() };
    let (ml, diag, qb) = (p.mlen(), p.cfg.diag_only, ws.qb_update);
    let mut top = Top2::new();
    ws.active.clear();
    if NK == 2 && !diag && !crate::rf_update::general_only() {
        // Four RFs at a time (the 2-D cross test's shape); the same `q`s.
        let active = &mut ws.active;
        crate::activation::for_each_q::<AVX>(&sub.centers, &sub.ms, &ws.xk, |i, q| {
            top.visit(p, qb, i, q, active)
        });
    } else {
        let kern = if diag { &sub.ds } else { &sub.ms };
        // Centres and metrics by chunks (no index arithmetic or bounds checks per RF).
        let rf_chunks = sub.centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
        for (i, (c, md)) in rf_chunks.enumerate() {
            // An RF at q ≥ max(qb, q2) is neither updated nor among the two most active.
            let q = quad(diag, c, md, &ws.xk[..nk], &mut ws.met.dx, qb.max(top.q2));
            top.visit(p, qb, i, q, &mut ws.active);
        }
    }
    top
}

/// Updates every RF in `ws.active` (steps 1–4), blends their predictions into `ws.yacc` and
/// returns the sum of the blended RFs' weights; the ids of RFs whose state diverged go to
/// `ws.diverged`, the leverage guard's count to `ws.pls.skipped`.
#[inline(always)]
fn update_active<const NK: usize, const NR: usize, const AVX: bool>(
    p: &Params,
    sub: &mut SubModel,
    o0: usize,
    ws: &mut Scratch,
) -> f64 {
    ws.yacc[..p.n_local_out()].iter_mut().for_each(|v| *v = 0.0);
    let mut sum_w = 0.0;
    ws.diverged.clear();
    ws.pls.skipped = 0;
    let groups = crate::rf_update_group::applies::<NK, NR>(p) && !crate::rf_update::general_only();
    let mut a = 0;
    while a < ws.active.len() {
        if groups {
            // The 2-D cross test's shape: several RFs at a time (the same results).
            a = crate::rf_update_group::update_groups(p, sub, a, o0, ws, &mut sum_w);
            if a == ws.active.len() {
                break;
            }
        }
        let (i, w, dwdq, ddwdqdq) = ws.active[a];
        let r = crate::rf_update::update_rf::<NK, NR, AVX>(p, sub, i, w, dwdq, ddwdqdq, o0, ws);
        if r.blended {
            sum_w += w;
        }
        if !r.finite {
            ws.diverged.push(sub.rfs[i].id);
        }
        a += 1;
    }
    sum_w
}

/// Numerical guard: removes the RFs in `ws.diverged`, each looked up by its id (`remove` moves
/// the last RF into the gap), and announces them as pruned; returns how many.
#[cold]
fn remove_diverged(p: &Params, sub: &mut SubModel, ws: &Scratch, cx: SubCtx<'_>) -> usize {
    for &id in &ws.diverged {
        let i = sub
            .rfs
            .iter()
            .position(|rf| rf.id == id)
            .expect("a diverged RF is in its sub-model");
        cx.events.push(RfEvent::Pruned {
            sub: cx.s,
            id: RfId(id),
        });
        sub.remove(p, i);
    }
    ws.diverged.len()
}

/// Step 5, no RF activated above `w_gen` (`w_max`, the nearest RF's activation): adds an RF
/// at the sample, a copy of the nearest RF (`top`) when that one is trustworthy and activated
/// above `0.1·w_gen`; reserves the scratch for the new RF count.
#[inline(never)]
fn add(p: &Params, sub: &mut SubModel, ws: &mut Scratch, cx: SubCtx<'_>, top: &Top2, w_max: f64) {
    let i1 = top.i1;
    let template =
        (i1 < usize::MAX && w_max > 0.1 * p.cfg.w_gen && sub.rfs[i1].trustworthy).then_some(i1);
    let id = *cx.next_id;
    *cx.next_id += 1;
    let y = &ws.yn[cx.o0..cx.o0 + p.n_local_out()];
    sub.add(p, id, &ws.xk, y, template);
    cx.events.push(RfEvent::Added {
        sub: cx.s,
        id: RfId(id),
        copied_from: template.map(|t| RfId(sub.rfs[t].id)),
    });
    let n = sub.rfs.len();
    if ws.active.capacity() < n {
        ws.active.reserve(n);
    }
    if ws.act_out.capacity() < n {
        ws.act_out.reserve(n);
    }
    if ws.diverged.capacity() < n {
        ws.diverged.reserve(n);
    }
}

/// Step 5, when the two nearest RFs (`top`) both activate above `w_prune`: removes one of
/// them. The C library v1.2 removes the wider of the two (smaller trace of `D`; on a tie the
/// second); LWPR.md and the library's Matlab code the narrower (on a tie the first). Returns
/// whether an RF was pruned.
#[inline(always)]
fn prune(p: &Params, sub: &mut SubModel, cx: SubCtx<'_>, top: &Top2) -> bool {
    let (i1, i2) = (top.i1, top.i2);
    // `w_sec` is 0 without a second RF, and `w_prune` is positive.
    let both = top.w_sec(p) > p.cfg.w_prune;
    if !both {
        return false;
    }
    let (t1, t2) = (sub.trace_d(p, i1), sub.trace_d(p, i2));
    let k = match p.cfg.prune_rule {
        PruneRule::Wider if t1 < t2 => i1,
        PruneRule::Wider => i2,
        PruneRule::Narrower if t2 > t1 => i2,
        PruneRule::Narrower => i1,
    };
    cx.events.push(RfEvent::Pruned {
        sub: cx.s,
        id: RfId(sub.rfs[k].id),
    });
    sub.remove(p, k);
    true
}
