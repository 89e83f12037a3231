//! The load correction of the re-adaptation (`docs/learner.md`, "Re-adaptation"): a payload or
//! heavier links change mostly the torque the arm needs to hold itself, a smooth function of the
//! state. Rather than asking every local controller to absorb it, the nominal behaviour gets a
//! correction `c(q, q̇) = Σ_i w_i b_i / Σ_i w_i`, one offset `b_i ∈ ℝⁿ` per receptive field of the
//! forward model, blended by the fields' activations `w_i`; the local controllers, which learn
//! `u − u0`, then stay valid.
//!
//! Learning, from measurements only: after a transition, the policy's command for the *measured*
//! `ẍ` is `û = u0 + c + π(q, q̇, ẍ)` (the blend of eq. 34 at `ẍ` instead of `ẍ_ref`). On the robot
//! the controllers were trained on, the executed command `u` and `û` agree up to exploration
//! noise; on a changed robot `ε = u − û` is the torque the change costs, in the directions the
//! controllers act in. Each active field moves its offset towards `c + ε`:
//! `b_i ← b_i + α a w_i (c + ε − b_i)`, `α = dt / load_time_constant`, `a` the re-adaptation's
//! strength — so on an unchanged robot (`a = 0`) nothing moves, and when the change is undone the
//! offsets move back the same way (slowly: `docs/decisions.md`, D-adapt).
//!
//! A field's offset is allocated the first time it learns (as its controller is when the field is
//! added); the blend and the update allocate nothing.

use super::{Features, Models};
use crate::config::LearnerConfig;
use crate::error::Result;
use crate::local::{confidence, smoothstep};
use lwpr::{Activation, RfId};
use osrl_dynamics::Measurement;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The policy's learned part for the measured `ẍ` of `cur` into `out`: the blend of eq. 34
/// (confidence × activation above the cutoff, scaled by `κ` where the support is thin) at
/// `(q, q̇, ẍ)`, without `u0`; `false` where no trained controller is active. `acts` are the
/// activations at `cur`; `phi` and `ui` are scratch.
#[allow(clippy::too_many_arguments)]
pub(crate) fn policy_at(
    cfg: &LearnerConfig,
    f: &Features,
    models: &Models,
    cur: &Measurement,
    acts: &[Activation],
    phi: &mut [f64],
    ui: &mut [f64],
    out: &mut [f64],
) -> Result<bool> {
    let (q, qd) = (cur.q.as_slice(), cur.qd.as_slice());
    let (trained_ess, cut) = (cfg.controllers.trained_ess, cfg.partition.activation_cutoff);
    f.controller_common(phi, cur.xdd.as_slice(), qd);
    out.fill(0.0);
    let mut sum_w = 0.0;
    for a in acts {
        let Some(local) = models.locals.map.get(&a.id) else {
            continue;
        };
        let w = confidence(local.ess, trained_ess) * (a.w - cut);
        if !(w > 0.0) {
            continue;
        }
        f.controller_local(phi, q, &local.center);
        local.rwr.mean_into(phi, ui)?;
        for (o, v) in out.iter_mut().zip(ui.iter()) {
            *o += w * v;
        }
        sum_w += w;
    }
    if !(sum_w > 0.0) {
        return Ok(false);
    }
    let kappa = smoothstep(sum_w / cfg.controllers.prior_weight);
    out.iter_mut().for_each(|v| *v *= kappa / sum_w);
    Ok(true)
}

/// The per-field offsets `b_i` and the last blended correction.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LoadCorrection {
    /// Offset `b_i` (N·m, one per joint) of each receptive field that has learned one.
    offsets: BTreeMap<RfId, Vec<f64>>,
}

impl LoadCorrection {
    /// Whether no field has an offset (the correction is then 0 everywhere).
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }

    /// Number of fields with an offset.
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// Largest offset entry in absolute value (N·m), 0 without offsets.
    pub fn max_abs(&self) -> f64 {
        self.offsets
            .values()
            .flat_map(|b| b.iter())
            .fold(0.0, |m: f64, v| m.max(v.abs()))
    }

    /// Adds `c = Σ w_i b_i / Σ w_i` over the fields of `acts` that have an offset to `u`; returns
    /// whether any had one.
    pub(crate) fn add_into(&self, acts: &[Activation], u: &mut [f64]) -> bool {
        if self.offsets.is_empty() {
            return false;
        }
        let sum_w: f64 = acts
            .iter()
            .filter(|a| self.offsets.contains_key(&a.id))
            .map(|a| a.w)
            .sum();
        if !(sum_w > 0.0) {
            return false;
        }
        for a in acts {
            if let Some(b) = self.offsets.get(&a.id) {
                let k = a.w / sum_w;
                for (o, v) in u.iter_mut().zip(b) {
                    *o += k * v;
                }
            }
        }
        true
    }

    /// Moves the offset of each field in `acts` towards `target` (`c + ε`) with gain `gain · w`
    /// (a field without one starts at `c`, the blend of its neighbours, given in `c`).
    pub(crate) fn learn(&mut self, acts: &[Activation], c: &[f64], target: &[f64], gain: f64) {
        for a in acts {
            let k = (gain * a.w).min(1.0);
            if !(k > 0.0) {
                continue;
            }
            let b = self.offsets.entry(a.id).or_insert_with(|| c.to_vec());
            for (bi, t) in b.iter_mut().zip(target) {
                *bi += k * (t - *bi);
            }
        }
    }

    /// Drops the offset of a removed field.
    pub(crate) fn remove(&mut self, id: RfId) {
        self.offsets.remove(&id);
    }
}

#[cfg(test)]
mod tests {
    use super::LoadCorrection;
    use lwpr::{Activation, RfId};

    fn act(id: u64, w: f64) -> Activation {
        Activation { id: RfId(id), w }
    }

    /// Repeated samples with the same target move the offsets there; the correction is the
    /// activation-weighted blend of the offsets, and 0 where no field has one.
    #[test]
    fn offsets_converge_to_the_target_and_blend_by_activation() {
        let mut load = LoadCorrection::default();
        let mut u = [1.0, 2.0];
        assert!(!load.add_into(&[act(1, 1.0)], &mut u));
        assert_eq!(u, [1.0, 2.0]);
        for _ in 0..5000 {
            load.learn(&[act(1, 1.0)], &[0.0, 0.0], &[3.0, -1.0], 0.01);
            load.learn(&[act(2, 0.5)], &[0.0, 0.0], &[1.0, 1.0], 0.01);
        }
        let mut c = [0.0; 2];
        assert!(load.add_into(&[act(1, 0.75), act(2, 0.25), act(3, 1.0)], &mut c));
        let want = [0.75 * 3.0 + 0.25, -0.75 + 0.25];
        for j in 0..2 {
            assert!((c[j] - want[j]).abs() < 1e-6, "{c:?} vs {want:?}");
        }
        assert_eq!(load.len(), 2);
        load.remove(RfId(1));
        assert_eq!(load.len(), 1);
        // With gain 0 nothing moves.
        let before = load.clone();
        load.learn(&[act(2, 1.0)], &[0.0, 0.0], &[9.0, 9.0], 0.0);
        assert_eq!(load, before);
    }
}
