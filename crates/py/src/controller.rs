//! `osrl.LearnedController`: a trained learner (`osrl_learn::LearnedController`, the task
//! controller of `osrl simulate --controller learned:F`) stepped from Python.

use crate::arrays::out1;
use crate::errors::{learn_err, setup_err};
use crate::meas::{read_checked, read_state, read_xdd, zeros};
use numpy::PyArray1;
use osrl_control::{Target, TaskController};
use osrl_dynamics::Measurement;
use osrl_learn::{LearnedController, Learner, ModelInfo, SavedModel};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;

/// A learned operational space controller and its scratch buffers (see `_osrl.pyi`).
#[pyclass(name = "LearnedController", module = "osrl")]
pub struct PyLearnedController {
    ctrl: LearnedController,
    info: ModelInfo,
    axes: Vec<usize>,
    /// The training summary (JSON) when the controller came from `osrl.train`.
    pub summary: Option<String>,
    meas: Measurement,
    target: Target,
    buf: Vec<f64>,
    goal: [Vec<f64>; 3],
    u: Vec<f64>,
}

impl PyLearnedController {
    /// The controller of a saved model.
    pub fn from_saved(saved: SavedModel) -> PyResult<Self> {
        let axes = saved.robot().task_axes().to_vec();
        let info = saved.info().clone();
        let ctrl = saved.controller().map_err(learn_err)?;
        let (n, m) = ctrl.learner().dims();
        Ok(Self {
            ctrl,
            info,
            axes,
            summary: None,
            meas: zeros(n, m),
            target: Target::default(),
            buf: Vec::with_capacity(n.max(m)),
            goal: [vec![0.0; m], vec![0.0; m], vec![0.0; m]],
            u: vec![0.0; n],
        })
    }

    fn saved(&self) -> PyResult<SavedModel> {
        SavedModel::new(self.info.clone(), self.ctrl.learner().clone()).map_err(learn_err)
    }
}

#[pymethods]
impl PyLearnedController {
    /// Reads a model saved by `osrl train` or `LearnedController.save` (GIL released).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let saved = py.detach(|| SavedModel::load(&path)).map_err(learn_err)?;
        Self::from_saved(saved)
    }

    /// Writes the model (its learner and what it needs besides) to `path` (GIL released).
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let saved = self.saved()?;
        py.detach(|| saved.save(&path)).map_err(learn_err)
    }

    /// The command `u` (N·m) for the measured state and the target on the task axes.
    #[pyo3(signature = (measurement, x_d, xd_d, xdd_d))]
    fn command<'py>(
        &mut self,
        py: Python<'py>,
        measurement: &Bound<'py, PyAny>,
        x_d: &Bound<'py, PyAny>,
        xd_d: &Bound<'py, PyAny>,
        xdd_d: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        read_state(measurement, "measurement", &mut self.meas, &mut self.buf)?;
        if self.ctrl.observer().is_on() {
            read_xdd(measurement, "measurement", &mut self.meas, &mut self.buf)?;
        }
        let m = self.axes.len();
        for (what, obj, dst) in [("x_d", x_d, 0), ("xd_d", xd_d, 1), ("xdd_d", xdd_d, 2)] {
            read_checked(what, obj, m, &mut self.buf)?;
            self.goal[dst].copy_from_slice(&self.buf);
        }
        let mut target = Target::default();
        for (i, &a) in self.axes.iter().enumerate() {
            target.x[a] = self.goal[0][i];
            target.xd[a] = self.goal[1][i];
            target.xdd[a] = self.goal[2][i];
        }
        self.target = target;
        self.ctrl
            .command(&self.meas, &self.target, &mut self.u)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(out1(py, &self.u))
    }

    /// Forgets the disturbance observer's estimate (before a new run from rest).
    fn reset(&mut self) {
        self.ctrl.reset_observer();
    }

    /// Whether the task-space disturbance observer runs (then `command` reads `xdd`).
    #[getter]
    fn observer(&self) -> bool {
        self.ctrl.observer().is_on()
    }

    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.ctrl.learner().dims().0
    }

    /// Task-space dimension.
    #[getter]
    fn task_dim(&self) -> usize {
        self.ctrl.learner().dims().1
    }

    /// The world axes (0 = x, 1 = y, 2 = z) of the task coordinates.
    #[getter]
    fn task_axes(&self) -> Vec<usize> {
        self.axes.clone()
    }

    /// Control period (s) the controller was trained at.
    #[getter]
    fn control_period(&self) -> f64 {
        self.info.control_period
    }

    /// The robot it was trained on: a built-in name or a URDF path.
    #[getter]
    fn robot(&self) -> String {
        self.info.robot.clone()
    }

    /// Home posture (rad): at rest on the start of the training path.
    #[getter]
    fn home<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        out1(py, &self.info.home)
    }

    /// Task gains `(kp, kd)` of the reference dynamics (eq. 2).
    #[getter]
    fn gains(&self) -> (f64, f64) {
        (self.info.gains.kp, self.info.gains.kd)
    }

    /// Simulated minutes of training.
    #[getter]
    fn sim_training_minutes(&self) -> f64 {
        self.info.sim_training_minutes
    }

    /// Number of local models (trained or not).
    #[getter]
    fn n_local_models(&self) -> usize {
        self.ctrl.learner().n_local_models()
    }

    /// Commands so far by source: `(learned, extrapolated, fallback)`.
    #[getter]
    fn counts(&self) -> (u64, u64, u64) {
        let c = self.ctrl.counts();
        (c.learned, c.extrapolated, c.fallback)
    }

    /// The learner's counters (a dict).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::learner::json_dict(py, &self.ctrl.learner().stats())
    }

    /// The training summary of `osrl.train` (a dict), or `None` for a loaded model.
    #[getter]
    fn training<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        match &self.summary {
            None => Ok(None),
            Some(s) => Ok(Some(py.import("json")?.call_method1("loads", (s,))?)),
        }
    }

    fn __repr__(&self) -> String {
        let (n, m) = self.ctrl.learner().dims();
        format!(
            "LearnedController(robot={:?}, dof={n}, task_dim={m}, n_local_models={}, sim_training_minutes={})",
            self.info.robot,
            self.ctrl.learner().n_local_models(),
            self.info.sim_training_minutes
        )
    }
}

/// The controller of `learner` trained in `setup` as `summary` says.
pub fn trained(
    setup: &osrl_experiments::Setup,
    learner: Learner,
    summary: &osrl_learn::train::TrainSummary,
) -> PyResult<PyLearnedController> {
    let saved = setup.saved(learner, summary).map_err(setup_err)?;
    let mut c = PyLearnedController::from_saved(saved)?;
    c.summary = serde_json::to_string(summary).ok();
    Ok(c)
}
