//! Configuration of the analytical controllers.

use crate::error::{ControlError, Result};
use crate::reference::TaskGains;
use serde::{Deserialize, Serialize};

/// Which analytical operational space control law.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Law {
    /// Eq. 4: `u = Jᵀ (J M⁻¹ Jᵀ)⁻¹ b`, i.e. eq. 7 with `N = M⁻¹` and `u0 = 0` (no null-space
    /// control: the posture drifts).
    Eq4,
    /// Eq. 7 (corrected: the crate README, "Choices") with the metric `N` and the nominal `u0`.
    #[default]
    Eq7,
}

/// The metric `N` of the cost `(u − u0)ᵀ N (u − u0)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MetricKind {
    /// `N = I` (the paper's choice for learning).
    #[default]
    Identity,
    /// `N = M(q)`.
    Mass,
    /// `N = M(q)⁻¹` (with `u0 = 0`: eq. 4).
    InverseMass,
    /// A constant symmetric positive-definite matrix given in `metric_matrix`.
    Matrix,
}

/// Settings of an analytical controller ([`crate::Osc`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OscConfig {
    /// Control law, `eq4` or `eq7`. Default `eq7`.
    pub law: Law,
    /// Metric `N` of eq. 7 (ignored by eq. 4, which uses `M⁻¹`). Default `identity`.
    pub metric: MetricKind,
    /// Rows of the constant `N` (n×n, symmetric positive definite) for `metric = "matrix"`.
    /// Default empty.
    pub metric_matrix: Vec<Vec<f64>>,
    /// Task-space gains of the reference dynamics (eq. 2).
    pub gains: TaskGains,
    /// Scale of the robot's joint PD gains in the nominal `u0` (eq. 6); 0 leaves only gravity
    /// compensation. Default 1.
    pub nominal_scale: f64,
    /// Relative threshold `ε` of the damped pseudo-inverse ([`crate::damping`]): damping starts
    /// when `σ_min(A) < ε σ_max(A)`; 0 switches it off. Default 1e-3.
    pub damping_threshold: f64,
}

impl Default for OscConfig {
    fn default() -> Self {
        Self {
            law: Law::Eq7,
            metric: MetricKind::Identity,
            metric_matrix: Vec::new(),
            gains: TaskGains::default(),
            nominal_scale: 1.0,
            damping_threshold: 1e-3,
        }
    }
}

impl OscConfig {
    /// Checks ranges and that a `matrix` metric has a matrix and only then. The matrix itself
    /// (size, symmetry, definiteness) is checked by [`crate::Osc::new`], which knows `n`.
    pub fn validate(&self) -> Result<()> {
        self.gains.validate()?;
        let bad = |m: String| Err(ControlError::InvalidConfig(m));
        if !(self.nominal_scale >= 0.0 && self.nominal_scale.is_finite()) {
            return bad(format!(
                "nominal_scale {} must be finite and ≥ 0",
                self.nominal_scale
            ));
        }
        if !(0.0..1.0).contains(&self.damping_threshold) {
            return bad(format!(
                "damping_threshold {} must be in [0, 1)",
                self.damping_threshold
            ));
        }
        match (self.metric, self.metric_matrix.is_empty()) {
            (MetricKind::Matrix, true) => bad("metric = \"matrix\" needs metric_matrix".into()),
            (MetricKind::Matrix, false) | (_, true) => Ok(()),
            (_, false) => bad("metric_matrix is given but metric is not \"matrix\"".into()),
        }
    }
}
