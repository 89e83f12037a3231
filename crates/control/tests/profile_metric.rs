//! The learner's cost metric chosen by the robot profile (`osrl_control::profile::metric_rule`):
//! the built-in arms keep `N = I`, the UR5 and the Panda, whose wrists eq. 7 with `N = I` turns
//! through more than a radian along their default paths, get `inverse_inertia`; a given
//! `metric` wins.

use osrl_control::profile::{
    load_robot, metric_rule, resolve, CostMetric, Source, METRIC_SWEEP_BOUND,
};
use osrl_dynamics::{robots, RobotProfile};

fn fixture(file: &str) -> String {
    format!(
        "{}/../dynamics/tests/fixtures/example-robot-data/{file}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn the_rule_compares_the_largest_sweep_with_the_bound() {
    assert_eq!(
        metric_rule(&[0.2, METRIC_SWEEP_BOUND]),
        CostMetric::Identity
    );
    assert_eq!(
        metric_rule(&[0.2, METRIC_SWEEP_BOUND * 1.01]),
        CostMetric::InverseInertia
    );
    assert_eq!(metric_rule(&[f64::NAN]), CostMetric::InverseInertia);
}

#[test]
fn built_in_arms_keep_the_identity_and_the_published_arms_get_the_inverse_inertia() {
    for model in [robots::planar3(), robots::sarcos7()] {
        let p = resolve(&model, &RobotProfile::default()).unwrap().profile;
        let sweep = p.joint_sweep.expect("simulated");
        assert_eq!(sweep.len(), model.nq());
        let max = sweep.iter().cloned().fold(0.0, f64::max);
        assert!(max > 0.05 && max <= METRIC_SWEEP_BOUND, "{sweep:?}");
        assert_eq!(p.metric, CostMetric::Identity, "{}", model.name());
        assert_eq!(p.sources["metric"], Source::Computed);
    }
    // The last joint of both: its Jacobian column is 0, so N = I spins it (D27).
    for file in ["ur5_robot.urdf", "panda.urdf"] {
        let given = RobotProfile::default();
        let model = load_robot(&fixture(file), &given).unwrap();
        let p = resolve(&model, &given).unwrap().profile;
        let sweep = p.joint_sweep.expect("simulated");
        assert!(
            sweep[model.nq() - 1] > 2.0 * METRIC_SWEEP_BOUND,
            "{file}: {sweep:?}"
        );
        assert_eq!(p.metric, CostMetric::InverseInertia, "{file}");
        // Given, it wins and is reported as given.
        let given: RobotProfile = serde_json::from_str(r#"{"metric": "identity"}"#).unwrap();
        let p = resolve(&model, &given).unwrap().profile;
        assert_eq!(p.metric, CostMetric::Identity, "{file}");
        assert_eq!(p.sources["metric"], Source::Given);
    }
}
