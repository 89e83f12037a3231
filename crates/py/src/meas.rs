//! Python measurements and targets into preallocated Rust buffers, checked before anything
//! changes: an `osrl.Measurement` (or any object with its attributes `t`, `q`, `qd`, `x`, `xd`,
//! `xdd`, `u`) into an `osrl_dynamics::Measurement` of known size.

use crate::arrays::read_into;
use nalgebra::DVector;
use osrl_dynamics::Measurement;
use pyo3::exceptions::{PyAttributeError, PyValueError};
use pyo3::intern;
use pyo3::prelude::*;

/// `obj` (a 1-D float64 array or a list of numbers) as exactly `len` finite values in `buf`.
pub fn read_checked(
    what: &str,
    obj: &Bound<'_, PyAny>,
    len: usize,
    buf: &mut Vec<f64>,
) -> PyResult<()> {
    read_into(what, obj, buf)?;
    if buf.len() != len {
        return Err(PyValueError::new_err(format!(
            "{what}: expected {len} values, got {}",
            buf.len()
        )));
    }
    if let Some(i) = buf.iter().position(|v| !v.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{what}[{i}] = {} is not finite",
            buf[i]
        )));
    }
    Ok(())
}

/// A zero measurement of a robot with `n` joints and an `m`-D task.
pub fn zeros(n: usize, m: usize) -> Measurement {
    Measurement {
        t: 0.0,
        q: DVector::zeros(n),
        qd: DVector::zeros(n),
        x: DVector::zeros(m),
        xd: DVector::zeros(m),
        xdd: DVector::zeros(m),
        u: DVector::zeros(n),
    }
}

/// Attribute `name` of `obj`. A missing attribute (`AttributeError`) is a `ValueError` saying
/// that `what` is not a measurement (the `AttributeError` as its cause); any other exception
/// raised while getting it (a property that fails) is the object's own and propagates as it is.
pub fn attr<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    name: &Bound<'py, pyo3::types::PyString>,
) -> PyResult<Bound<'py, PyAny>> {
    obj.getattr(name).map_err(|e| {
        let py = obj.py();
        if !e.is_instance_of::<PyAttributeError>(py) {
            return e;
        }
        let err = PyValueError::new_err(format!(
            "{what}: expected an osrl.Measurement, it has no `{name}`"
        ));
        err.set_cause(py, Some(e));
        err
    })
}

/// Reads attribute `name` of `obj` (`what.name` in errors) into `dst`, through `buf`.
fn field(
    obj: &Bound<'_, PyAny>,
    what: &str,
    name: &Bound<'_, pyo3::types::PyString>,
    dst: &mut DVector<f64>,
    buf: &mut Vec<f64>,
) -> PyResult<()> {
    let v = attr(obj, what, name)?;
    read_checked(&format!("{what}.{name}"), &v, dst.len(), buf)?;
    dst.copy_from_slice(buf);
    Ok(())
}

/// The joint and task state `q, q̇, x, ẋ` of `obj` into `dst` (the fields a controller reads).
/// On an error `dst` may be partly written: callers pass a scratch measurement.
pub fn read_state(
    obj: &Bound<'_, PyAny>,
    what: &str,
    dst: &mut Measurement,
    buf: &mut Vec<f64>,
) -> PyResult<()> {
    let py = obj.py();
    field(obj, what, intern!(py, "q"), &mut dst.q, buf)?;
    field(obj, what, intern!(py, "qd"), &mut dst.qd, buf)?;
    field(obj, what, intern!(py, "x"), &mut dst.x, buf)?;
    field(obj, what, intern!(py, "xd"), &mut dst.xd, buf)
}

/// The measured task acceleration `xdd` of `obj` into `dst.xdd` (the disturbance observer's
/// input).
pub fn read_xdd(
    obj: &Bound<'_, PyAny>,
    what: &str,
    dst: &mut Measurement,
    buf: &mut Vec<f64>,
) -> PyResult<()> {
    field(obj, what, intern!(obj.py(), "xdd"), &mut dst.xdd, buf)
}

/// Every field of `obj` into `dst` (sizes from `dst`); see [`read_state`].
pub fn read_all(
    obj: &Bound<'_, PyAny>,
    what: &str,
    dst: &mut Measurement,
    buf: &mut Vec<f64>,
) -> PyResult<()> {
    let py = obj.py();
    read_state(obj, what, dst, buf)?;
    field(obj, what, intern!(py, "xdd"), &mut dst.xdd, buf)?;
    field(obj, what, intern!(py, "u"), &mut dst.u, buf)?;
    let t = attr(obj, what, intern!(py, "t"))?;
    let t: f64 = t.extract().map_err(|e| {
        let ty = t
            .get_type()
            .name()
            .map_or_else(|_| "?".to_string(), |n| n.to_string());
        let err = PyValueError::new_err(format!("{what}.t: expected a number, got {ty}"));
        err.set_cause(py, Some(e));
        err
    })?;
    if !t.is_finite() {
        return Err(PyValueError::new_err(format!(
            "{what}.t = {t} is not finite"
        )));
    }
    dst.t = t;
    Ok(())
}
