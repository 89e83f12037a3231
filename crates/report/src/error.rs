//! The report crate's one error type.

use std::path::Path;
use thiserror::Error;

/// Everything that can go wrong while drawing or writing the report.
#[derive(Debug, Error)]
pub enum ReportError {
    /// A figure could not be drawn (plotters' error, or an empty figure).
    #[error("{0}")]
    Draw(String),
    /// A CSV file is malformed (the message names the file, line and column).
    #[error("{0}")]
    Csv(String),
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    /// A report folder lacks what its page is drawn from, or holds something else.
    #[error("{0}")]
    Folder(String),
    #[error(transparent)]
    Experiment(#[from] osrl_experiments::ExperimentError),
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    #[error(transparent)]
    Toml(#[from] toml::ser::Error),
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, ReportError>;

impl ReportError {
    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        ReportError::Io {
            path: path.display().to_string(),
            source,
        }
    }
}

/// Creates `dir` and its parents.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| ReportError::io(dir, e))
}

/// Writes `text` to `path`.
pub(crate) fn write(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).map_err(|e| ReportError::io(path, e))
}
