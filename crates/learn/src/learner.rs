//! The learner: gravity model, forward model (the partition) and local RWR controllers, updated
//! from measured transitions only (DESIGN.md §2 — it never sees a robot model).

use crate::config::LearnerConfig;
use crate::error::{LearnError, Result};
use crate::forward::ForwardModel;
use crate::gravity::GravityModel;
use crate::local::LocalControllers;
use lwpr::{Activation, RfEvent};
use osrl_dynamics::Measurement;

/// Counters of what the learner did and refused.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LearnerStats {
    /// Transitions learned from.
    pub samples: u64,
    /// Measurements rejected (non-finite or absurd).
    pub rejected: u64,
    /// Commands computed, and those that fell back to `u0`: no trained controller was active,
    /// or the blend was not finite (then also counted in `non_finite`).
    pub commands: u64,
    pub fallbacks: u64,
    /// Commands extrapolated from trained controllers active below the cutoff.
    pub extrapolations: u64,
    /// Receptive fields removed by `prune_untrained_after` (with their controllers).
    pub pruned_untrained: u64,
    /// Commands with at least one joint clipped to its torque limit.
    pub clipped: u64,
    /// Commands whose learned blend was not finite and fell back to `u0`.
    pub non_finite: u64,
    /// Local M-steps done and those that failed (too few samples).
    pub m_steps: u64,
    pub failed_m_steps: u64,
}

/// Scratch buffers of the learning step and the command (allocated once).
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    pub acts: Vec<Activation>,
    pub events: Vec<RfEvent>,
    /// Receptive fields to prune (`prune_untrained_after`).
    pub stale: Vec<lwpr::RfId>,
    pub phi: Vec<f64>,
    pub u0: Vec<f64>,
    pub du: Vec<f64>,
    /// Null-space part of `du` (hindsight shrinkage).
    pub z: Vec<f64>,
    pub ui: Vec<f64>,
    pub target: Vec<f64>,
    pub phi_d: Vec<f64>,
    pub a_hat: Vec<f64>,
    pub y: Vec<f64>,
    pub s: Vec<f64>,
}

/// The learned operational space controller's state (paper section IV).
#[derive(Clone, Debug)]
pub struct Learner {
    pub(crate) cfg: LearnerConfig,
    pub(crate) n: usize,
    pub(crate) m: usize,
    pub(crate) gravity: Option<GravityModel>,
    /// The static gravity model (`gravity_static`), used for `u0` once `ĝ` is frozen.
    pub(crate) gravity_static: Option<GravityModel>,
    pub(crate) forward: Option<ForwardModel>,
    pub(crate) locals: LocalControllers,
    /// Measurements kept until the models exist (the warm-up).
    pub(crate) warm: Vec<Measurement>,
    pub(crate) dt: f64,
    /// Standard deviation of each joint's torque during the warm-up (N·m).
    pub(crate) torque_scale: Vec<f64>,
    pub(crate) stats: LearnerStats,
    /// `ĝ` no longer learns (see [`Learner::freeze_gravity`]).
    pub(crate) gravity_frozen: bool,
    pub(crate) ws: Scratch,
}

impl Learner {
    /// A learner for a robot with `n` joints and an `m`-dimensional task, controlled every `dt`
    /// seconds. Fails on an invalid config.
    pub fn new(n: usize, m: usize, dt: f64, cfg: LearnerConfig) -> Result<Self> {
        cfg.validate(n)?;
        if m == 0 || m > n || !(dt > 0.0) {
            return Err(LearnError::InvalidConfig(format!(
                "need 0 < m ≤ n and dt > 0 (n = {n}, m = {m}, dt = {dt})"
            )));
        }
        let p = n_features(&cfg, n, m);
        let ws = Scratch {
            acts: Vec::with_capacity(4096),
            events: Vec::with_capacity(16),
            stale: Vec::with_capacity(4096),
            phi: vec![0.0; p],
            u0: vec![0.0; n],
            du: vec![0.0; n],
            z: vec![0.0; n],
            ui: vec![0.0; n],
            target: vec![0.0; n],
            phi_d: vec![0.0; crate::local::dynamics_features(n, cfg.dynamics_bilinear)],
            a_hat: vec![0.0; m * n],
            y: vec![0.0; m],
            s: vec![0.0; m * m],
        };
        Ok(Self {
            warm: Vec::with_capacity(cfg.warmup_samples + 1),
            cfg,
            n,
            m,
            gravity: None,
            gravity_static: None,
            forward: None,
            locals: LocalControllers::default(),
            dt,
            torque_scale: vec![1.0; n],
            stats: LearnerStats::default(),
            gravity_frozen: false,
            ws,
        })
    }

    pub fn config(&self) -> &LearnerConfig {
        &self.cfg
    }
    /// Sets the torque limits of the commands (N·m, one per joint; empty: none), e.g. on a
    /// controller saved without them. Fails (nothing changed) on a wrong count or a limit that
    /// is not finite and > 0.
    pub fn set_torque_limits(&mut self, tau_max: &[f64]) -> Result<()> {
        let cfg = LearnerConfig {
            torque_limits: tau_max.to_vec(),
            ..self.cfg.clone()
        };
        cfg.validate(self.n)?;
        self.cfg = cfg;
        Ok(())
    }
    pub fn stats(&self) -> LearnerStats {
        self.stats
    }
    /// Number of joints and task dimensions.
    pub fn dims(&self) -> (usize, usize) {
        (self.n, self.m)
    }
    /// Number of local controllers (= receptive fields of the forward model).
    pub fn n_local_models(&self) -> usize {
        self.locals.len()
    }
    /// Summaries of the local controllers (effective sample size, σ, τ).
    pub fn local_summaries(&self) -> Vec<crate::local::LocalSummary> {
        self.locals.summaries()
    }
    /// The forward model (the partition), once the warm-up is over.
    pub fn forward_model(&self) -> Option<&ForwardModel> {
        self.forward.as_ref()
    }
    /// `Â = ∂ẍ/∂u` at `(q, q̇)` from the local dynamics regressions of the active receptive
    /// fields (m×n row-major into `a`); `false` without support or before the warm-up ends.
    pub fn input_gain(&mut self, q: &[f64], qd: &[f64], a: &mut [f64]) -> Result<bool> {
        let (n, m) = (self.n, self.m);
        let Some(f) = self.forward.as_mut() else {
            return Ok(false);
        };
        f.activations(q, qd, self.cfg.activation_cutoff, &mut self.ws.acts)?;
        Ok(step::blended_gain(&self.locals, &self.ws.acts, q, n, m, a))
    }
    /// Stops (or resumes) the learning of the gravity model `ĝ`. The training driver freezes it
    /// when on-policy learning starts unless `gravity_on_policy` is set: along a single path `q̇`
    /// and `q̈` are functions of `q`, so the inverse-dynamics regression cannot separate them and
    /// its value at `q̇ = q̈ = 0` drifts (measured on planar3: `u0` error 0.003–0.03 of the
    /// command variance after babbling, 0.3 after 5 minutes on the figure-8).
    pub fn freeze_gravity(&mut self, frozen: bool) {
        self.gravity_frozen = frozen;
    }
    /// Whether `ĝ` is frozen.
    pub fn gravity_frozen(&self) -> bool {
        self.gravity_frozen
    }
    /// Local controllers with enough data to act.
    pub fn n_trained(&self) -> usize {
        self.locals.n_trained(self.cfg.min_ess)
    }
    /// The gravity model `ĝ`, once the warm-up is over.
    pub fn gravity_model(&self) -> Option<&crate::gravity::GravityModel> {
        self.gravity.as_ref()
    }
    /// The static gravity model, if configured and past the warm-up.
    pub fn gravity_static_model(&self) -> Option<&GravityModel> {
        self.gravity_static.as_ref()
    }
    /// Receptive fields of the gravity model.
    pub fn n_gravity_rfs(&self) -> usize {
        self.gravity.as_ref().map_or(0, |g| g.n_rfs())
    }
    /// Whether the warm-up is over and the models exist.
    pub fn ready(&self) -> bool {
        self.forward.is_some()
    }

    /// Checks a measurement: right sizes, finite, and not absurd.
    pub fn check(&self, meas: &Measurement) -> Result<()> {
        let (n, m) = (self.n, self.m);
        if meas.q.len() != n
            || meas.qd.len() != n
            || meas.u.len() != n
            || meas.x.len() != m
            || meas.xd.len() != m
            || meas.xdd.len() != m
        {
            return Err(LearnError::BadMeasurement(format!(
                "sizes do not match a robot with {n} joints and {m} task dimensions"
            )));
        }
        let all = meas
            .q
            .iter()
            .chain(meas.qd.iter())
            .chain(meas.u.iter())
            .chain(meas.x.iter())
            .chain(meas.xd.iter())
            .chain(meas.xdd.iter());
        if let Some(v) = all.clone().find(|v| !v.is_finite()) {
            return Err(LearnError::BadMeasurement(format!("non-finite value {v}")));
        }
        let lim = self.cfg.max_abs_acceleration;
        if meas.xdd.amax() > lim || meas.qd.amax() > 0.1 * lim {
            return Err(LearnError::BadMeasurement(format!(
                "absurd: |ẍ| = {:.3e} m/s², |q̇| = {:.3e} rad/s",
                meas.xdd.amax(),
                meas.qd.amax()
            )));
        }
        Ok(())
    }

    /// Learns from the transition `prev → cur` (the command `cur.u` was held in between). A
    /// rejected measurement is counted and changes nothing.
    pub fn learn(&mut self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        if let Err(e) = self.check(cur).and_then(|_| self.check(prev)) {
            self.stats.rejected += 1;
            return Err(e);
        }
        if self.forward.is_none() {
            if self.warm.is_empty() {
                self.warm.push(prev.clone());
            }
            self.warm.push(cur.clone());
            if self.warm.len() > self.cfg.warmup_samples {
                self.init_models()?;
            }
            return Ok(());
        }
        self.learn_ready(prev, cur)
    }
}

/// Length of the feature vector `φ = [ẍᵀ, q̇ᵀ, (q − c)ᵀ?, 1]` of the local controllers.
pub(crate) fn n_features(cfg: &LearnerConfig, n: usize, m: usize) -> usize {
    m + n + 1 + if cfg.position_features { n } else { 0 }
}

#[path = "learner_step.rs"]
mod step;
pub use step::CommandSource;
impl Learner {
    /// The models from the warm-up data, then the warm-up replayed into them.
    fn init_models(&mut self) -> Result<()> {
        let (n, m) = (self.n, self.m);
        let warm = std::mem::take(&mut self.warm);
        let std = |f: &dyn Fn(&Measurement) -> f64| {
            let k = warm.len() as f64;
            let mean = warm.iter().map(f).sum::<f64>() / k;
            let var = warm.iter().map(|w| (f(w) - mean).powi(2)).sum::<f64>() / k;
            var.sqrt().max(1e-3)
        };
        let torque: Vec<f64> = (0..n).map(|i| std(&|w: &Measurement| w.u[i])).collect();
        let acc = (0..m)
            .map(|k| std(&|w: &Measurement| w.xdd[k]))
            .fold(0.0, f64::max);
        let jacc = (1..warm.len())
            .map(|k| ((&warm[k].qd - &warm[k - 1].qd) / self.dt).amax())
            .fold(0.0, f64::max)
            .max(1.0)
            / 3.0;
        self.torque_scale = torque.clone();
        let vs = self.cfg.velocity_scale;
        self.gravity = Some(GravityModel::new(
            n,
            &self.cfg.gravity,
            self.cfg.gravity_velocity_products,
            vs,
            jacc,
            &torque,
        )?);
        self.gravity_static = match self.cfg.gravity_static {
            Some(gate) => Some(GravityModel::new_static(
                n,
                &self.cfg.gravity,
                gate,
                vs,
                jacc,
                &torque,
            )?),
            None => None,
        };
        self.forward = Some(ForwardModel::new(
            n,
            m,
            &self.cfg.forward,
            vs,
            &torque,
            acc,
            self.cfg.forward_uses_q,
        )?);
        for k in 1..warm.len() {
            self.learn_ready(&warm[k - 1], &warm[k])?;
        }
        Ok(())
    }
}
