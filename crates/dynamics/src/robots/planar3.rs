//! `planar3`: a three-link arm in the vertical x–z plane, sized like a human arm.

use crate::inertia::Inertia;
use crate::model::{Friction, JointKind, JointLimits, Link, Model, ModelSpec, GRAVITY};
use crate::spatial::Pose;
use nalgebra::{Matrix3, Vector3};

/// Link lengths (m): upper arm, forearm, hand-and-tool.
pub const LENGTHS: [f64; 3] = [0.40, 0.35, 0.30];
/// Link masses (kg).
pub const MASSES: [f64; 3] = [2.5, 1.5, 0.75];
/// Viscous joint friction (N·m·s/rad).
pub const VISCOUS: [f64; 3] = [0.2, 0.15, 0.1];

/// The planar 3-DOF arm of the paper's first experiment.
///
/// Joint 1 (shoulder) sits at the world origin; every joint turns about the world's −y axis, so a
/// positive angle turns the arm counter-clockwise in the x–z plane seen with x to the right and z
/// up. At `q = 0` the arm points along +x. Each link is a uniform rod of length `LENGTHS[i]` and
/// mass `MASSES[i]` with its centre of mass at mid-length, a radius of 4 cm for the inertia about
/// its long axis, and viscous friction `VISCOUS[i]`. Limits: shoulder [−2.6, 2.0] rad, elbow
/// [−0.2, 2.7] rad, wrist [−1.6, 1.6] rad; torques ±60, ±40, ±20 N·m. Task space: the end-effector's
/// (x, z). Rest posture (−1.0, 1.4, 0.7) rad; PD gains Kp = (20, 15, 8), Kd = (4, 3, 1.5).
pub fn planar3() -> Model {
    let names = ["shoulder", "elbow", "wrist"];
    let limits = [(-2.6, 2.0, 60.0), (-0.2, 2.7, 40.0), (-1.6, 1.6, 20.0)];
    let links = (0..3)
        .map(|i| {
            let (l, m) = (LENGTHS[i], MASSES[i]);
            let origin = if i == 0 { 0.0 } else { LENGTHS[i - 1] };
            let r2 = 0.04f64 * 0.04;
            let across = m * (l * l / 12.0 + r2 / 4.0);
            let inertia_com = Matrix3::from_diagonal(&Vector3::new(m * r2 / 2.0, across, across));
            Link {
                name: format!("{}_link", names[i]),
                joint_name: format!("{}_joint", names[i]),
                origin: Pose::new(Matrix3::identity(), Vector3::new(origin, 0.0, 0.0)),
                axis: Vector3::new(0.0, -1.0, 0.0),
                kind: JointKind::Revolute,
                inertia: Inertia::from_com(m, Vector3::new(l / 2.0, 0.0, 0.0), inertia_com),
                friction: Friction {
                    viscous: VISCOUS[i],
                    ..Friction::default()
                },
                limits: JointLimits {
                    q_min: limits[i].0,
                    q_max: limits[i].1,
                    qd_max: 6.0,
                    tau_max: limits[i].2,
                },
            }
        })
        .collect();
    Model::new(ModelSpec {
        name: "planar3".into(),
        links,
        ee_offset: Vector3::new(LENGTHS[2], 0.0, 0.0),
        gravity: GRAVITY,
        task_axes: vec![0, 2],
        q_start: vec![-1.0, 1.4, 0.7],
        q_rest: vec![-1.0, 1.4, 0.7],
        kp: vec![20.0, 15.0, 8.0],
        kd: vec![4.0, 3.0, 1.5],
        urdf: None,
    })
    .expect("planar3 parameters are valid")
}
