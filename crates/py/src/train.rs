//! `osrl.train(robot, ...)`: the Rust trainer of `osrl train` (`osrl_learn::train::train`)
//! driving a robot written in Python (`ROBOT_PROTOCOL.md`) through [`PyBot`] (an
//! `osrl_dynamics::Robot` that calls the object's `step` with the GIL held); the training
//! itself runs with the GIL released.

use crate::config::from_dict;
use crate::controller::{trained, PyLearnedController};
use crate::errors::{learn_err, setup_err};
use crate::pybot::{header, PyBot};
use osrl_control::TrajectoryConfig;
use osrl_dynamics::SimConfig;
use osrl_experiments::Setup;
use osrl_learn::train::TrainConfig;
use osrl_learn::{Learner, LearnerConfig};
use pyo3::exceptions::{PyTypeError, PyUserWarning, PyValueError};
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

/// Whether `section` of the `config` dict of `osrl.train` (already checked by [`sections`])
/// gives `key`.
fn gives(config: Option<&Bound<'_, PyAny>>, section: &str, key: &str) -> PyResult<bool> {
    let Some(d) = config.and_then(|c| c.cast::<PyDict>().ok()) else {
        return Ok(false);
    };
    match d.get_item(section)? {
        Some(sec) => match sec.cast::<PyDict>() {
            Ok(sec) => sec.contains(key),
            Err(_) => Ok(false),
        },
        None => Ok(false),
    }
}

/// `ValueError` unless a keyword argument and the same setting in the config agree.
fn agree<T: PartialEq + std::fmt::Debug>(
    kw: &str,
    kw_value: &T,
    key: &str,
    config_value: &T,
) -> PyResult<()> {
    if kw_value == config_value {
        return Ok(());
    }
    Err(PyValueError::new_err(format!(
        "{kw}={kw_value:?} and config{key} = {config_value:?} disagree: give it once (or the \
         same value in both)"
    )))
}

/// `Ok`, or a warning or an error when the training learned nothing (the learner never finished
/// its warm-up, so the controller has no local models): an error when the robot gave enough
/// measurements for the warm-up but the learner's guards rejected them (the counts say how
/// many), a warning when the training was too short for the warm-up.
fn check_learned(py: Python<'_>, learner: &Learner, minutes: f64) -> PyResult<()> {
    if learner.n_local_models() > 0 {
        return Ok(());
    }
    let st = learner.stats();
    let g = &learner.config().guards;
    let warmup = g.warmup_samples as u64;
    let seen = st.samples + st.rejected;
    if st.rejected > 0 && seen >= warmup {
        return Err(PyValueError::new_err(format!(
            "osrl.train learned nothing: the learner rejected {} of the robot's {seen} \
             measurements as non-finite or absurd (|q̇| above learner.guards.max_abs_velocity = \
             {} rad/s, |ẍ| above max_abs_acceleration = {} m/s², ...) and accepted {}, fewer \
             than its warm-up needs (learner.guards.warmup_samples = {warmup}), so the controller \
             has no local models; check what robot.step() returns",
            st.rejected, g.max_abs_velocity, g.max_abs_acceleration, st.samples
        )));
    }
    let msg = format!(
        "osrl.train: {minutes} simulated minutes gave the learner {} samples ({} rejected), \
         fewer than its warm-up needs (learner.guards.warmup_samples = {warmup}): the controller \
         has no local models; train longer (minutes) or lower the warm-up",
        st.samples, st.rejected
    );
    PyErr::warn(
        py,
        &py.get_type::<PyUserWarning>(),
        &std::ffi::CString::new(msg).expect("no NUL"),
        1,
    )
}

/// Trains a learned controller on `robot` (see `_osrl.pyi`). `trajectory`, `minutes` and `seed`
/// default to the config's `trajectory.kind`, `train.minutes` and `train.seed` (themselves
/// figure8, 30 and 0 when not given); given in both places, they must agree.
#[pyfunction]
#[pyo3(signature = (robot, trajectory = None, minutes = None, seed = None, config = None, model = None))]
pub fn train(
    py: Python<'_>,
    robot: &Bound<'_, PyAny>,
    trajectory: Option<&str>,
    minutes: Option<f64>,
    seed: Option<&Bound<'_, PyAny>>,
    config: Option<&Bound<'_, PyAny>>,
    model: Option<String>,
) -> PyResult<PyLearnedController> {
    if robot.is_none() {
        // Before the model's name, which would blame the missing `osrl_name`.
        header(robot)?;
    }
    let name = match model {
        Some(m) => m,
        None => match robot.getattr("osrl_name") {
            Ok(n) if !n.is_none() => n.extract().map_err(|_| {
                PyValueError::new_err(format!(
                    "robot.osrl_name: expected a str (a built-in robot or a URDF path), got {}",
                    n.get_type()
                        .name()
                        .map_or_else(|_| "?".into(), |t| t.to_string())
                ))
            })?,
            // A property that fails is the robot's own error.
            Err(e) if !e.is_instance_of::<pyo3::exceptions::PyAttributeError>(py) => return Err(e),
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
    if let Some(kind) = trajectory {
        let in_config = gives(config, "trajectory", "kind")?;
        crate::trajectory::merge_kind(&mut traj, kind, in_config, "trajectory", "['trajectory']")?;
    }
    if let Some(minutes) = minutes {
        if !(minutes >= 0.0 && minutes.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "minutes = {minutes}: need a finite number ≥ 0"
            )));
        }
        if gives(config, "train", "minutes")? {
            agree("minutes", &minutes, "['train']['minutes']", &tcfg.minutes)?;
        }
        tcfg.minutes = minutes;
    }
    if let Some(seed) = seed.filter(|s| !s.is_none()) {
        let seed = crate::args::seed("seed", seed)?;
        if gives(config, "train", "seed")? {
            agree("seed", &seed, "['train']['seed']", &tcfg.seed)?;
        }
        tcfg.seed = seed;
    }
    let head = header(robot)?;
    let (n, m, dt) = head;
    let sim = SimConfig {
        control_period: dt,
        ..SimConfig::default()
    };
    let setup = Setup::along(&name, traj).map_err(setup_err)?;
    let truth = setup.model();
    if (n, m) != (truth.nq(), truth.task_dim()) {
        return Err(PyValueError::new_err(format!(
            "robot.dof = {n} and robot.task_dim = {m}, but osrl's model {name} (model=, or \
             robot.osrl_name) has {} joints and a {}-D task",
            truth.nq(),
            truth.task_dim()
        )));
    }
    let setup = setup
        .with_sim(sim)
        .map_err(|e| PyValueError::new_err(format!("robot.control_period = {dt} s: {e}")))?
        .with_learner(lcfg)
        .and_then(|s| s.with_train(tcfg))
        .map_err(setup_err)?;
    let truth = setup.model();
    let mut bot = PyBot::new(robot, head, &setup.learner_config().guards.torque_limits)?;
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
    check_learned(py, &learner, setup.train_config().minutes)?;
    trained(&setup, learner, &summary)
}
