//! A continuation (on-policy learning with no babbling before it, as `osrl adapt` runs one)
//! with `hold_before_continuation` starts from the PD hold at home, not from zero torque, and
//! with `freeze_static_in_continuation` leaves the static gravity model as it was.

use super::babble::pd_command;
use super::run_fixture::Recording;
use crate::learner::fixture;
use crate::train::{BabbleConfig, TrainConfig};
use crate::Learner;
use osrl_dynamics::Robot;

/// A continuation of `seconds` (no babbling) on planar3 with `cfg`'s other settings.
fn continue_for(robot: &mut Recording, learner: &mut Learner, seconds: f64, cfg: TrainConfig) {
    let cfg = TrainConfig {
        minutes: seconds / 60.0,
        eval_every_minutes: 0.0,
        babble: BabbleConfig {
            minutes: 0.0,
            ..BabbleConfig::default()
        },
        ..cfg
    };
    super::run_fixture::train_planar3(robot, learner, &cfg);
}

/// The fixture's robot, recording.
fn recording() -> Recording {
    Recording::new(fixture::robot())
}

/// With `hold_before_continuation`, the first command of a continuation on planar3 (a learner
/// past its warm-up, at rest at home) is the hold's `ĝ(home)` — several N·m, not zero — and
/// the arm stays at home for the first second instead of sagging while the first episode fades
/// in from zero torque (without it the first command sent is zero).
#[test]
fn a_continuation_starts_from_the_hold_not_from_zero_torque() {
    let (mut learner, _, _) = fixture::ready(fixture::config(), 200, 1000);
    let mut robot = recording();
    let home = robot.measurement().clone();
    let cfg = TrainConfig {
        hold_before_continuation: true,
        // The hold alone: this fixture's `ĝ` comes from a short warm-up, and the static model
        // learning in the hold is what keeps the arm within 0.01 rad here (frozen: 0.019).
        freeze_static_in_continuation: false,
        ..TrainConfig::default()
    };
    let mut hold = vec![0.0; 3];
    let (q, zero) = (home.q.as_slice().to_vec(), [0.0; 3]);
    let scale = cfg.babble.gain_scale;
    pd_command(&mut learner.clone(), &home, &q, &zero, scale, &mut hold).unwrap();
    continue_for(&mut robot, &mut learner, 1.0, cfg);
    let big = hold.iter().fold(0.0, |m: f64, g| m.max(g.abs()));
    assert!(big > 1.0, "ĝ(home) = {hold:?} N·m");
    let first = &robot.sent[0];
    let off = first.iter().zip(&hold).map(|(u, g)| (u - g).abs());
    assert!(off.fold(0.0, f64::max) < 1e-9, "{first:?} vs {hold:?}");
    let sag = robot.sim.measurement().q.iter().zip(&q);
    let sag = sag.fold(0.0, |m: f64, (a, b)| m.max((a - b).abs()));
    assert!(sag < 0.01, "{sag} rad from home after 1 s");
}

/// The static gravity model after a 2-s continuation on planar3 (hold first, then on-policy),
/// serialised, and before it.
fn static_model_around_continuation(freeze: bool) -> (String, String) {
    let (mut learner, _, _) = fixture::ready(fixture::config(), 200, 1000);
    let text = |l: &Learner| serde_json::to_string(l.gravity_static_model().unwrap()).unwrap();
    let before = text(&learner);
    let cfg = TrainConfig {
        freeze_static_in_continuation: freeze,
        ..TrainConfig::default()
    };
    continue_for(&mut recording(), &mut learner, 2.0, cfg);
    (before, text(&learner))
}

/// With `freeze_static_in_continuation` (the default) the static gravity model learns nothing
/// in a continuation; without it the same run changes it (so the check can fail).
#[test]
fn a_continuation_leaves_the_static_gravity_model_alone() {
    let (before, after) = static_model_around_continuation(true);
    assert!(before == after, "the static gravity model changed");
    let (before, after) = static_model_around_continuation(false);
    assert!(
        before != after,
        "unfrozen, the run did not teach the static model anything"
    );
}
