//! `osrl.Learner`: the learner of the learned operational space controller
//! (`osrl_learn::Learner`) stepped from Python — commands for a reference acceleration, and
//! learning from each transition between two measurements.

use crate::args::{self, count, short};
use crate::arrays::out1;
use crate::config::from_dict;
use crate::errors::learn_err;
use crate::meas::{read_all, read_checked, zeros};
use numpy::PyArray1;
use osrl_dynamics::Measurement;
use osrl_learn::{load_robot, Learner, LearnerConfig, CONTROL_PERIOD_RANGE, PERIOD_TOLERANCE};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A learner, its exploration noise generator and scratch buffers (see `_osrl.pyi`).
#[pyclass(name = "Learner", module = "osrl")]
pub struct PyLearner {
    learner: Learner,
    rng: ChaCha8Rng,
    prev: Measurement,
    cur: Measurement,
    q: Vec<f64>,
    qd: Vec<f64>,
    xdd: Vec<f64>,
    u: Vec<f64>,
}

/// A serde value as a Python dict (through JSON).
pub fn json_dict<'py, T: serde::Serialize>(py: Python<'py>, v: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(v).expect("serialises");
    py.import("json")?.call_method1("loads", (text,))
}

/// `config` (a dict of `[learner]` keys, or `None`) with the data-sheet fields of `robot`
/// (a built-in name or a URDF path; none: as given) filled in.
pub fn learner_config(
    config: Option<&Bound<'_, PyAny>>,
    robot: Option<&str>,
) -> PyResult<LearnerConfig> {
    let mut cfg: LearnerConfig = from_dict("learner config", config)?;
    if let Some(name) = robot {
        let model = load_robot(name).map_err(learn_err)?;
        let spec = model.spec();
        let tau: Vec<f64> = model.tau_max().collect();
        cfg.fill_data_sheet(&spec.kp, &spec.kd, &spec.q_rest, &tau);
    }
    Ok(cfg)
}

/// `Ok` if `dt` (named `what`) is a control period a saved model accepts
/// (`osrl_learn::CONTROL_PERIOD_RANGE`, 0.1 ms to 100 ms): a learner outside it could neither be
/// saved nor learn sensibly (its rates and time constants are per control period).
pub fn check_control_period(what: &str, dt: f64) -> PyResult<()> {
    let r = &CONTROL_PERIOD_RANGE;
    if r.contains(&dt) {
        return Ok(());
    }
    Err(PyValueError::new_err(format!(
        "{what} = {} s: must be within [{}, {}] s, the range a saved model accepts",
        short(dt),
        short(*r.start()),
        short(*r.end())
    )))
}

#[pymethods]
impl PyLearner {
    #[new]
    #[pyo3(signature = (dof, task_dim, control_period, robot = None, config = None, seed = None))]
    fn new(
        dof: &Bound<'_, PyAny>,
        task_dim: &Bound<'_, PyAny>,
        control_period: f64,
        robot: Option<&str>,
        config: Option<&Bound<'_, PyAny>>,
        seed: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let (dof, task_dim) = (count("dof", dof)?, count("task_dim", task_dim)?);
        // `None`: the default seed, 0.
        let seed = seed.map_or(Ok(0), |s| args::seed("seed", s))?;
        check_control_period("control_period", control_period)?;
        let cfg = learner_config(config, robot)?;
        let learner = Learner::new(dof, task_dim, control_period, cfg).map_err(learn_err)?;
        Ok(Self {
            learner,
            rng: ChaCha8Rng::seed_from_u64(seed),
            prev: zeros(dof, task_dim),
            cur: zeros(dof, task_dim),
            q: Vec::with_capacity(dof),
            qd: Vec::with_capacity(dof),
            xdd: Vec::with_capacity(task_dim),
            u: vec![0.0; dof],
        })
    }

    /// The command for the reference acceleration `xdd_ref` at `(q, qd)`.
    #[pyo3(signature = (q, qd, xdd_ref, explore = false, seed = None))]
    fn command<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        qd: &Bound<'py, PyAny>,
        xdd_ref: &Bound<'py, PyAny>,
        explore: bool,
        seed: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let seed = seed
            .filter(|s| !s.is_none())
            .map(|s| args::seed("seed", s))
            .transpose()?;
        let (n, m) = self.learner.dims();
        read_checked("q", q, n, &mut self.q)?;
        read_checked("qd", qd, n, &mut self.qd)?;
        read_checked("xdd_ref", xdd_ref, m, &mut self.xdd)?;
        if let Some(s) = seed {
            self.rng = ChaCha8Rng::seed_from_u64(s);
        }
        let rng = if explore { Some(&mut self.rng) } else { None };
        self.learner
            .command(&self.q, &self.qd, &self.xdd, rng, &mut self.u)
            .map_err(learn_err)?;
        Ok(out1(py, &self.u))
    }

    /// Learns from the transition `prev → cur` (two `osrl.Measurement`s; `cur.u` was held);
    /// `cur` must be one control period after `prev` (within [`PERIOD_TOLERANCE`]).
    fn learn(&mut self, prev: &Bound<'_, PyAny>, cur: &Bound<'_, PyAny>) -> PyResult<()> {
        read_all(prev, "prev", &mut self.prev, &mut self.q)?;
        read_all(cur, "cur", &mut self.cur, &mut self.q)?;
        let dt = self.learner.control_period();
        let (t0, t1) = (self.prev.t, self.cur.t);
        let gap = t1 - t0;
        let within = (gap - dt).abs() <= PERIOD_TOLERANCE * dt;
        if !within {
            let why = if gap <= 0.0 {
                "time does not advance (is prev the measurement before cur?)".to_string()
            } else {
                format!(
                    "{:.3} control periods apart: learn takes consecutive measurements (the \
                     previous cur as prev; after a reset, the reset's measurement)",
                    gap / dt
                )
            };
            return Err(PyValueError::new_err(format!(
                "learn(prev, cur): cur.t − prev.t = {} − {} = {} s, but the control period is \
                 {} s (±{:.0} %): {why}; nothing was learned",
                short(t1),
                short(t0),
                short(gap),
                short(dt),
                PERIOD_TOLERANCE * 100.0
            )));
        }
        self.learner.learn(&self.prev, &self.cur).map_err(learn_err)
    }

    /// Starts a new sequence of commands (`last_sent`: the command the robot holds, if known).
    #[pyo3(signature = (last_sent = None))]
    fn start_episode(&mut self, last_sent: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        match last_sent {
            None => self.learner.start_episode(None).map_err(learn_err),
            Some(u) => {
                read_checked("last_sent", u, self.learner.dims().0, &mut self.q)?;
                self.learner.start_episode(Some(&self.q)).map_err(learn_err)
            }
        }
    }

    /// Whether the warm-up is over and the local models exist.
    #[getter]
    fn ready(&self) -> bool {
        self.learner.ready()
    }

    #[getter]
    fn n_local_models(&self) -> usize {
        self.learner.n_local_models()
    }

    #[getter]
    fn n_trained(&self) -> usize {
        self.learner.n_trained()
    }

    #[getter]
    fn dof(&self) -> usize {
        self.learner.dims().0
    }

    #[getter]
    fn task_dim(&self) -> usize {
        self.learner.dims().1
    }

    #[getter]
    fn control_period(&self) -> f64 {
        self.learner.control_period()
    }

    /// The learner's counters (a dict).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_dict(py, &self.learner.stats())
    }

    /// The config in use (a dict of `[learner]` keys).
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_dict(py, self.learner.config())
    }

    fn __repr__(&self) -> String {
        let (n, m) = self.learner.dims();
        format!(
            "Learner(dof={n}, task_dim={m}, ready={}, n_local_models={})",
            self.learner.ready(),
            self.learner.n_local_models()
        )
    }
}
