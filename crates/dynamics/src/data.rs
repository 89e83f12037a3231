//! The preallocated workspace of the dynamics algorithms: one per thread, reused for every call.

use crate::inertia::{ArticulatedInertia, Inertia};
use crate::model::{Link, Model};
use crate::sincos;
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
    /// `sin q_i`, `cos q_i` of the last joint poses, padded to a multiple of 4 joints.
    pub(crate) sin_q: Vec<f64>,
    pub(crate) cos_q: Vec<f64>,
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
            sin_q: vec![0.0; n.next_multiple_of(4)],
            cos_q: vec![0.0; n.next_multiple_of(4)],
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

/// Joint poses `ᵖX_i(q_i)` ([`crate::Link::joint_pose`]) for every link, the sines and cosines
/// four joints at a time ([`sincos::sin_cos_slices`]); without testing each axis when every
/// joint is revolute about one `±e_k` ([`Model::revolute_axis`]).
#[inline]
pub(crate) fn update_joint_poses(model: &Model, data: &mut Data, q: &[f64]) {
    sincos::sin_cos_slices(q, &mut data.sin_q, &mut data.cos_q);
    match model.revolute_axis() {
        Some(0) => poses(model, data, q, unit_axis_pose::<0>),
        Some(1) => poses(model, data, q, unit_axis_pose::<1>),
        Some(2) => poses(model, data, q, unit_axis_pose::<2>),
        _ => poses(model, data, q, Link::joint_pose_sc),
    }
}

/// `data.joint_pose[i] = pose(link_i, q_i, (sin q_i, cos q_i))`.
#[inline(always)]
fn poses(model: &Model, data: &mut Data, q: &[f64], pose: impl Fn(&Link, f64, (f64, f64)) -> Pose) {
    let sc = data.sin_q.iter().zip(&data.cos_q);
    for (((x, l), &qi), (&s, &c)) in data.joint_pose.iter_mut().zip(model.links()).zip(q).zip(sc) {
        *x = pose(l, qi, (s, c));
    }
}

/// [`Link::joint_pose`] for a joint revolute about `±e_K`.
#[inline(always)]
fn unit_axis_pose<const K: usize>(l: &Link, _q: f64, sc: (f64, f64)) -> Pose {
    Pose::new(
        rotate_about_unit::<K>(&l.origin.rot, l.axis[K], sc),
        l.origin.trans,
    )
}
