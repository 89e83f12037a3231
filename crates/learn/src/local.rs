//! The local controllers: one reward-weighted regression per receptive field of the forward
//! model, `u^i = [ẍ_refᵀ, q̇ᵀ, 1] β^i` (eq. 31), following the partition as it changes.

use crate::error::Result;
use lwpr::RfId;
use nalgebra::DMatrix;
use rwr::{OnlineRwr, RwrConfig};
use std::collections::BTreeMap;

/// One local controller and its bookkeeping.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Local {
    pub rwr: OnlineRwr,
    /// Local linear dynamics `ẍ ≈ [uᵀ, q̇ᵀ, (q − c)ᵀ, 1] Θ` by activation-weighted least squares
    /// (a plain weighted regression: fixed `τ`, zero cost); its `u` rows give `Â = ∂ẍ/∂u`.
    pub dynamics: OnlineRwr,
    /// M-steps of the dynamics regression done.
    pub dynamics_updates: u64,
    /// Centre of its receptive field in `(q, q̇)`.
    pub center: Vec<f64>,
    /// Samples since the last M-step.
    pub pending: usize,
    /// M-steps done.
    pub updates: u64,
    /// Effective sample size after the last M-step.
    pub ess: f64,
    /// The learner's sample count when its field was last active above the cutoff (or created).
    pub last_active: u64,
}

/// The shape of the local dynamics regressions: number of features and forgetting factor.
#[derive(Clone, Copy, Debug)]
pub struct DynamicsSpec {
    pub features: usize,
    pub forgetting: f64,
}

/// Features of the local dynamics regression for `n` joints: `[u, q̇, q − c, 1]` and, if
/// `bilinear`, `u_j (q_k − c_k)`.
pub fn dynamics_features(n: usize, bilinear: bool) -> usize {
    3 * n + 1 + if bilinear { n * n } else { 0 }
}

/// All local controllers, keyed by the stable id of their receptive field.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct LocalControllers {
    pub map: BTreeMap<RfId, Local>,
}

impl LocalControllers {
    /// A controller for a new receptive field: `θ` copied from `source` if given and trained,
    /// else from the trained controller with the nearest centre, else the constant command
    /// `u_init` (zero when empty; `d` actions, `p` features, `m` task dimensions).
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &mut self,
        id: RfId,
        center: Vec<f64>,
        source: Option<RfId>,
        u_init: &[f64],
        d: usize,
        m: usize,
        p: usize,
        cfg: &RwrConfig,
        min_ess: f64,
        dynamics: DynamicsSpec,
    ) -> Result<()> {
        let trained = |l: &&Local| l.ess >= min_ess;
        let from = source
            .and_then(|s| self.map.get(&s))
            .filter(trained)
            .or_else(|| {
                self.map
                    .values()
                    .filter(trained)
                    .min_by(|a, b| dist2(&a.center, &center).total_cmp(&dist2(&b.center, &center)))
            });
        let (theta, sigma) = match from {
            Some(l) => (l.rwr.theta().clone(), l.rwr.sigma()),
            None => {
                let mut theta = DMatrix::zeros(p, d);
                for (j, u) in u_init.iter().enumerate() {
                    theta[(p - 1, j)] = *u;
                }
                (theta, cfg.sigma_init)
            }
        };
        let cfg = RwrConfig {
            sigma_init: sigma.max(cfg.sigma_min).max(f64::MIN_POSITIVE),
            ..cfg.clone()
        };
        let rwr = OnlineRwr::with_theta(theta, cfg.clone())?;
        let dyn_cfg = RwrConfig {
            adapt_tau: false,
            update_sigma: false,
            tau_init: 1.0,
            ridge: 1e-6,
            min_ess: 0.0,
            tau_max: None,
            ridge_to_previous: false,
            forgetting: dynamics.forgetting,
            ..cfg
        };
        let dynamics = OnlineRwr::new(dynamics.features, m, dyn_cfg)?;
        self.map.insert(
            id,
            Local {
                rwr,
                dynamics,
                dynamics_updates: 0,
                center,
                pending: 0,
                updates: 0,
                ess: 0.0,
                last_active: 0,
            },
        );
        Ok(())
    }

    pub fn remove(&mut self, id: RfId) {
        self.map.remove(&id);
    }

    /// Appends to `out` the ids of the untrained controllers (`ess < min_ess`) whose field was
    /// last active before sample `before`.
    pub fn stale_untrained(&self, min_ess: f64, before: u64, out: &mut Vec<RfId>) {
        out.extend(
            self.map
                .iter()
                .filter(|(_, l)| l.ess < min_ess && l.last_active < before)
                .map(|(id, _)| *id),
        );
    }

    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// How many controllers are trained (effective sample size ≥ `min_ess`).
    pub fn n_trained(&self, min_ess: f64) -> usize {
        self.map.values().filter(|l| l.ess >= min_ess).count()
    }
}

fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// A summary of one local controller, for diagnostics and reports.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct LocalSummary {
    pub id: u64,
    pub ess: f64,
    pub sigma: f64,
    pub tau: f64,
    pub updates: u64,
}

impl LocalControllers {
    /// Summaries of every local controller, by id.
    pub fn summaries(&self) -> Vec<LocalSummary> {
        self.map
            .iter()
            .map(|(id, l)| LocalSummary {
                id: id.0,
                ess: l.ess,
                sigma: l.rwr.sigma(),
                tau: l.rwr.tau(),
                updates: l.updates,
            })
            .collect()
    }
}
