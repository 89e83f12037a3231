//! A ball joint written as three revolute joints on massless links has a gimbal lock where its
//! mass matrix is singular; the simulator refuses a model whose limits reach it, naming the
//! joints and the angle, instead of diverging (issue 28: the `human` URDF of example-robot-data
//! crashed `osrl train` with "joint state is not finite" at t = 246 s, its right shoulder at
//! `right_shoulder_X` = 1.46–1.48 rad, near the lock at π/2).

use osrl_dynamics::gimbal::gimbals;
use osrl_dynamics::urdf::{load_urdf_with, parse_urdf, UrdfOptions};
use osrl_dynamics::{crba, Model, Robot, SimConfig, SimRobot};
use std::f64::consts::FRAC_PI_2;

fn dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/example-robot-data")
}

/// A shoulder as the human URDF writes it: Z, then X, then Y about one point, the first two
/// links massless, an upper arm of 2 kg below; the X joint's limits are `[-1, x_max]`.
fn shoulder(x_max: f64) -> Model {
    let joint = |name: &str, parent: &str, child: &str, axis: &str, lo: f64, hi: f64| {
        format!(
            r#"<joint name="{name}" type="revolute"><origin xyz="0 0 0"/><axis xyz="{axis}"/>
               <parent link="{parent}"/><child link="{child}"/>
               <limit effort="50" velocity="5" lower="{lo}" upper="{hi}"/></joint>"#
        )
    };
    let text = format!(
        r#"<robot name="shoulder"><link name="base"/><link name="v1"/><link name="v2"/>
           <link name="upperarm"><inertial><mass value="2"/><origin xyz="0 -0.15 0"/>
           <inertia ixx="0.02" iyy="0.003" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>
           <link name="tool"/>
           <joint name="tip" type="fixed"><origin xyz="0 -0.3 0"/><parent link="upperarm"/>
           <child link="tool"/></joint>
           {}{}{}</robot>"#,
        joint("sz", "base", "v1", "0 0 1", -3.0, 3.0),
        joint("sx", "v1", "v2", "-1 0 0", -1.0, x_max),
        joint("sy", "v2", "upperarm", "0 1 0", -1.5, 3.0),
    );
    parse_urdf(&text).unwrap()
}

#[test]
fn the_gimbal_lock_is_found_in_closed_form_and_the_mass_matrix_is_singular_there() {
    let model = shoulder(3.0);
    let found = gimbals(&model);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].joints, [0, 1, 2]);
    // Within [-1, 3] only +π/2 (−π/2 is below the lower limit).
    assert_eq!(found[0].singular_at.len(), 1);
    assert!((found[0].singular_at[0] - FRAC_PI_2).abs() < 1e-12);
    // M's smallest eigenvalue: 0 at the lock, growing as the square of the distance from it.
    let mut data = model.data();
    let mut lmin = |x: f64| {
        let m = crba(&model, &mut data, &[0.3, x, 0.7]).unwrap().clone();
        m.symmetric_eigen().eigenvalues.min()
    };
    assert!(lmin(FRAC_PI_2).abs() < 1e-12);
    let (far, near) = (lmin(FRAC_PI_2 - 0.02), lmin(FRAC_PI_2 - 0.01));
    assert!((far / near - 4.0).abs() < 0.1, "{far} / {near}");
}

#[test]
fn a_gimbal_inside_the_limits_is_refused_and_one_outside_is_simulated() {
    let err = SimRobot::new(shoulder(3.0), SimConfig::default())
        .err()
        .expect("refused")
        .to_string();
    for word in ["'sz'", "'sx'", "'sy'", "1.5708", "gimbal lock", "<limit>"] {
        assert!(err.contains(word), "{word} in {err}");
    }
    // Limits that stop the X joint short of the lock: accepted, and a second of a held
    // command at the limit stays finite.
    let model = shoulder(1.2);
    assert!(gimbals(&model).is_empty());
    let mut sim = SimRobot::new(model, SimConfig::default()).unwrap();
    for _ in 0..500 {
        sim.step(&[2.0, 10.0, -1.0]).unwrap();
    }
    assert!(sim.measurement().q[1] <= 1.2 + 1e-12);
}

#[test]
fn the_published_human_is_refused_naming_its_right_shoulder() {
    let opts = UrdfOptions {
        tip: Some("right_hand".into()),
        ..UrdfOptions::default()
    };
    let model = load_urdf_with(&dir().join("human.urdf"), &opts).unwrap();
    let err = SimRobot::new(model.clone(), SimConfig::default())
        .err()
        .expect("the human's right shoulder reaches its gimbal lock")
        .to_string();
    for word in [
        "right_shoulder_Z",
        "right_shoulder_X",
        "right_shoulder_Y",
        "1.5708",
    ] {
        assert!(err.contains(word), "{word} in {err}");
    }
    // Locking the middle joint removes the lock: the arm is simulated.
    let mut opts = opts;
    opts.push_lock("right_shoulder_X=1.0").unwrap();
    let locked = load_urdf_with(&dir().join("human.urdf"), &opts).unwrap();
    assert_eq!(locked.nq(), model.nq() - 1);
    assert!(gimbals(&locked).is_empty());
    SimRobot::new(locked, SimConfig::default()).unwrap();
}

#[test]
fn no_published_arm_of_the_fixtures_has_a_gimbal() {
    for (file, tip) in [
        ("panda.urdf", None),
        ("ur5_robot.urdf", None),
        ("kinova.urdf", None),
        ("talos_left_arm.urdf", None),
        ("baxter.urdf", Some("right_gripper")),
        ("so101.urdf", None),
    ] {
        let opts = UrdfOptions {
            tip: tip.map(String::from),
            ..UrdfOptions::default()
        };
        let model = load_urdf_with(&dir().join(file), &opts).unwrap();
        assert!(gimbals(&model).is_empty(), "{file}");
    }
}
