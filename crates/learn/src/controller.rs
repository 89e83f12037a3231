//! The learned controller as an [`osrl_control::TaskController`]: the reference acceleration
//! `ẍ_ref` of eq. 2 with the training's task gains, then the learned command (eq. 34) without
//! exploration, so the closed-loop driver [`osrl_control::run_closed_loop`] runs it as it runs
//! the analytical eq. 7.
//!
//! ```
//! use osrl_control::{check_reachable, run_closed_loop, IkOptions, TrajectoryConfig};
//! use osrl_dynamics::{robots, SimConfig, SimRobot};
//! use osrl_learn::train::{train_simulated, BabbleConfig, TrainConfig};
//! use osrl_learn::{LearnedController, LearnerConfig};
//!
//! let model = robots::planar3();
//! let traj = TrajectoryConfig::default().build(&model)?; // the default figure-8
//! let home = check_reachable(&model, &traj, &IkOptions::default())?.q_start;
//! let spec = model.spec();
//! let tau_max: Vec<f64> = model.tau_max().collect();
//! let mut lcfg = LearnerConfig::for_robot(&spec.kp, &spec.kd, &spec.q_rest, &tau_max);
//! lcfg.guards.warmup_samples = 200; // a small warm-up: this example trains for 0.2 simulated minutes
//! let tcfg = TrainConfig {
//!     minutes: 0.2,
//!     babble: BabbleConfig { minutes: 0.1, ..BabbleConfig::default() },
//!     eval_every_minutes: 0.0,
//!     ..TrainConfig::default()
//! };
//! let (learner, _summary) = train_simulated(&model, &traj, &home, lcfg, &tcfg, 1, &mut ())?;
//! let mut ctrl = LearnedController::new(learner, tcfg.gains, model.task_axes())?;
//! let mut sim = SimRobot::new(model.clone(), SimConfig::default())?;
//! sim.reset(&home, &[0.0; 3])?;
//! let run = run_closed_loop(&mut sim, &mut ctrl, &traj, model.task_axes(), 8.0)?;
//! assert_eq!(ctrl.counts().total(), 4000); // 8 s at 500 Hz, one command per step
//! assert!(run.metrics.tracking_rms_mm.is_finite());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::dob::{observed_reference, Dob};
use crate::error::{LearnError, Result};
use crate::learner::{CommandSource, Learner};
use osrl_control::{ControlError, Target, TaskController, TaskGains};
use osrl_dynamics::Measurement;

/// How many commands came from each source ([`CommandSource`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct SourceCounts {
    /// The blend of the trained local controllers (eq. 34).
    pub learned: u64,
    /// Extrapolated from trained controllers active below the cutoff.
    pub extrapolated: u64,
    /// The nominal `u0`: no trained controller near.
    pub fallback: u64,
}

impl SourceCounts {
    /// All commands counted.
    pub fn total(&self) -> u64 {
        self.learned + self.extrapolated + self.fallback
    }
}

/// A trained [`Learner`] behind the [`TaskController`] interface: `ẍ_ref` from eq. 2 with
/// `gains`, then [`Learner::command`] without exploration. Counts the commands by source.
/// Does not allocate per command.
pub struct LearnedController {
    learner: Learner,
    gains: TaskGains,
    axes: Vec<usize>,
    xdd_ref: Vec<f64>,
    counts: SourceCounts,
    dob: crate::Dob,
}

impl LearnedController {
    /// A controller of `learner` with the task gains `gains` of eq. 2 (those it was trained
    /// with); `axes` are the world axes of the task coordinates (the robot's task axes).
    ///
    /// # Errors
    /// [`LearnError::Dimension`] if `axes` does not have the learner's task dimension or names
    /// an axis other than 0–2; [`LearnError::InvalidConfig`] for gains that are not finite and
    /// non-negative.
    pub fn new(learner: Learner, gains: TaskGains, axes: &[usize]) -> Result<Self> {
        let (_, m) = learner.dims();
        if axes.len() != m || axes.iter().any(|&a| a > 2) {
            return Err(LearnError::Dimension {
                what: "task axes (each 0, 1 or 2)",
                expected: m,
                got: axes.len(),
            });
        }
        gains
            .validate()
            .map_err(|e| LearnError::InvalidConfig(e.to_string()))?;
        Ok(Self {
            dob: learner.observer(),
            learner,
            gains,
            axes: axes.to_vec(),
            xdd_ref: vec![0.0; m],
            counts: SourceCounts::default(),
        })
    }

    /// The learner (its counters, local models).
    pub fn learner(&self) -> &Learner {
        &self.learner
    }

    /// The learner back.
    pub fn into_learner(self) -> Learner {
        self.learner
    }

    /// The task gains of eq. 2.
    pub fn gains(&self) -> TaskGains {
        self.gains
    }

    /// Commands so far, by source.
    pub fn counts(&self) -> SourceCounts {
        self.counts
    }

    /// The task-space disturbance observer (on for a learner whose re-adaptation is enabled,
    /// e.g. one saved by `osrl adapt`; it then reads the measured `ẍ`).
    pub fn observer(&self) -> &crate::Dob {
        &self.dob
    }

    /// Forgets the observer's estimate, e.g. before a new run from rest.
    pub fn reset_observer(&mut self) {
        self.dob.reset();
    }
}

/// The learned command without exploration for `target` at `meas` (`u`, eq. 34's blend) on the
/// reference of [`observed_reference`](crate::dob::observed_reference) (the observer learning from `meas`): what
/// `LearnedController` and the evaluation send. Returns the command's source.
///
/// # Errors
/// The learner's error (bad measurement, wrong sizes).
#[allow(clippy::too_many_arguments)]
pub(crate) fn observed_command(
    learner: &mut Learner,
    gains: &TaskGains,
    target: &Target,
    axes: &[usize],
    meas: &Measurement,
    dob: &mut Dob,
    xdd_ref: &mut [f64],
    u: &mut [f64],
) -> Result<CommandSource> {
    observed_reference(gains, target, axes, meas, dob, true, xdd_ref);
    let (q, qd) = (meas.q.as_slice(), meas.qd.as_slice());
    learner.command::<rand_chacha::ChaCha8Rng>(q, qd, xdd_ref, None, u)
}

impl TaskController for LearnedController {
    fn command(
        &mut self,
        meas: &Measurement,
        target: &Target,
        u: &mut [f64],
    ) -> osrl_control::Result<()> {
        let src = observed_command(
            &mut self.learner,
            &self.gains,
            target,
            &self.axes,
            meas,
            &mut self.dob,
            &mut self.xdd_ref,
            u,
        )?;
        match src {
            CommandSource::Learned => self.counts.learned += 1,
            CommandSource::Extrapolated => self.counts.extrapolated += 1,
            CommandSource::Fallback => self.counts.fallback += 1,
        }
        Ok(())
    }
}

/// A learned controller's failure as the closed-loop driver's error: the control and dynamics
/// errors the learner passed on keep their variants; every other error becomes
/// [`ControlError::Controller`] for the `learned` controller, with its message.
impl From<LearnError> for ControlError {
    fn from(e: LearnError) -> Self {
        match e {
            LearnError::Control(c) => c,
            LearnError::Robot(d) => ControlError::Dynamics(d),
            other => ControlError::Controller {
                controller: "learned",
                reason: other.to_string(),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::LearnerConfig;

    fn learner() -> Learner {
        let m = osrl_dynamics::robots::planar3();
        let spec = m.spec();
        let tau: Vec<f64> = m.tau_max().collect();
        let cfg = LearnerConfig::for_robot(&spec.kp, &spec.kd, &spec.q_rest, &tau);
        Learner::new(3, 2, 0.002, cfg).unwrap()
    }

    #[test]
    fn axes_and_gains_are_checked() {
        let g = TaskGains::default();
        assert!(LearnedController::new(learner(), g, &[0, 2]).is_ok());
        assert!(LearnedController::new(learner(), g, &[0]).is_err());
        assert!(LearnedController::new(learner(), g, &[0, 3]).is_err());
        let bad = TaskGains {
            kp: f64::NAN,
            kd: 1.0,
        };
        assert!(LearnedController::new(learner(), bad, &[0, 2]).is_err());
    }

    /// Before any training the learned command is the nominal `u0` (a fallback, counted), and
    /// a bad measurement is the learner's error carried into the driver's error type.
    #[test]
    fn an_untrained_learner_falls_back_and_errors_carry_over() {
        let model = osrl_dynamics::robots::planar3();
        let mut c = LearnedController::new(learner(), TaskGains::default(), &[0, 2]).unwrap();
        let traj = osrl_control::TrajectoryConfig::default()
            .build(&model)
            .unwrap();
        let mut sim =
            osrl_dynamics::SimRobot::new(model.clone(), osrl_dynamics::SimConfig::default())
                .unwrap();
        let q = model.spec().q_start.clone();
        sim.reset(&q, &[0.0; 3]).unwrap();
        let meas = osrl_dynamics::Robot::measurement(&sim).clone();
        let mut u = [0.0; 3];
        c.command(&meas, &traj.sample(0.0), &mut u).unwrap();
        assert_eq!(c.counts().fallback, 1);
        let mut u0 = [0.0; 3];
        let mut l = c.into_learner();
        l.nominal(meas.q.as_slice(), meas.qd.as_slice(), &mut u0)
            .unwrap();
        let lim = l.config().guards.torque_limits.clone();
        for i in 0..3 {
            assert_eq!(u[i], u0[i].clamp(-lim[i], lim[i]), "joint {i}");
        }
        let mut c = LearnedController::new(l, TaskGains::default(), &[0, 2]).unwrap();
        let err = c
            .command(&meas, &traj.sample(0.0), &mut [0.0; 2])
            .unwrap_err();
        assert!(
            matches!(
                err,
                ControlError::Controller {
                    controller: "learned",
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(err.to_string().starts_with("learned controller: "), "{err}");
        let d = osrl_dynamics::DynamicsError::InvalidConfig("x".into());
        assert_eq!(
            ControlError::from(LearnError::Robot(d.clone())),
            ControlError::Dynamics(d)
        );
    }
}
