//! URDF export → import round trips, and clear errors for malformed or unsupported files.

mod common;
use common::{models, rand_vec, rng};
use osrl_dynamics::urdf::{parse_urdf, parse_urdf_with, to_urdf, UrdfOptions};
use osrl_dynamics::{compute_all, DynamicsError};

#[test]
fn export_then_import_gives_the_same_dynamics() {
    let mut r = rng(31);
    for model in models() {
        let back = parse_urdf(&to_urdf(&model)).unwrap_or_else(|e| panic!("{}: {e}", model.name()));
        assert_eq!(back.nq(), model.nq());
        assert_eq!(back.task_axes(), model.task_axes(), "{}", model.name());
        let (mut d1, mut d2) = (model.data(), back.data());
        for _ in 0..10 {
            let q = rand_vec(&mut r, model.nq(), 2.0);
            let qd = rand_vec(&mut r, model.nq(), 2.0);
            compute_all(&model, &mut d1, &q, &qd).unwrap();
            compute_all(&back, &mut d2, &q, &qd).unwrap();
            let tol = 1e-12 * (1.0 + d1.h.amax() + d1.mass.amax());
            assert!((&d1.mass - &d2.mass).amax() < tol, "{} M", model.name());
            assert!((&d1.h - &d2.h).amax() < tol, "{} h", model.name());
            assert!((&d1.jac - &d2.jac).amax() < 1e-12 && (d1.ee_pos - d2.ee_pos).amax() < 1e-12);
        }
        for (a, b) in model.links().iter().zip(back.links()) {
            assert_eq!(a.limits.q_min, b.limits.q_min);
            if a.limits.tau_max.is_finite() {
                assert_eq!(a.limits.tau_max, b.limits.tau_max);
            }
            assert_eq!(a.friction.viscous, b.friction.viscous);
        }
    }
}

fn urdf_error(text: &str) -> String {
    match parse_urdf(text) {
        Err(DynamicsError::Urdf(m)) => m,
        Err(other) => panic!("expected a URDF error, got {other}"),
        Ok(_) => panic!("expected an error for:\n{text}"),
    }
}

const LINKS: &str = r#"<link name="base"/><link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link><link name="b"/>"#;

/// A robot with links base, a, b; `joints` must attach a and b.
fn robot(joints: &str) -> String {
    format!("<robot name=\"t\">{LINKS}{joints}</robot>")
}

const FIXED_B: &str =
    r#"<joint name="jb" type="fixed"><parent link="a"/><child link="b"/></joint>"#;

#[test]
fn malformed_and_unsupported_files_name_the_element() {
    assert!(urdf_error("<robot><link name=").contains("malformed XML"));
    assert!(urdf_error("<model/>").contains("expected <robot>"));
    let m = urdf_error(&robot(
        r#"<joint name="j1" type="ball"><parent link="base"/><child link="a"/></joint>"#,
    ));
    assert!(m.contains("j1") && m.contains("ball"), "{m}");
    // A floating joint on the chain to the tip.
    let floating = robot(
        r#"<joint name="j1" type="floating"><parent link="base"/><child link="a"/></joint><joint name="j2" type="continuous"><parent link="a"/><child link="b"/></joint>"#,
    );
    let tip_a = UrdfOptions {
        tip: Some("b".into()),
        ..UrdfOptions::default()
    };
    match parse_urdf_with(&floating, &tip_a) {
        Err(DynamicsError::Urdf(m)) => assert!(m.contains("j1") && m.contains("floating"), "{m}"),
        other => panic!("expected an error, got {other:?}"),
    }
    let m = urdf_error(
        &robot(
            r#"<joint name="j1" type="revolute"><parent link="base"/><child link="a"/></joint>"#,
        )
        .replace("</robot>", &format!("{FIXED_B}</robot>")),
    );
    assert!(m.contains("j1") && m.contains("<limit>"), "{m}");
    let m = urdf_error(&robot(
        r#"<joint name="j1" type="continuous"><parent link="base"/><child link="zz"/></joint>"#,
    ));
    assert!(m.contains("j1") && m.contains("zz"), "{m}");
    let m = urdf_error(&robot(
        r#"<joint name="j1" type="continuous"><parent link="base"/><child link="a"/><origin xyz="1 nope 0"/></joint><joint name="j2" type="continuous"><parent link="a"/><child link="b"/></joint>"#,
    ));
    assert!(m.contains("j1") && m.contains("xyz"), "{m}");
    // Two arms from the base: no guess, unless the tip is given (the other arm is locked).
    let two = robot(
        r#"<joint name="j1" type="continuous"><parent link="base"/><child link="a"/></joint><joint name="j2" type="continuous"><parent link="base"/><child link="b"/></joint>"#,
    );
    let m = urdf_error(&two);
    assert!(
        m.contains("j1") && m.contains("j2") && m.contains("tip option"),
        "{m}"
    );
    let tip_a = UrdfOptions {
        tip: Some("a".into()),
        ..UrdfOptions::default()
    };
    let model = parse_urdf_with(&two, &tip_a).unwrap();
    let locked = &model.spec().urdf.as_ref().unwrap().locked;
    assert_eq!((model.nq(), locked[0].name.as_str()), (1, "j2"));
    let m = urdf_error(&robot(
        r#"<joint name="j1" type="continuous"><parent link="base"/><child link="a"/></joint>"#,
    ));
    assert!(m.contains("root"), "two roots (b is unattached): {m}");
}

#[test]
fn fixed_joints_are_folded_into_their_parent() {
    // A continuous joint, then a fixed joint carrying a 2 kg point mass 0.5 m along x: the same as
    // one link with that mass, and the end-effector at the fixed link's origin.
    let text = r#"<robot name="t">
      <link name="base"/>
      <link name="a"/>
      <link name="tip"><inertial><mass value="2"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
      <joint name="j" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint>
      <joint name="f" type="fixed"><parent link="a"/><child link="tip"/><origin xyz="0.5 0 0"/></joint>
    </robot>"#;
    // No link is named like an end-effector: the tip is the link the last joint moves, 'a'.
    let model = parse_urdf(text).unwrap();
    assert_eq!(model.spec().urdf.as_ref().unwrap().tip, "a");
    assert_eq!(model.spec().ee_offset, nalgebra::Vector3::zeros());
    let tip = UrdfOptions {
        tip: Some("tip".into()),
        ..UrdfOptions::default()
    };
    let model = parse_urdf_with(text, &tip).unwrap();
    assert_eq!(model.nq(), 1);
    assert_eq!(model.task_axes(), &[0, 1]);
    let mut data = model.data();
    let m = osrl_dynamics::crba(&model, &mut data, &[0.3]).unwrap();
    assert!((m[(0, 0)] - 2.0 * 0.25).abs() < 1e-12);
    osrl_dynamics::forward_kinematics(&model, &mut data, &[0.0]).unwrap();
    assert!((data.ee_pos.x - 0.5).abs() < 1e-12);
}

/// A point mass whose zero inertia carries round-off in a product (iCub's `head`: `ixz`
/// 2.4e-35, every other entry 0; principal moments ±2.4e-35 about a trace of 0) loads as the
/// point mass it is; an impossible inertia is still refused, naming the link.
#[test]
fn round_off_in_a_point_mass_is_accepted_and_impossible_inertias_refused() {
    let arm = |inertia: &str| {
        format!(
            r#"<robot name="t"><link name="base"/>
      <link name="head"><inertial><mass value="1.33687"/><origin xyz="0.0185 -0.1108 0"/><inertia {inertia}/></inertial></link>
      <joint name="j" type="continuous"><parent link="base"/><child link="head"/><axis xyz="0 0 1"/></joint>
    </robot>"#
        )
    };
    let model = parse_urdf(&arm(
        r#"ixx="0" ixy="0" ixz="2.40741e-35" iyy="0" iyz="0" izz="0""#,
    ))
    .unwrap();
    let mut data = model.data();
    let m = osrl_dynamics::crba(&model, &mut data, &[0.0]).unwrap();
    let r2 = 0.0185f64.powi(2) + 0.1108f64.powi(2);
    assert!((m[(0, 0)] - 1.33687 * r2).abs() < 1e-12, "{}", m[(0, 0)]);
    let m = urdf_error(&arm(
        r#"ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="-1e-9""#,
    ));
    assert!(
        m.contains("'head'") && m.contains("positive semi-definite"),
        "{m}"
    );
    let m = urdf_error(&arm(
        r#"ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.3""#,
    ));
    assert!(
        m.contains("'head'") && m.contains("triangle inequality"),
        "{m}"
    );
}

/// Huge but finite geometry and masses are refused naming the link, instead of loading and
/// then giving an infinite mass matrix.
#[test]
fn huge_lengths_and_masses_are_refused_by_link() {
    let text = std::fs::read_to_string("tests/fixtures/planar3.urdf").unwrap();
    osrl_dynamics::urdf::parse_urdf(&text).unwrap();
    let far = text.replacen(
        r#"<origin xyz="0.4 0.0 0.0""#,
        r#"<origin xyz="1e200 0.0 0.0""#,
        1,
    );
    let heavy = text.replacen(r#"<mass value="2.5"/>"#, r#"<mass value="1e300"/>"#, 1);
    for (t, want) in [(far, "elbow_link"), (heavy, "shoulder_link")] {
        assert_ne!(t, text);
        let e = match parse_urdf(&t) {
            Err(e) => e.to_string(),
            Ok(m) => panic!("loaded {}", m.name()),
        };
        assert!(e.contains(want) && e.contains("beyond"), "{e}");
    }
}
