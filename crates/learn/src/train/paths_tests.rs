//! Tests of the training driver with a path source (`paths.rs`): kept apart so that `paths.rs`
//! does not depend on the driver that depends on it.

use super::paths::PathSource;
use crate::error::Result;
use crate::learner::fixture;
use crate::train::{OnEvaluation, TrainConfig, Trainer};
use crate::Learner;
use nalgebra::Vector3;
use osrl_control::{Trajectory, TrajectoryConfig};
use osrl_dynamics::robots;

/// Hands out `path` (approached from `from` when given) and counts the calls.
struct Fixed {
    path: Trajectory,
    calls: u64,
}
impl PathSource for Fixed {
    fn next_path(&mut self) -> Result<Trajectory> {
        self.calls += 1;
        Ok(self.path.clone())
    }
}

fn run(path: Trajectory) -> (Result<crate::train::TrainSummary>, u64) {
    let model = robots::planar3();
    let traj = TrajectoryConfig::default().build(&model).unwrap();
    let mut sim = fixture::robot();
    let mut learner = Learner::new(3, 2, 0.002, fixture::config()).unwrap();
    let cfg = TrainConfig {
        reset_error: 1e-9,
        ..fixture::short_training(0.5)
    };
    let axes = model.task_axes().to_vec();
    let mut evaluate = |_: &mut Learner| Ok(Default::default());
    let mut obs = OnEvaluation(|_: &crate::train::Progress| {});
    let mut src = Fixed { path, calls: 0 };
    let t = Trainer::new(
        &mut sim,
        &mut learner,
        &traj,
        &axes,
        &cfg,
        &mut evaluate,
        &mut obs,
    )
    .unwrap();
    let r = t.with_paths(&mut src).run();
    (r, src.calls)
}

/// Each episode draws one path from the source; a path that does not start at home's task
/// point is refused with an error naming the distance.
#[test]
fn each_episode_draws_a_path_and_one_away_from_home_is_refused() {
    let model = robots::planar3();
    let traj = TrajectoryConfig::default().build(&model).unwrap();
    let start = traj.start();
    let circle = Trajectory::circle(
        start + Vector3::new(0.05, 0.0, 0.0),
        Vector3::x(),
        Vector3::z(),
        0.05,
        4.0,
        1.0,
    )
    .unwrap();
    let approached = circle.clone().with_approach(start, 1.0).unwrap();
    let (summary, calls) = run(approached);
    let summary = summary.unwrap();
    assert!(summary.episodes > 0);
    assert_eq!(
        (summary.paths_drawn, calls),
        (summary.episodes, summary.episodes)
    );
    let (err, _) = run(circle);
    let e = err.unwrap_err().to_string();
    assert!(e.contains("home's task point") && e.contains("mm"), "{e}");
}
