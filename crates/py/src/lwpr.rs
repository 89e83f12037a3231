//! `osrl.Lwpr`: the `lwpr` crate's model on numpy arrays.
//!
//! Every method validates its whole input before the model changes (a batch is checked row by
//! row first), so an exception leaves the model as it was. The single-sample calls keep the
//! GIL (they take about a microsecond); batches, `save` and `load` release it.

use crate::args::count;
use crate::arrays::{alloc, matrix, out1, out2, read_into, Matrix};
use crate::arrays::{Arr1, Arr2};
use crate::config;
use crate::errors::lwpr_err;
use lwpr::{Lwpr, LwprError, MAX_NORMALISED};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use std::path::PathBuf;

/// An incremental LWPR model mapping `n_in` inputs to `n_out` outputs (see `python/osrl/_osrl.pyi`
/// for the Python documentation).
#[pyclass(name = "Lwpr", module = "osrl")]
pub struct PyLwpr {
    model: Lwpr,
    /// Input buffers of the single-sample calls ([`read_into`]).
    xb: Vec<f64>,
    yb: Vec<f64>,
    /// Output buffers of the single-sample calls.
    y: Vec<f64>,
    conf: Vec<f64>,
    jac: Vec<f64>,
}

impl PyLwpr {
    fn wrap(model: Lwpr) -> Self {
        let (n_in, n_out) = (model.n_in(), model.n_out());
        PyLwpr {
            model,
            xb: Vec::with_capacity(n_in),
            yb: Vec::with_capacity(n_out),
            y: vec![0.0; n_out],
            conf: vec![0.0; n_out],
            jac: vec![0.0; n_out * n_in],
        }
    }

    /// Checks what `Lwpr::update` checks of every row of a batch, so that the batch either
    /// fails before the first update or runs through: finite values (done by [`matrix`]) and
    /// the normalised magnitudes of the inputs the model uses and of the outputs.
    fn check_batch(&self, x: &Matrix, y: &Matrix) -> PyResult<()> {
        if x.rows != y.rows {
            return Err(PyValueError::new_err(format!(
                "X has {} rows and Y has {}: one target row per input row",
                x.rows, y.rows
            )));
        }
        let p = self.model.params();
        let used: Vec<usize> = p.kdims.iter().chain(&p.rdims).copied().collect();
        for i in 0..x.rows {
            for &k in &used {
                check_scale(i, "x", x.row(i)[k], k, p.norm_in[k])?;
            }
            for (k, &v) in y.row(i).iter().enumerate() {
                check_scale(i, "y", v, k, p.norm_out[k])?;
            }
        }
        Ok(())
    }
}

/// The update's bound on a normalised value (`lwpr::LwprError::Scale`), for row `row` of a batch.
fn check_scale(
    row: usize,
    what: &'static str,
    value: f64,
    index: usize,
    norm: f64,
) -> PyResult<()> {
    if value.abs() <= MAX_NORMALISED * norm {
        return Ok(());
    }
    let scaled = value / norm;
    let e = LwprError::Scale {
        what,
        index,
        value,
        norm,
        scaled,
    };
    Err(PyValueError::new_err(format!(
        "row {row}: {e}; nothing was changed"
    )))
}

#[pymethods]
impl PyLwpr {
    #[new]
    #[pyo3(signature = (n_in, n_out, **config))]
    fn new(
        n_in: &Bound<'_, PyAny>,
        n_out: &Bound<'_, PyAny>,
        config: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let (n_in, n_out) = (count("n_in", n_in)?, count("n_out", n_out)?);
        let cfg = config::from_kwargs(config)?;
        Ok(Self::wrap(
            Lwpr::new(n_in, n_out, &cfg).map_err(|e| lwpr_err(e, None))?,
        ))
    }

    /// Learns from one sample; returns the prediction of the receptive fields it updated, after
    /// their update (the reference library's `lwpr_update` `yp`; NaN for an output where no
    /// trustworthy receptive field was updated): not the prediction before learning.
    fn update<'py>(
        &mut self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        y: &Bound<'py, PyAny>,
    ) -> PyResult<Arr1<'py>> {
        read_into("x", x, &mut self.xb)?;
        read_into("y", y, &mut self.yb)?;
        self.model
            .update(&self.xb, &self.yb)
            .map_err(|e| lwpr_err(e, None))?;
        self.model.drain_events().for_each(drop);
        Ok(out1(py, self.model.last_update_prediction()))
    }

    /// Learns from the rows of `X` and `Y` in order; returns each update's prediction as
    /// `update` does (rows of NaN where no trustworthy RF was updated). At most
    /// `MAX_BATCH_VALUES` values. Releases the GIL.
    #[pyo3(name = "update_batch")]
    #[allow(non_snake_case)]
    fn update_batch<'py>(
        &mut self,
        py: Python<'py>,
        X: &Bound<'py, PyAny>,
        Y: &Bound<'py, PyAny>,
    ) -> PyResult<Arr2<'py>> {
        let (n_in, n_out) = (self.model.n_in(), self.model.n_out());
        let x = matrix("X", X, n_in)?;
        let y = matrix("Y", Y, n_out)?;
        self.check_batch(&x, &y)?;
        let mut pred = alloc("Y", "result", x.rows, n_out)?;
        let model = &mut self.model;
        let res = py.detach(|| {
            for i in 0..x.rows {
                if let Err(e) = model.update(x.row(i), y.row(i)) {
                    return Err((i, e, pred));
                }
                model.drain_events().for_each(drop);
                pred.extend_from_slice(model.last_update_prediction());
            }
            Ok(pred)
        });
        match res {
            Ok(pred) => Ok(out2(py, x.rows, n_out, pred)),
            // Not reached: the checks above are the update's own.
            Err((i, e, _)) => Err(PyValueError::new_err(format!(
                "row {i}: {e} (rows 0..{i} were learned)"
            ))),
        }
    }

    /// The prediction at `x` (length `n_out`). Raises `osrl.NoSupportError` where no
    /// trustworthy receptive field is active, unless `strict=False` (then 0 there).
    #[pyo3(signature = (x, *, strict = true))]
    fn predict<'py>(
        &mut self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        strict: bool,
    ) -> PyResult<Arr1<'py>> {
        read_into("x", x, &mut self.xb)?;
        let res = if strict {
            self.model.predict(&self.xb, &mut self.y).map(drop)
        } else {
            self.model
                .predict_with_support(&self.xb, &mut self.y, &mut self.conf)
        };
        res.map_err(|e| lwpr_err(e, None))?;
        Ok(out1(py, &self.y))
    }

    /// Predictions at the rows of `X`, shape `(N, n_out)`. At most `MAX_BATCH_VALUES` values.
    /// Releases the GIL.
    #[pyo3(signature = (X, *, strict = true))]
    #[allow(non_snake_case)]
    fn predict_batch<'py>(
        &mut self,
        py: Python<'py>,
        X: &Bound<'py, PyAny>,
        strict: bool,
    ) -> PyResult<Arr2<'py>> {
        let (n_in, n_out) = (self.model.n_in(), self.model.n_out());
        let x = matrix("X", X, n_in)?;
        let mut out = alloc("X", "result", x.rows, n_out)?;
        out.resize(x.rows * n_out, 0.0);
        let model = &mut self.model;
        let res = py.detach(|| {
            let mut support = vec![0.0; n_out];
            for (i, y) in out.chunks_exact_mut(n_out.max(1)).enumerate() {
                let r = if strict {
                    model.predict(x.row(i), y).map(drop)
                } else {
                    model.predict_with_support(x.row(i), y, &mut support)
                };
                r.map_err(|e| (i, e))?;
            }
            Ok(out)
        });
        match res {
            Ok(out) => Ok(out2(py, x.rows, n_out, out)),
            Err((i, e)) => {
                let err = lwpr_err(e, None);
                let msg = format!("X row {i}: {}", err.value(py));
                Err(PyErr::from_type(err.get_type(py), msg))
            }
        }
    }

    /// `(y, conf)`: the prediction and its confidence bound per output (output units).
    fn predict_conf<'py>(
        &mut self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<(Arr1<'py>, Arr1<'py>)> {
        read_into("x", x, &mut self.xb)?;
        self.model
            .predict_conf(&self.xb, &mut self.y, &mut self.conf)
            .map_err(|e| lwpr_err(e, None))?;
        Ok((out1(py, &self.y), out1(py, &self.conf)))
    }

    /// The Jacobian `∂ŷ/∂x` at `x`, shape `(n_out, n_in)`.
    fn jacobian<'py>(&mut self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Arr2<'py>> {
        read_into("x", x, &mut self.xb)?;
        self.model
            .predict_jacobian(&self.xb, &mut self.y, &mut self.jac)
            .map_err(|e| lwpr_err(e, None))?;
        let (n_in, n_out) = (self.model.n_in(), self.model.n_out());
        Ok(out2(py, n_out, n_in, self.jac.clone()))
    }

    /// Receptive fields per sub-model (one entry per output, or one when RFs are shared).
    #[getter]
    fn n_rfs(&self) -> Vec<usize> {
        self.model.n_rfs()
    }

    #[getter]
    fn n_in(&self) -> usize {
        self.model.n_in()
    }

    #[getter]
    fn n_out(&self) -> usize {
        self.model.n_out()
    }

    /// Updates so far.
    #[getter]
    fn n_updates(&self) -> u64 {
        self.model.n_updates()
    }

    /// The config (every key, defaults filled in) as a dict.
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        config::to_dict(py, &self.model.params().cfg)
    }

    /// How often the update's numerical guards stepped in since creation or loading.
    #[getter]
    fn warnings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let w = self.model.warnings();
        let d = PyDict::new(py);
        d.set_item("metric_skipped", w.metric_skipped)?;
        d.set_item("removed_non_finite", w.removed_non_finite)?;
        Ok(d)
    }

    /// Writes the model to `path` (a new file renamed into place; a failure leaves any old
    /// file whole). Refuses to replace a folder, a link or a device. Releases the GIL.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        // `osrl_files::write_atomic` refuses a folder, a link or a device (IsADirectoryError,
        // OSError) before writing.
        let model = &self.model;
        py.detach(|| model.save(&path))
            .map_err(|e| lwpr_err(e, Some(&path)))
    }

    /// Reads a model written by `save` (or `osrl lwpr fit --save`). Releases the GIL.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let m = py
            .detach(|| Lwpr::load(&path))
            .map_err(|e| lwpr_err(e, Some(&path)))?;
        Ok(Self::wrap(m))
    }

    /// The model in the file format of `save`, as bytes.
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.model.to_bytes())
    }

    /// A model from `to_bytes` output.
    #[staticmethod]
    fn from_bytes(data: &[u8]) -> PyResult<Self> {
        Ok(Self::wrap(
            Lwpr::from_bytes(data).map_err(|e| lwpr_err(e, None))?,
        ))
    }

    /// Pickling goes through `to_bytes` (bit-exact).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let ctor = py.get_type::<PyLwpr>().getattr("from_bytes")?;
        PyTuple::new(
            py,
            [ctor, PyTuple::new(py, [self.to_bytes(py)])?.into_any()],
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "osrl.Lwpr(n_in={}, n_out={}, n_rfs={:?}, n_updates={})",
            self.model.n_in(),
            self.model.n_out(),
            self.model.n_rfs(),
            self.model.n_updates()
        )
    }
}
