//! Test fixture of the driver's tests: a training run on planar3 without evaluations or an
//! observer.

use crate::train::{OnEvaluation, Progress, TrainConfig, TrainSummary, Trainer};
use crate::Learner;
use osrl_dynamics::{robots, Measurement, Robot, SimRobot};

/// A training run of `learner` on `robot` (planar3) along its default figure-8 with `cfg`, no
/// evaluations, no observer: the driver's tests.
pub fn train_planar3<R: Robot + ?Sized>(
    robot: &mut R,
    learner: &mut Learner,
    cfg: &TrainConfig,
) -> TrainSummary {
    with_planar3_trainer(robot, learner, cfg, |t| t.run().unwrap())
}

/// `f` on the driver of `learner` on `robot` (planar3) along its default figure-8 with `cfg`,
/// no evaluations, no observer.
pub fn with_planar3_trainer<R: Robot + ?Sized, T>(
    robot: &mut R,
    learner: &mut Learner,
    cfg: &TrainConfig,
    f: impl FnOnce(Trainer<'_, R>) -> T,
) -> T {
    let model = robots::planar3();
    let traj = osrl_control::TrajectoryConfig::default()
        .build(&model)
        .unwrap();
    let axes = model.task_axes().to_vec();
    let mut evaluate = |_: &mut Learner| Ok(Default::default());
    let mut obs = OnEvaluation(|_: &Progress| {});
    f(Trainer::new(robot, learner, &traj, &axes, cfg, &mut evaluate, &mut obs).unwrap())
}

/// A simulated robot that records the commands it is sent.
pub struct Recording {
    pub sim: SimRobot,
    pub sent: Vec<Vec<f64>>,
}

impl Robot for Recording {
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
        self.sent.push(u.to_vec());
        self.sim.step(u)
    }
}

impl Recording {
    /// Records the commands sent to `sim`.
    pub fn new(sim: SimRobot) -> Self {
        Self {
            sim,
            sent: Vec::new(),
        }
    }

    /// The largest change of one joint's command between consecutive commands sent.
    pub fn max_step(&self) -> f64 {
        (self.sent.windows(2))
            .flat_map(|w| w[0].iter().zip(&w[1]).map(|(a, b)| (a - b).abs()))
            .fold(0.0, f64::max)
    }
}
