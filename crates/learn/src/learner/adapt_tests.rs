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
