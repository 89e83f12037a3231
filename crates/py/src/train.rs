//! `osrl.train(robot, ...)`: the Rust trainer of `osrl train` (`osrl_learn::train::train`)
//! driving a robot written in Python (`ROBOT_PROTOCOL.md`) through [`PyBot`] (an
//! `osrl_dynamics::Robot` that calls the object's `step` with the GIL held); the training
//! itself runs with the GIL released.

use crate::config::from_dict;
use crate::controller::{trained, PyLearnedController};
use crate::errors::{learn_err, setup_err};
use crate::pybot::PyBot;
use osrl_control::TrajectoryConfig;
use osrl_dynamics::SimConfig;
use osrl_experiments::Setup;
use osrl_learn::train::TrainConfig;
use osrl_learn::{Learner, LearnerConfig};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The `config` dict of `osrl.train`: `{"learner": {...}, "train": {...}, "trajectory": {...}}`.
fn sections(
    config: Option<&Bound<'_, PyAny>>,
) -> PyResult<(LearnerConfig, TrainConfig, TrajectoryConfig)> {
    let empty = |py| PyDict::new(py).into_any();
    let Some(cfg) = config.filter(|c| !c.is_none()) else {
        return Ok(Default::default());
    };
    let d = cfg.cast::<PyDict>().map_err(|_| {
        PyTypeError::new_err("config: expected a dict with keys learner, train, trajectory")
    })?;
    for k in d.keys() {
        let k: String = k.extract()?;
        if !["learner", "train", "trajectory"].contains(&k.as_str()) {
            return Err(PyValueError::new_err(format!(
                "config: unknown section '{k}' (expected learner, train, trajectory)"
            )));
        }
    }
    let get = |k: &str| -> PyResult<Bound<'_, PyAny>> {
        Ok(d.get_item(k)?.unwrap_or_else(|| empty(cfg.py())))
    };
    Ok((
        from_dict("learner config", Some(&get("learner")?))?,
        from_dict("train config", Some(&get("train")?))?,
        from_dict("trajectory config", Some(&get("trajectory")?))?,
    ))
}

/// Trains a learned controller on `robot` (see `_osrl.pyi`).
#[pyfunction]
#[pyo3(signature = (robot, trajectory = "figure8", minutes = 30.0, seed = 0, config = None, model = None))]
pub fn train(
    py: Python<'_>,
    robot: &Bound<'_, PyAny>,
    trajectory: &str,
    minutes: f64,
    seed: u64,
    config: Option<&Bound<'_, PyAny>>,
    model: Option<String>,
) -> PyResult<PyLearnedController> {
    let name = match model {
        Some(m) => m,
        None => match robot.getattr("osrl_name") {
            Ok(n) if !n.is_none() => n.extract()?,
            _ => {
                return Err(PyValueError::new_err(
                    "model: osrl's model of the robot (a built-in name or a URDF path) is \
                     needed for the evaluations and the saved model; this robot has no \
                     `osrl_name`: pass model=",
                ))
            }
        },
    };
    let (lcfg, mut tcfg, mut traj) = sections(config)?;
    crate::trajectory::set_kind(&mut traj, trajectory)?;
    if !(minutes >= 0.0 && minutes.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "minutes = {minutes}: need a finite number ≥ 0"
        )));
    }
    tcfg.minutes = minutes;
    tcfg.seed = seed;
    let mut bot = PyBot::new(robot)?;
    let sim = SimConfig {
        control_period: bot.dt,
        ..SimConfig::default()
    };
    let setup = Setup::along(&name, traj)
        .and_then(|s| s.with_sim(sim))
        .and_then(|s| s.with_learner(lcfg))
        .and_then(|s| s.with_train(tcfg))
        .map_err(setup_err)?;
    let truth = setup.model();
    if (bot.n, bot.m) != (truth.nq(), truth.task_dim()) {
        return Err(PyValueError::new_err(format!(
            "robot: {} joints and a {}-D task, but osrl's model {name} has {} and {}",
            bot.n,
            bot.m,
            truth.nq(),
            truth.task_dim()
        )));
    }
    bot.reset(py, setup.home())?;
    let run = py.detach(|| -> osrl_learn::Result<_> {
        let (n, m, dt) = (truth.nq(), truth.task_dim(), bot.dt);
        let mut learner = Learner::new(n, m, dt, setup.learner_config().clone())?;
        let mut ev = setup
            .evaluator(truth)
            .map_err(|e| osrl_learn::LearnError::InvalidConfig(e.to_string()))?;
        let mut evaluate = |l: &mut Learner| ev.evaluate(l);
        let summary = osrl_learn::train::train(
            &mut bot,
            &mut learner,
            setup.trajectory(),
            truth.task_axes(),
            setup.train_config(),
            &mut evaluate,
            &mut |_| {},
        )?;
        Ok((learner, summary))
    });
    let (learner, summary) = match (run, bot.err.take()) {
        (Ok(r), _) => r,
        (Err(_), Some(e)) => return Err(e),
        (Err(e), None) => return Err(learn_err(e)),
    };
    trained(&setup, learner, &summary)
}
