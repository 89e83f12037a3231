//! The training driver (argmin style: explicit state, a driver, an observer; `docs/learner.md`,
//! "Training"): motor babbling under joint PD control with the learned gravity compensation, then
//! on-policy learning while tracking the task path with exploration noise, evaluated at regular
//! intervals.
//!
//! The driver talks to the robot only through [`Robot`]; evaluation is a callback supplied by the
//! caller (who may own a simulator and its model — the driver never does).

mod babble;
#[cfg(test)]
mod brake_return_tests;
mod config;
#[cfg(test)]
mod continuation_tests;
mod curriculum;
#[cfg(test)]
mod held_reference_tests;
mod home;
mod observer;
mod on_policy;
mod paths;
#[cfg(test)]
mod paths_tests;
mod posture_holds;
mod postures;
#[cfg(test)]
mod postures_tests;
mod rollback;
#[cfg(test)]
mod rollback_tests;
#[cfg(test)]
pub(crate) mod run_fixture;
mod safety;
#[cfg(test)]
mod step_limit_tests;
mod trainer;

pub use config::{BabbleConfig, TrainConfig};
pub use curriculum::{CurriculumConfig, QuietHolds};
pub use observer::{
    EpisodeOutcome, EpisodeRecord, EpisodeReport, Observer, OnEvaluation, Phase, Progress,
};
pub use paths::PathSource;
pub use posture_holds::{HeldReference, PostureHolds};
pub use safety::{StepPoint, STEP_BIN_SECONDS};
pub use trainer::{Evaluate, TrainSummary, Trainer};

use crate::error::Result;
use crate::eval::EvalResult;
use crate::learner::Learner;
use osrl_control::Trajectory;
use osrl_dynamics::Robot;

/// Trains `learner` on `robot` (at rest at its home posture on the path start): [`Trainer::run`]
/// with `observe` called after each evaluation.
///
/// # Errors
/// As [`Trainer::new`] and [`Trainer::run`].
pub fn train<R: Robot + ?Sized>(
    robot: &mut R,
    learner: &mut Learner,
    traj: &Trajectory,
    axes: &[usize],
    cfg: &TrainConfig,
    evaluate: &mut dyn FnMut(&mut Learner) -> Result<EvalResult>,
    observe: &mut dyn FnMut(&Progress),
) -> Result<TrainSummary> {
    let mut observer = OnEvaluation(observe);
    Trainer::new(robot, learner, traj, axes, cfg, evaluate, &mut observer)?.run()
}

/// [`Trainer::run`] on a simulated robot, for examples and experiments: a fresh learner with `lcfg`
/// trained on a [`SimRobot`](osrl_dynamics::SimRobot) of `truth` (default
/// [`SimConfig`](osrl_dynamics::SimConfig), noise seeded with `cfg.seed`) starting at rest at
/// `home`, evaluated by an [`Evaluator`](crate::eval::Evaluator) on the same model over
/// `eval_periods` periods. The model serves the simulator and the evaluator; the learner sees
/// only measurements.
///
/// # Errors
/// As [`train`], or a `home` or `lcfg` that does not fit `truth`.
pub fn train_simulated(
    truth: &osrl_dynamics::Model,
    traj: &Trajectory,
    home: &[f64],
    lcfg: crate::LearnerConfig,
    cfg: &TrainConfig,
    eval_periods: usize,
    observer: &mut dyn Observer,
) -> Result<(Learner, TrainSummary)> {
    let sim_cfg = osrl_dynamics::SimConfig {
        seed: cfg.seed,
        ..Default::default()
    };
    let (n, dt) = (truth.nq(), sim_cfg.control_period);
    let mut sim = osrl_dynamics::SimRobot::new(truth.clone(), sim_cfg)?;
    sim.reset(home, &vec![0.0; n])?;
    let inverse_inertia =
        lcfg.controllers.cost_metric() == crate::config::CostMetric::InverseInertia;
    let mut learner = Learner::new(n, truth.task_dim(), dt, lcfg)?;
    let mut ev = crate::eval::Evaluator::new(
        truth.clone(),
        Default::default(),
        traj.clone(),
        home.to_vec(),
        cfg.gains,
        eval_periods,
    )?;
    if inverse_inertia {
        ev.set_metric(osrl_control::MetricKind::InverseMass)?;
    }
    let axes = truth.task_axes();
    let mut evaluate = |l: &mut Learner| ev.evaluate(l);
    let summary = Trainer::new(
        &mut sim,
        &mut learner,
        traj,
        axes,
        cfg,
        &mut evaluate,
        observer,
    )?
    .run()?;
    Ok((learner, summary))
}
