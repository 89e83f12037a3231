//! `TrainConfig::command_step_limit`: no on-policy command moves further than the limit from
//! the one before, and the commands it held are counted (`docs/decisions.md`, D24).

use super::{TrainConfig, Trainer};
use crate::learner::fixture;
use crate::Learner;
use osrl_control::TrajectoryConfig;
use osrl_dynamics::robots;

/// A short planar3 run (babbling, then on-policy episodes with exploration) with `limit`.
fn run(limit: Option<f64>) -> super::TrainSummary {
    let model = robots::planar3();
    let traj = TrajectoryConfig::default().build(&model).unwrap();
    let mut sim = fixture::robot();
    let mut learner = Learner::new(3, 2, 0.002, fixture::config()).unwrap();
    let cfg = TrainConfig {
        command_step_limit: limit,
        ..fixture::short_training(0.6)
    };
    train_quietly(&mut sim, &mut learner, &traj, &cfg)
}

/// Trains `learner` on the fixture arm `sim` along `traj` with `cfg`: no evaluations, no
/// observer (planar3's task axes).
pub(super) fn train_quietly(
    sim: &mut osrl_dynamics::SimRobot,
    learner: &mut Learner,
    traj: &osrl_control::Trajectory,
    cfg: &TrainConfig,
) -> super::TrainSummary {
    let axes = robots::planar3().task_axes().to_vec();
    let mut evaluate = |_: &mut Learner| Ok(Default::default());
    Trainer::new(sim, learner, traj, &axes, cfg, &mut evaluate, &mut ())
        .unwrap()
        .run()
        .unwrap()
}

/// With a limit of a quarter of the largest on-policy step of the same run without it, no
/// on-policy command steps further than the limit, and the held commands are counted in
/// `rate_limited`.
#[test]
fn on_policy_commands_stay_within_the_step_limit() {
    let free = run(None);
    assert!(free.max_command_step > 0.0, "{free:?}");
    assert_eq!(free.step_limited, 0);
    let limit = 0.25 * free.max_command_step;
    let limited = run(Some(limit));
    assert!(
        limited.max_command_step <= limit * (1.0 + 1e-9),
        "{} > {limit}",
        limited.max_command_step
    );
    assert!(limited.step_limited > 0);
    assert!(limited.rate_limited() >= limited.step_limited);
}
