//! Cross-check against Pinocchio: fixtures made by `scripts/pinocchio_fixtures.py` from the URDF
//! that `osrl robot --urdf` exports (built-in robots) or that the `export_urdf` example writes
//! (random arms mixing revolute and prismatic joints), committed next to them; 100 random states
//! per robot. The published arms are in `published.rs`.

mod common;
use common::{against_pinocchio, PINOCCHIO_QUANTITIES};
use osrl_dynamics::{robots, urdf::to_urdf, Model};
use serde_json::Value;
use std::path::PathBuf;

fn fixtures(robot: &str) -> (String, Value) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let urdf = std::fs::read_to_string(dir.join(format!("{robot}.urdf"))).expect("fixture URDF");
    let json =
        std::fs::read_to_string(dir.join(format!("{robot}.pinocchio.json"))).expect("fixture JSON");
    (
        urdf,
        serde_json::from_str(&json).expect("fixture JSON parses"),
    )
}

fn check(model: Model) {
    let (urdf, fx) = fixtures(model.name());
    assert_eq!(
        to_urdf(&model),
        urdf,
        "{}: the exported URDF changed; rerun scripts/pinocchio_fixtures.py",
        model.name()
    );
    let worst = against_pinocchio(&model, &fx);
    eprintln!(
        "{} vs Pinocchio, worst relative difference: {:?}",
        model.name(),
        PINOCCHIO_QUANTITIES.iter().zip(worst).collect::<Vec<_>>()
    );
    for (name, w) in PINOCCHIO_QUANTITIES.iter().zip(worst) {
        assert!(
            w <= 1e-9,
            "{}: {name} differs from Pinocchio by {w:e} (relative)",
            model.name()
        );
    }
}

#[test]
fn planar3_agrees_with_pinocchio() {
    check(robots::planar3());
}

#[test]
fn sarcos7_agrees_with_pinocchio() {
    check(robots::sarcos7());
}

#[test]
fn arms_with_prismatic_joints_agree_with_pinocchio() {
    check(robots::random_mixed_arm(7, 3, true));
    check(robots::random_mixed_arm(4, 8, true));
}
