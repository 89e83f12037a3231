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
    /// A finite input or output value is larger in magnitude than [`MAX_NORMALISED`] once
    /// divided by its normalisation (`norm_in` for `x`, `norm_out` for `y`).
    #[error(
        "{what}[{index}] = {} is {} after dividing by norm_{io}[{index}] = {}; LWPR needs \
         normalised values within ±{} (its update forms their squares and higher powers): set \
         norm_{io} to the data's scale, e.g. \"std\"",
        num(*value), num(*scaled), num(*norm), num(MAX_NORMALISED),
        io = if *what == "x" { "in" } else { "out" }
    )]
    Scale {
        /// Which argument (`"x"` or `"y"`).
        what: &'static str,
        /// Position of the offending value.
        index: usize,
        /// The value.
        value: f64,
        /// Its divisor.
        norm: f64,
        /// `value / norm`.
        scaled: f64,
    },
    /// No trustworthy receptive field has an activation above the cutoff for this input: the
    /// model has no support there (the reference library would silently return 0).
    #[error("no receptive field is active for output {output} at this input")]
    NoActiveRf {
        /// Output (sub-model) without support.
        output: usize,
    },
    /// The prediction came out infinite or NaN from finite inputs: the model's coefficients
    /// overflow at this input (a model file edited by hand or by a bug; training never makes
    /// one).
    #[error(
        "the prediction of output {output} is not finite ({value}): the model's coefficients \
         overflow at this input"
    )]
    PredictionOverflow {
        /// The output.
        output: usize,
        /// Its value.
        value: f64,
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
    /// A model file that is not a regular file, too large, or cannot be read or written
    /// (`osrl_files`; the message starts with the path).
    #[error(transparent)]
    File(#[from] osrl_files::FileError),
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

/// Largest magnitude of a normalised input or output that [`crate::Lwpr::update`] accepts.
///
/// The update forms squares and higher powers of these values (its metric step, for example,
/// multiplies squared errors by squared projections); outputs beyond about ±1e77 make a
/// receptive field's state overflow to NaN (measured on the 2-D cross test), and ±1e40 leaves
/// a margin for the other factors. Data normalised to its own scale is of order 1.
pub const MAX_NORMALISED: f64 = 1e40;

/// `v` as `Display` prints it when that is short, else in scientific notation.
pub(crate) fn num(v: f64) -> String {
    if v == 0.0 || (1e-4..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Checks that `v[i] / norm[i]` lies within ±[`MAX_NORMALISED`] for every `i` in `dims` (`v`
/// finite, `norm` > 0).
pub(crate) fn check_scale(
    what: &'static str,
    v: &[f64],
    norm: &[f64],
    dims: impl IntoIterator<Item = usize>,
) -> Result<(), LwprError> {
    for index in dims {
        let (value, n) = (v[index], norm[index]);
        if value.abs() > MAX_NORMALISED * n {
            return Err(LwprError::Scale {
                what,
                index,
                value,
                norm: n,
                scaled: value / n,
            });
        }
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
