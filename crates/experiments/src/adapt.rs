//! Continual learning on a changed robot (issue 26): a trained learner keeps learning on-policy
//! while the simulated robot carries a payload, heavier links or more friction
//! ([`osrl_control::RobotChange`]), with its re-adaptation switched on; and the robot that
//! changes (and changes back) in the middle of a run. The learner sees only measurements; the
//! change is made to the simulator, and the evaluators score it on the changed true model.

use crate::error::{ExperimentError, Result};
use crate::Setup;
use osrl_control::RobotChange;
use osrl_dynamics::{Measurement, Model, Robot, SimConfig, SimRobot};
use osrl_learn::eval::EvalResult;
use osrl_learn::train::{Progress, TrainConfig, TrainSummary};
use osrl_learn::{AdaptationConfig, AdaptationSignal, Learner};
use std::cell::Cell;
use std::rc::Rc;

/// Path points at which [`RobotChange::check_holdable`] checks the gravity torques.
pub const HOLD_SAMPLES: usize = 64;

/// The outcome of [`adapt`].
#[derive(Clone, Debug)]
pub struct Adapted {
    /// The learner before any learning, on the unchanged robot (its nominal tracking).
    pub nominal: EvalResult,
    /// The same learner on the changed robot, before any learning.
    pub before: EvalResult,
    /// The same again with the re-adaptation's settings, before any learning: what the
    /// task-space disturbance observer does alone (`None` when it is off).
    pub before_observer: Option<EvalResult>,
    /// The learner with the re-adaptation's settings (the observer) on the unchanged robot,
    /// before any learning (`None` with the observer off).
    pub nominal_observer: Option<EvalResult>,
    /// The run on the changed robot (its curve from the first evaluation after minute 0).
    pub summary: TrainSummary,
    /// The re-adaptation's largest level during the run.
    pub peak_level: f64,
    /// Learning steps taken while re-adapting.
    pub adapting_steps: u64,
    /// The re-adaptation's state at each evaluation: `(simulated minutes, signal)`.
    pub signal: Vec<(f64, AdaptationSignal)>,
}

impl Adapted {
    /// The first simulated minute at which the learning curve meets `pred` (0 if the learner
    /// met it before any learning; `None` if never).
    pub fn minutes_to(&self, pred: impl Fn(&EvalResult) -> bool) -> Option<f64> {
        if !self.before.diverged && pred(&self.before) {
            return Some(0.0);
        }
        self.summary.minutes_to(pred)
    }

    /// The first simulated minute from which the learning curve meets `pred` at every later
    /// evaluation (0 if the learner met it before any learning and never failed it; `None` if
    /// the last evaluation does not).
    pub fn minutes_to_stay(&self, pred: impl Fn(&EvalResult) -> bool) -> Option<f64> {
        let all = self
            .summary
            .learning_curve
            .iter()
            .all(|(_, e)| !e.diverged && pred(e));
        if all && !self.before.diverged && pred(&self.before) {
            return Some(0.0);
        }
        self.summary.minutes_to_stay(pred)
    }
}

/// The checked change for `setup`'s robot: in range, and an arm that can still hold itself
/// within its torque limits along the path.
///
/// # Errors
/// [`osrl_control::ControlError::ChangeSpec`] saying what is wrong.
pub fn checked_change(setup: &Setup, change: &RobotChange) -> Result<Model> {
    change.check_holdable(
        setup.model(),
        setup.trajectory(),
        setup.home(),
        HOLD_SAMPLES,
    )?;
    Ok(change.apply(setup.model())?)
}

/// The training settings of a continuation: `base` with no babbling, `minutes` long.
pub fn continuation(base: &TrainConfig, minutes: f64) -> TrainConfig {
    let mut cfg = base.clone();
    cfg.minutes = minutes;
    cfg.babble.minutes = 0.0;
    cfg
}

/// `learner` keeps learning for `cfg.minutes` on the robot of `setup` changed by `change` (no
/// babbling; `cfg` as given, e.g. [`continuation`]), re-adapting with `adaptation` (its
/// `enabled` is set). The re-adaptation's level starts afresh, so an in-memory and a saved and
/// reloaded learner give the same numbers.
///
/// # Errors
/// The change's check ([`checked_change`]), or a simulation, learning or evaluation error.
pub fn adapt(
    setup: &Setup,
    learner: &mut Learner,
    change: &RobotChange,
    adaptation: AdaptationConfig,
    cfg: &TrainConfig,
    observe: &mut dyn FnMut(&Progress),
) -> Result<Adapted> {
    let changed = checked_change(setup, change)?;
    let nominal = setup.evaluator(setup.model())?.evaluate(learner)?;
    let mut ev = setup.evaluator(&changed)?;
    let before = ev.evaluate(learner)?;
    learner.set_adaptation(AdaptationConfig {
        enabled: true,
        ..adaptation
    })?;
    learner.reset_adaptation();
    let (before_observer, nominal_observer) = match learner.observer().is_on() {
        true => (
            Some(ev.evaluate(learner)?),
            Some(setup.evaluator(setup.model())?.evaluate(learner)?),
        ),
        false => (None, None),
    };
    let mut sim = simulator(setup, changed.clone(), cfg.seed)?;
    let axes = changed.task_axes().to_vec();
    let mut signal = Vec::new();
    let mut evaluate = |l: &mut Learner| {
        signal.push((0.0, l.adaptation()));
        ev.evaluate(l)
    };
    let summary = osrl_learn::train::train(
        &mut sim,
        learner,
        setup.trajectory(),
        &axes,
        cfg,
        &mut evaluate,
        observe,
    )?;
    let last = learner.adaptation();
    // One signal per evaluation, at the learning curve's times.
    for (p, (t, _)) in signal.iter_mut().zip(&summary.learning_curve) {
        p.0 = *t;
    }
    Ok(Adapted {
        nominal,
        before,
        before_observer,
        nominal_observer,
        summary,
        peak_level: last.peak_level,
        adapting_steps: last.adapting_steps,
        signal,
    })
}

/// `setup`'s simulator of `truth`, seeded with `seed`, at rest at home.
fn simulator(setup: &Setup, truth: Model, seed: u64) -> Result<SimRobot> {
    let n = truth.nq();
    let sim_cfg = SimConfig {
        seed,
        ..setup.sim().clone()
    };
    let mut sim = SimRobot::new(truth, sim_cfg)?;
    sim.reset(setup.home(), &vec![0.0; n])?;
    Ok(sim)
}

/// When the robot changes in a run, and back: simulated minutes of the run.
#[derive(Clone, Debug, PartialEq)]
pub struct ChangeSchedule {
    pub change: RobotChange,
    /// The change is made at this minute (≥ 0).
    pub at: f64,
    /// And removed again at this one (after `at`), if given.
    pub revert_at: Option<f64>,
}

/// A simulated robot that changes at scheduled control steps (and back); `changed` tells the
/// evaluator which model is the truth now.
pub(crate) struct Changing {
    sim: SimRobot,
    nominal: Model,
    changed: Model,
    steps: u64,
    at: u64,
    revert: Option<u64>,
    state: Rc<Cell<bool>>,
}

impl Changing {
    /// `setup`'s simulator (seeded with `seed`, at rest at home) that becomes `changed` at
    /// `schedule.at` and `setup`'s model again at `schedule.revert_at` (simulated minutes of
    /// control steps from now).
    pub(crate) fn new(
        setup: &Setup,
        changed: Model,
        schedule: &ChangeSchedule,
        seed: u64,
    ) -> Result<Self> {
        let per_min = 60.0 / setup.sim().control_period;
        Ok(Self {
            sim: simulator(setup, setup.model().clone(), seed)?,
            nominal: setup.model().clone(),
            changed,
            steps: 0,
            at: (schedule.at * per_min).round() as u64,
            revert: schedule.revert_at.map(|r| (r * per_min).round() as u64),
            state: Rc::new(Cell::new(false)),
        })
    }

    /// Whether the robot is changed now (shared: it tells an evaluator which model is the
    /// truth).
    pub(crate) fn state(&self) -> Rc<Cell<bool>> {
        self.state.clone()
    }
}

impl Robot for Changing {
    fn dof(&self) -> usize {
        self.sim.dof()
    }
    fn task_dim(&self) -> usize {
        self.sim.task_dim()
    }
    fn control_period(&self) -> f64 {
        self.sim.control_period()
    }
    fn torque_limits(&self) -> &[f64] {
        self.sim.torque_limits()
    }
    fn joint_limits(&self) -> (&[f64], &[f64]) {
        self.sim.joint_limits()
    }
    fn measurement(&self) -> &Measurement {
        self.sim.measurement()
    }
    fn step(&mut self, u: &[f64]) -> osrl_dynamics::Result<&Measurement> {
        if self.steps == self.at {
            self.sim.set_model(self.changed.clone())?;
            self.state.set(true);
        }
        if Some(self.steps) == self.revert {
            self.sim.set_model(self.nominal.clone())?;
            self.state.set(false);
        }
        self.steps += 1;
        self.sim.step(u)
    }
}

/// Trains a fresh learner on `setup`'s robot (babbling and all, `setup`'s training settings)
/// while the robot changes at `schedule.at` and back at `schedule.revert_at`; the learner
/// re-adapts with `adaptation` (its `enabled` is set). Each evaluation scores the learner on the
/// robot as it is at that moment.
///
/// # Errors
/// The change's check, a schedule out of range, or a training error.
pub fn train_with_change(
    setup: &Setup,
    schedule: &ChangeSchedule,
    adaptation: AdaptationConfig,
    observe: &mut dyn FnMut(&Progress),
) -> Result<(Learner, TrainSummary)> {
    let changed = checked_change(setup, &schedule.change)?;
    let cfg = setup.train_config();
    let ok_at = schedule.at >= 0.0 && schedule.at.is_finite();
    let ok_revert = schedule
        .revert_at
        .is_none_or(|r| r > schedule.at && r.is_finite());
    if !ok_at || !ok_revert {
        return Err(ExperimentError::Invalid(format!(
            "--change-at {} / --revert-at {:?}: need 0 ≤ change-at < revert-at, finite",
            schedule.at, schedule.revert_at
        )));
    }
    let dt = setup.sim().control_period;
    let (n, m) = (setup.model().nq(), setup.model().task_dim());
    let mut lcfg = setup.learner_config().clone();
    lcfg.adaptation = AdaptationConfig {
        enabled: true,
        ..adaptation
    };
    let mut learner = Learner::new(n, m, dt, lcfg)?;
    let summary = run_changing(setup, &changed, schedule, &mut learner, cfg, observe)?;
    Ok((learner, summary))
}

/// Trains `learner` with `cfg` on the simulated robot that becomes `changed` (the truth only) as
/// `schedule` says, each evaluation scoring the robot as it is at that moment.
///
/// # Errors
/// A simulator or training error.
pub(crate) fn run_changing(
    setup: &Setup,
    changed: &Model,
    schedule: &ChangeSchedule,
    learner: &mut Learner,
    cfg: &TrainConfig,
    observe: &mut dyn FnMut(&Progress),
) -> Result<TrainSummary> {
    let mut robot = Changing::new(setup, changed.clone(), schedule, cfg.seed)?;
    let state = robot.state();
    let mut ev_nominal = setup.evaluator(setup.model())?;
    let mut ev_changed = setup.evaluator(changed)?;
    let mut evaluate = |l: &mut Learner| {
        if state.get() {
            ev_changed.evaluate(l)
        } else {
            ev_nominal.evaluate(l)
        }
    };
    let axes = setup.model().task_axes().to_vec();
    Ok(osrl_learn::train::train(
        &mut robot,
        learner,
        setup.trajectory(),
        &axes,
        cfg,
        &mut evaluate,
        observe,
    )?)
}
