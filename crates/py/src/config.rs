//! `osrl.Lwpr(n_in, n_out, **config)`: keyword arguments to an `lwpr::LwprConfig` and back.
//!
//! The keywords are the crate's config fields (`lwpr::LwprConfig`, the snake-case parameter
//! names of the reference library); their values are what the CLI's TOML takes: numbers,
//! booleans, strings (`kernel = "bisquare"`), lists or numpy arrays (`init_d`, `norm_in`,
//! `kernel_dims`), `None` for an optional value. The values go through the crate's own serde
//! (JSON form), so the binding and the CLI accept exactly the same configs.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde::de::DeserializeOwned;
use serde_json::{Map, Number, Value};

/// The config keys, in the crate's order.
pub fn keys() -> Vec<String> {
    match serde_json::to_value(lwpr::LwprConfig::default()) {
        Ok(Value::Object(m)) => m.keys().cloned().collect(),
        _ => unreachable!("LwprConfig serialises to an object"),
    }
}

/// Deepest nesting of lists and dicts in a config value: the crates' configs nest a few levels
/// (a dict of sections, a list of rows), so anything deeper is a mistake, most likely a list or
/// dict that contains itself; the conversion recurses, and this bound keeps it off the end of
/// the stack.
pub const MAX_DEPTH: usize = 64;

/// A Python value as JSON (dicts with string keys nest); `key` names it in errors.
pub fn to_json(key: &str, v: &Bound<'_, PyAny>) -> PyResult<Value> {
    to_json_at(key, v, 0)
}

/// [`to_json`] of a value nested `depth` lists, dicts or `tolist()` results deep; `key` is its
/// path (`init_d[2][0]`, `learner config.guards.torque_limits`).
fn to_json_at(key: &str, v: &Bound<'_, PyAny>, depth: usize) -> PyResult<Value> {
    if v.is_none() {
        return Ok(Value::Null);
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return match v.extract::<i64>() {
            Ok(i) => Ok(Value::Number(i.into())),
            Err(_) => Err(PyValueError::new_err(format!("{key} = {v}: out of range"))),
        };
    }
    if v.is_instance_of::<PyFloat>() {
        let f: f64 = v.extract()?;
        return Number::from_f64(f)
            .map(Value::Number)
            .ok_or_else(|| PyValueError::new_err(format!("{key} = {f}: must be finite")));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    let nested = v.cast::<PyDict>().is_ok()
        || v.is_instance_of::<PyList>()
        || v.is_instance_of::<PyTuple>()
        || v.hasattr("tolist")?;
    if nested && depth >= MAX_DEPTH {
        // The path of a cycle repeats itself: its start says where it is.
        let path: String = match key.char_indices().nth(100) {
            Some((cut, _)) => format!("{}…", &key[..cut]),
            None => key.to_string(),
        };
        return Err(PyValueError::new_err(format!(
            "{path}: nested more than {MAX_DEPTH} lists or dicts deep (a list or dict that \
             contains itself, or an object whose tolist() returns itself?)"
        )));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut map = Map::new();
        for (k, item) in d.iter() {
            let name: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("{key}: keys must be strings")))?;
            let value = to_json_at(&format!("{key}.{name}"), &item, depth + 1)?;
            map.insert(name, value);
        }
        return Ok(Value::Object(map));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: PyResult<Vec<Value>> = v
            .try_iter()?
            .enumerate()
            .map(|(i, item)| to_json_at(&format!("{key}[{i}]"), &item?, depth + 1))
            .collect();
        return Ok(Value::Array(items?));
    }
    // numpy arrays and scalars (np.float64 is a float already; np.int64 and arrays are not).
    if v.hasattr("tolist")? {
        return to_json_at(key, &v.call_method0("tolist")?, depth + 1);
    }
    Err(PyTypeError::new_err(format!(
        "{key}: unsupported value of type {}",
        v.get_type().name()?
    )))
}

/// The config from keyword arguments (all optional; unknown keys are a `TypeError`, bad values
/// a `ValueError`, as the crate's serde and validation phrase them).
pub fn from_kwargs(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<lwpr::LwprConfig> {
    let mut map = Map::new();
    let known = keys();
    if let Some(kw) = kwargs {
        for (k, v) in kw.iter() {
            let key: String = k.extract()?;
            if !known.contains(&key) {
                return Err(PyTypeError::new_err(format!(
                    "Lwpr() got an unexpected keyword argument '{key}' (LWPR config keys: {})",
                    known.join(", ")
                )));
            }
            let value = to_json(&key, &v)?;
            map.insert(key, value);
        }
    }
    let cfg: lwpr::LwprConfig = serde_json::from_value(Value::Object(map))
        .map_err(|e| PyValueError::new_err(format!("invalid LWPR config: {e}")))?;
    if has_std(&cfg) {
        return Err(PyValueError::new_err(
            "norm_in/norm_out = \"std\" needs the training data: pass the standard deviations \
             (e.g. norm_in=X.std(axis=0)), as `osrl lwpr fit` resolves them",
        ));
    }
    Ok(cfg)
}

fn has_std(cfg: &lwpr::LwprConfig) -> bool {
    use lwpr::{Norm, NormKeyword};
    let std = Norm::Keyword(NormKeyword::Std);
    cfg.norm_in == std || cfg.norm_out == std
}

/// The config as a Python dict (JSON form: lists for vectors, strings for enums).
pub fn to_dict<'py>(py: Python<'py>, cfg: &lwpr::LwprConfig) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(cfg).expect("LwprConfig serialises");
    py.import("json")?.call_method1("loads", (text,))
}

/// A serde config (`deny_unknown_fields`, defaults for missing keys) from a Python dict (or
/// `None`: the defaults); `what` names it in errors. Unknown keys and bad values are a
/// `ValueError` phrased by serde (`unknown field `x`, expected one of ...`).
pub fn from_dict<T: DeserializeOwned + Default>(
    what: &str,
    obj: Option<&Bound<'_, PyAny>>,
) -> PyResult<T> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(T::default());
    };
    if obj.cast::<PyDict>().is_err() {
        return Err(PyTypeError::new_err(format!(
            "{what}: expected a dict, got {}",
            obj.get_type().name()?
        )));
    }
    let value = to_json(what, obj)?;
    serde_json::from_value(value).map_err(|e| PyValueError::new_err(format!("invalid {what}: {e}")))
}
