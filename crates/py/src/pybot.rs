//! A Python robot (`ROBOT_PROTOCOL.md`) as an `osrl_dynamics::Robot`, for the Rust trainer:
//! each `step` takes the GIL, calls the object's `step` and reads the measurement it returns.

use crate::arrays::out1;
use crate::meas::{read_all, zeros};
use osrl_dynamics::{DynamicsError, Measurement, Robot};
use pyo3::exceptions::PyValueError;
use pyo3::intern;
use pyo3::prelude::*;

/// A Python robot as an `osrl_dynamics::Robot`; a Python exception raised by its `step` is kept
/// in `err` (the trainer sees a `DynamicsError`) and raised again when the training stops.
pub struct PyBot {
    pub obj: Py<PyAny>,
    pub n: usize,
    pub m: usize,
    pub dt: f64,
    tau: Vec<f64>,
    q_min: Vec<f64>,
    q_max: Vec<f64>,
    meas: Measurement,
    next: Measurement,
    buf: Vec<f64>,
    steps: u64,
    pub err: Option<PyErr>,
}

/// Attribute `name` of `obj` as exactly `len` values (±inf allowed: limits).
fn limits(obj: &Bound<'_, PyAny>, what: &str, len: usize) -> PyResult<Vec<f64>> {
    let v: Vec<f64> = obj.extract()?;
    if v.len() != len || v.iter().any(|x| x.is_nan()) {
        return Err(PyValueError::new_err(format!(
            "robot.{what}: expected {len} numbers (±inf for none), got {v:?}"
        )));
    }
    Ok(v)
}

impl PyBot {
    pub fn new(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        let py = obj.py();
        let n: usize = obj.getattr(intern!(py, "dof"))?.extract()?;
        let m: usize = obj.getattr(intern!(py, "task_dim"))?.extract()?;
        let dt: f64 = obj.getattr(intern!(py, "control_period"))?.extract()?;
        let tau = limits(&obj.getattr("torque_limits")?, "torque_limits", n)?;
        let (lo, hi): (Bound<PyAny>, Bound<PyAny>) = obj.getattr("joint_limits")?.extract()?;
        Ok(Self {
            obj: obj.clone().unbind(),
            n,
            m,
            dt,
            tau,
            q_min: limits(&lo, "joint_limits[0]", n)?,
            q_max: limits(&hi, "joint_limits[1]", n)?,
            meas: zeros(n, m),
            next: zeros(n, m),
            buf: Vec::with_capacity(n),
            steps: 0,
            err: None,
        })
    }

    /// Puts the robot at rest at `home`.
    pub fn reset(&mut self, py: Python<'_>, home: &[f64]) -> PyResult<()> {
        let zero = vec![0.0; self.n];
        let m = self
            .obj
            .bind(py)
            .call_method1("reset", (out1(py, home), out1(py, &zero)))?;
        read_all(&m, "robot.reset()", &mut self.meas, &mut self.buf)
    }
}

impl Robot for PyBot {
    fn dof(&self) -> usize {
        self.n
    }
    fn task_dim(&self) -> usize {
        self.m
    }
    fn control_period(&self) -> f64 {
        self.dt
    }
    fn torque_limits(&self) -> &[f64] {
        &self.tau
    }
    fn joint_limits(&self) -> (&[f64], &[f64]) {
        (&self.q_min, &self.q_max)
    }
    fn measurement(&self) -> &Measurement {
        &self.meas
    }
    fn step(&mut self, u: &[f64]) -> Result<&Measurement, DynamicsError> {
        self.steps += 1;
        let res = Python::attach(|py| -> PyResult<()> {
            if self.steps.is_multiple_of(250) {
                py.check_signals()?;
            }
            let m = self
                .obj
                .bind(py)
                .call_method1(intern!(py, "step"), (out1(py, u),))?;
            read_all(&m, "robot.step()", &mut self.next, &mut self.buf)
        });
        match res {
            Ok(()) => {
                std::mem::swap(&mut self.meas, &mut self.next);
                Ok(&self.meas)
            }
            Err(e) => {
                let msg = format!("the Python robot's step failed: {e}");
                self.err = Some(e);
                Err(DynamicsError::InvalidConfig(msg))
            }
        }
    }
}
