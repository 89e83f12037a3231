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
    /// A path that is not a regular file, a file too large, or an I/O error (`osrl_files`).
    #[error(transparent)]
    File(#[from] osrl_files::FileError),
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

/// Writes `text` to `path` ([`osrl_files::write_atomic`]: only over a regular file or a new
/// path).
pub(crate) fn write(path: &Path, text: &str) -> Result<()> {
    Ok(osrl_files::write_atomic(path, text.as_bytes())?)
}

/// Largest data file of a report folder read back (`results.json`, `figures.json`, an SVG, a
/// CSV time series): 1 GiB.
pub const MAX_READ_BYTES: u64 = 1 << 30;

/// Reads the text of `path`, a regular file of at most [`MAX_READ_BYTES`].
pub(crate) fn read_text(path: &Path) -> Result<String> {
    Ok(osrl_files::read_text_limited(path, MAX_READ_BYTES)?)
}
