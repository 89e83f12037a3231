//! numpy arrays in and out. Inputs are float64 arrays of the right number of dimensions (any
//! strides) or lists/tuples of numbers; anything else is a `ValueError` that names the argument
//! and says what it got. Lengths and finiteness of single vectors are checked by the crates
//! (before they change anything); batches are checked here, whole, before the first row is used.

use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyReadonlyArray1, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyMemoryError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// A new 1-D float64 array (a method's result).
pub type Arr1<'py> = Bound<'py, PyArray1<f64>>;
/// A new 2-D float64 array (a method's result).
pub type Arr2<'py> = Bound<'py, PyArray2<f64>>;

/// A 1-D input: borrowed from a contiguous float64 array, or copied.
pub enum Vector<'py> {
    Borrowed(PyReadonlyArray1<'py, f64>),
    Owned(Vec<f64>),
}

impl Vector<'_> {
    /// The values.
    pub fn as_slice(&self) -> &[f64] {
        match self {
            // Contiguity was checked when the vector was made.
            Vector::Borrowed(a) => a.as_slice().expect("contiguous"),
            Vector::Owned(v) => v,
        }
    }
}

/// A shape as Python prints it: `(3, 2)`, `(3,)`.
fn shape_str(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// `"a int64 array of shape (3, 2)"`: what a wrong array is, for error messages.
fn describe(a: &Bound<'_, PyUntypedArray>) -> String {
    format!("a {} array of shape {}", a.dtype(), shape_str(a.shape()))
}

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map_or_else(|_| "?".into(), |n| n.to_string())
}

/// A list or tuple as numbers; `None` for any other object.
fn sequence(what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Option<Vec<f64>>> {
    if !(obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>()) {
        return Ok(None);
    }
    obj.extract::<Vec<f64>>()
        .map(Some)
        .map_err(|_| PyValueError::new_err(format!("{what}: expected a list of numbers (float64)")))
}

/// A 1-D float64 input named `what`.
pub fn vector<'py>(what: &str, obj: &Bound<'py, PyAny>) -> PyResult<Vector<'py>> {
    if let Ok(a) = obj.cast::<PyArray1<f64>>() {
        let r = a
            .try_readonly()
            .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))?;
        if r.as_slice().is_ok() {
            return Ok(Vector::Borrowed(r));
        }
        return Ok(Vector::Owned(r.as_array().iter().copied().collect()));
    }
    if let Ok(a) = obj.cast::<PyUntypedArray>() {
        return Err(PyValueError::new_err(format!(
            "{what}: expected a 1-D float64 array, got {}",
            describe(a)
        )));
    }
    match sequence(what, obj)? {
        Some(v) => Ok(Vector::Owned(v)),
        None => Err(PyValueError::new_err(format!(
            "{what}: expected a 1-D float64 numpy array, got {}",
            type_name(obj)
        ))),
    }
}

/// A 1-D float64 input named `what`, copied into `buf` (its previous contents are replaced).
/// The single-sample calls of the hot paths read their inputs this way: a contiguous float64
/// array is copied directly, without rust-numpy's borrow bookkeeping (about 100 ns per array);
/// anything else goes through [`vector`].
pub fn read_into(what: &str, obj: &Bound<'_, PyAny>, buf: &mut Vec<f64>) -> PyResult<()> {
    if let Ok(a) = obj.cast::<PyArray1<f64>>() {
        if a.is_contiguous() && a.is_aligned() {
            buf.clear();
            // SAFETY: the GIL is held and no Python code runs until the copy is done, so no
            // Python code writes the array meanwhile; the slice does not outlive the copy.
            // (Native code writing the array from another thread without the GIL would race
            // with the safe `readonly()` as well: its borrow flags cover Rust borrows only.)
            buf.extend_from_slice(unsafe { a.as_slice() }.expect("contiguous and aligned"));
            return Ok(());
        }
    }
    let v = vector(what, obj)?;
    buf.clear();
    buf.extend_from_slice(v.as_slice());
    Ok(())
}

/// A batch: `rows × cols` values, row-major, copied (so the GIL can be released while it is
/// used) and checked: every entry finite.
pub struct Matrix {
    pub rows: usize,
    pub cols: usize,
    pub data: Vec<f64>,
}

impl Matrix {
    /// Row `i`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.cols..(i + 1) * self.cols]
    }
}

/// A 2-D float64 input named `what` with `cols` columns (a 1-D array or list of numbers counts
/// as one column when `cols == 1`); every entry must be finite.
pub fn matrix(what: &str, obj: &Bound<'_, PyAny>, cols: usize) -> PyResult<Matrix> {
    let shape_err = |got: String| {
        PyValueError::new_err(format!(
            "{what}: expected a float64 array of shape (N, {cols}), got {got}"
        ))
    };
    let (rows, data) = if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        let r = a
            .try_readonly()
            .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))?;
        let shape = r.shape().to_vec();
        let rows = match shape[..] {
            [n, c] if c == cols => n,
            [n] if cols == 1 => n,
            _ => return Err(shape_err(format!("shape {}", shape_str(&shape)))),
        };
        // Row-major whatever the strides (iteration is in logical order), into a buffer
        // reserved first: a broadcast view of 10¹² rows is refused here, not by an abort.
        let mut data = alloc(what, "copy", rows, cols)?;
        data.extend(r.as_array().iter().copied());
        (rows, data)
    } else if let Ok(a) = obj.cast::<PyUntypedArray>() {
        return Err(shape_err(describe(a)));
    } else if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        from_rows(what, obj, cols).map_err(|_| shape_err("a list that is not one".into()))?
    } else {
        return Err(shape_err(type_name(obj)));
    };
    if let Some(k) = data.iter().position(|v| !v.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{what}[{}, {}] is not finite ({}); nothing was changed",
            k / cols,
            k % cols,
            data[k]
        )));
    }
    Ok(Matrix { rows, cols, data })
}

/// Most values a batch may hold (its copy, or its result): 2³¹ float64 values, 16 GiB. Batches
/// are copied whole (so that the GIL can be released while they run), so a larger one — most
/// likely a broadcast view such as `np.broadcast_to(x, (10**12, n))`, which costs no memory
/// until it is copied — is refused before anything is allocated; split it into smaller batches.
pub const MAX_BATCH_VALUES: usize = 1 << 31;

/// An empty buffer with room for `rows × cols` values, the `what` batch's `purpose` (`copy`,
/// `result`): a `ValueError` beyond [`MAX_BATCH_VALUES`], a `MemoryError` if the allocation
/// fails, both saying how large the batch is.
pub fn alloc(what: &str, purpose: &str, rows: usize, cols: usize) -> PyResult<Vec<f64>> {
    let values = rows
        .checked_mul(cols)
        .filter(|&v| v <= MAX_BATCH_VALUES)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "{what}: {rows} rows × {cols} columns is more than {MAX_BATCH_VALUES} values \
                 (16 GiB of float64) for its {purpose}; split it into smaller batches"
            ))
        })?;
    let mut v = Vec::new();
    v.try_reserve_exact(values).map_err(|_| {
        PyMemoryError::new_err(format!(
            "{what}: cannot allocate {} MiB for the {purpose} of {rows} rows × {cols} columns; \
             split it into smaller batches",
            (values * 8) >> 20
        ))
    })?;
    Ok(v)
}

/// A list of rows (or, for one column, of numbers) as row-major values.
fn from_rows(what: &str, obj: &Bound<'_, PyAny>, cols: usize) -> PyResult<(usize, Vec<f64>)> {
    if cols == 1 {
        if let Ok(v) = obj.extract::<Vec<f64>>() {
            return Ok((v.len(), v));
        }
    }
    let rows: Vec<Vec<f64>> = obj.extract()?;
    if rows.iter().any(|r| r.len() != cols) {
        return Err(PyValueError::new_err(format!("{what}: ragged rows")));
    }
    Ok((rows.len(), rows.concat()))
}

/// A new 1-D array.
pub fn out1<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

/// A new `rows × cols` array from row-major values.
pub fn out2(py: Python<'_>, rows: usize, cols: usize, v: Vec<f64>) -> Bound<'_, PyArray2<f64>> {
    Array2::from_shape_vec((rows, cols), v)
        .expect("rows × cols values")
        .into_pyarray(py)
}
