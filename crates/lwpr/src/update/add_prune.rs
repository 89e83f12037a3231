//! Step 5 of an update (`docs/lwpr.md`, "One update"): a new RF where no RF is active
//! enough, or the pruning of one of two RFs that overlap too much; and the numerical guard's
//! removal of RFs whose state diverged.

use crate::config::PruneRule;
use crate::params::Params;
use crate::rf::{RfEvent, RfId, SubModel};
use crate::scratch::Scratch;
use crate::update::activation::Top2;

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

/// Numerical guard: removes the RFs in `ws.diverged`, each looked up by its id (`remove` moves
/// the last RF into the gap), and announces them as pruned; returns how many.
#[cold]
pub(crate) fn remove_diverged(
    p: &Params,
    sub: &mut SubModel,
    ws: &Scratch,
    cx: SubCtx<'_>,
) -> usize {
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
pub(crate) fn add(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
    top: &Top2,
    w_max: f64,
) {
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
/// second); the written descriptions and the library's Matlab code the narrower (on a tie the first). Returns
/// whether an RF was pruned.
#[inline(always)]
pub(crate) fn prune(p: &Params, sub: &mut SubModel, cx: SubCtx<'_>, top: &Top2) -> bool {
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
