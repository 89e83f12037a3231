//! `sarcos7`: the SARCOS Master Arm with its identified parameters (`docs/robots.md`).

use crate::inertia::Inertia;
use crate::model::{Friction, JointKind, JointLimits, Link, Model, ModelSpec, GRAVITY};
use crate::spatial::{axis_angle, Pose};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

const L0: f64 = 0.4;
const L1: f64 = 0.0381;
const L2: f64 = 0.287;
const L3: f64 = 0.0025;
const L4: f64 = 0.2781;
const L5: f64 = 0.0081;

/// Per joint: name, translation in the parent frame, fixed rotation `Rx(a) Ry(b) Rz(c)`.
fn frames() -> [(&'static str, [f64; 3], [f64; 3]); 7] {
    let s = FRAC_PI_4.sin();
    [
        ("SFE", [L0 * s, 0.0, L0 * s], [0.0, FRAC_PI_4, 0.0]),
        ("SAA", [0.0, 0.0, 0.0], [-FRAC_PI_2, 0.0, FRAC_PI_4]),
        ("HR", [0.0, -L1, 0.0], [0.0, FRAC_PI_2, 0.0]),
        ("EB", [0.0, 0.0, L2], [FRAC_PI_2, 0.0, -FRAC_PI_2]),
        ("WR", [0.0, 0.0, -L3], [0.0, -FRAC_PI_2, 0.0]),
        ("WFE", [0.0, 0.0, L4], [-FRAC_PI_2, 0.0, 0.0]),
        ("WAA", [0.0, 0.0, L5], [0.0, FRAC_PI_2, PI]),
    ]
}

/// Identified inertial parameters per link: m, mcm (x, y, z), I11, I12, I13, I22, I23, I33 (about
/// the frame origin), viscous friction.
const INERTIAL: [[f64; 11]; 7] = [
    [
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.000118, 0.000004,
    ],
    [
        0.0, 0.0, 0.0, 0.0, 0.002120, -0.001411, 0.000405, 0.001061, -0.000297, 0.000096, 0.001393,
    ],
    [
        0.001015, -0.000006, -0.000020, 0.000001, 0.000167, -0.000061, -0.001712, 0.000263,
        0.001618, 0.031939, 0.0,
    ],
    [
        0.184753, 0.004733, -0.028430, 0.031864, 0.009976, 0.000323, -0.000886, 0.007213, 0.005136,
        0.004646, 0.000008,
    ],
    [
        3.357057, 0.139895, 0.111372, 0.192788, 0.038183, -0.004881, 0.000878, 0.016913, -0.006484,
        0.012918, 0.000779,
    ],
    [
        1.339042, 0.068897, -0.033112, 0.036859, 0.001855, 0.001716, -0.001769, 0.004567, 0.001081,
        0.014714, 0.000579,
    ],
    [
        0.895628, -0.046017, 0.070786, 0.026518, 0.007859, 0.003288, -0.001617, 0.003268,
        -0.001317, 0.014124, 0.000539,
    ],
];

/// Joint limits (rad), rest posture (rad), PD gains Kp (N·m/rad), Kd (N·m·s/rad).
const JOINTS: [[f64; 5]; 7] = [
    [-0.447280, 1.370363, 0.0, 40.0, 6.0],
    [-1.288088, 0.184510, -0.4, 40.0, 4.0],
    [-1.570548, 1.384645, 0.0, 30.0, 2.0],
    [0.586132, 2.208897, 1.57, 30.0, 2.0],
    [-1.462808, 1.539668, 0.0, 20.0, 0.5],
    [-0.766664, 0.876223, 0.0, 10.0, 0.4],
    [-0.648700, 0.762463, 0.0, 8.0, 0.35],
];

/// The 7-DOF SARCOS Master Arm: 3-DOF shoulder (SFE, SAA, HR), elbow (EB), 3-DOF wrist (WR, WFE,
/// WAA); identified base parameters (the two proximal links are massless, as identified); torque
/// limit 100 N·m per joint; end-effector (0, 0.085, 0) in the last frame; task space the 3-D
/// end-effector position. Start posture (0, −0.3, 0, 1.57, 0, 0, 0).
pub fn sarcos7() -> Model {
    let links = frames()
        .iter()
        .zip(INERTIAL.iter().zip(JOINTS.iter()))
        .map(|(&(name, t, [a, b, c]), (p, j))| {
            let rot = axis_angle(&Vector3::x(), a)
                * axis_angle(&Vector3::y(), b)
                * axis_angle(&Vector3::z(), c);
            let inertia = Matrix3::new(p[4], p[5], p[6], p[5], p[7], p[8], p[6], p[8], p[9]);
            Link {
                name: name.to_string(),
                joint_name: format!("{name}_joint"),
                origin: Pose::new(rot, Vector3::from(t)),
                axis: Vector3::z(),
                kind: JointKind::Revolute,
                inertia: Inertia::from_origin(p[0], Vector3::new(p[1], p[2], p[3]), inertia),
                friction: Friction {
                    viscous: p[10],
                    ..Friction::default()
                },
                limits: JointLimits {
                    q_min: j[0],
                    q_max: j[1],
                    qd_max: f64::INFINITY,
                    tau_max: 100.0,
                },
            }
        })
        .collect();
    Model::new(ModelSpec {
        name: "sarcos7".into(),
        links,
        ee_offset: Vector3::new(0.0, 0.085, 0.0),
        gravity: GRAVITY,
        task_axes: vec![0, 1, 2],
        q_start: vec![0.0, -0.3, 0.0, 1.57, 0.0, 0.0, 0.0],
        q_rest: JOINTS.iter().map(|j| j[2]).collect(),
        kp: JOINTS.iter().map(|j| j[3]).collect(),
        kd: JOINTS.iter().map(|j| j[4]).collect(),
        urdf: None,
    })
    .expect("sarcos7 parameters are valid")
}
