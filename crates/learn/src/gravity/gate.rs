//! Which samples teach the static gravity model: still ones (`docs/learner.md`, "Gravity"),
//! at most a budget per posture (`budget.rs`, `docs/decisions.md` D30).

use serde::{Deserialize, Serialize};

/// Which samples count as still for the static gravity model: every joint below both limits.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StaticGate {
    /// Largest joint speed (rad/s). Default 0.01.
    pub max_velocity: f64,
    /// Largest joint acceleration (rad/s², from `Δq̇/dt`). Default 0.1.
    pub max_acceleration: f64,
    /// Still samples learned per posture (`posture_radius` apart), the rest ignored; 0: all.
    /// Default 250 (0.5 s at 2 ms): the arm rests at home between every two episodes,
    /// and home's repeated samples, which carry no slope, would otherwise outweigh the other
    /// postures and drift `ĝ` (`budget.rs`).
    pub max_samples_per_posture: u32,
    /// Radius of a posture for `max_samples_per_posture` (rad, every joint). Default 0.02:
    /// twice the settle tolerance at home (`TrainConfig::home_tolerance`, 0.01), about a
    /// twelfth of the gravity model's kernel width (0.25 rad).
    pub posture_radius: f64,
}

impl Default for StaticGate {
    fn default() -> Self {
        Self {
            max_velocity: 0.01,
            max_acceleration: 0.1,
            max_samples_per_posture: 250,
            posture_radius: 0.02,
        }
    }
}

impl StaticGate {
    /// Whether a transition from joint speeds `qd0` to `qd1` over `dt` seconds is still:
    /// every joint's midpoint speed and `Δq̇ / dt` below the limits.
    pub fn is_still(&self, qd0: &[f64], qd1: &[f64], dt: f64) -> bool {
        qd0.iter().zip(qd1).all(|(a, b)| {
            (0.5 * (a + b)).abs() < self.max_velocity
                && ((b - a) / dt).abs() < self.max_acceleration
        })
    }

    /// Checks the ranges: both still limits and the posture radius finite and positive.
    ///
    /// # Errors
    /// A message naming the field out of range.
    pub fn validate(&self) -> std::result::Result<(), String> {
        let pos = |x: f64| x.is_finite() && x > 0.0;
        let bad = [
            ("max_velocity", self.max_velocity, "rad/s"),
            ("max_acceleration", self.max_acceleration, "rad/s²"),
            ("posture_radius", self.posture_radius, "rad"),
        ]
        .into_iter()
        .find(|(_, v, _)| !pos(*v));
        match bad {
            Some((name, v, unit)) => Err(format!(
                "gravity.static_gate.{name} {v} must be finite and > 0 ({unit})"
            )),
            None => Ok(()),
        }
    }
}
