//! Hostile sizes (issue 30): deep and large files load in linear time without recursion, and
//! files beyond the documented limits are refused with an error saying which limit.

use osrl_dynamics::urdf::{parse_urdf, parse_urdf_with, UrdfOptions, MAX_LINKS, MAX_URDF_BYTES};
use osrl_dynamics::{DynamicsError, MAX_DOF};
use std::fmt::Write;

const MASS: &str = r#"<inertial><mass value="0.01"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>"#;

/// One revolute joint from `base` to `l0`, then `n` links `l1..=ln`, each on a joint of type
/// `kind` below the previous one (a chain `n` deep), 1 cm apart.
fn chain(n: usize, kind: &str) -> String {
    let mut s = String::from(r#"<robot name="deep"><link name="base"/>"#);
    for i in 0..=n {
        let _ = write!(s, r#"<link name="l{i}">{MASS}</link>"#);
    }
    s.push_str(r#"<joint name="j0" type="revolute"><parent link="base"/><child link="l0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"#);
    for i in 1..=n {
        let _ = write!(
            s,
            r#"<joint name="j{i}" type="{kind}"><parent link="l{}"/><child link="l{i}"/><origin xyz="0.01 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"#,
            i - 1
        );
    }
    s.push_str("</robot>");
    s
}

fn urdf_error(text: &str) -> String {
    match parse_urdf(text) {
        Err(DynamicsError::Urdf(m)) => m,
        other => panic!("expected a URDF error, got {other:?}"),
    }
}

#[test]
fn twelve_thousand_nested_fixed_joints_load_without_stack_overflow() {
    let text = chain(12_000, "fixed");
    assert!(text.len() > 1_500_000);
    let tip = UrdfOptions {
        tip: Some("l12000".into()),
        ..UrdfOptions::default()
    };
    let model = parse_urdf_with(&text, &tip).unwrap();
    assert_eq!(model.nq(), 1);
    // All 12,001 links lumped into the one body; the tip 120 m out along x.
    let i = &model.links()[0].inertia;
    assert!((i.mass - 0.01 * 12_001.0).abs() < 1e-9, "{}", i.mass);
    assert!((model.spec().ee_offset.x - 120.0).abs() < 1e-9);
}

/// Almost 100,000 links (≈ 9 MB, below the limits) on fixed joints, listed in reverse so that
/// no scan finds a parent early: linear loading takes about a second; any quadratic scan over
/// links or joints (10¹⁰ steps) would take many minutes.
#[test]
fn a_large_file_of_fixed_links_loads_in_linear_time() {
    let n = MAX_LINKS - 2;
    let mut text = String::from(r#"<robot name="wide"><link name="base"/>"#);
    text.push_str(r#"<link name="l0"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>"#);
    text.push_str(
        r#"<joint name="j0" type="continuous"><parent link="base"/><child link="l0"/></joint>"#,
    );
    for i in (1..=n).rev() {
        let _ = write!(
            text,
            r#"<link name="l{i}"/><joint name="j{i}" type="fixed"><parent link="l{}"/><child link="l{i}"/></joint>"#,
            i - 1
        );
    }
    text.push_str("</robot>");
    assert!(text.len() < MAX_URDF_BYTES);
    let tip = UrdfOptions {
        tip: Some("l1".into()),
        ..UrdfOptions::default()
    };
    let model = parse_urdf_with(&text, &tip).unwrap();
    assert_eq!(model.nq(), 1);
    assert_eq!(model.links()[0].inertia.mass, 1.0);
}

#[test]
fn files_beyond_the_limits_are_refused_naming_the_limit() {
    // Bytes: checked before parsing.
    let mut text = chain(1, "fixed");
    text.push_str(&" ".repeat(MAX_URDF_BYTES));
    let m = urdf_error(&text);
    assert!(
        m.contains("bytes") && m.contains(&MAX_URDF_BYTES.to_string()),
        "{m}"
    );
    // Links.
    let mut many = String::from("<robot name=\"t\">");
    for i in 0..=MAX_LINKS {
        let _ = write!(many, "<link name=\"{i}\"/>");
    }
    many.push_str("</robot>");
    let m = urdf_error(&many);
    assert!(
        m.contains("links") && m.contains(&MAX_LINKS.to_string()),
        "{m}"
    );
    // Degrees of freedom: a chain of revolute joints longer than the model accepts.
    let m = urdf_error(&chain(MAX_DOF + 5, "revolute"));
    assert!(
        m.contains("degrees of freedom") && m.contains(&MAX_DOF.to_string()),
        "{m}"
    );
    // A cycle of joints is named, not followed for ever.
    let cycle = r#"<robot name="c"><link name="base"/><link name="a"/><link name="b"/>
      <joint name="r" type="fixed"><parent link="base"/><child link="a"/></joint>
      <joint name="x" type="fixed"><parent link="a"/><child link="b"/></joint>
      <joint name="y" type="fixed"><parent link="b"/><child link="a"/></joint></robot>"#;
    let m = urdf_error(cycle);
    assert!(m.contains("'a'"), "{m}");
}
