//! `osrl.Robot`: an `osrl-dynamics` model (a built-in robot or a URDF) and its workspace, with
//! the algorithms on numpy arrays. Conventions are the crate's: world frame z up, gravity
//! 9.81 m/s² along −z, `M(q) q̈ + h(q, q̇) = u` with `h = C q̇ + g + τ_f`; `rnea` and `aba` are
//! rigid-body (no friction), `forward_dynamics` and `nonlinear_effects` include the friction.

use crate::args::short;
use crate::arrays::{out1, out2, vector};
use crate::arrays::{Arr1, Arr2};
use crate::errors::{dyn_err, file_err};
use osrl_dynamics::{self as dynamics, robots, urdf, Data, Model};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;

/// A robot model and its preallocated workspace (see `python/osrl/_osrl.pyi`).
#[pyclass(name = "Robot", module = "osrl")]
pub struct PyRobot {
    model: Model,
    data: Data,
}

impl PyRobot {
    fn wrap(model: Model) -> Self {
        let data = model.data();
        PyRobot { model, data }
    }

    fn n(&self) -> usize {
        self.model.nq()
    }

    /// `f(model, data, q, qd, x)` on Python values: the third vector named `third`, the result
    /// named `out` checked finite ([`finite_result`]) and returned as a numpy array.
    fn dynamics3<'py>(
        &mut self,
        py: Python<'py>,
        (func, f): (&str, Dynamics3),
        out: &str,
        [q, qd, x]: [&Bound<'py, PyAny>; 3],
        third: &str,
    ) -> PyResult<Arr1<'py>> {
        let (q, qd, x) = (vector("q", q)?, vector("qd", qd)?, vector(third, x)?);
        let (q, qd, x) = (q.as_slice(), qd.as_slice(), x.as_slice());
        let r = f(&self.model, &mut self.data, q, qd, x).map_err(dyn_err)?;
        finite_result(
            func,
            &[(out, r.as_slice())],
            &[("q", q), ("qd", qd), (third, x)],
        )?;
        Ok(out1(py, r.as_slice()))
    }
}

/// A dynamics function of the crate on three joint vectors (`rnea`, `aba`, `forward_dynamics`).
type Dynamics3 = for<'a> fn(
    &Model,
    &'a mut Data,
    &[f64],
    &[f64],
    &[f64],
) -> dynamics::Result<&'a nalgebra::DVector<f64>>;

/// The loader's options for `tip` (`None`: the loader's naming rule chooses the end effector).
fn urdf_options(tip: Option<String>) -> urdf::UrdfOptions {
    urdf::UrdfOptions {
        tip,
        ..urdf::UrdfOptions::default()
    }
}

/// `Ok` if every value of the results `outs` (name, values) of `func` is finite; otherwise a
/// `ValueError` naming `func`, the first value that is not, and the input most likely to have
/// overflowed the computation. The inputs are finite (checked by the crate), so a result that
/// is not comes from an overflow: velocities enter squared (Coriolis and centrifugal terms,
/// `J̇ q̇`), positions through sines and cosines (revolute) or linearly and squared
/// (prismatic), accelerations and torques linearly; the likely culprit is the input with the
/// largest magnitude on that scale.
fn finite_result(func: &str, outs: &[(&str, &[f64])], inputs: &[(&str, &[f64])]) -> PyResult<()> {
    let Some((name, i, v)) = outs.iter().find_map(|(name, vals)| {
        vals.iter()
            .position(|v| !v.is_finite())
            .map(|i| (name, i, vals[i]))
    }) else {
        return Ok(());
    };
    let amax = |x: &[f64]| x.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let squared = |input: &str| matches!(input, "q" | "qd");
    let scale = |(input, x): &(&str, &[f64])| {
        let a = amax(x);
        if squared(input) {
            a * a
        } else {
            a
        }
    };
    let sizes: Vec<String> = inputs
        .iter()
        .map(|(input, x)| format!("max |{input}| = {}", short(amax(x))))
        .collect();
    let culprit = inputs
        .iter()
        .max_by(|a, b| scale(a).total_cmp(&scale(b)))
        .map(|(input, _)| *input)
        .unwrap_or("?");
    Err(PyValueError::new_err(format!(
        "{func}: the result is not finite ({name}[{i}] = {v}): the computation overflowed float64 \
         with these inputs ({}), most likely through {culprit}; the inputs must be physically \
         plausible",
        sizes.join(", ")
    )))
}

/// The columns of a column-major 3×n or n×n matrix as a row-major copy.
fn rows_of<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Vec<f64> {
    let (r, c) = m.shape();
    (0..r * c).map(|k| m[(k / c, k % c)]).collect()
}

#[pymethods]
impl PyRobot {
    /// A built-in robot by name (`Robot.builtins()` lists them).
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        Ok(Self::wrap(robots::by_name(name).map_err(dyn_err)?))
    }

    /// The names of the built-in robots.
    #[staticmethod]
    fn builtins() -> Vec<&'static str> {
        robots::BUILTIN.to_vec()
    }

    /// A robot from a URDF file (the chain from the root to the end-effector link `tip`; `None`:
    /// the loader's naming rule chooses it).
    #[staticmethod]
    #[pyo3(signature = (path, tip = None))]
    fn from_urdf(path: PathBuf, tip: Option<String>) -> PyResult<Self> {
        // A regular file within the URDF size limit (a FIFO would block).
        let text =
            osrl_files::read_text_limited(&path, urdf::MAX_URDF_BYTES as u64).map_err(file_err)?;
        let model = urdf::parse_urdf_with(&text, &urdf_options(tip))
            .map_err(|e| PyValueError::new_err(format!("{}: {e}", path.display())))?;
        Ok(Self::wrap(model))
    }

    /// A robot from URDF text (`tip` as for `from_urdf`).
    #[staticmethod]
    #[pyo3(signature = (text, tip = None))]
    fn from_urdf_string(text: &str, tip: Option<String>) -> PyResult<Self> {
        Ok(Self::wrap(
            urdf::parse_urdf_with(text, &urdf_options(tip)).map_err(dyn_err)?,
        ))
    }

    /// The model as URDF text (what `osrl robot --robot NAME --urdf` prints).
    fn to_urdf(&self) -> String {
        urdf::to_urdf(&self.model)
    }

    #[getter]
    fn name(&self) -> &str {
        self.model.name()
    }

    /// Number of joints `n`.
    #[getter]
    fn dof(&self) -> usize {
        self.n()
    }

    /// Task-space dimension `m` (the world axes in `task_axes`).
    #[getter]
    fn task_dim(&self) -> usize {
        self.model.task_dim()
    }

    /// World axes (0 = x, 1 = y, 2 = z) of the end-effector position that form the task space.
    #[getter]
    fn task_axes(&self) -> Vec<usize> {
        self.model.task_axes().to_vec()
    }

    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.model
            .links()
            .iter()
            .map(|l| l.joint_name.clone())
            .collect()
    }

    /// Lower joint limits (rad; −inf: none).
    #[getter]
    fn q_min<'py>(&self, py: Python<'py>) -> Arr1<'py> {
        out1(py, &self.model.q_min().collect::<Vec<_>>())
    }

    /// Upper joint limits (rad; inf: none).
    #[getter]
    fn q_max<'py>(&self, py: Python<'py>) -> Arr1<'py> {
        out1(py, &self.model.q_max().collect::<Vec<_>>())
    }

    /// Torque limits (N·m; inf: none).
    #[getter]
    fn tau_max<'py>(&self, py: Python<'py>) -> Arr1<'py> {
        out1(py, &self.model.tau_max().collect::<Vec<_>>())
    }

    /// Default start posture (rad).
    #[getter]
    fn q_start<'py>(&self, py: Python<'py>) -> Arr1<'py> {
        out1(py, &self.model.spec().q_start)
    }

    /// Rest posture of the nominal null-space behaviour (rad).
    #[getter]
    fn q_rest<'py>(&self, py: Python<'py>) -> Arr1<'py> {
        out1(py, &self.model.spec().q_rest)
    }

    /// Total mass (kg).
    #[getter]
    fn total_mass(&self) -> f64 {
        self.model.total_mass()
    }

    /// End-effector position in the world (m), shape `(3,)`.
    fn fk<'py>(&mut self, py: Python<'py>, q: &Bound<'py, PyAny>) -> PyResult<Arr1<'py>> {
        let q = vector("q", q)?;
        dynamics::forward_kinematics(&self.model, &mut self.data, q.as_slice()).map_err(dyn_err)?;
        finite_result(
            "fk",
            &[("x", self.data.ee_pos.as_slice())],
            &[("q", q.as_slice())],
        )?;
        Ok(out1(py, self.data.ee_pos.as_slice()))
    }

    /// `(x, xd, jdot_qd)`: end-effector position (m), velocity `J q̇` (m/s) and bias
    /// acceleration `J̇ q̇` (m/s²) in the world, each of shape `(3,)`.
    fn kinematics<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
    ) -> PyResult<(Arr1<'py>, Arr1<'py>, Arr1<'py>)> {
        let (q, qd) = (vector("q", q)?, vector("qd", qd)?);
        dynamics::kinematics(&self.model, &mut self.data, q.as_slice(), qd.as_slice())
            .map_err(dyn_err)?;
        let d = &self.data;
        finite_result(
            "kinematics",
            &[
                ("x", d.ee_pos.as_slice()),
                ("xd", d.ee_vel.as_slice()),
                ("jdot_qd", d.jdot_qd.as_slice()),
            ],
            &[("q", q.as_slice()), ("qd", qd.as_slice())],
        )?;
        Ok((
            out1(py, d.ee_pos.as_slice()),
            out1(py, d.ee_vel.as_slice()),
            out1(py, d.jdot_qd.as_slice()),
        ))
    }

    /// End-effector point Jacobian `∂x/∂q` in the world, shape `(3, n)`.
    fn jacobian<'py>(&mut self, py: Python<'py>, q: &Bound<'py, PyAny>) -> PyResult<Arr2<'py>> {
        let q = vector("q", q)?;
        dynamics::jacobian(&self.model, &mut self.data, q.as_slice()).map_err(dyn_err)?;
        let jac = rows_of(&self.data.jac);
        finite_result("jacobian", &[("J", &jac)], &[("q", q.as_slice())])?;
        Ok(out2(py, 3, self.n(), jac))
    }

    /// Joint-space mass matrix `M(q)` (kg·m²), shape `(n, n)` (CRBA).
    fn mass_matrix<'py>(&mut self, py: Python<'py>, q: &Bound<'py, PyAny>) -> PyResult<Arr2<'py>> {
        let q = vector("q", q)?;
        let n = self.n();
        let m = dynamics::crba(&self.model, &mut self.data, q.as_slice()).map_err(dyn_err)?;
        let m = rows_of(m);
        finite_result("mass_matrix", &[("M", &m)], &[("q", q.as_slice())])?;
        Ok(out2(py, n, n, m))
    }

    /// Gravity torques `g(q)` (N·m).
    fn gravity<'py>(&mut self, py: Python<'py>, q: &Bound<'py, PyAny>) -> PyResult<Arr1<'py>> {
        let q = vector("q", q)?;
        let g = dynamics::gravity(&self.model, &mut self.data, q.as_slice()).map_err(dyn_err)?;
        finite_result("gravity", &[("g", g.as_slice())], &[("q", q.as_slice())])?;
        Ok(out1(py, g.as_slice()))
    }

    /// Non-inertial torques `h(q, q̇) = C q̇ + g + τ_f` (N·m), friction included.
    fn nonlinear_effects<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
    ) -> PyResult<Arr1<'py>> {
        let (q, qd) = (vector("q", q)?, vector("qd", qd)?);
        let h =
            dynamics::nonlinear_effects(&self.model, &mut self.data, q.as_slice(), qd.as_slice())
                .map_err(dyn_err)?;
        finite_result(
            "nonlinear_effects",
            &[("h", h.as_slice())],
            &[("q", q.as_slice()), ("qd", qd.as_slice())],
        )?;
        Ok(out1(py, h.as_slice()))
    }

    /// Joint friction torques `τ_f(q̇)` (N·m).
    fn friction<'py>(&self, py: Python<'py>, qd: &Bound<'py, PyAny>) -> PyResult<Arr1<'py>> {
        let qd = vector("qd", qd)?;
        dynamics::check_vec("qd", qd.as_slice(), self.n()).map_err(dyn_err)?;
        let mut f = vec![0.0; self.n()];
        self.model.friction(qd.as_slice(), &mut f);
        finite_result("friction", &[("tau_f", &f)], &[("qd", qd.as_slice())])?;
        Ok(out1(py, &f))
    }

    /// Inverse dynamics `τ = M q̈ + C q̇ + g` (N·m; rigid body, no friction).
    fn rnea<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        qdd: &Bound<'py, PyAny>,
    ) -> PyResult<Arr1<'py>> {
        let f = ("rnea", dynamics::rnea as Dynamics3);
        self.dynamics3(py, f, "tau", [q, qd, qdd], "qdd")
    }

    /// Forward dynamics `q̈ = M⁻¹(τ − C q̇ − g)` (rad/s²; rigid body, no friction), by ABA.
    fn aba<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
    ) -> PyResult<Arr1<'py>> {
        let f = ("aba", dynamics::aba as Dynamics3);
        self.dynamics3(py, f, "qdd", [q, qd, tau], "tau")
    }

    /// Forward dynamics of the robot with friction, `q̈ = M⁻¹(u − h(q, q̇))` (rad/s²).
    fn forward_dynamics<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        u: &Bound<'py, PyAny>,
    ) -> PyResult<Arr1<'py>> {
        let f = ("forward_dynamics", dynamics::forward_dynamics as Dynamics3);
        self.dynamics3(py, f, "qdd", [q, qd, u], "u")
    }

    fn __repr__(&self) -> String {
        format!(
            "osrl.Robot({:?}, dof={}, task_axes={:?})",
            self.model.name(),
            self.n(),
            self.model.task_axes()
        )
    }
}
