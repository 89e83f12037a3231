//! The preallocated workspace of the dynamics algorithms: one per thread, reused for every call.

use crate::inertia::{ArticulatedInertia, Inertia};
use crate::model::Model;
use crate::spatial::{rotate_about_unit, Force, Motion, Pose};
use nalgebra::{DMatrix, DVector, Matrix3xX, Vector3};

/// Workspace and results of the dynamics algorithms for one [`Model`]. Create it once with
/// [`Model::data`]; the algorithms then never allocate. Output fields are public for reading;
/// each is documented with the call that fills it.
#[derive(Clone, Debug)]
pub struct Data {
    /// Pose of each link's joint frame in its parent frame at the last `q` (any algorithm).
    pub joint_pose: Vec<Pose>,
    /// Pose of each link's joint frame in the world ([`crate::forward_kinematics`]).
    pub world_pose: Vec<Pose>,
    /// Spatial velocity of each link in its own frame ([`crate::kinematics`], RNEA, ABA).
    pub v: Vec<Motion>,
    /// Spatial acceleration of each link in its own frame.
    pub a: Vec<Motion>,
    /// Spatial force transmitted by each joint (RNEA).
    pub f: Vec<Force>,
    /// Composite rigid-body inertias (CRBA).
    pub ic: Vec<Inertia>,
    /// Articulated-body quantities (ABA).
    pub ia: Vec<ArticulatedInertia>,
    pub pa: Vec<Force>,
    pub(crate) c: Vec<Motion>,
    pub(crate) u_ang: Vec<Vector3<f64>>,
    pub(crate) u_lin: Vec<Vector3<f64>>,
    pub(crate) d_inv: Vec<f64>,
    pub(crate) u: Vec<f64>,
    /// Joint torques of the last [`crate::rnea`] call (N·m).
    pub tau: DVector<f64>,
    /// Joint accelerations of the last [`crate::aba`] / [`crate::forward_dynamics`] call (rad/s²).
    pub qdd: DVector<f64>,
    /// Joint-space mass matrix `M(q)` of the last [`crate::crba`] call (kg·m²).
    pub mass: DMatrix<f64>,
    /// Gravity torques `g(q)` ([`crate::gravity`], [`crate::compute_all`]).
    pub g: DVector<f64>,
    /// Non-inertial torques `h(q, q̇) = C q̇ + g + τ_f` ([`crate::nonlinear_effects`]).
    pub h: DVector<f64>,
    /// Friction torques `τ_f(q̇)`.
    pub friction: DVector<f64>,
    /// End-effector position in the world (m) ([`crate::forward_kinematics`]).
    pub ee_pos: Vector3<f64>,
    /// End-effector velocity in the world (m/s) ([`crate::kinematics`]).
    pub ee_vel: Vector3<f64>,
    /// `J̇ q̇` of the end-effector point in the world (m/s²) ([`crate::kinematics`]).
    pub jdot_qd: Vector3<f64>,
    /// End-effector point Jacobian `∂x/∂q` in the world, 3×n ([`crate::jacobian`]).
    pub jac: Matrix3xX<f64>,
}

impl Data {
    /// Allocates every buffer for `model`.
    pub fn new(model: &Model) -> Self {
        let n = model.nq();
        Self {
            joint_pose: vec![Pose::identity(); n],
            world_pose: vec![Pose::identity(); n],
            v: vec![Motion::default(); n],
            a: vec![Motion::default(); n],
            f: vec![Force::default(); n],
            ic: vec![Inertia::zero(); n],
            ia: vec![ArticulatedInertia::default(); n],
            pa: vec![Force::default(); n],
            c: vec![Motion::default(); n],
            u_ang: vec![Vector3::zeros(); n],
            u_lin: vec![Vector3::zeros(); n],
            d_inv: vec![0.0; n],
            u: vec![0.0; n],
            tau: DVector::zeros(n),
            qdd: DVector::zeros(n),
            mass: DMatrix::zeros(n, n),
            g: DVector::zeros(n),
            h: DVector::zeros(n),
            friction: DVector::zeros(n),
            ee_pos: Vector3::zeros(),
            ee_vel: Vector3::zeros(),
            jdot_qd: Vector3::zeros(),
            jac: Matrix3xX::zeros(n),
        }
    }

    /// Number of joints this workspace was made for.
    pub fn nq(&self) -> usize {
        self.tau.len()
    }
}

/// Joint poses `ᵖX_i(q_i)` ([`crate::Link::joint_pose`]) for every link; without testing each
/// axis when every joint is revolute about one `±e_k` ([`Model::revolute_axis`]).
#[inline]
pub(crate) fn update_joint_poses(model: &Model, data: &mut Data, q: &[f64]) {
    match model.revolute_axis() {
        Some(0) => unit_axis_poses::<0>(model, data, q),
        Some(1) => unit_axis_poses::<1>(model, data, q),
        Some(2) => unit_axis_poses::<2>(model, data, q),
        _ => {
            for ((x, l), &qi) in data.joint_pose.iter_mut().zip(model.links()).zip(q) {
                *x = l.joint_pose(qi);
            }
        }
    }
}

/// [`update_joint_poses`] for joints all revolute about `±e_K`.
#[inline(always)]
fn unit_axis_poses<const K: usize>(model: &Model, data: &mut Data, q: &[f64]) {
    for ((x, l), &qi) in data.joint_pose.iter_mut().zip(model.links()).zip(q) {
        *x = Pose::new(
            rotate_about_unit::<K>(&l.origin.rot, l.axis[K], qi),
            l.origin.trans,
        );
    }
}
