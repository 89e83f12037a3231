//! The experiments crate's one error type.

use thiserror::Error;

/// Everything that can go wrong while setting up or running an experiment.
#[derive(Debug, Error)]
pub enum ExperimentError {
    /// A setting is out of range (the message names it).
    #[error("{0}")]
    Invalid(String),
    #[error(transparent)]
    Learn(#[from] osrl_learn::LearnError),
    #[error(transparent)]
    Control(#[from] osrl_control::ControlError),
    #[error(transparent)]
    Dynamics(#[from] osrl_dynamics::DynamicsError),
    #[error(transparent)]
    Rwr(#[from] rwr::RwrError),
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    /// A path that is not a regular file, a file too large, or an I/O error (`osrl_files`).
    #[error(transparent)]
    File(#[from] osrl_files::FileError),
    /// A results file is not valid JSON of the expected layout.
    #[error("{path}: {source}")]
    Json {
        path: String,
        source: serde_json::Error,
    },
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, ExperimentError>;
