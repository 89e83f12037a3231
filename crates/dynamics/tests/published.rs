//! Published arms, as published: the URDFs of `example-robot-data` 6.0.0 (copied unchanged to
//! `fixtures/example-robot-data/`, licences alongside) load with the documented rules, and their
//! dynamics agree with Pinocchio's on the original files (reduced there with `buildReducedModel`
//! to the same degrees of freedom, the other joints locked at the same positions) to 1e-9 at 100
//! random states. Fixtures: `scripts/pinocchio_fixtures.py published`.

mod common;
use common::{against_pinocchio, PINOCCHIO_QUANTITIES};
use osrl_dynamics::urdf::{load_urdf_with, UrdfOptions};
use osrl_dynamics::DynamicsError;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::PathBuf;

const ARMS: [&str; 13] = [
    "panda",
    "ur3",
    "ur5",
    "ur10",
    "jaco2",
    "xarm7",
    "z1",
    "so100",
    "so101",
    "talos_left_arm",
    "tiago",
    "baxter",
    "twodofs",
];

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/example-robot-data")
}

fn fixture(arm: &str) -> Value {
    let text =
        std::fs::read_to_string(dir().join(format!("{arm}.pinocchio.json"))).expect("fixture JSON");
    serde_json::from_str(&text).expect("fixture JSON parses")
}

/// Loads one arm as its fixture says and checks the loader's choices against the fixture's.
fn load(arm: &str, fx: &Value) -> osrl_dynamics::Model {
    let opts = UrdfOptions {
        tip: fx["tip_option"].as_str().map(String::from),
        ..UrdfOptions::default()
    };
    let file = dir().join(fx["file"].as_str().unwrap());
    let model = load_urdf_with(&file, &opts).unwrap_or_else(|e| panic!("{arm}: {e}"));
    let import = model
        .spec()
        .urdf
        .clone()
        .expect("a URDF model reports its choices");
    assert_eq!(import.tip, fx["tip"].as_str().unwrap(), "{arm}: tip");
    let dof: Vec<&str> = model
        .links()
        .iter()
        .map(|l| l.joint_name.as_str())
        .collect();
    let want: Vec<&str> = fx["dof"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(dof, want, "{arm}: degrees of freedom");
    let locked: BTreeMap<String, f64> = import
        .locked
        .iter()
        .map(|l| (l.name.clone(), l.value))
        .collect();
    let want: BTreeMap<String, f64> = fx["locked"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| (k.clone(), v.as_f64().unwrap()))
        .collect();
    assert_eq!(locked, want, "{arm}: locked joints");
    model
}

#[test]
fn published_arms_load_and_agree_with_pinocchio() {
    eprintln!("| arm | DOF | tip (rule) | locked | max rel. error vs Pinocchio (M, g, RNEA, ABA, x/J, J̇q̇) |");
    for arm in ARMS {
        let fx = fixture(arm);
        let model = load(arm, &fx);
        let worst = against_pinocchio(&model, &fx);
        let import = model.spec().urdf.clone().unwrap();
        let max = worst.iter().fold(0.0f64, |m, &w| m.max(w));
        eprintln!(
            "| {arm} | {} | {} ({}) | {} | {max:.1e} |",
            model.nq(),
            import.tip,
            import.tip_rule,
            import.locked.len()
        );
        for (name, w) in PINOCCHIO_QUANTITIES.iter().zip(worst) {
            assert!(
                w <= 1e-9,
                "{arm}: {name} differs from Pinocchio by {w:e} (relative)"
            );
        }
    }
}

#[test]
fn panda_fingers_are_locked_and_lumped_into_the_hand() {
    let fx = fixture("panda");
    let model = load("panda", &fx);
    let import = model.spec().urdf.as_ref().unwrap();
    let reasons: Vec<(&str, &str)> = import
        .locked
        .iter()
        .map(|l| (l.name.as_str(), l.reason.as_str()))
        .collect();
    assert_eq!(
        reasons,
        [
            ("panda_finger_joint1", "finger/gripper name"),
            ("panda_finger_joint2", "mimics 'panda_finger_joint1'")
        ]
    );
    // The last body carries link7, the hand (0.73 kg) and both fingers (0.015 kg each).
    let last = &model.links()[6].inertia;
    assert!(
        (last.mass - (0.735522 + 0.73 + 0.03)).abs() < 1e-12,
        "{}",
        last.mass
    );
    // Opening the fingers moves mass but keeps the total.
    let opts = UrdfOptions {
        lock: vec![("panda_finger_joint1".into(), Some(0.04))],
        ..UrdfOptions::default()
    };
    let open = load_urdf_with(&dir().join("panda.urdf"), &opts).unwrap();
    let locked = &open.spec().urdf.as_ref().unwrap().locked;
    assert_eq!((locked[0].value, locked[1].value), (0.04, 0.04));
    let lumped = &open.links()[6].inertia;
    assert!((lumped.mass - last.mass).abs() < 1e-15);
    assert!(
        (lumped.inertia - last.inertia).amax() > 1e-6,
        "the fingers moved"
    );
}

fn urdf_error(file: &str, opts: &UrdfOptions) -> String {
    match load_urdf_with(&dir().join(file), opts) {
        Err(DynamicsError::Urdf(m)) => m,
        other => panic!("{file}: expected a URDF error, got {other:?}"),
    }
}

#[test]
fn published_files_that_cannot_be_used_are_refused_with_the_reason() {
    let m = urdf_error("double_pendulum.urdf", &UrdfOptions::default());
    assert!(
        m.contains("double_pendulum.urdf") && m.contains("joint1") && m.contains("effort"),
        "{m}"
    );
    let m = urdf_error("finger_edu.urdf", &UrdfOptions::default());
    assert!(m.contains("gripper") && m.contains("unlock"), "{m}");
    // Named as the arm, with its joints unlocked, the finger loads.
    let opts = UrdfOptions {
        tip: Some("finger_tip_link".into()),
        unlock: vec![
            "finger_base_to_upper_joint".into(),
            "finger_upper_to_middle_joint".into(),
            "finger_middle_to_lower_joint".into(),
        ],
        ..UrdfOptions::default()
    };
    let model = load_urdf_with(&dir().join("finger_edu.urdf"), &opts).unwrap();
    assert_eq!(model.nq(), 3);
    // Baxter has two arms: the default rule does not guess between them.
    let m = urdf_error("baxter.urdf", &UrdfOptions::default());
    assert!(m.contains("tip option"), "{m}");
    // A mimic joint cannot follow a moving leader.
    let opts = UrdfOptions {
        tip: Some("panda_leftfinger".into()),
        unlock: vec!["panda_finger_joint1".into()],
        ..UrdfOptions::default()
    };
    let m = urdf_error("panda.urdf", &opts);
    assert!(
        m.contains("panda_finger_joint2") && m.contains("mimics"),
        "{m}"
    );
}
