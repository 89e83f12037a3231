//! The control crate's one error type.

use osrl_dynamics::DynamicsError;
use thiserror::Error;

/// Everything that can go wrong in `osrl-control`.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ControlError {
    /// An error of the dynamics (wrong length, non-finite state, invalid model, divergence).
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// A vector argument has the wrong length.
    #[error("{what}: expected {expected} values, got {got}")]
    Dimension {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    /// The metric `N` of eq. 7 is not symmetric positive definite.
    #[error("metric N is not symmetric positive definite: {0}")]
    MetricNotPositiveDefinite(String),
    /// The controller's mass matrix failed its Cholesky factorisation.
    #[error("mass matrix of the controller's model is not positive definite (pivot {0})")]
    MassNotPositiveDefinite(usize),
    /// The task-space system `A Aᵀ (+ damping)` cannot be solved (damping switched off at a
    /// singular configuration).
    #[error("singular task-space system: {0}")]
    Singular(String),
    /// A trajectory description is malformed (non-finite, zero period, parallel directions, ...).
    #[error("invalid trajectory: {0}")]
    InvalidTrajectory(String),
    /// A trajectory leaves the arm's reach or its joint limits.
    #[error("unreachable trajectory: {0}")]
    Unreachable(String),
    /// A configuration value is out of range.
    #[error("invalid control config: {0}")]
    InvalidConfig(String),
    /// A robot profile value is malformed or out of range, or the arm cannot be given a
    /// profile it can track with (`osrl_control::profile`): the field and why.
    #[error("robot profile {field}: {reason}")]
    Profile { field: String, reason: String },
    /// A model-error description (`--model-error`) cannot be parsed or is out of range.
    #[error("invalid model error '{spec}': {reason}")]
    ModelErrorSpec { spec: String, reason: String },
    /// A change of the robot (`--change`) cannot be parsed, is out of range, or leaves an arm
    /// that cannot hold itself within its torque limits.
    #[error("invalid robot change '{spec}': {reason}")]
    ChangeSpec { spec: String, reason: String },
    /// A [`crate::TaskController`] defined outside this crate failed (e.g. the learned
    /// controller of `osrl-learn`, whose error converts into this one): which controller, and
    /// its error's message.
    #[error("{controller} controller: {reason}")]
    Controller {
        controller: &'static str,
        reason: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, ControlError>;

/// Checks that `v` has `expected` entries, all finite.
pub(crate) fn check(what: &'static str, v: &[f64], expected: usize) -> Result<()> {
    if v.len() != expected {
        return Err(ControlError::Dimension {
            what,
            expected,
            got: v.len(),
        });
    }
    Ok(osrl_dynamics::check_finite(what, v)?)
}
