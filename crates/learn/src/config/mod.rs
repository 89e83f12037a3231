//! Settings of the learner, grouped by the parts of the learned controller (paper section IV):
//! the nominal behaviour, the gravity model, the partition, the local controllers, their local
//! dynamics, exploration and the guards. Validated once by [`LearnerConfig::validate`].

/// Control periods (s) a learner and a saved model may have: 10 kHz to 10 Hz.
pub const CONTROL_PERIOD_RANGE: std::ops::RangeInclusive<f64> = 1e-4..=0.1;

mod adaptation;
mod groups;
pub mod scaled;
mod validate;

pub use adaptation::{AdaptationConfig, AdaptationSource};

pub use groups::{
    ControllerConfig, CostKind, CostMetric, DynamicsConfig, DynamicsRegression, Experimental,
    ExplorationConfig, GravityConfig, GuardConfig, NoiseProcess, NominalConfig, PartitionConfig,
};
use serde::{Deserialize, Serialize};

/// All settings of the learner (models and local controllers). The defaults are the learner of
/// `docs/learner.md`; [`LearnerConfig::for_robot`] adds a robot's data sheet.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LearnerConfig {
    /// `u0 = ĝ(q) − K_Dq q̇ − K_Pq (q − q_rest)`; filled from the data sheet.
    pub nominal: NominalConfig,
    /// The gravity model `ĝ`.
    pub gravity: GravityConfig,
    /// The forward model whose receptive fields partition the state space.
    pub partition: PartitionConfig,
    /// The local controllers and their reward-weighted regression.
    pub controllers: ControllerConfig,
    /// The local dynamics `Â = ∂ẍ/∂u` of each receptive field.
    pub dynamics: DynamicsConfig,
    /// Exploration noise.
    pub exploration: ExplorationConfig,
    /// Limits on measurements and commands.
    pub guards: GuardConfig,
    /// Re-adaptation to a changed robot (off by default).
    #[serde(skip_serializing_if = "AdaptationConfig::is_default")]
    pub adaptation: AdaptationConfig,
    #[doc(hidden)]
    #[serde(skip_serializing_if = "Experimental::is_default")]
    pub experimental: Experimental,
}

impl Experimental {
    fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

impl LearnerConfig {
    /// The defaults with the nominal behaviour and torque limits of a robot's data sheet: its
    /// joint PD gains, rest posture and torque limits (N·m; an infinite limit is stored as
    /// `f64::MAX`, no limit, so the config stays plain JSON). No dynamics parameters.
    pub fn for_robot(kp: &[f64], kd: &[f64], q_rest: &[f64], tau_max: &[f64]) -> Self {
        let mut c = Self::default();
        c.fill_data_sheet(kp, kd, q_rest, tau_max);
        c
    }

    /// Fills the data-sheet fields left empty — `nominal.kp`, `nominal.kd`, `nominal.q_rest`
    /// and `guards.torque_limits` — from a robot's data sheet (as [`LearnerConfig::for_robot`]);
    /// fields already set are kept.
    pub fn fill_data_sheet(&mut self, kp: &[f64], kd: &[f64], q_rest: &[f64], tau_max: &[f64]) {
        let nom = &mut self.nominal;
        for (v, def) in [
            (&mut nom.kp, kp),
            (&mut nom.kd, kd),
            (&mut nom.q_rest, q_rest),
        ] {
            if v.is_empty() {
                *v = def.to_vec();
            }
        }
        if self.guards.torque_limits.is_empty() {
            self.guards.torque_limits = Self::data_sheet_limits(tau_max);
        }
    }

    /// A data sheet's torque limits (N·m) as `guards.torque_limits`: an infinite limit (none)
    /// becomes `f64::MAX`, so the config stays plain JSON.
    pub fn data_sheet_limits(tau_max: &[f64]) -> Vec<f64> {
        tau_max.iter().map(|t| t.min(f64::MAX)).collect()
    }
}
