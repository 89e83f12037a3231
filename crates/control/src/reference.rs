//! Reference dynamics, paper eq. 2: `ẍ_ref = ẍ_d + K_D (ẋ_d − ẋ) + K_P (x_d − x)`.

use crate::trajectory::Target;
use serde::{Deserialize, Serialize};

/// Task-space feedback gains of eq. 2, the same on every task axis.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TaskGains {
    /// Stiffness `K_P` (1/s²). Default 900 (error bandwidth ω = 30 rad/s).
    pub kp: f64,
    /// Damping `K_D` (1/s). Default 60 (critical damping `2√K_P`).
    pub kd: f64,
}

impl Default for TaskGains {
    fn default() -> Self {
        Self {
            kp: 900.0,
            kd: 60.0,
        }
    }
}

impl TaskGains {
    /// Both gains finite and ≥ 0.
    pub fn validate(&self) -> crate::Result<()> {
        if self.kp >= 0.0 && self.kd >= 0.0 && self.kp.is_finite() && self.kd.is_finite() {
            Ok(())
        } else {
            Err(crate::ControlError::InvalidConfig(format!(
                "task gains kp = {}, kd = {} must be finite and ≥ 0",
                self.kp, self.kd
            )))
        }
    }
}

/// Eq. 2 on the task axes `axes` (world axes of the task coordinates): `x`, `xd` are the measured
/// task position (m) and velocity (m/s) with one entry per axis, `out` gets `ẍ_ref` (m/s²).
/// Panics if the slices are shorter than `axes`.
#[inline]
pub fn reference_acceleration(
    gains: &TaskGains,
    target: &Target,
    axes: &[usize],
    x: &[f64],
    xd: &[f64],
    out: &mut [f64],
) {
    for (k, &a) in axes.iter().enumerate() {
        out[k] =
            target.xdd[a] + gains.kd * (target.xd[a] - xd[k]) + gains.kp * (target.x[a] - x[k]);
    }
}

/// The tracking error `‖x − x_d‖` (m) of the measured task position `x` (one entry per task
/// axis in `axes`, the world axes of the task coordinates) against `target`.
#[inline]
pub fn task_error(target: &Target, axes: &[usize], x: &[f64]) -> f64 {
    axes.iter()
        .enumerate()
        .map(|(k, &a)| (x[k] - target.x[a]).powi(2))
        .sum::<f64>()
        .sqrt()
}
