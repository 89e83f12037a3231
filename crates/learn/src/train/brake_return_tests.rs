//! `TrainConfig::brake_return_from_velocity`: the first PD move after a braked episode starts
//! its reference at the arm's measured velocity, so the PD's damping term does not brake the
//! arm at once; the velocity is used by that move only.

use super::babble::pd_command;
use super::run_fixture::Recording;
use super::TrainConfig;
use crate::learner::fixture;
use osrl_dynamics::Robot;

/// The first two commands of a 0.8-s PD move from the arm's posture (moving at `qd`) to a
/// target, with the move's reference starting at `v0` (`None`: at rest); and whether the
/// velocity was left for a later move.
fn first_commands(qd: &[f64], v0: Option<Vec<f64>>) -> (Vec<Vec<f64>>, bool) {
    let (mut learner, _, _) = fixture::ready(fixture::config(), 200, 1000);
    let mut robot = Recording::new(fixture::robot());
    let q0 = robot.measurement().q.as_slice().to_vec();
    robot.sim.reset(&q0, qd).unwrap();
    let cfg = TrainConfig::default();
    let left = super::run_fixture::with_planar3_trainer(&mut robot, &mut learner, &cfg, |mut t| {
        t.move_v0 = v0;
        let target: Vec<f64> = q0.iter().map(|q| q + 0.1).collect();
        let limit = t.steps + 2;
        t.pd_move_from(&q0, &target, 0.8, 0.0, 0.0, limit).unwrap();
        t.move_v0.is_some()
    });
    (robot.sent, left)
}

/// From the measured velocity the first command is `ĝ` alone (the reference at the measured
/// state); from rest it carries the damping `−s K_D q̇`, several N·m at 1 rad/s.
#[test]
fn a_move_from_the_measured_velocity_does_not_brake_the_arm_at_once() {
    let qd = [1.0, -0.8, 0.6];
    let (from_rest, _) = first_commands(&qd, None);
    let (moving, left) = first_commands(&qd, Some(qd.to_vec()));
    assert!(!left, "the velocity must serve one move only");
    // `ĝ` at the measured state: the PD command with the reference there.
    let (mut learner, _, _) = fixture::ready(fixture::config(), 200, 1000);
    let mut robot = fixture::robot();
    let q0 = robot.measurement().q.as_slice().to_vec();
    robot.reset(&q0, &qd).unwrap();
    let meas = robot.measurement().clone();
    let mut g = vec![0.0; 3];
    let scale = TrainConfig::default().babble.gain_scale;
    pd_command(&mut learner, &meas, &q0, &qd, scale, &mut g).unwrap();
    let off = |u: &[f64]| {
        u.iter()
            .zip(&g)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    assert!(off(&moving[0]) < 1e-9, "{:?} vs ĝ {g:?}", moving[0]);
    assert!(off(&from_rest[0]) > 1.0, "{:?} vs ĝ {g:?}", from_rest[0]);
}
