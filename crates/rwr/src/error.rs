//! The crate's one error type.

use thiserror::Error;

/// Everything that can go wrong in `rwr`. Every fallible call that returns one of these has
/// changed nothing.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RwrError {
    /// A configuration field is out of its documented range.
    #[error("invalid config: {0}")]
    InvalidConfig(String),
    /// An input has the wrong length or shape.
    #[error("dimension mismatch in {what}: expected {expected}, got {got}")]
    Dimension {
        /// Which input.
        what: &'static str,
        /// Expected length (or rows/columns).
        expected: usize,
        /// Length received.
        got: usize,
    },
    /// A feature, action or external weight is NaN or infinite.
    #[error("non-finite value in {0}")]
    NonFinite(&'static str),
    /// A cost is negative or non-finite (costs must satisfy `r ≥ 0`, eq. 22).
    #[error("cost must be finite and >= 0, got {0}")]
    BadCost(f64),
    /// An external sample weight is negative.
    #[error("external weight must be finite and >= 0, got {0}")]
    BadWeight(f64),
    /// No sample carries positive weight, so eq. 23 is undefined.
    #[error("no sample with positive weight")]
    NoWeight,
    /// The weighted Gram matrix plus ridge is not positive definite.
    #[error("weighted Gram matrix is not positive definite (add ridge or samples)")]
    Singular,
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, RwrError>;
