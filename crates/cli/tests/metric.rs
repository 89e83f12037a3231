//! The robot profile's cost metric end to end: `osrl robot` prints it with the sweep, `osrl
//! train` with defaults learns the UR5 in `N = M⁻¹`, the saved model carries the estimated `N`,
//! and `osrl eval` of the saved model gives the training's own last evaluation (the same `u*`,
//! eq. 7 with `N = M⁻¹` on the profiled arm).

mod common;
use common::{last_json, osrl};

fn ur5() -> String {
    format!(
        "{}/../dynamics/tests/fixtures/example-robot-data/ur5_robot.urdf",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn the_ur5_trains_in_its_profiles_metric_and_eval_of_the_saved_model_agrees() {
    let (ok, out, err) = osrl(&["robot", "--robot", &ur5(), "--json"]);
    assert!(ok, "{err}");
    let r = last_json(&out);
    assert_eq!(r["profile"]["metric"], "inverse_inertia", "{r}");
    assert_eq!(r["profile"]["joint_sweep"].as_array().unwrap().len(), 6);
    let dir = std::env::temp_dir().join(format!("osrl-metric-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("ur5.osrl");
    let m = model.to_str().unwrap();
    let args = [
        "train",
        "--robot",
        &ur5(),
        "--minutes",
        "0.4",
        "--seed",
        "1",
    ];
    let (ok, out, err) = osrl(&[&args[..], &["--out", m, "--json"]].concat());
    assert!(ok, "{err}");
    let t = last_json(&out);
    let saved = osrl_learn::SavedModel::load(&model).unwrap();
    let cfg = saved.learner().config();
    assert_eq!(
        cfg.controllers.metric,
        Some(osrl_learn::CostMetric::InverseInertia)
    );
    assert_eq!(saved.learner().cost_metric().map(|n| n.len()), Some(36));
    let (ok, out, err) = osrl(&["eval", "--model", m, "--json"]);
    assert!(ok, "{err}");
    let e = last_json(&out);
    for k in ["tracking_rms_mm", "command_nmse"] {
        assert!(t[k].as_f64().unwrap().is_finite(), "{k}: {t}");
        assert_eq!(e[k], t[k], "{k}: eval {e} vs train {t}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
