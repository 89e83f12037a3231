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

/// Largest task stiffness `K_P` (1/s²): an error bandwidth of 10⁴ rad/s, beyond what any
/// control loop of a few kHz realises; larger gains only overflow the command.
pub const MAX_TASK_KP: f64 = 1e8;
/// Largest task damping `K_D` (1/s): critical damping at [`MAX_TASK_KP`].
pub const MAX_TASK_KD: f64 = 2e4;

impl TaskGains {
    /// `kp` in [0, [`MAX_TASK_KP`]] and `kd` in [0, [`MAX_TASK_KD`]].
    ///
    /// # Errors
    /// [`crate::ControlError::InvalidConfig`] naming the gain, its value and its range.
    pub fn validate(&self) -> crate::Result<()> {
        for (key, v, hi) in [("kp", self.kp, MAX_TASK_KP), ("kd", self.kd, MAX_TASK_KD)] {
            if !(0.0..=hi).contains(&v) {
                return Err(crate::ControlError::InvalidConfig(format!(
                    "task gain {key} = {v:?}: must lie in [0, {hi:?}]"
                )));
            }
        }
        Ok(())
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
