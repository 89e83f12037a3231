//! The re-adaptation's signal on the fixture's planar3 (`adapt.rs`): which residual floor the
//! difference form of the local dynamics uses.

use super::fixture;
use crate::config::AdaptationConfig;
use osrl_control::RobotChange;
use osrl_dynamics::robots;

/// The fixture's learner (warm-up and 4 s of sweep), then `k` more sweep steps with the
/// re-adaptation on (`adaptation`, `enabled` set) on planar3 changed by `change`; the level's
/// peak.
fn peak_level(adaptation: AdaptationConfig, change: &str, k: usize) -> f64 {
    let (mut learner, mut sim, _) = fixture::ready(fixture::config(), 200, 2000);
    let change: RobotChange = change.parse().unwrap();
    sim.set_model(change.apply(&robots::planar3()).unwrap())
        .unwrap();
    learner
        .set_adaptation(AdaptationConfig {
            enabled: true,
            ..adaptation
        })
        .unwrap();
    learner.reset_adaptation();
    fixture::sweep(&mut learner, &mut sim, k);
    learner.adaptation().peak_level
}

/// In the difference form (the default) the fields' residuals are floored at
/// `residual_floor_difference` (m/s³), not at the levels' `residual_floor` (m/s²): a floor far
/// above the residuals lowers the level (the fixture's young fields still mispredict a few
/// samples by more than it), a huge level floor changes nothing.
#[test]
fn the_difference_form_floors_the_residual_at_its_own_floor() {
    let base = AdaptationConfig::default();
    let k = 1500;
    let default = peak_level(base.clone(), "none", k);
    let tiny = peak_level(
        AdaptationConfig {
            residual_floor_difference: 1e-6,
            ..base.clone()
        },
        "none",
        k,
    );
    let huge = peak_level(
        AdaptationConfig {
            residual_floor_difference: 1e3,
            ..base.clone()
        },
        "none",
        k,
    );
    let level_floor = peak_level(
        AdaptationConfig {
            residual_floor: 1e3,
            ..base
        },
        "none",
        k,
    );
    assert!(default > 0.0 && tiny >= default, "{tiny} {default}");
    assert!(huge < 0.5 * default, "{huge} vs {default}");
    assert_eq!(level_floor, default);
}

/// The task-space disturbance observer runs while re-adapting or with `observer_always`, and
/// not otherwise (the training runs of E1–E7) nor with `observer_seconds = 0`.
#[test]
fn the_observer_runs_while_re_adapting_or_when_asked() {
    let on = |adaptation: AdaptationConfig| {
        let mut cfg = fixture::config();
        cfg.adaptation = adaptation;
        crate::Learner::new(3, 2, 0.002, cfg)
            .unwrap()
            .observer()
            .is_on()
    };
    let d = AdaptationConfig::default;
    assert!(!on(d()));
    assert!(on(AdaptationConfig {
        enabled: true,
        ..d()
    }));
    assert!(on(AdaptationConfig {
        observer_always: true,
        ..d()
    }));
    assert!(!on(AdaptationConfig {
        enabled: true,
        observer_seconds: 0.0,
        ..d()
    }));
}

/// After a detected change (with the floor 0), with the strength then held at 0 (the cap at 0),
/// a continuing learner (`reset_adaptation`) keeps its controllers forgetting at
/// `controller_floor`: its command after the same sweep differs from the one with the floor 0.
/// A learner in its first training (no `reset_adaptation`) gives the same bits with either
/// floor.
#[test]
fn only_a_continuing_learner_keeps_its_controllers_forgetting() {
    let run = |floor: f64, continuing: bool| {
        let (mut learner, mut sim, _) = fixture::ready(fixture::config(), 200, 2000);
        let change: RobotChange = "payload=0.5".parse().unwrap();
        sim.set_model(change.apply(&robots::planar3()).unwrap())
            .unwrap();
        let cfg = |controller_floor| AdaptationConfig {
            enabled: true,
            controller_floor,
            ..AdaptationConfig::default()
        };
        learner.set_adaptation(cfg(0.0)).unwrap();
        if continuing {
            learner.reset_adaptation();
        }
        assert_eq!(learner.adaptation().continuation, continuing);
        learner.observe_offset(10.0);
        fixture::sweep(&mut learner, &mut sim, 500);
        assert!(learner.adaptation().detected);
        learner.adapt.cap = 0.0;
        learner.observe_offset(0.0);
        learner.set_adaptation(cfg(floor)).unwrap();
        let last = fixture::sweep(&mut learner, &mut sim, 1500);
        assert_eq!(learner.adaptation().strength, 0.0);
        let mut u = [0.0; 3];
        let xdd = [0.1, -0.2];
        learner
            .command::<rand_chacha::ChaCha8Rng>(
                last.q.as_slice(),
                last.qd.as_slice(),
                &xdd[..learner.m],
                None,
                &mut u,
            )
            .unwrap();
        u
    };
    assert_ne!(run(0.1, true), run(0.0, true));
    assert_eq!(run(0.1, false), run(0.0, false));
}
