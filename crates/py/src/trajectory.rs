//! `osrl.Trajectory(robot, kind, config)`: the task-space path that `osrl.train` trains along
//! and evaluates on (the `Setup`'s trajectory of osrl's model of the robot), sampled from Python
//! so that a loop outside the trainer (a MuJoCo evaluation, a plot) follows the same targets.

use crate::arrays::out1;
use crate::config::from_dict;
use crate::errors::setup_err;
use numpy::PyArray1;
use osrl_control::{Trajectory, TrajectoryConfig};
use osrl_experiments::Setup;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A trajectory of osrl's model of a robot, on its task axes (see `_osrl.pyi`).
#[pyclass(name = "Trajectory", module = "osrl", frozen)]
pub struct PyTrajectory {
    traj: Trajectory,
    axes: Vec<usize>,
    home: Vec<f64>,
}

/// `kind` (`figure8`, `circle`, `min_jerk`) into `traj`, or `ValueError`.
pub fn set_kind(traj: &mut TrajectoryConfig, kind: &str) -> PyResult<()> {
    traj.kind = serde_json::from_value(serde_json::Value::String(kind.into())).map_err(|_| {
        PyValueError::new_err(format!(
            "trajectory '{kind}': expected figure8, circle or min_jerk"
        ))
    })?;
    Ok(())
}

/// `kind` (the keyword argument `kw`) into `traj`; when the config gave a kind too
/// (`in_config`, at `where_` + `['kind']`), the two must be the same.
pub fn merge_kind(
    traj: &mut TrajectoryConfig,
    kind: &str,
    in_config: bool,
    kw: &str,
    where_: &str,
) -> PyResult<()> {
    let given = traj.kind;
    set_kind(traj, kind)?;
    if in_config && traj.kind != given {
        let name = serde_json::to_value(given)
            .ok()
            .and_then(|v| v.as_str().map(String::from))
            .unwrap_or_else(|| format!("{given:?}"));
        return Err(PyValueError::new_err(format!(
            "{kw}={kind:?} and config{where_}['kind'] = {name:?} disagree: give it once (or the \
             same value in both)"
        )));
    }
    Ok(())
}

#[pymethods]
impl PyTrajectory {
    /// The trajectory `osrl.train(robot, kind, config={"trajectory": config})` uses for osrl's
    /// model `robot` (a built-in name or a URDF path). `kind` defaults to the config's `kind`
    /// (itself figure8 by default); given in both, they must agree.
    #[new]
    #[pyo3(signature = (robot, kind = None, config = None))]
    fn new(robot: &str, kind: Option<&str>, config: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let mut cfg: TrajectoryConfig = from_dict("trajectory config", config)?;
        if let Some(kind) = kind {
            let in_config = match config.and_then(|c| c.cast::<PyDict>().ok()) {
                Some(d) => d.contains("kind")?,
                None => false,
            };
            merge_kind(&mut cfg, kind, in_config, "kind", "")?;
        }
        let setup = Setup::along(robot, cfg).map_err(setup_err)?;
        Ok(Self {
            traj: setup.trajectory().clone(),
            axes: setup.model().task_axes().to_vec(),
            home: setup.home().to_vec(),
        })
    }

    /// `(x_d, ẋ_d, ẍ_d)` at time `t` (s) on the task axes (m, m/s, m/s²).
    #[allow(clippy::type_complexity)]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        t: f64,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        if !t.is_finite() {
            return Err(PyValueError::new_err(format!("t = {t}: must be finite")));
        }
        let s = self.traj.sample(t);
        let pick =
            |v: &nalgebra::Vector3<f64>| -> Vec<f64> { self.axes.iter().map(|&a| v[a]).collect() };
        Ok((
            out1(py, &pick(&s.x)),
            out1(py, &pick(&s.xd)),
            out1(py, &pick(&s.xdd)),
        ))
    }

    /// Seconds of one cycle of the path.
    #[getter]
    fn period(&self) -> f64 {
        self.traj.period()
    }
    /// Seconds of the smooth start (0 for minimum-jerk moves).
    #[getter]
    fn ramp(&self) -> f64 {
        self.traj.ramp()
    }
    /// The home posture (rad): at rest on the start of the path.
    #[getter]
    fn home<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        out1(py, &self.home)
    }
    /// The world axes of the task space.
    #[getter]
    fn task_axes(&self) -> Vec<usize> {
        self.axes.clone()
    }
}
