//! A learned controller on a path partly outside its trained fields (`docs/learner.md`, "Thin
//! support"; `docs/decisions.md`, D40): with the nearest trained controllers commanding there
//! (`controllers.neighbour_cutoff`, the default) it tracks a figure-8 moved 7 cm up from the one
//! it trained on several times better than with `u0` alone, whose PD pull to the rest posture
//! drags the arm off the path. On the trained path the option changes nothing. Measured with
//! `osrl eval --config` on planar3 controllers of 10 simulated minutes (seed 0): 0.46 mm against
//! 3.44 mm, support share 0.93 and 0.96.

use osrl_experiments::Setup;
use osrl_learn::train::TrainConfig;

#[test]
fn the_nearest_controllers_keep_tracking_where_the_path_leaves_the_fields() {
    let base = Setup::new("planar3").unwrap();
    let train = TrainConfig {
        minutes: 10.0,
        eval_every_minutes: 0.0,
        ..TrainConfig::default()
    };
    let mut off_cfg = base.learner_config().clone();
    off_cfg.controllers.neighbour_cutoff = 0.0;
    let on = base.clone().with_train(train.clone()).unwrap();
    let off = base
        .clone()
        .with_learner(off_cfg)
        .unwrap()
        .with_train(train)
        .unwrap();
    let mut moved = base.trajectory_config().clone();
    let c = base.profile().path.centre;
    moved.centre = Some([c[0], c[1], c[2] + 0.07]);
    let model = base.model().clone();
    let mut results = Vec::new();
    for setup in [&on, &off] {
        let (mut learner, summary) = setup.train(&model, &mut |_| {}).unwrap();
        assert_eq!(summary.aborted_episodes, 0);
        let own = setup
            .evaluator(&model)
            .unwrap()
            .evaluate(&mut learner)
            .unwrap();
        let away = setup.clone().with_trajectory(moved.clone()).unwrap();
        let e = away
            .evaluator(&model)
            .unwrap()
            .evaluate(&mut learner)
            .unwrap();
        results.push((own, e));
    }
    let ((own_on, on), (own_off, off)) = (&results[0], &results[1]);
    eprintln!(
        "moved figure-8: neighbours {:.3} mm / nMSE {:.4} (support {:.2}), u0 alone {:.3} mm / \
         nMSE {:.4} (support {:.2})",
        on.tracking_rms_mm,
        on.command_nmse,
        on.support_share,
        off.tracking_rms_mm,
        off.command_nmse,
        off.support_share
    );
    // On the trained path no command has thin support: the same run, bit for bit.
    assert_eq!(own_on.tracking_rms_mm, own_off.tracking_rms_mm);
    assert_eq!(own_on.command_nmse, own_off.command_nmse);
    // The moved path leaves the fields, and there the neighbours track far better.
    assert!(off.support_share < 1.0 && on.support_share < 1.0);
    assert!(
        !on.diverged && on.tracking_rms_mm < 1.0,
        "{:.3} mm",
        on.tracking_rms_mm
    );
    assert!(
        on.tracking_rms_mm < 0.5 * off.tracking_rms_mm,
        "neighbours {:.3} mm, u0 alone {:.3} mm",
        on.tracking_rms_mm,
        off.tracking_rms_mm
    );
}
