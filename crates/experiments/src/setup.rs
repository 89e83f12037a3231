//! [`Setup`]: the robot, its task trajectory, the home posture at rest on the path start, the
//! simulator, the learner and the training run — what every experiment, command, example and
//! test builds before it runs, built in one place.

use crate::error::{ExperimentError, Result};
use osrl_control::profile::{self, ResolvedProfile};
use osrl_control::{
    check_reachable, run_closed_loop, IkOptions, ModelError, Osc, OscConfig, Run, TaskController,
    Trajectory, TrajectoryConfig,
};
use osrl_dynamics::{Model, RobotProfile, SimConfig, SimRobot};
use osrl_learn::eval::Evaluator;
use osrl_learn::train::{Progress, TrainConfig, TrainSummary};
use osrl_learn::{Learner, LearnerConfig, ModelInfo, SavedModel, CONTROL_PERIOD_RANGE};

/// A robot with its trajectory, home posture, simulator, learner and training settings, each
/// checked when it is set (the `with_*` methods rebuild what depends on it).
///
/// ```
/// use osrl_experiments::Setup;
/// let setup = Setup::new("planar3")?;                  // the default figure-8, 500 Hz
/// assert_eq!(setup.steps_per_period(), 2000);          // 4 s at 2 ms
/// let bad = osrl_dynamics::SimConfig { control_period: 1e-9, ..Default::default() };
/// assert!(setup.clone().with_sim(bad).is_err());       // refused, naming control_period
/// # Ok::<(), osrl_experiments::ExperimentError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Setup {
    robot: String,
    model: Model,
    /// The profile given (saved with a trained model, which resolves it again).
    given: RobotProfile,
    profile: ResolvedProfile,
    trajectory: TrajectoryConfig,
    traj: Trajectory,
    home: Vec<f64>,
    sim: SimConfig,
    learner: LearnerConfig,
    train: TrainConfig,
    eval_periods: usize,
}

fn invalid(m: String) -> ExperimentError {
    ExperimentError::Invalid(m)
}

impl Setup {
    /// The robot `robot` (a built-in name or a URDF file, [`osrl_learn::load_robot`]) with the
    /// defaults: its default figure-8, the default simulator (2 ms), its data sheet's learner
    /// config, the default training run, two evaluated periods per evaluation.
    ///
    /// # Errors
    /// An unknown robot, an unreadable URDF, a trajectory the arm cannot follow.
    pub fn new(robot: &str) -> Result<Self> {
        Self::along(robot, TrajectoryConfig::default())
    }

    /// As [`Setup::new`], along the trajectory `trajectory`.
    ///
    /// # Errors
    /// As [`Setup::new`].
    pub fn along(robot: &str, trajectory: TrajectoryConfig) -> Result<Self> {
        Self::profiled(robot, &RobotProfile::default(), trajectory)
    }

    /// As [`Setup::along`] with a robot profile ([`osrl_control::profile`]): the URDF is read
    /// with its tip and locks, and the model gets the profile's postures, gains and torque
    /// limits, each value given or computed from the model; the trajectory's unset centre,
    /// plane and size are the profile's path.
    ///
    /// # Errors
    /// As [`Setup::new`], or a profile value that is malformed or does not fit the arm (the
    /// error names the field), or an arm that cannot be profiled (the error says why).
    pub fn profiled(
        robot: &str,
        given: &RobotProfile,
        trajectory: TrajectoryConfig,
    ) -> Result<Self> {
        let model = profile::load_robot(robot, given)?;
        Self::from_model_with(robot_reference(robot), model, given, trajectory)
    }

    /// As [`Setup::along`] for a robot model already loaded; `robot` is how a saved model names
    /// it (a built-in name, or the URDF file's absolute path). The model gets its default
    /// profile (a built-in robot's data sheet, a URDF's embedded or computed values).
    ///
    /// # Errors
    /// As [`Setup::new`].
    pub fn from_model(robot: String, model: Model, trajectory: TrajectoryConfig) -> Result<Self> {
        Self::from_model_with(robot, model, &RobotProfile::default(), trajectory)
    }

    fn from_model_with(
        robot: String,
        model: Model,
        given: &RobotProfile,
        trajectory: TrajectoryConfig,
    ) -> Result<Self> {
        let profiled = profile::resolve(&model, given)?;
        let trajectory = profiled.trajectory(&trajectory);
        let embedded = profiled.as_given();
        let (model, profile) = (embed(profiled.model, embedded)?, profiled.profile);
        let traj = trajectory.build(&model)?;
        let home = check_reachable(&model, &traj, &IkOptions::default())?.q_start;
        let learner = data_sheet(&model, &profile, LearnerConfig::default())?;
        Ok(Self {
            robot,
            model,
            given: RobotProfile {
                name: None,
                ..given.clone()
            },
            profile,
            trajectory,
            traj,
            home,
            sim: SimConfig::default(),
            learner,
            train: TrainConfig::default(),
            eval_periods: 2,
        })
    }

    /// The set-up a saved model was trained in: its robot (with the profile it was given),
    /// trajectory, task gains, control period and seed (the home posture is found on the trajectory again, as for training,
    /// and must be the saved one).
    ///
    /// # Errors
    /// As [`Setup::new`], or a saved home posture that is not the one found on the trajectory
    /// (more than 1e-6 rad apart).
    pub fn from_saved(saved: &SavedModel) -> Result<Self> {
        let info = saved.info();
        let sim = SimConfig {
            control_period: info.control_period,
            ..SimConfig::default()
        };
        let train = TrainConfig {
            gains: info.gains,
            seed: info.seed,
            ..TrainConfig::default()
        };
        let setup = Self::from_model_with(
            info.robot.clone(),
            saved.robot().clone(),
            &info.profile,
            info.trajectory.clone(),
        )?;
        let apart = setup
            .home
            .iter()
            .zip(&info.home)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        if !(apart <= 1e-6) || setup.home.len() != info.home.len() {
            return Err(invalid(format!(
                "home: the saved {:?} rad is not the posture at rest on the start of the training \
                 path, {:?} rad",
                info.home, setup.home
            )));
        }
        setup.with_sim(sim)?.with_train(train)
    }

    /// This set-up along another trajectory (home found again on its start).
    ///
    /// # Errors
    /// A malformed trajectory, or one the arm cannot follow.
    pub fn with_trajectory(mut self, cfg: TrajectoryConfig) -> Result<Self> {
        self.traj = cfg.build(&self.model)?;
        self.home = check_reachable(&self.model, &self.traj, &IkOptions::default())?.q_start;
        self.trajectory = cfg;
        Ok(self)
    }

    /// This set-up with another simulator: its control period is also the learner's.
    ///
    /// # Errors
    /// [`ExperimentError::Invalid`] naming `control_period` outside
    /// [`osrl_learn::CONTROL_PERIOD_RANGE`] or one that leaves fewer than two steps per
    /// trajectory period; the simulator's own checks.
    pub fn with_sim(mut self, sim: SimConfig) -> Result<Self> {
        sim.validate()?;
        let dt = sim.control_period;
        if !CONTROL_PERIOD_RANGE.contains(&dt) {
            return Err(invalid(format!(
                "[sim] control_period = {dt:?} s is not within {}–{} s",
                CONTROL_PERIOD_RANGE.start(),
                CONTROL_PERIOD_RANGE.end()
            )));
        }
        if self.traj.steps_per_period(dt) < 2 {
            return Err(invalid(format!(
                "[sim] control_period = {dt:?} s: fewer than two steps per trajectory period"
            )));
        }
        self.sim = sim;
        Ok(self)
    }

    /// This set-up with another learner config; empty data-sheet fields (nominal gains, rest
    /// posture, torque limits) take the robot's.
    ///
    /// # Errors
    /// The config's own checks for this robot.
    pub fn with_learner(mut self, cfg: LearnerConfig) -> Result<Self> {
        self.learner = data_sheet(&self.model, &self.profile, cfg)?;
        Ok(self)
    }

    /// This set-up with another training run.
    ///
    /// # Errors
    /// The config's own checks, or task gains without a positive `kp`.
    pub fn with_train(mut self, cfg: TrainConfig) -> Result<Self> {
        cfg.validate()?;
        cfg.gains.validate()?;
        if !(cfg.gains.kp > 0.0) {
            return Err(invalid(format!(
                "[train] gains.kp = {}: need kp > 0 (a task without position gain is not tracked)",
                cfg.gains.kp
            )));
        }
        self.train = cfg;
        Ok(self)
    }

    /// This set-up with `periods` evaluated periods per evaluation (after one warm-up period).
    ///
    /// # Errors
    /// [`ExperimentError::Invalid`] for 0.
    pub fn with_eval_periods(mut self, periods: usize) -> Result<Self> {
        if periods == 0 {
            return Err(invalid("evaluated periods must be at least 1".into()));
        }
        self.eval_periods = periods;
        Ok(self)
    }

    /// The robot as a saved model names it.
    pub fn robot(&self) -> &str {
        &self.robot
    }
    /// The robot's model (the simulated robot's, without model errors), its profile applied.
    pub fn model(&self) -> &Model {
        &self.model
    }
    /// The robot's resolved profile: every value and where it came from.
    pub fn profile(&self) -> &ResolvedProfile {
        &self.profile
    }
    /// The trajectory's config and the trajectory built from it for this robot.
    pub fn trajectory_config(&self) -> &TrajectoryConfig {
        &self.trajectory
    }
    pub fn trajectory(&self) -> &Trajectory {
        &self.traj
    }
    /// Home posture (rad): at rest on the start of the path.
    pub fn home(&self) -> &[f64] {
        &self.home
    }
    pub fn sim(&self) -> &SimConfig {
        &self.sim
    }
    pub fn learner_config(&self) -> &LearnerConfig {
        &self.learner
    }

    /// The learner config a training run starts from: [`Setup::learner_config`]; for a family,
    /// with the static gravity model's on-policy learning off unless the family's
    /// `static_gravity_on_policy` is on, and the family's `command_projection`,
    /// `neighbour_cutoff`, `controller_bilinear` and `dynamics_weight_power` (`docs/family.md`).
    pub fn training_learner_config(&self) -> LearnerConfig {
        let mut cfg = self.learner.clone();
        if self.trajectory.kind == osrl_control::TrajectoryKind::Family {
            let family = &self.trajectory.family;
            cfg.gravity.static_on_policy &= family.static_gravity_on_policy;
            cfg.controllers.command_projection = family.command_projection;
            cfg.controllers.neighbour_cutoff = family.neighbour_cutoff;
            cfg.controllers.bilinear = family.controller_bilinear;
            cfg.dynamics.weight_power = family.dynamics_weight_power;
        }
        cfg
    }
    pub fn train_config(&self) -> &TrainConfig {
        &self.train
    }
    pub fn eval_periods(&self) -> usize {
        self.eval_periods
    }
    /// Control steps per trajectory period ([`Trajectory::steps_per_period`]).
    pub fn steps_per_period(&self) -> usize {
        self.traj.steps_per_period(self.sim.control_period)
    }

    /// The robot carrying an unmodelled payload of `kg` at the end-effector.
    ///
    /// # Errors
    /// A negative or non-finite mass.
    pub fn with_payload(&self, kg: f64) -> Result<Model> {
        let error = ModelError {
            payload: kg,
            ..ModelError::default()
        };
        Ok(error.apply(&self.model)?.0)
    }

    /// An evaluator on `truth` (this robot, or one with a payload): its own simulator, the
    /// training's task gains, [`Setup::eval_periods`] evaluated periods after a warm-up one;
    /// eq. 7's metric is the learner's cost metric (`controllers.metric`: `N = I`, or `M⁻¹`).
    ///
    /// # Errors
    /// A model that does not fit the home posture.
    pub fn evaluator(&self, truth: &Model) -> Result<Evaluator> {
        let mut ev = Evaluator::new(
            truth.clone(),
            self.sim.clone(),
            self.traj.clone(),
            self.home.clone(),
            self.train.gains,
            self.eval_periods,
        )?;
        if self.learner.controllers.cost_metric() == osrl_learn::CostMetric::InverseInertia {
            ev.set_metric(osrl_control::MetricKind::InverseMass)?;
        }
        Ok(ev)
    }

    /// Trains a fresh learner on a simulated `truth` robot (this set-up's simulator, its noise
    /// seeded with the training seed) from rest at home, evaluating it on the same model; the
    /// learner sees only measurements. `observe` sees each evaluation. With `[trajectory] kind =
    /// "family"` each episode runs a path drawn from the family.
    ///
    /// # Errors
    /// As [`osrl_learn::train::train`].
    pub fn train(
        &self,
        truth: &Model,
        observe: &mut dyn FnMut(&Progress),
    ) -> Result<(Learner, TrainSummary)> {
        let sim_cfg = SimConfig {
            seed: self.train.seed,
            ..self.sim.clone()
        };
        let mut sim = SimRobot::new(truth.clone(), sim_cfg)?;
        sim.reset(&self.home, &vec![0.0; truth.nq()])?;
        let (n, m) = (truth.nq(), truth.task_dim());
        let dt = self.sim.control_period;
        let mut learner = Learner::new(n, m, dt, self.training_learner_config())?;
        let mut ev = self.evaluator(truth)?;
        let axes = truth.task_axes();
        let mut evaluate = |l: &mut Learner| ev.evaluate(l);
        let mut observer = osrl_learn::train::OnEvaluation(observe);
        let trainer = osrl_learn::train::Trainer::new(
            &mut sim,
            &mut learner,
            &self.traj,
            axes,
            &self.train,
            &mut evaluate,
            &mut observer,
        )?;
        // A family: one drawn path per episode, seeded with the training seed
        // (`crate::family`); evaluations stay on the base figure-8.
        let summary = if self.trajectory.kind == osrl_control::TrajectoryKind::Family {
            let mut paths = crate::family::FamilySource(self.family_sampler(self.train.seed)?);
            trainer.with_paths(&mut paths).run()?
        } else {
            trainer.run()?
        };
        Ok((learner, summary))
    }

    /// Runs `ctrl` for `seconds` on a simulated `truth` robot (this set-up's simulator) from
    /// rest at home along the trajectory ([`run_closed_loop`]).
    ///
    /// # Errors
    /// As [`run_closed_loop`].
    pub fn closed_loop(
        &self,
        truth: Model,
        ctrl: &mut dyn TaskController,
        seconds: f64,
    ) -> Result<Run> {
        let mut sim = SimRobot::new(truth, self.sim.clone())?;
        sim.reset(&self.home, &vec![0.0; self.model.nq()])?;
        let axes = self.model.task_axes();
        Ok(run_closed_loop(&mut sim, ctrl, &self.traj, axes, seconds)?)
    }

    /// The analytical controller `osc` (eq. 4 or eq. 7) whose model has `error`, on the robot
    /// (carrying the error's payload, if any) for `seconds`.
    ///
    /// # Errors
    /// As [`Setup::closed_loop`], or a model error or controller config out of range.
    pub fn analytical(&self, osc: &OscConfig, error: &ModelError, seconds: f64) -> Result<Run> {
        let (sim_model, ctrl_model) = error.apply(&self.model)?;
        let mut ctrl = Osc::new(ctrl_model, osc.clone())?;
        self.closed_loop(sim_model, &mut ctrl, seconds)
    }

    /// `learner`, trained in this set-up as `summary` says, as a saved model.
    ///
    /// # Errors
    /// As [`SavedModel::new`].
    pub fn saved(&self, learner: Learner, summary: &TrainSummary) -> Result<SavedModel> {
        let info = ModelInfo {
            robot: self.robot.clone(),
            trajectory: self.trajectory.clone(),
            home: self.home.clone(),
            gains: self.train.gains,
            control_period: self.sim.control_period,
            sim_training_minutes: summary.sim_training_minutes,
            seed: self.train.seed,
            profile: self.given.clone(),
        };
        Ok(SavedModel::new(info, learner)?)
    }
}

/// A URDF robot with its resolved profile as the one its file carries, so that the model saved
/// with a trained learner resolves to the same home, gains and path without the profile it was
/// trained with (built-in robots carry their profile in the model's data sheet already).
fn embed(model: Model, resolved: RobotProfile) -> Result<Model> {
    let mut spec = model.spec().clone();
    match spec.urdf.as_mut() {
        Some(u) if u.profile.as_ref() != Some(&resolved) => u.profile = Some(resolved),
        _ => return Ok(model),
    }
    Ok(Model::new(spec)?)
}

/// `cfg` with its empty data-sheet fields filled from `model` and an unset cost metric from
/// the robot's resolved `profile`, checked for it.
fn data_sheet(
    model: &Model,
    profile: &ResolvedProfile,
    mut cfg: LearnerConfig,
) -> Result<LearnerConfig> {
    cfg.controllers.metric = cfg.controllers.metric.or(Some(profile.metric));
    let spec = model.spec();
    let tau_max: Vec<f64> = model.tau_max().collect();
    cfg.fill_data_sheet(&spec.kp, &spec.kd, &spec.q_rest, &tau_max);
    cfg.validate(model.nq())?;
    Ok(cfg)
}

/// A robot spec as a saved model records it: built-in names as they are, files as absolute
/// paths (so the model can be used from another folder).
fn robot_reference(robot: &str) -> String {
    if osrl_dynamics::robots::BUILTIN.contains(&robot) {
        return robot.into();
    }
    std::fs::canonicalize(robot).map_or(robot.into(), |a| a.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setting_is_checked_and_the_control_period_is_the_learners() {
        let s = Setup::new("planar3").unwrap();
        assert_eq!(s.home().len(), 3);
        assert_eq!(s.learner_config().nominal.kp, s.model().spec().kp);
        let sim = |dt| SimConfig {
            control_period: dt,
            ..SimConfig::default()
        };
        for dt in [1e-9, 1e6, f64::NAN, -0.002] {
            assert!(s.clone().with_sim(sim(dt)).is_err(), "{dt}");
        }
        let s4 = s.clone().with_sim(sim(0.004)).unwrap();
        assert_eq!(s4.steps_per_period(), 1000);
        let bad = TrainConfig {
            minutes: -1.0,
            ..TrainConfig::default()
        };
        assert!(s.clone().with_train(bad).is_err());
        assert!(s.clone().with_eval_periods(0).is_err());
        assert!(Setup::new("planar4").is_err());
        let mut l = LearnerConfig::default();
        l.nominal.kp = vec![1.0; 2];
        assert!(s.clone().with_learner(l).is_err());
    }

    /// The learner's cost metric is the robot profile's unless the learner config sets it.
    #[test]
    fn the_cost_metric_is_the_profiles_unless_the_learner_config_sets_it() {
        use osrl_learn::CostMetric;
        let metric = |s: &Setup| s.learner_config().controllers.metric;
        let s = Setup::new("planar3").unwrap();
        assert_eq!(metric(&s), Some(CostMetric::Identity));
        let mut cfg = LearnerConfig::default();
        cfg.controllers.metric = Some(CostMetric::InverseInertia);
        let set = s.clone().with_learner(cfg).unwrap();
        assert_eq!(metric(&set), Some(CostMetric::InverseInertia));
        let ur5 = format!(
            "{}/../dynamics/tests/fixtures/example-robot-data/ur5_robot.urdf",
            env!("CARGO_MANIFEST_DIR")
        );
        let arm = Setup::new(&ur5).unwrap();
        assert_eq!(arm.profile().metric, CostMetric::InverseInertia);
        assert_eq!(metric(&arm), Some(CostMetric::InverseInertia));
        let unset = arm.clone().with_learner(LearnerConfig::default()).unwrap();
        assert_eq!(metric(&unset), Some(CostMetric::InverseInertia));
        let mut cfg = LearnerConfig::default();
        cfg.controllers.metric = Some(CostMetric::Identity);
        assert_eq!(
            metric(&arm.with_learner(cfg).unwrap()),
            Some(CostMetric::Identity)
        );
    }

    #[test]
    fn family_training_turns_the_static_gravity_models_on_policy_learning_off_unless_asked() {
        let s = Setup::new("planar3").unwrap();
        let on = |s: &Setup| s.training_learner_config().gravity.static_on_policy;
        // One path: the learner's own setting (on by default).
        assert!(s.learner_config().gravity.static_on_policy && on(&s));
        let mut fam = s.family_config();
        let family = s.clone().with_trajectory(fam.clone()).unwrap();
        assert!(!on(&family));
        // The set-up's learner config itself is unchanged; asked for, it stays on.
        assert!(family.learner_config().gravity.static_on_policy);
        fam.family.static_gravity_on_policy = true;
        assert!(on(&s.clone().with_trajectory(fam).unwrap()));
    }

    #[test]
    fn family_training_takes_the_familys_command_projection() {
        let s = Setup::new("planar3").unwrap();
        let kappa = |s: &Setup| s.training_learner_config().controllers.command_projection;
        // One path: the learner's own share (0.5 by default).
        assert_eq!(kappa(&s), s.learner_config().controllers.command_projection);
        assert_eq!(kappa(&s), 0.5);
        let mut fam = s.family_config();
        assert_eq!(kappa(&s.clone().with_trajectory(fam.clone()).unwrap()), 1.0);
        fam.family.command_projection = 0.25;
        assert_eq!(
            kappa(&s.clone().with_trajectory(fam.clone()).unwrap()),
            0.25
        );
        fam.family.command_projection = 1.5;
        let err = s.clone().with_trajectory(fam).unwrap_err().to_string();
        assert!(err.contains("command_projection = 1.5"), "{err}");
    }

    #[test]
    fn family_training_takes_the_familys_controller_features() {
        let s = Setup::new("planar3").unwrap();
        let bilinear = |s: &Setup| s.training_learner_config().controllers.bilinear;
        assert!(!bilinear(&s));
        let mut fam = s.family_config();
        assert!(!bilinear(&s.clone().with_trajectory(fam.clone()).unwrap()));
        fam.family.controller_bilinear = true;
        let family = s.clone().with_trajectory(fam).unwrap();
        assert!(bilinear(&family));
        // The set-up's own learner config is unchanged.
        assert!(!family.learner_config().controllers.bilinear);
    }

    #[test]
    fn family_training_takes_the_familys_dynamics_weight_power() {
        let s = Setup::new("planar3").unwrap();
        let power = |s: &Setup| s.training_learner_config().dynamics.weight_power;
        assert_eq!(power(&s), 1.0);
        let mut fam = s.family_config();
        let family = s.clone().with_trajectory(fam.clone()).unwrap();
        assert_eq!(power(&family), 2.0);
        assert_eq!(family.learner_config().dynamics.weight_power, 1.0);
        fam.family.dynamics_weight_power = 1.0;
        assert_eq!(power(&s.clone().with_trajectory(fam.clone()).unwrap()), 1.0);
        fam.family.dynamics_weight_power = 0.5;
        let err = s.clone().with_trajectory(fam).unwrap_err().to_string();
        assert!(err.contains("dynamics_weight_power = 0.5"), "{err}");
    }

    #[test]
    fn family_training_takes_the_familys_neighbour_cutoff() {
        let s = Setup::new("planar3").unwrap();
        let far = |s: &Setup| s.training_learner_config().controllers.neighbour_cutoff;
        assert_eq!(far(&s), 1e-8);
        let mut fam = s.family_config();
        assert_eq!(far(&s.clone().with_trajectory(fam.clone()).unwrap()), 1e-40);
        fam.family.neighbour_cutoff = 0.0;
        assert_eq!(far(&s.clone().with_trajectory(fam.clone()).unwrap()), 0.0);
        fam.family.neighbour_cutoff = 0.01;
        let err = s.clone().with_trajectory(fam).unwrap_err().to_string();
        assert!(err.contains("neighbour_cutoff = 0.01"), "{err}");
    }
}
