//! `PostureHolds::held_reference`: under a gravity error (a learner trained on the unloaded
//! planar3, continued on the arm with a 0.5 kg payload) the arm sags from each held posture; a
//! move that starts its reference at the held posture keeps the PD command continuous, one that
//! starts at the measured posture drops the P-term in one period. And
//! `PostureHolds::readapting_count`: how many postures a re-adapting learner holds.

use super::run_fixture::Recording;
use super::{BabbleConfig, HeldReference, PostureHolds, TrainConfig};
use crate::learner::fixture;
use crate::Learner;
use osrl_control::{RobotChange, TrajectoryConfig};
use osrl_dynamics::{robots, SimConfig, SimRobot};

/// The holds of these runs: three per return home, postures recorded every 0.1 s.
fn holds(held_reference: HeldReference) -> PostureHolds {
    PostureHolds {
        count: 3,
        record_every: 0.1,
        held_reference,
        ..PostureHolds::default()
    }
}

/// planar3 (`payload` kg at the end-effector) at rest at the start of its default figure-8,
/// recording.
fn robot(payload: f64) -> Recording {
    let truth = robots::planar3();
    let traj = TrajectoryConfig::default().build(&truth).unwrap();
    let reach = osrl_control::check_reachable(&truth, &traj, &Default::default()).unwrap();
    let change: RobotChange = format!("payload={payload}").parse().unwrap();
    let mut sim = SimRobot::new(change.apply(&truth).unwrap(), SimConfig::default()).unwrap();
    sim.reset(&reach.q_start, &[0.0; 3]).unwrap();
    Recording::new(sim)
}

/// A continuation of `minutes` (no babbling, 3-s episodes) with `holds`.
fn continuation(minutes: f64, holds: PostureHolds) -> TrainConfig {
    TrainConfig {
        minutes,
        eval_every_minutes: 0.0,
        episode_seconds: 3.0,
        babble: BabbleConfig {
            minutes: 0.0,
            ..BabbleConfig::default()
        },
        posture_holds: holds,
        ..TrainConfig::default()
    }
}

/// The largest command step of a 0.4-minute continuation (no babbling, 3-s episodes) of
/// `learner` on the loaded arm with `holds`.
fn loaded_continuation(learner: &Learner, holds: PostureHolds) -> f64 {
    let mut learner = learner.clone();
    let mut robot = robot(0.5);
    let cfg = continuation(0.4, holds);
    let summary = super::run_fixture::train_planar3(&mut robot, &mut learner, &cfg);
    assert!(summary.episodes >= 3, "{summary:?}");
    robot.max_step()
}

/// A planar3 learner trained for 0.8 minutes (3-s episodes, 3 holds per return home) on the
/// unloaded arm.
fn trained_unloaded() -> Learner {
    let mut learner = Learner::new(3, 2, 0.002, fixture::config()).unwrap();
    let cfg = TrainConfig {
        episode_seconds: 3.0,
        posture_holds: holds(HeldReference::Never),
        ..fixture::short_training(0.8)
    };
    super::run_fixture::train_planar3(&mut robot(0.0), &mut learner, &cfg);
    learner
}

/// Trained on the unloaded arm, continued on the loaded one: with the reference starting at the
/// held posture the largest command step is a fraction of the one without, which the sag's
/// P-term dominates.
#[test]
fn a_move_from_a_held_posture_keeps_the_command_continuous() {
    let learner = trained_unloaded();
    let measured = loaded_continuation(&learner, holds(HeldReference::Never));
    let held = loaded_continuation(&learner, holds(HeldReference::Always));
    assert!(
        held < 0.5 * measured,
        "largest step {held} N·m from the held posture vs {measured} from the measured one"
    );
}

/// With the measured reference, a fade from each hold's last command (`handover_seconds`)
/// keeps the command continuous too: the P-term that the reference drops leaves over 0.1 s.
#[test]
fn a_handover_fade_after_a_hold_keeps_the_command_continuous() {
    let learner = trained_unloaded();
    let step = |handover_seconds: f64| {
        let holds = PostureHolds {
            handover_seconds,
            ..holds(HeldReference::Never)
        };
        loaded_continuation(&learner, holds)
    };
    let (abrupt, faded) = (step(0.0), step(0.1));
    assert!(
        faded < 0.5 * abrupt,
        "largest step {faded} N·m with the handover fade vs {abrupt} without"
    );
}

/// The null-space correction's updates after a 0.3-minute continuation of `learner` on the
/// unloaded arm with `count` holds per return home and `readapting_count` while re-adapting.
fn null_updates_after(learner: &Learner, count: usize, readapting_count: usize) -> u64 {
    let mut learner = learner.clone();
    let holds = PostureHolds {
        count,
        readapting_count,
        ..holds(HeldReference::Never)
    };
    let cfg = continuation(0.3, holds);
    super::run_fixture::train_planar3(&mut robot(0.0), &mut learner, &cfg);
    let models = fixture::models(&mut learner);
    models
        .gravity_null
        .as_ref()
        .map_or(0, |g| g.lwpr().n_updates())
}

/// While the learner re-adapts, the driver holds `readapting_count` postures per return home
/// instead of `count`: the correction learns more samples in the same time; otherwise the
/// option changes nothing.
#[test]
fn a_readapting_learner_holds_readapting_count_postures() {
    let mut learner = trained_unloaded();
    let before = null_updates_after(&learner, 1, 1);
    assert_eq!(null_updates_after(&learner, 1, 4), before);
    learner.adapt.detected = true;
    let one = null_updates_after(&learner, 1, 1);
    let four = null_updates_after(&learner, 1, 4);
    assert!(
        four > one + 300,
        "null-space correction updates: {four} vs {one}"
    );
}
