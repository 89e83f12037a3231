//! Test fixture of the driver's tests: a training run on planar3 without evaluations or an
//! observer.

use crate::train::{OnEvaluation, Progress, TrainConfig, TrainSummary, Trainer};
use crate::Learner;
use osrl_dynamics::{robots, Robot};

/// A training run of `learner` on `robot` (planar3) along its default figure-8 with `cfg`, no
/// evaluations, no observer: the driver's tests.
pub fn train_planar3<R: Robot + ?Sized>(
    robot: &mut R,
    learner: &mut Learner,
    cfg: &TrainConfig,
) -> TrainSummary {
    let model = robots::planar3();
    let traj = osrl_control::TrajectoryConfig::default()
        .build(&model)
        .unwrap();
    let axes = model.task_axes().to_vec();
    let mut evaluate = |_: &mut Learner| Ok(Default::default());
    let mut obs = OnEvaluation(|_: &Progress| {});
    Trainer::new(robot, learner, &traj, &axes, cfg, &mut evaluate, &mut obs)
        .unwrap()
        .run()
        .unwrap()
}
