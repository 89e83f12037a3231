//! Issue 27's small test: a family-trained planar3 controller beats a figure-8-only one of the
//! same training time on a held-out circle (drawn with the held-out seed): both its tracking and
//! its command nMSE there are below 3/4 of the figure-8-only controller's. Measured after 8
//! simulated minutes, seed 0: 0.328 mm / 0.107 against 0.566 mm / 0.206 (with the local dynamics
//! on differences, D23; before it, 0.22 mm / 0.37 against 1.35 mm / 0.62, when the tracking was
//! asserted below half and the nMSE, then closer, was not asserted).

use osrl_control::TrajectoryKind;
use osrl_experiments::family::held_out;
use osrl_experiments::Setup;
use osrl_learn::train::TrainConfig;

#[test]
fn a_family_trained_controller_beats_a_figure8_only_one_on_a_held_out_circle() {
    let base = Setup::new("planar3").unwrap();
    let train = TrainConfig {
        minutes: 8.0,
        eval_every_minutes: 0.0,
        ..TrainConfig::default()
    };
    let figure8 = base.clone().with_train(train.clone()).unwrap();
    let family = base
        .clone()
        .with_trajectory(base.family_config())
        .unwrap()
        .with_train(train)
        .unwrap();
    assert_eq!(family.home(), figure8.home());
    let paths = held_out(&base, 1).unwrap();
    let circle = paths
        .iter()
        .find(|p| p.config.kind == TrajectoryKind::Circle)
        .unwrap();
    let model = base.model().clone();
    let mut results = Vec::new();
    for setup in [&figure8, &family] {
        let (mut learner, summary) = setup.train(&model, &mut |_| {}).unwrap();
        assert_eq!(summary.aborted_episodes, 0);
        let e = setup.evaluate_path(&model, &mut learner, circle).unwrap();
        results.push((e, summary.paths_drawn));
    }
    let ((f8, drawn_f8), (fam, drawn_fam)) = (&results[0], &results[1]);
    assert_eq!(*drawn_f8, 0);
    assert!(*drawn_fam > 0);
    assert!(!fam.diverged);
    eprintln!(
        "held-out circle: family {:.3} mm / nMSE {:.4}, figure-8 only {:.3} mm / nMSE {:.4}",
        fam.tracking_rms_mm, fam.command_nmse, f8.tracking_rms_mm, f8.command_nmse
    );
    assert!(
        fam.tracking_rms_mm < 0.75 * f8.tracking_rms_mm
            && fam.command_nmse < 0.75 * f8.command_nmse,
        "family {:.3} mm / {:.4}, figure-8 only {:.3} mm / {:.4}",
        fam.tracking_rms_mm,
        fam.command_nmse,
        f8.tracking_rms_mm,
        f8.command_nmse
    );
}
