//! The crate's error type.

/// Everything that can go wrong in this crate. Every fallible call leaves the model unchanged
/// when it returns an error.
#[derive(Debug, thiserror::Error)]
pub enum LwprError {
    /// A configuration value is out of range or inconsistent with the model's dimensions.
    #[error("invalid LWPR config: {0}")]
    Config(String),
    /// An input or output slice has the wrong length.
    #[error("{what} has length {got}, expected {expected}")]
    Dimension {
        /// Which argument.
        what: &'static str,
        /// Required length.
        expected: usize,
        /// Given length.
        got: usize,
    },
    /// An input or output value is NaN or infinite.
    #[error("{what}[{index}] is not finite ({value})")]
    NonFinite {
        /// Which argument.
        what: &'static str,
        /// Position of the offending value.
        index: usize,
        /// The value.
        value: f64,
    },
    /// No trustworthy receptive field has an activation above the cutoff for this input: the
    /// model has no support there (the reference library would silently return 0).
    #[error("no receptive field is active for output {output} at this input")]
    NoActiveRf {
        /// Output (sub-model) without support.
        output: usize,
    },
    /// A sub-model index out of range.
    #[error("sub-model {index} does not exist (the model has {count})")]
    NoSubModel {
        /// Requested index.
        index: usize,
        /// Number of sub-models.
        count: usize,
    },
    /// A saved model is corrupted, truncated, of another format version, or inconsistent.
    #[error("cannot read LWPR model: {0}")]
    Format(String),
    /// File system error while saving or loading (its text is in the message, so it is not
    /// also a `source`: error chains print it once).
    #[error("LWPR model file: {0}")]
    Io(std::io::Error),
}

impl From<std::io::Error> for LwprError {
    fn from(e: std::io::Error) -> LwprError {
        LwprError::Io(e)
    }
}

/// Checks a slice's length and that every entry is finite.
pub(crate) fn check_vec(what: &'static str, v: &[f64], expected: usize) -> Result<(), LwprError> {
    if v.len() != expected {
        return Err(LwprError::Dimension {
            what,
            expected,
            got: v.len(),
        });
    }
    if let Some((index, &value)) = v.iter().enumerate().find(|(_, a)| !a.is_finite()) {
        return Err(LwprError::NonFinite { what, index, value });
    }
    Ok(())
}

/// Checks an output buffer's length.
pub(crate) fn check_len(what: &'static str, len: usize, expected: usize) -> Result<(), LwprError> {
    if len != expected {
        return Err(LwprError::Dimension {
            what,
            expected,
            got: len,
        });
    }
    Ok(())
}
