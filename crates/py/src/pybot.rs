//! A Python robot (`ROBOT_PROTOCOL.md`) as an `osrl_dynamics::Robot`, for the Rust trainer:
//! each `step` takes the GIL, calls the object's `step` and reads the measurement it returns.

use crate::args::{count, number, short};
use crate::arrays::out1;
use crate::learner::check_control_period;
use crate::meas::{read_all, zeros};
use osrl_dynamics::{DynamicsError, Measurement, Robot};
use pyo3::exceptions::{PyAttributeError, PyTypeError, PyValueError};
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
    /// The largest measured command accepted per joint ([`U_LIMIT_FACTOR`]).
    u_max: Vec<f64>,
    q_min: Vec<f64>,
    q_max: Vec<f64>,
    meas: Measurement,
    next: Measurement,
    buf: Vec<f64>,
    steps: u64,
    pub err: Option<PyErr>,
}

/// The largest measured command `robot.step().u` accepted, as a multiple of the joint's torque
/// limit: `step` clips commands to ±the limits (ROBOT_PROTOCOL.md), so a measured command far
/// beyond them is a broken measurement, and the learner would take its scale from it.
pub const U_LIMIT_FACTOR: f64 = 10.0;

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map_or_else(|_| "?".into(), |n| n.to_string())
}

/// Attribute `name` of the robot: a missing one is a `ValueError` naming `robot.<name>` (the
/// `AttributeError` as its cause); any other exception raised while getting it is the robot's
/// own and propagates.
fn attr<'py>(obj: &Bound<'py, PyAny>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    obj.getattr(name).map_err(|e| {
        let py = obj.py();
        if !e.is_instance_of::<PyAttributeError>(py) {
            return e;
        }
        let err = PyValueError::new_err(format!(
            "robot.{name}: the robot ({}) has no `{name}`; a robot needs dof, task_dim, \
             control_period, torque_limits, joint_limits, reset and step (ROBOT_PROTOCOL.md)",
            type_name(obj)
        ));
        err.set_cause(py, Some(e));
        err
    })
}

/// `obj` (named `what`) as exactly `len` numbers, none of them NaN.
fn numbers(obj: &Bound<'_, PyAny>, what: &str, len: usize) -> PyResult<Vec<f64>> {
    let v: Vec<f64> = obj.extract().map_err(|_| {
        PyValueError::new_err(format!(
            "{what}: expected {len} numbers (a 1-D float64 array), got {} {}",
            type_name(obj),
            obj.repr().map_or_else(|_| "?".into(), |r| r.to_string())
        ))
    })?;
    if v.len() != len {
        return Err(PyValueError::new_err(format!(
            "{what}: expected {len} numbers (one per joint, robot.dof = {len}), got {}: {v:?}",
            v.len()
        )));
    }
    if let Some(i) = v.iter().position(|x| x.is_nan()) {
        return Err(PyValueError::new_err(format!("{what}[{i}] is NaN")));
    }
    Ok(v)
}

/// `robot.torque_limits`: `n` limits, each > 0 (inf: none, as ROBOT_PROTOCOL.md allows).
fn torque_limits(obj: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<f64>> {
    let what = "robot.torque_limits";
    let tau = numbers(&attr(obj, "torque_limits")?, what, n)?;
    if let Some(i) = tau.iter().position(|&t| t.is_nan() || t <= 0.0) {
        return Err(PyValueError::new_err(format!(
            "{what}[{i}] = {}: a torque limit must be > 0 N·m (inf for none); got {tau:?}",
            tau[i]
        )));
    }
    Ok(tau)
}

/// `robot.joint_limits`: a pair `(q_min, q_max)` of `n` numbers each with `q_min < q_max`
/// (∓inf for none, as ROBOT_PROTOCOL.md allows).
fn joint_limits(obj: &Bound<'_, PyAny>, n: usize) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let what = "robot.joint_limits";
    let lim = attr(obj, "joint_limits")?;
    let pair: Vec<Bound<'_, PyAny>> = lim
        .try_iter()
        .and_then(|it| it.collect::<PyResult<Vec<_>>>())
        .ok()
        .filter(|p| p.len() == 2)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "{what}: expected a pair (q_min, q_max) of {n} numbers each, got {} {}",
                type_name(&lim),
                lim.repr().map_or_else(|_| "?".into(), |r| r.to_string())
            ))
        })?;
    let lo = numbers(&pair[0], &format!("{what}[0] (q_min)"), n)?;
    let hi = numbers(&pair[1], &format!("{what}[1] (q_max)"), n)?;
    if let Some(i) = (0..n).find(|&i| lo[i].is_nan() || hi[i].is_nan() || lo[i] >= hi[i]) {
        return Err(PyValueError::new_err(format!(
            "{what}: joint {i} has q_min = {} ≥ q_max = {}; need q_min < q_max (−inf and inf \
             for none)",
            lo[i], hi[i]
        )));
    }
    Ok((lo, hi))
}

/// The robot's `dof`, `task_dim` and `control_period`, each checked and named in errors.
pub fn header(obj: &Bound<'_, PyAny>) -> PyResult<(usize, usize, f64)> {
    if obj.is_none() {
        return Err(PyTypeError::new_err(
            "robot: expected a robot (an object of ROBOT_PROTOCOL.md, e.g. \
             osrl.mujoco.MujocoRobot), got None",
        ));
    }
    let n = count("robot.dof", &attr(obj, "dof")?)?;
    let m = count("robot.task_dim", &attr(obj, "task_dim")?)?;
    let dt = number("robot.control_period", &attr(obj, "control_period")?)?;
    check_control_period("robot.control_period", dt)?;
    Ok((n, m, dt))
}

impl PyBot {
    /// The robot `obj` with `n` joints, an `m`-D task and control period `dt` (from
    /// [`header`]); its torque and joint limits are read and checked here. `data_sheet_tau`: the
    /// torque limits of osrl's model, which bound the measured command of a joint the robot
    /// gives no limit for (see [`U_LIMIT_FACTOR`]).
    pub fn new(
        obj: &Bound<'_, PyAny>,
        (n, m, dt): (usize, usize, f64),
        data_sheet_tau: &[f64],
    ) -> PyResult<Self> {
        let tau = torque_limits(obj, n)?;
        let (q_min, q_max) = joint_limits(obj, n)?;
        let u_max = tau
            .iter()
            .enumerate()
            .map(|(i, &t)| {
                let t = if t.is_finite() {
                    t
                } else {
                    data_sheet_tau.get(i).copied().unwrap_or(f64::INFINITY)
                };
                U_LIMIT_FACTOR * t
            })
            .collect();
        Ok(Self {
            obj: obj.clone().unbind(),
            n,
            m,
            dt,
            tau,
            u_max,
            q_min,
            q_max,
            meas: zeros(n, m),
            next: zeros(n, m),
            buf: Vec::with_capacity(n),
            steps: 0,
            err: None,
        })
    }

    /// `Ok` if the measured command `u` of `what` (`robot.step()`) is within
    /// [`U_LIMIT_FACTOR`] times the torque limits.
    fn check_u(&self, what: &str, u: &[f64]) -> PyResult<()> {
        match (0..u.len()).find(|&i| u[i].is_nan() || u[i].abs() > self.u_max[i]) {
            None => Ok(()),
            Some(i) => Err(PyValueError::new_err(format!(
                "{what}.u[{i}] = {} N·m: beyond {U_LIMIT_FACTOR} × the joint's torque limit \
                 ({} N·m; robot.torque_limits, or osrl's model's where the robot gives none): \
                 u is the command being applied, after clipping (ROBOT_PROTOCOL.md)",
                short(u[i]),
                short(self.u_max[i] / U_LIMIT_FACTOR)
            ))),
        }
    }

    /// Puts the robot at rest at `home`.
    pub fn reset(&mut self, py: Python<'_>, home: &[f64]) -> PyResult<()> {
        let zero = vec![0.0; self.n];
        let m = self
            .obj
            .bind(py)
            .call_method1("reset", (out1(py, home), out1(py, &zero)))?;
        read_all(&m, "robot.reset()", &mut self.meas, &mut self.buf)?;
        self.check_u("robot.reset()", self.meas.u.as_slice())
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
            read_all(&m, "robot.step()", &mut self.next, &mut self.buf)?;
            self.check_u("robot.step()", self.next.u.as_slice())
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
