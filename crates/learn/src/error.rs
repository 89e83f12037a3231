//! The learn crate's one error type.

use thiserror::Error;

/// Everything that can go wrong while learning or running the learned controller.
#[derive(Debug, Error)]
pub enum LearnError {
    #[error("invalid learner config: {0}")]
    InvalidConfig(String),
    #[error("{what}: expected {expected} values, got {got}")]
    Dimension {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    /// A measurement was rejected (non-finite or absurd); the learner is unchanged.
    #[error("measurement rejected: {0}")]
    BadMeasurement(String),
    /// A value the learner computed was NaN or infinite.
    #[error("{0} is not finite")]
    NonFinite(&'static str),
    #[error(transparent)]
    Lwpr(#[from] lwpr::LwprError),
    #[error(transparent)]
    Rwr(#[from] rwr::RwrError),
    #[error(transparent)]
    Robot(#[from] osrl_dynamics::DynamicsError),
    #[error(transparent)]
    Control(#[from] osrl_control::ControlError),
    /// A saved controller could not be read; the controller in memory is untouched.
    #[error("cannot load learned controller: {0}")]
    Load(String),
    /// A model file that is not a regular file, too large, or cannot be read or written
    /// (`osrl_files`; the message starts with the path).
    #[error(transparent)]
    File(#[from] osrl_files::FileError),
}

pub type Result<T> = std::result::Result<T, LearnError>;
