//! Errors of the crates as Python exceptions: bad input is `ValueError` (the crates leave the
//! model unchanged), file-system failures are the matching `OSError` subclass, and a prediction
//! without support is `osrl.NoSupportError` (a `ValueError`: the input is outside the model's
//! domain, as `math.log(-1)` is outside the logarithm's).

use pyo3::exceptions::PyValueError;
use pyo3::PyErr;
use std::path::Path;

pyo3::create_exception!(
    osrl,
    NoSupportError,
    PyValueError,
    "No trustworthy receptive field of an LWPR model is active at this input (for some output): \
     the model has no support there. `predict(x, strict=False)` returns 0 instead, as the \
     reference LWPR library does."
);

/// An `lwpr` error as a Python exception (`path`: the file of a save or load, if any).
pub fn lwpr_err(e: lwpr::LwprError, path: Option<&Path>) -> PyErr {
    match e {
        lwpr::LwprError::NoActiveRf { .. } => NoSupportError::new_err(e.to_string()),
        lwpr::LwprError::Io(io) => io_err(io, path),
        lwpr::LwprError::File(f) => file_err(f),
        lwpr::LwprError::Format(_) => match path {
            Some(p) => PyValueError::new_err(format!("{}: {e}", p.display())),
            None => PyValueError::new_err(e.to_string()),
        },
        other => PyValueError::new_err(other.to_string()),
    }
}

/// An `osrl-dynamics` error as a Python exception: all of them are about the input (a state
/// of the wrong length or not finite, a model or URDF that is invalid, a singular mass matrix).
pub fn dyn_err(e: osrl_dynamics::DynamicsError) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A refused or failed file (`osrl_files`) as the `OSError` subclass Python would raise; its
/// message names the file.
pub fn file_err(e: osrl_files::FileError) -> PyErr {
    use std::io::{Error, ErrorKind};
    let kind = match &e {
        osrl_files::FileError::Io { source, .. } => source.kind(),
        osrl_files::FileError::NotRegular {
            kind: "directory", ..
        } => ErrorKind::IsADirectory,
        osrl_files::FileError::MissingFolder { .. } => ErrorKind::NotFound,
        _ => ErrorKind::Other,
    };
    PyErr::from(Error::new(kind, e.to_string()))
}

/// A file-system error as the `OSError` subclass Python would raise, naming the file.
pub fn io_err(e: std::io::Error, path: Option<&Path>) -> PyErr {
    let msg = match path {
        Some(p) => format!("{}: {e}", p.display()),
        None => e.to_string(),
    };
    PyErr::from(std::io::Error::new(e.kind(), msg))
}

/// An `osrl-learn` error as a Python exception: files as `OSError`, a robot's or a
/// controller's failure on the input as `ValueError`, everything else (bad configs, bad
/// measurements, dimensions, unreadable models) as `ValueError` too, naming what was wrong.
pub fn learn_err(e: osrl_learn::LearnError) -> PyErr {
    match e {
        osrl_learn::LearnError::File(f) => file_err(f),
        other => PyValueError::new_err(other.to_string()),
    }
}

/// An `osrl-experiments` error (a training set-up) as a Python exception.
pub fn setup_err(e: osrl_experiments::ExperimentError) -> PyErr {
    PyValueError::new_err(e.to_string())
}
