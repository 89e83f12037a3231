//! The rollback of a re-adapting learner (`rollback.rs`): `Learner::restore` brings back the
//! checkpoint's models and keeps the counters; the driver rolls back after
//! `adaptation.rollback_after` failed episodes in a row, caps the strength, and never when the
//! rollbacks are off or the learner does not re-adapt.

use crate::config::AdaptationConfig;
use crate::learner::fixture;
use crate::train::TrainConfig;
use crate::Learner;

/// The learner's bytes with `stats` counters (the saved form includes them).
fn bytes_with_counters(l: &Learner, stats: crate::LearnerStats) -> Vec<u8> {
    let mut l = l.clone();
    l.stats = stats;
    l.to_bytes().unwrap()
}

/// After more learning the learner differs from its checkpoint; restored, it is the checkpoint
/// byte for byte except for the counters, which stay those of the learner that ran.
#[test]
fn restore_brings_back_the_models_and_keeps_the_counters() {
    let (mut learner, mut sim, _) = fixture::ready(fixture::config(), 200, 300);
    let checkpoint = learner.clone();
    fixture::sweep(&mut learner, &mut sim, 500);
    let ran = learner.stats();
    assert_ne!(ran, checkpoint.stats(), "the sweep counted nothing");
    assert_ne!(
        bytes_with_counters(&learner, ran),
        bytes_with_counters(&checkpoint, ran),
        "the sweep changed no model"
    );
    learner.restore(&checkpoint).unwrap();
    assert_eq!(learner.stats(), ran);
    assert_eq!(
        learner.to_bytes().unwrap(),
        bytes_with_counters(&checkpoint, ran)
    );
    // A checkpoint of other dimensions is refused and changes nothing.
    let other = Learner::new(4, 2, 0.002, LearnerConfigFor4::get()).unwrap();
    let before = learner.to_bytes().unwrap();
    let e = learner.restore(&other).unwrap_err().to_string();
    assert!(e.contains("checkpoint"), "{e}");
    assert_eq!(learner.to_bytes().unwrap(), before);
}

/// A 4-joint config (planar3's data sheet with one joint more).
struct LearnerConfigFor4;
impl LearnerConfigFor4 {
    fn get() -> crate::LearnerConfig {
        let kp = [100.0; 4];
        let kd = [10.0; 4];
        crate::LearnerConfig::for_robot(&kp, &kd, &[0.0; 4], &[50.0; 4])
    }
}

/// A run of 0.3 minutes on planar3 (a continuation, or 0.1 minutes of babbling first) in which
/// every episode aborts at once (`reset_error` tiny), with the re-adaptation `enabled` and
/// `rollback_after`; the returns home learn nothing. Returns the summary and the learner.
fn failing_run(
    rollback_after: u32,
    enabled: bool,
    babble_minutes: f64,
    learner: Learner,
) -> (super::TrainSummary, Learner) {
    let mut learner = learner;
    learner
        .set_adaptation(AdaptationConfig {
            enabled,
            rollback_after,
            ..AdaptationConfig::default()
        })
        .unwrap();
    let cfg = TrainConfig {
        reset_error: 1e-9,
        learn_returning_home: false,
        babble: crate::train::BabbleConfig {
            minutes: babble_minutes,
            ..Default::default()
        },
        ..fixture::short_training(0.3)
    };
    let summary = super::run_fixture::train_planar3(&mut fixture::robot(), &mut learner, &cfg);
    (summary, learner)
}

/// A continuation of [`failing_run`] from the fixture's learner.
fn failing_continuation(rollback_after: u32, enabled: bool) -> (super::TrainSummary, Learner) {
    let (learner, _, _) = fixture::ready(fixture::config(), 200, 1000);
    failing_run(rollback_after, enabled, 0.0, learner)
}

/// Every episode fails: with `rollback_after = 2` every second episode rolls back (marked in
/// the episode log) and each halves the strength's cap; with rollbacks off, or the
/// re-adaptation off, or after babbling (not a continuation), none happens.
#[test]
fn failed_episodes_in_a_row_roll_the_learner_back() {
    let (s, learner) = failing_continuation(2, true);
    assert!(s.episodes >= 4, "{} episodes", s.episodes);
    assert_eq!(s.aborted_episodes, s.episodes);
    assert_eq!(s.rollbacks, s.episodes / 2);
    let marked: Vec<bool> = s.episode_log.iter().map(|e| e.rolled_back).collect();
    assert!(marked.iter().enumerate().all(|(i, m)| *m == (i % 2 == 1)));
    let cap = 0.5f64.powi(s.rollbacks as i32);
    assert_eq!(learner.adaptation().cap, cap);
    assert!(learner.adaptation().strength <= cap);
    for (after, enabled) in [(0, true), (2, false)] {
        let (s, l) = failing_continuation(after, enabled);
        assert_eq!(s.rollbacks, 0);
        assert!(s.episode_log.iter().all(|e| !e.rolled_back));
        assert_eq!(l.adaptation().cap, 1.0);
    }
    let fresh = Learner::new(3, 2, 0.002, fixture::config()).unwrap();
    let (s, _) = failing_run(2, true, 0.1, fresh);
    assert!(s.episodes >= 2 && s.aborted_episodes == s.episodes, "{s:?}");
    assert_eq!(s.rollbacks, 0);
}

/// With `rollback_after = 1` every failed episode rolls back and nothing else learns (the
/// returns home do not): the learner ends with the models it started with, byte for byte,
/// although its episodes learned (without the rollback it ends elsewhere).
#[test]
fn a_rollback_restores_the_models_the_episodes_changed() {
    let (start, _, _) = fixture::ready(fixture::config(), 200, 1000);
    let (s, end) = failing_run(1, true, 0.0, start.clone());
    assert!(s.rollbacks >= 2 && s.rollbacks == s.episodes, "{s:?}");
    let ran = end.stats();
    assert!(
        ran.samples > start.stats().samples,
        "the episodes learned nothing"
    );
    assert!(models(&end) == models(&start), "the models differ");
    let (_, kept) = failing_run(0, true, 0.0, start.clone());
    assert!(
        models(&kept) != models(&start),
        "without the rollback the episodes changed nothing"
    );
}

/// The learner's models and load correction as bytes (not its flags: the driver freezes `ĝ`).
fn models(l: &Learner) -> Vec<u8> {
    let mut b = postcard::to_allocvec(&l.state.models()).unwrap();
    b.extend(postcard::to_allocvec(&l.load).unwrap());
    b
}
