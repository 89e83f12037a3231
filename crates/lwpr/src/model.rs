//! The model and one update (`shared/LWPR.md`, "One update").

use crate::activation::Top2;
use crate::config::{LwprConfig, PruneRule};
use crate::error::{check_scale, check_vec};
use crate::params::Params;
use crate::partition::{RfEvent, RfId};
use crate::rf::SubModel;
use crate::scratch::{quad, Scratch};
use crate::LwprError;
use serde::{Deserialize, Serialize};

/// An incremental LWPR model mapping `n_in` inputs to `n_out` outputs.
///
/// Update with [`Lwpr::update`], predict with [`Lwpr::predict`] (and the `_conf`/`_jacobian`
/// variants); both reuse buffers held by the model and do not allocate except when the
/// partition changes (an RF is added, or a PLS model grows beyond its reserved directions).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Lwpr {
    pub(crate) p: Params,
    pub(crate) subs: Vec<SubModel>,
    pub(crate) next_id: u64,
    pub(crate) n_updates: u64,
    #[serde(skip)]
    pub(crate) ws: Scratch,
    #[serde(skip)]
    pub(crate) events: Vec<RfEvent>,
    #[serde(skip)]
    pub(crate) warnings: Warnings,
}

/// What one update did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UpdateInfo {
    /// Largest activation of an existing RF at the input (over all sub-models), before any RF
    /// was added.
    pub max_w: f64,
    /// RFs added by this update (at most one per sub-model).
    pub added: usize,
    /// RFs pruned by this update (at most one per sub-model).
    pub pruned: usize,
    /// RF updates done (RFs with activation above 0.001, summed over the sub-models); the
    /// cost of an update is roughly proportional to it.
    pub updated: usize,
    /// Numerical guard: outputs of updated RFs whose distance-metric terms were skipped
    /// because the sample's leverage was not below 1 (the leave-one-out cost is undefined
    /// there; the reference library would divide by `1 − h ≤ 0`). Rare: two over 100 seeds of
    /// the 2-D cross test (about 6 million metric steps); common under fast forgetting with
    /// inputs that rarely move.
    pub metric_skipped: usize,
    /// Numerical guard: RFs removed because their prediction at the sample, their regression
    /// (`β`, `p`, `u`) or their metric stopped being finite (announced as [`RfEvent::Pruned`]);
    /// the sub-model concerned neither adds nor prunes in that update.
    pub removed_non_finite: usize,
}

/// Counts of the numerical guards' interventions since the model was created or loaded
/// (not saved with it). See [`UpdateInfo`] for what each counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Warnings {
    /// Sum of [`UpdateInfo::metric_skipped`].
    pub metric_skipped: u64,
    /// Sum of [`UpdateInfo::removed_non_finite`].
    pub removed_non_finite: u64,
}

impl Lwpr {
    /// A model with no receptive fields. Validates `config` (once) for these dimensions.
    pub fn new(n_in: usize, n_out: usize, config: &LwprConfig) -> Result<Lwpr, LwprError> {
        let p = config.validate(n_in, n_out)?;
        let ws = Scratch::new(&p, 0);
        Ok(Lwpr {
            subs: (0..p.n_sub()).map(|_| SubModel::new()).collect(),
            p,
            next_id: 0,
            n_updates: 0,
            ws,
            events: Vec::with_capacity(64),
            warnings: Warnings::default(),
        })
    }

    /// The validated parameters.
    pub fn params(&self) -> &Params {
        &self.p
    }

    /// Number of inputs.
    pub fn n_in(&self) -> usize {
        self.p.n_in
    }

    /// Number of outputs.
    pub fn n_out(&self) -> usize {
        self.p.n_out
    }

    /// Number of sub-models (1 with shared RFs, else `n_out`).
    pub fn n_sub(&self) -> usize {
        self.subs.len()
    }

    /// Number of RFs per sub-model.
    pub fn n_rfs(&self) -> Vec<usize> {
        self.subs.iter().map(|s| s.rfs.len()).collect()
    }

    /// Total number of RFs.
    pub fn n_rfs_total(&self) -> usize {
        self.subs.iter().map(|s| s.rfs.len()).sum()
    }

    /// How often the numerical guards stepped in since the model was created or loaded.
    pub fn warnings(&self) -> Warnings {
        self.warnings
    }

    /// Number of updates so far.
    pub fn n_updates(&self) -> u64 {
        self.n_updates
    }

    /// The prediction the last update made before learning from its sample (user units;
    /// NaN for an output where no trustworthy RF was updated).
    pub fn last_update_prediction(&self) -> &[f64] {
        &self.ws.last_yp
    }

    /// Learns from one sample `(x, y)`. Fails without changing anything when a length is wrong,
    /// a value is not finite, or a value the model uses exceeds [`crate::MAX_NORMALISED`] in
    /// magnitude once divided by its `norm_in`/`norm_out` ([`LwprError::Scale`]). RF additions
    /// and removals are queued as [`RfEvent`]s.
    pub fn update(&mut self, x: &[f64], y: &[f64]) -> Result<UpdateInfo, LwprError> {
        check_vec("x", x, self.p.n_in)?;
        check_vec("y", y, self.p.n_out)?;
        // Inputs the model does not use (outside `kernel_dims` and `regression_dims`) are free.
        let used = self.p.kdims.iter().chain(&self.p.rdims).copied();
        check_scale("x", x, &self.p.norm_in, used)?;
        check_scale("y", y, &self.p.norm_out, 0..y.len())?;
        let Lwpr {
            p,
            subs,
            next_id,
            ws,
            events,
            ..
        } = self;
        ws.invalidate();
        ws.load_x(p, x);
        for o in 0..p.n_out {
            ws.yn[o] = y[o] / p.norm_out[o];
        }
        let mut info = UpdateInfo {
            max_w: 0.0,
            added: 0,
            pruned: 0,
            updated: 0,
            metric_skipped: 0,
            removed_non_finite: 0,
        };
        let ny = p.n_local_out();
        for (s, sub) in subs.iter_mut().enumerate() {
            let o0 = s * ny;
            let r = update_sub(p, sub, s, o0, ws, events, next_id);
            info.max_w = info.max_w.max(r.max_w);
            info.added += r.added as usize;
            info.pruned += r.pruned as usize;
            info.updated += ws.active.len();
            info.metric_skipped += r.metric_skipped;
            info.removed_non_finite += r.removed;
        }
        for o in 0..p.n_out {
            ws.last_yp[o] *= p.norm_out[o];
        }
        self.n_updates += 1;
        self.warnings.metric_skipped += info.metric_skipped as u64;
        self.warnings.removed_non_finite += info.removed_non_finite as u64;
        Ok(info)
    }

    /// Removes and returns the queued RF events (oldest first). The queue grows until drained.
    pub fn drain_events(&mut self) -> std::vec::Drain<'_, RfEvent> {
        self.events.drain(..)
    }

    /// The queued RF events, without removing them.
    pub fn events(&self) -> &[RfEvent] {
        &self.events
    }
}

/// What the update of one sub-model did.
#[derive(Clone, Copy, Debug, Default)]
struct SubOutcome {
    /// Largest activation of an existing RF.
    max_w: f64,
    /// An RF was added.
    added: bool,
    /// An RF was pruned.
    pruned: bool,
    /// Outputs of RFs whose metric terms the leverage guard skipped.
    metric_skipped: usize,
    /// RFs removed because their state stopped being finite.
    removed: usize,
}

/// Updates sub-model `s` (outputs `o0..o0+ny` of `ws.yn`).
///
/// The same code is compiled twice, once for the baseline target and once with AVX2 enabled
/// (chosen at run time); vector instructions do the same IEEE operations in the same order,
/// so both give bit-identical results.
fn update_sub(
    p: &Params,
    sub: &mut SubModel,
    s: usize,
    o0: usize,
    ws: &mut Scratch,
    events: &mut Vec<RfEvent>,
    next_id: &mut u64,
) -> SubOutcome {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::has_avx2() {
        // SAFETY: the CPU supports AVX2 (checked at run time).
        return unsafe { update_sub_avx2(p, sub, s, o0, ws, events, next_id) };
    }
    update_sub_dims::<false>(p, sub, s, o0, ws, events, next_id)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn update_sub_avx2(
    p: &Params,
    sub: &mut SubModel,
    s: usize,
    o0: usize,
    ws: &mut Scratch,
    events: &mut Vec<RfEvent>,
    next_id: &mut u64,
) -> SubOutcome {
    update_sub_dims::<true>(p, sub, s, o0, ws, events, next_id)
}

/// Small input spaces get their own copy of the update with the dimensions as constants, so
/// that the loops over them unroll (the arithmetic is the same).
#[inline(always)]
fn update_sub_dims<const AVX: bool>(
    p: &Params,
    sub: &mut SubModel,
    s: usize,
    o0: usize,
    ws: &mut Scratch,
    events: &mut Vec<RfEvent>,
    next_id: &mut u64,
) -> SubOutcome {
    match (p.nk(), p.nr()) {
        (1, 1) => update_sub_impl::<1, 1, AVX>(p, sub, s, o0, ws, events, next_id),
        (2, 2) => update_sub_impl::<2, 2, AVX>(p, sub, s, o0, ws, events, next_id),
        // The shapes of the learned controllers' models (crate `osrl-learn`): the forward model
        // (kernel on `(q, q̇)`, regression on `(q, q̇, u)`) and the gravity model (kernel on `q`,
        // regression on `(q, q̇, q̈)`) of the 7-DOF and the 3-DOF arms.
        (14, 21) => update_sub_impl::<14, 21, AVX>(p, sub, s, o0, ws, events, next_id),
        (7, 21) => update_sub_impl::<7, 21, AVX>(p, sub, s, o0, ws, events, next_id),
        (6, 9) => update_sub_impl::<6, 9, AVX>(p, sub, s, o0, ws, events, next_id),
        (3, 9) => update_sub_impl::<3, 9, AVX>(p, sub, s, o0, ws, events, next_id),
        // 21 inputs: the robot inverse-dynamics benchmark `[q, q̇, q̈]` and the 21-D cross.
        (21, 21) => update_sub_impl::<21, 21, AVX>(p, sub, s, o0, ws, events, next_id),
        _ => update_sub_impl::<0, 0, AVX>(p, sub, s, o0, ws, events, next_id),
    }
}

/// The update of one sub-model; `NK`, `NR` > 0 fix the kernel and regression dimensions at
/// compile time (0: taken from `p`).
#[inline(always)]
fn update_sub_impl<const NK: usize, const NR: usize, const AVX: bool>(
    p: &Params,
    sub: &mut SubModel,
    s: usize,
    o0: usize,
    ws: &mut Scratch,
    events: &mut Vec<RfEvent>,
    next_id: &mut u64,
) -> SubOutcome {
    let nk = if NK > 0 { NK } else { p.nk() };
    let (ml, ny) = (p.mlen(), p.n_local_out());
    let diag = p.cfg.diag_only;
    let qb = ws.qb_update;
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
    let Top2 {
        q1,
        i1,
        w1,
        q2,
        i2,
        w2,
    } = top;
    ws.yacc[..ny].iter_mut().for_each(|v| *v = 0.0);
    let mut sum_w = 0.0;
    let mut out = SubOutcome::default();
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
    for o in 0..ny {
        ws.last_yp[o0 + o] = if sum_w > 0.0 {
            ws.yacc[o] / sum_w
        } else {
            f64::NAN
        };
    }
    out.metric_skipped = ws.pls.skipped;
    // Add or prune (step 5).
    let w_max = if i1 < usize::MAX {
        w1.unwrap_or_else(|| p.kernel(q1).0)
    } else {
        0.0
    };
    out.max_w = w_max;
    if !ws.diverged.is_empty() {
        // Numerical guard: RFs whose state diverged are removed, each looked up by its id
        // (`remove` moves the last RF into the gap); the indices of the two nearest RFs are
        // stale now, so this sub-model neither adds nor prunes in this update.
        for &id in &ws.diverged {
            let i = sub
                .rfs
                .iter()
                .position(|rf| rf.id == id)
                .expect("a diverged RF is in its sub-model");
            events.push(RfEvent::Pruned {
                sub: s,
                id: RfId(id),
            });
            sub.remove(p, i);
        }
        out.removed = ws.diverged.len();
        return out;
    }
    if w_max <= p.cfg.w_gen {
        let template =
            (i1 < usize::MAX && w_max > 0.1 * p.cfg.w_gen && sub.rfs[i1].trustworthy).then_some(i1);
        let id = *next_id;
        *next_id += 1;
        let y = &ws.yn[o0..o0 + ny];
        sub.add(p, id, &ws.xk, y, template);
        events.push(RfEvent::Added {
            sub: s,
            id: RfId(id),
            copied_from: template.map(|t| RfId(sub.rfs[t].id)),
        });
        if ws.active.capacity() < sub.rfs.len() {
            ws.active.reserve(sub.rfs.len());
        }
        if ws.act_out.capacity() < sub.rfs.len() {
            ws.act_out.reserve(sub.rfs.len());
        }
        if ws.diverged.capacity() < sub.rfs.len() {
            ws.diverged.reserve(sub.rfs.len());
        }
        out.added = true;
        return out;
    }
    if i2 < usize::MAX && w2.unwrap_or_else(|| p.kernel(q2).0) > p.cfg.w_prune {
        // The C library v1.2 removes the wider of the two (smaller trace of D; on a tie the
        // second); LWPR.md and the library's Matlab code the narrower (on a tie the first).
        let (t1, t2) = (sub.trace_d(p, i1), sub.trace_d(p, i2));
        let k = match p.cfg.prune_rule {
            PruneRule::Wider if t1 < t2 => i1,
            PruneRule::Wider => i2,
            PruneRule::Narrower if t2 > t1 => i2,
            PruneRule::Narrower => i1,
        };
        events.push(RfEvent::Pruned {
            sub: s,
            id: RfId(sub.rfs[k].id),
        });
        sub.remove(p, k);
        out.pruned = true;
    }
    out
}
