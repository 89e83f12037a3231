//! The model and one update (`docs/lwpr.md`, "One update"): the checks and the normalisation
//! of a sample (step 1), then the update of each sub-model (`update/`, on the fast path).

use crate::config::LwprConfig;
use crate::error::{check_scale, check_vec};
use crate::params::Params;
use crate::rf::{RfEvent, SubModel};
use crate::scratch::Scratch;
use crate::update::{SubCtx, SubOutcome};
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

    /// The prediction of the last update at its sample: the updated receptive fields' own
    /// predictions, each made after its regression learned from the sample, blended by their
    /// activations (the reference's `lwpr_update` returns the same `yp`; user units; NaN for an
    /// output where no trustworthy RF was updated).
    pub fn last_update_prediction(&self) -> &[f64] {
        &self.ws.last_yp
    }

    /// Learns from one sample `(x, y)`. Fails without changing anything when a length is wrong,
    /// a value is not finite, or a value the model uses exceeds [`crate::MAX_NORMALISED`] in
    /// magnitude once divided by its `norm_in`/`norm_out` ([`LwprError::Scale`]). RF additions
    /// and removals are queued as [`RfEvent`]s.
    pub fn update(&mut self, x: &[f64], y: &[f64]) -> Result<UpdateInfo, LwprError> {
        self.update_by(x, y, crate::fast::update_sub)
    }

    /// [`Lwpr::update`] with each sub-model updated by `update_sub` (the fast path; tests pass
    /// the reference, `update::update_sub::<Reference>`, or the fast path with some
    /// specialisations off).
    pub(crate) fn update_by(
        &mut self,
        x: &[f64],
        y: &[f64],
        update_sub: impl Fn(&Params, &mut SubModel, &mut Scratch, SubCtx<'_>) -> SubOutcome,
    ) -> Result<UpdateInfo, LwprError> {
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
            let cx = SubCtx {
                s,
                o0,
                events,
                next_id,
            };
            let r = update_sub(p, sub, ws, cx);
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
