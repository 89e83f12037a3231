//! URDF export of a [`Model`].

use crate::inertia::Inertia;
use crate::model::{JointKind, Model};
use crate::spatial::matrix_to_rpy;
use nalgebra::{Matrix3, Vector3};
use std::fmt::Write;

/// Shortest decimal that parses back to the same `f64`.
fn num(x: f64) -> String {
    format!("{x:?}")
}

fn vec3(v: &Vector3<f64>) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

fn origin(xyz: &Vector3<f64>, rot: &Matrix3<f64>) -> String {
    let (r, p, y) = matrix_to_rpy(rot);
    format!(
        "<origin xyz=\"{}\" rpy=\"{} {} {}\"/>",
        vec3(xyz),
        num(r),
        num(p),
        num(y)
    )
}

/// A link with its `<inertial>` (centre of mass and inertia about it).
fn write_link(s: &mut String, l: &crate::model::Link) {
    let i = &l.inertia;
    let ic = i.inertia_com();
    let _ = writeln!(s, "  <link name=\"{}\">", l.name);
    let _ = writeln!(s, "    <inertial>");
    let _ = writeln!(
        s,
        "      <origin xyz=\"{}\" rpy=\"0 0 0\"/>",
        vec3(&i.com())
    );
    let _ = writeln!(s, "      <mass value=\"{}\"/>", num(i.mass));
    let _ = writeln!(
        s,
        "      <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>",
        num(ic[(0, 0)]),
        num(ic[(0, 1)]),
        num(ic[(0, 2)]),
        num(ic[(1, 1)]),
        num(ic[(1, 2)]),
        num(ic[(2, 2)])
    );
    let _ = writeln!(s, "    </inertial>");
    let _ = writeln!(s, "  </link>");
}

/// The model as a URDF document. Gravity is not part of URDF: the model's is assumed to be the
/// URDF convention (9.81 m/s² along −z). Postures and gains only with [`to_urdf_with_profile`];
/// task axes are found again by the loader. A model
/// with a link inertia that no rigid body has (identified base parameters) gets the element
/// `<osrl identified_inertias="true"/>`, so that it loads back.
pub fn to_urdf(model: &Model) -> String {
    to_urdf_with_profile(model, None)
}

/// As [`to_urdf`], with a robot profile written as an `<osrl_profile .../>` element (postures,
/// gains, torque limits, path placement; see [`crate::RobotProfile`]) that the loader reads back
/// into [`crate::UrdfImport::profile`].
pub fn to_urdf_with_profile(model: &Model, profile: Option<&crate::RobotProfile>) -> String {
    let spec = model.spec();
    let mut s = String::new();
    let _ = writeln!(s, "<?xml version=\"1.0\"?>");
    let _ = writeln!(s, "<!-- {} exported by osrl -->", spec.name);
    let _ = writeln!(s, "<robot name=\"{}\">", spec.name);
    let identified = spec.links.iter().any(|l| {
        Inertia::unphysical(&l.inertia.inertia_com(), l.inertia.inertia.trace().abs()).is_some()
    });
    if identified {
        // Identified base parameters: physical for the arm as a whole, not link by link.
        let _ = writeln!(s, "  <osrl identified_inertias=\"true\"/>");
    }
    if let Some(p) = profile {
        s.push_str(&super::profile_xml::write(p));
    }
    let _ = writeln!(s, "  <link name=\"base_link\"/>");
    let mut parent = "base_link".to_string();
    for l in &spec.links {
        write_link(&mut s, l);
        let lim = &l.limits;
        let limited = lim.q_min.is_finite() && lim.q_max.is_finite();
        let kind = match (l.kind, limited) {
            (JointKind::Revolute, true) => "revolute",
            (JointKind::Revolute, false) => "continuous",
            (JointKind::Prismatic, _) => "prismatic",
        };
        let _ = writeln!(s, "  <joint name=\"{}\" type=\"{kind}\">", l.joint_name);
        let _ = writeln!(s, "    <parent link=\"{parent}\"/>");
        let _ = writeln!(s, "    <child link=\"{}\"/>", l.name);
        let _ = writeln!(s, "    {}", origin(&l.origin.trans, &l.origin.rot));
        let _ = writeln!(s, "    <axis xyz=\"{}\"/>", vec3(&l.axis));
        let finite_or = |x: f64, d: f64| if x.is_finite() { x } else { d };
        let mut limit = format!(
            "effort=\"{}\" velocity=\"{}\"",
            num(finite_or(lim.tau_max, 1e6)),
            num(finite_or(lim.qd_max, 1e6))
        );
        if kind != "continuous" {
            // URDF has no unlimited prismatic joint: ±1e6 m stands for "no limit".
            limit = format!(
                "lower=\"{}\" upper=\"{}\" {limit}",
                num(finite_or(lim.q_min, -1e6)),
                num(finite_or(lim.q_max, 1e6))
            );
        }
        let _ = writeln!(s, "    <limit {limit}/>");
        let f = &l.friction;
        let _ = writeln!(
            s,
            "    <dynamics damping=\"{}\" friction=\"{}\"/>",
            num(f.viscous),
            num(f.coulomb)
        );
        let _ = writeln!(s, "  </joint>");
        parent = l.name.clone();
    }
    let _ = writeln!(s, "  <link name=\"ee_link\"/>");
    let _ = writeln!(s, "  <joint name=\"ee_joint\" type=\"fixed\">");
    let _ = writeln!(s, "    <parent link=\"{parent}\"/>");
    let _ = writeln!(s, "    <child link=\"ee_link\"/>");
    let _ = writeln!(s, "    {}", origin(&spec.ee_offset, &Matrix3::identity()));
    let _ = writeln!(s, "  </joint>");
    let _ = writeln!(s, "</robot>");
    s
}
