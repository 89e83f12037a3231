//! The local controllers: one reward-weighted regression per receptive field of the partition,
//! `u^i = u0 + φᵀ β^i` (eq. 31), each with its local dynamics regression, following the partition
//! as fields are added and pruned; their M-steps (eqs. 23–24, 28).

use crate::error::Result;
use lwpr::RfId;
use nalgebra::DMatrix;
use rwr::{OnlineRwr, RwrConfig};
use std::collections::BTreeMap;

/// Confidence `c ∈ [0, 1]` of a controller whose last M-step had effective sample size `ess`:
/// 0 up to half of `trained_ess`, 1 from 1.5 times it, linear in between.
pub(crate) fn confidence(ess: f64, trained_ess: f64) -> f64 {
    (ess / trained_ess - 0.5).clamp(0.0, 1.0)
}

/// `smoothstep(x) = x² (3 − 2x)` of `x` clamped to `[0, 1]`: the fades of the command's blend,
/// of its neighbours (`learner/nearest.rs`), of the load correction and of the driver's
/// hand-overs.
pub(crate) fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// The weight `w̃ = c (w − cutoff)` of a controller of confidence `c` ([`confidence`] of its
/// `ess`) whose field is active at `w` in the command's blend (eq. 34, `learner/command.rs`):
/// 0 where the field enters at the cutoff and for an untrained controller.
pub(crate) fn blend_weight(ess: f64, trained_ess: f64, w: f64, cutoff: f64) -> f64 {
    confidence(ess, trained_ess) * (w - cutoff)
}

/// One local controller and its bookkeeping.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Local {
    /// The controller `β^i` (features × joints) with its `τ_i`, `σ_i` and sufficient statistics.
    pub rwr: OnlineRwr,
    /// Local linear dynamics `ẍ ≈ φ_dᵀ Θ` by activation-weighted least squares (a plain weighted
    /// regression: fixed `τ`, zero cost); its `u` rows give `Â = ∂ẍ/∂u`.
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
    /// The command's `β` before the last M-step (`controllers.step_spread`): the controller
    /// commands with a blend from it to `rwr`'s `β`. Not saved (a loaded controller commands
    /// with its own `β`).
    #[serde(skip)]
    pub theta_from: Option<DMatrix<f64>>,
    /// Commands this controller took part in since its last M-step (saturating).
    #[serde(skip)]
    pub ramp: u32,
    /// `Â_i`'s coefficients of the local dynamics laid out for the blend
    /// (`Features::gain_table`), rebuilt at each M-step of the dynamics. Empty until the first
    /// one after creation or a load; `Θ` is then read directly, with the same bits.
    #[serde(skip)]
    pub gain_table: Vec<f64>,
}

/// What a new local controller is made of: its feature layouts and regression settings.
#[derive(Clone, Debug)]
pub(crate) struct LocalSpec<'a> {
    /// The layouts of the controller's `φ` and the local dynamics' `φ_d`.
    pub features: crate::learner::Features,
    /// Forgetting and trust region (m/s², 0 = none) of the local dynamics regression.
    pub dynamics_forgetting: f64,
    pub dynamics_trust_region: f64,
    pub rwr: &'a RwrConfig,
    /// Effective sample size at which a controller counts as trained.
    pub trained_ess: f64,
}

/// How fast a field learns at an M-step: the dynamics are re-solved at every `solve_every`-th
/// M-step (at every one with `solve_always`), the trust region is widened by `trust_scale`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pace {
    pub solve_every: u64,
    pub solve_always: bool,
    pub trust_scale: f64,
    /// `controllers.step_spread`.
    pub spread: usize,
    /// The feature layout (for [`Local::gain_table`]).
    pub features: crate::learner::Features,
}

/// The outcome of one M-step of a local controller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MStep {
    Done,
    Failed,
}

impl Local {
    /// Records one hindsight sample (`phi → target`, cost `r`, activation `w`) and runs the
    /// M-step when `update_every` samples are pending, at the `pace` given (when the local
    /// dynamics are re-solved, how far the controller may move). `None` when no M-step was due.
    pub(crate) fn observe(
        &mut self,
        phi: &[f64],
        target: &[f64],
        r: f64,
        w: f64,
        update_every: usize,
        pace: Pace,
    ) -> Result<Option<MStep>> {
        self.rwr.observe(phi, target, r, w)?;
        self.pending += 1;
        if self.pending < update_every {
            return Ok(None);
        }
        self.pending = 0;
        let solve = pace.solve_always || self.updates.is_multiple_of(pace.solve_every);
        if solve && self.dynamics.update().is_ok() {
            self.dynamics_updates += 1;
            pace.features
                .gain_table(self.dynamics.theta(), &mut self.gain_table);
        }
        if pace.spread > 1 {
            // Ramp from the β commanded now (mid-ramp: the blend) to the new one.
            let a = self.alpha(pace.spread);
            let theta = self.rwr.theta();
            match self.theta_from.as_mut() {
                Some(f) => f.zip_apply(theta, |f, t| *f += a * (t - *f)),
                None => self.theta_from = Some(theta.clone()),
            }
            self.ramp = 0;
        }
        Ok(Some(match self.rwr.update_scaled(pace.trust_scale) {
            Ok(info) => {
                self.ess = info.ess;
                self.updates += 1;
                MStep::Done
            }
            Err(_) => MStep::Failed,
        }))
    }

    /// `α ∈ [0, 1]` of the ramp from `theta_from` to the new `β`: `ramp / spread`.
    fn alpha(&self, spread: usize) -> f64 {
        (self.ramp as f64 / spread.max(1) as f64).min(1.0)
    }

    /// The controller's mean command `(1 − α) β_fromᵀφ + α βᵀφ` into `out` for one more command
    /// (it advances the ramp; `tmp`: scratch of the same length). Does not allocate.
    pub(crate) fn mean_into(
        &mut self,
        phi: &[f64],
        spread: usize,
        out: &mut [f64],
        tmp: &mut [f64],
    ) -> Result<()> {
        self.ramp = self.ramp.saturating_add(1);
        self.mean_held(phi, spread, out, tmp)
    }

    /// [`Local::mean_into`] without advancing the ramp: a neighbour's command where the
    /// support is thin (`learner/nearest.rs`), which is not the controller's own command.
    pub(crate) fn mean_held(
        &self,
        phi: &[f64],
        spread: usize,
        out: &mut [f64],
        tmp: &mut [f64],
    ) -> Result<()> {
        self.rwr.mean_into(phi, out)?;
        let a = self.alpha(spread);
        let Some(from) = self.theta_from.as_ref().filter(|_| a < 1.0) else {
            return Ok(());
        };
        let p = from.nrows();
        for (j, t) in tmp.iter_mut().enumerate() {
            let col = &from.as_slice()[j * p..(j + 1) * p];
            *t = col.iter().zip(phi).map(|(c, f)| c * f).sum();
        }
        for (o, t) in out.iter_mut().zip(tmp.iter()) {
            *o = t + a * (*o - t);
        }
        Ok(())
    }

    /// Whether the controller's effective sample size is below `ess`.
    pub fn untrained(&self, ess: f64) -> bool {
        self.ess < ess
    }
}

/// All local controllers, keyed by the stable id of their receptive field.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct LocalControllers {
    pub map: BTreeMap<RfId, Local>,
}

impl LocalControllers {
    /// A controller for a new receptive field at `center`, created at sample `now`, starting
    /// from `init` (`β` and `σ`, e.g. its trained neighbours' blend at its centre) or, without
    /// one, from the constant command `u_init` (zero when empty) and `σ0`.
    pub(crate) fn add(
        &mut self,
        id: RfId,
        center: Vec<f64>,
        init: Option<(DMatrix<f64>, f64)>,
        u_init: &[f64],
        spec: &LocalSpec,
        now: u64,
    ) -> Result<()> {
        let f = &spec.features;
        let (n, m) = f.dims();
        let (theta, sigma) = init.unwrap_or_else(|| {
            let mut theta = DMatrix::zeros(f.controller_len(), n);
            for (j, u) in u_init.iter().enumerate() {
                theta[(f.controller_constant(), j)] = *u;
            }
            (theta, spec.rwr.sigma_init)
        });
        let cfg = RwrConfig {
            sigma_init: sigma.max(spec.rwr.sigma_min).max(f64::MIN_POSITIVE),
            ..spec.rwr.clone()
        };
        let rwr = OnlineRwr::with_theta(theta, cfg.clone())?;
        let dynamics = OnlineRwr::new(f.dynamics_len(), m, dynamics_config(cfg, spec))?;
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
                last_active: now,
                theta_from: None,
                ramp: 0,
                gain_table: Vec::with_capacity(m * (n + n * n)),
            },
        );
        Ok(())
    }

    /// The blend of the trained controllers active at `center` (activations `acts` there, each
    /// weighted by its confidence) as one controller centred at `center`: each `β_j` moved to
    /// `center` so that it gives the same command at every `q` (`Features::recentre`), and
    /// their blended `σ`. `None` if no trained controller is active.
    pub(crate) fn neighbour_blend(
        &self,
        acts: &[lwpr::Activation],
        center: &[f64],
        features: &crate::learner::Features,
        trained_ess: f64,
    ) -> Option<(DMatrix<f64>, f64)> {
        let mut out: Option<(DMatrix<f64>, f64)> = None;
        let mut sum_w = 0.0;
        for a in acts {
            let Some(l) = self.map.get(&a.id) else {
                continue;
            };
            let w = confidence(l.ess, trained_ess) * a.w;
            if !(w > 0.0) {
                continue;
            }
            let mut beta = l.rwr.theta().clone();
            features.recentre(&mut beta, &l.center, center);
            let (acc, sigma) =
                out.get_or_insert_with(|| (DMatrix::zeros(beta.nrows(), beta.ncols()), 0.0));
            *acc += w * beta;
            *sigma += w * l.rwr.sigma();
            sum_w += w;
        }
        out.map(|(b, s)| (b / sum_w, s / sum_w))
    }

    pub fn remove(&mut self, id: RfId) {
        self.map.remove(&id);
    }

    /// Appends to `out` the ids of the untrained controllers whose field was last active before
    /// sample `before`.
    pub(crate) fn stale_untrained(&self, trained_ess: f64, before: u64, out: &mut Vec<RfId>) {
        out.extend(
            self.map
                .iter()
                .filter(|(_, l)| l.untrained(trained_ess / 2.0) && l.last_active < before)
                .map(|(id, _)| *id),
        );
    }

    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// How many controllers have any confidence (effective sample size above half of
    /// `trained_ess`).
    pub fn n_trained(&self, trained_ess: f64) -> usize {
        self.map
            .values()
            .filter(|l| confidence(l.ess, trained_ess) > 0.0)
            .count()
    }

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

/// The local dynamics regression's settings: a plain weighted least squares (fixed `τ`, no `σ`
/// update, no floors) with its own forgetting and trust region (not the controllers').
fn dynamics_config(cfg: RwrConfig, spec: &LocalSpec) -> RwrConfig {
    RwrConfig {
        adapt_tau: false,
        update_sigma: false,
        tau_init: 1.0,
        ridge: 1e-6,
        min_ess: 0.0,
        min_ess_share: 0.0,
        tau_max: None,
        ridge_to_previous: false,
        forgetting: spec.dynamics_forgetting,
        trust_region: (spec.dynamics_trust_region > 0.0).then_some(spec.dynamics_trust_region),
        ..cfg
    }
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
