//! Scalar arguments and attributes read by name, so that a wrong one is an error that says which
//! it was: PyO3's own conversion of a `usize` or `u64` argument raises a bare `OverflowError`
//! ("can't convert negative int to unsigned") for `-1`, and a robot's attributes are not
//! arguments at all.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat};

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map_or_else(|_| "?".into(), |n| n.to_string())
}

/// `obj` as an integer in `0..=max` (`range` says so in errors): an `int` or anything with `__index__` (numpy integers);
/// `bool` and `float` are a `TypeError`, a value out of range a `ValueError`, each naming
/// `name`.
fn integer(name: &str, obj: &Bound<'_, PyAny>, max: u64, range: &str) -> PyResult<u64> {
    if obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyFloat>() {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected an integer, got {} {}",
            type_name(obj),
            obj.repr().map_or_else(|_| "?".into(), |r| r.to_string())
        )));
    }
    let v: i128 = match obj.extract() {
        Ok(v) => v,
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(obj.py()) => {
            return Err(PyValueError::new_err(format!(
                "{name} = {obj}: expected an integer {range}"
            )))
        }
        Err(_) => {
            return Err(PyTypeError::new_err(format!(
                "{name}: expected an integer, got {}",
                type_name(obj)
            )))
        }
    };
    u64::try_from(v)
        .ok()
        .filter(|&v| v <= max)
        .ok_or_else(|| PyValueError::new_err(format!("{name} = {v}: expected an integer {range}")))
}

/// A count (a dimension, a number of joints) named `name`: an integer ≥ 0.
pub fn count(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    // usize is 64 bits on every platform the wheel is built for.
    Ok(integer(name, obj, usize::MAX as u64, "≥ 0")? as usize)
}

/// A seed named `name`: an integer in `[0, 2⁶⁴ − 1]`.
pub fn seed(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<u64> {
    integer(name, obj, u64::MAX, "in [0, 2**64)")
}

/// A number named `name` (an `int`, a `float` or anything with `__float__`).
pub fn number(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<f64> {
    if obj.is_instance_of::<PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a number, got bool"
        )));
    }
    obj.extract().map_err(|e| {
        let err =
            PyTypeError::new_err(format!("{name}: expected a number, got {}", type_name(obj)));
        err.set_cause(obj.py(), Some(e));
        err
    })
}

/// `v` as Python would print it, about: plain digits for ordinary magnitudes (`60`, `0.002`),
/// an exponent for the extremes (`1e300`, `5e-324`) that Rust's `{}` writes out in full.
pub fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
