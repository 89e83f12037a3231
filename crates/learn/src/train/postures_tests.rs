//! `TrainConfig::posture_holds`: the holds at recorded path postures teach the static gravity
//! model and nothing else; `Learner::learn_static_gravity` touches no other model.

use super::{PostureHolds, TrainConfig};
use crate::learner::fixture;
use crate::Learner;
use osrl_control::TrajectoryConfig;
use osrl_dynamics::robots;

/// Updates of the static gravity model's LWPR so far.
fn static_updates(learner: &mut Learner) -> u64 {
    let g = fixture::models(learner).gravity_static.as_ref();
    g.expect("the fixture has a static model")
        .lwpr()
        .n_updates()
}

/// A short planar3 run from home with 3-s episodes (so the arm returns home often), the static
/// model learning on-policy only in the posture holds, or with the null-space correction
/// (`correction`) the correction in its place; returns the summary and the learner.
fn run(holds: usize, correction: bool) -> (super::TrainSummary, Learner) {
    let model = robots::planar3();
    let traj = TrajectoryConfig::default().build(&model).unwrap();
    let mut sim = fixture::robot();
    let reach = osrl_control::check_reachable(&model, &traj, &Default::default()).unwrap();
    sim.reset(&reach.q_start, &[0.0; 3]).unwrap();
    let mut lcfg = fixture::config();
    lcfg.gravity.static_on_policy = false;
    lcfg.gravity.null_correction = correction;
    let mut learner = Learner::new(3, 2, 0.002, lcfg).unwrap();
    let cfg = TrainConfig {
        episode_seconds: 3.0,
        posture_holds: PostureHolds {
            count: holds,
            record_every: 0.1,
            ..PostureHolds::default()
        },
        ..fixture::short_training(0.7)
    };
    let summary = super::step_limit_tests::train_quietly(&mut sim, &mut learner, &traj, &cfg);
    (summary, learner)
}

/// With the static model frozen on-policy, only the posture holds add to its data; their
/// transitions are not learning steps of the other models (fewer of those in the same time).
#[test]
fn posture_holds_teach_the_static_gravity_model_only() {
    let (off, mut l_off) = run(0, false);
    let (on, mut l_on) = run(2, false);
    assert!(off.episodes >= 2 && on.episodes >= 2, "{off:?}\n{on:?}");
    let (u_off, u_on) = (static_updates(&mut l_off), static_updates(&mut l_on));
    assert!(
        u_on > u_off + 100,
        "static updates {u_on} vs {u_off}: {:?}",
        on.episode_log
    );
    assert!(
        on.stats.samples < off.stats.samples,
        "learning steps {} vs {}",
        on.stats.samples,
        off.stats.samples
    );
}

/// `learn_static_gravity` on a still transition updates the static model once and leaves the
/// learning-step count and the forward model alone.
#[test]
fn learn_static_gravity_touches_only_the_static_model() {
    let mut cfg = fixture::config();
    cfg.gravity.null_correction = false;
    let (mut learner, _, last) = fixture::ready(cfg, 200, 50);
    let mut prev = last.clone();
    prev.qd.fill(0.0);
    let mut cur = prev.clone();
    cur.t += 0.002;
    let samples = learner.stats().samples;
    let forward = fixture::models(&mut learner).forward.lwpr().n_updates();
    let before = static_updates(&mut learner);
    learner.learn_static_gravity(&prev, &cur).unwrap();
    assert_eq!(static_updates(&mut learner), before + 1);
    assert_eq!(learner.stats().samples, samples);
    assert_eq!(
        fixture::models(&mut learner).forward.lwpr().n_updates(),
        forward
    );
    // A moving transition is not still: no update.
    cur.qd.fill(1.0);
    learner.learn_static_gravity(&prev, &cur).unwrap();
    assert_eq!(static_updates(&mut learner), before + 1);
}

/// With the null-space correction (the default), the holds teach the correction's model and
/// leave the static model as a run without holds leaves it; the command then differs from the
/// run without the correction only by the correction.
#[test]
fn with_the_correction_the_holds_teach_it_instead_of_the_static_model() {
    let (off, mut l_off) = run(0, true);
    let (on, mut l_on) = run(2, true);
    assert!(off.episodes >= 2 && on.episodes >= 2, "{off:?}\n{on:?}");
    assert_eq!(static_updates(&mut l_on), static_updates(&mut l_off));
    let updates = |l: &mut Learner| {
        fixture::models(l)
            .gravity_null
            .as_ref()
            .map_or(0, |g| g.lwpr().n_updates())
    };
    assert_eq!(updates(&mut l_off), 0);
    assert!(updates(&mut l_on) > 100, "{}", updates(&mut l_on));
}
