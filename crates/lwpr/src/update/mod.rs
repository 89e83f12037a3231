//! One update of the model (`docs/lwpr.md`, "One update"), the reference code, step by step
//! under the names of the description:
//!
//! 1. normalise the sample (`Lwpr::update`, `model.rs`);
//! 2. the activation pass: every RF's activation, the RFs to update, the two nearest
//!    ([`activation`]);
//! 3. for each RF to update, in order: (a) the weighted means, (b) the PLS regression, (c) its
//!    prediction into the blend, (d) the distance metric, (e) the PLS growth test, (f)
//!    forgetting ([`rf`], with [`regression`] for (a), (b), (e), (f) and [`metric`],
//!    [`metric_derivatives`], [`metric_step`] for (d));
//! 4. the blended prediction before learning;
//! 5. a new RF, or the pruning of one of two overlapping RFs ([`add_prune`]).
//!
//! [`update_sub`] is generic over the [`Stages`] it runs: `reference::Reference` (in the tests) is this
//! code alone; the fast path (`fast/`) replaces some stages by specialisations that give the
//! same bits.

pub(crate) mod activation;
pub(crate) mod add_prune;
pub(crate) mod metric;
pub(crate) mod metric_derivatives;
pub(crate) mod metric_step;
pub(crate) mod prefetch;
#[cfg(test)]
pub(crate) mod reference;
pub(crate) mod regression;
pub(crate) mod rf;
pub(crate) mod stages;

pub(crate) use add_prune::SubCtx;
pub(crate) use metric::MetricScratch;
pub(crate) use regression::PlsScratch;
pub(crate) use stages::Stages;

use crate::params::Params;
use crate::rf::SubModel;
use crate::scratch::Scratch;
use add_prune::{add, prune, remove_diverged};

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

/// Updates sub-model `sub` with the sample in `ws` (steps 2–5), its stages computed by `S`.
#[inline(always)]
pub(crate) fn update_sub<S: Stages>(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    let ny = p.n_local_out();
    // Step 2: the RFs to update (into `ws.active`) and the two nearest.
    let top = S::activations(p, sub, ws);
    // Step 3 for each of them, with (c) their predictions blended.
    let sum_w = S::update_active(p, sub, cx.o0, ws);
    // Step 4: the prediction before learning.
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
        // Numerical guard: the indices of the two nearest RFs are stale now, so no step 5.
        out.removed = remove_diverged(p, sub, ws, cx);
    } else if w_max <= p.cfg.w_gen {
        // Step 5: no RF is active enough.
        add(p, sub, ws, cx, &top, w_max);
        out.added = true;
    } else {
        // Step 5: two RFs may overlap too much.
        out.pruned = prune(p, sub, cx, &top);
    }
    out
}
