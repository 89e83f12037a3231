//! The dynamics crate's one error type.

use thiserror::Error;

/// Everything that can go wrong in `osrl-dynamics`.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DynamicsError {
    /// A vector argument has the wrong length.
    #[error("{what}: expected {expected} values, got {got}")]
    Dimension {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    /// A state, command or parameter is NaN or infinite.
    #[error("{what}[{index}] is not finite ({value})")]
    NonFinite {
        what: &'static str,
        index: usize,
        value: f64,
    },
    /// A model parameter is invalid (negative mass, asymmetric inertia, bad limits, ...).
    #[error("invalid model: {0}")]
    InvalidModel(String),
    /// The articulated inertia along a joint axis is not positive: the mass matrix is singular.
    #[error("mass matrix not positive definite at joint {joint} (articulated inertia {value:e})")]
    Singular { joint: usize, value: f64 },
    /// A URDF file is malformed or uses something unsupported; names the element.
    #[error("URDF: {0}")]
    Urdf(String),
    /// The simulation produced a non-finite state; the state before the step is kept.
    #[error("simulation diverged at t = {t:.4} s: {what} is not finite")]
    Diverged { t: f64, what: &'static str },
    /// A simulator configuration value is out of range.
    #[error("invalid simulator config: {0}")]
    InvalidConfig(String),
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, DynamicsError>;

/// Checks that `v` has `expected` entries, all finite.
pub fn check_vec(what: &'static str, v: &[f64], expected: usize) -> Result<()> {
    if v.len() != expected {
        return Err(DynamicsError::Dimension {
            what,
            expected,
            got: v.len(),
        });
    }
    check_finite(what, v)
}

/// Checks that every entry of `v` is finite.
pub fn check_finite(what: &'static str, v: &[f64]) -> Result<()> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(DynamicsError::NonFinite {
            what,
            index,
            value: v[index],
        }),
        None => Ok(()),
    }
}
