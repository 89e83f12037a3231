//! Rigid-body dynamics of serial arms with revolute and prismatic joints, the built-in robots,
//! URDF import and export, and the simulated robot.
//!
//! Design (after Pinocchio): an immutable [`Model`] and a preallocated [`Data`] workspace; one
//! algorithm per module named by its acronym ([`rnea`], [`crba`], [`aba`]); the hot calls never
//! allocate. Conventions: world frame z up, gravity 9.81 m/s² along −z; `M(q) q̈ + h(q, q̇) = u`
//! with `h = C q̇ + g + τ_f` (the paper writes `M q̈ = F + u`, so its `F` is `−h`).
//!
//! ```
//! use osrl_dynamics::{robots, compute_all};
//! let model = robots::sarcos7();
//! let mut data = model.data();
//! let q = model.spec().q_start.clone();
//! let qd = vec![0.1; 7];
//! compute_all(&model, &mut data, &q, &qd).unwrap();
//! // data.mass = M(q), data.jac = J(q), data.jdot_qd = J̇q̇, data.h = h(q, q̇), data.g = g(q)
//! assert!((data.g[0] - 6.335692).abs() < 1e-5);
//! ```
// `!(x > 0.0)` is this crate's idiom for "not positive, or NaN" (inputs are validated so that
// NaN fails): the negated comparisons are deliberate.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod aba;
pub mod crba;
mod data;
pub mod energy;
mod error;
pub mod gimbal;
pub mod inertia;
pub mod jacobian;
pub mod kinematics;
mod model;
pub mod profile;
pub mod rnea;
pub mod robots;
pub mod sim;
pub mod sincos;
pub mod spatial;
mod subspace;
pub mod urdf;

pub use aba::{aba, forward_dynamics};
pub use crba::crba;
pub use data::Data;
pub use energy::energy;
pub use error::{check_finite, check_vec, DynamicsError, Result};
pub use inertia::Inertia;
pub use jacobian::{jacobian, jacobian_from_fk};
pub use kinematics::{forward_kinematics, kinematics};
pub use model::{
    Friction, JointKind, JointLimits, Link, LockedJoint, Model, ModelSpec, UrdfImport, GRAVITY,
    MAX_DOF, MAX_JOINT_KD, MAX_JOINT_KP, MAX_LENGTH, MAX_MASS,
};
pub use profile::{CostMetric, PathPlacement, RobotProfile};
pub use rnea::{gravity, nonlinear_effects, rnea};
pub use sim::{
    FrictionScheme, Measurement, Robot, SimConfig, SimRobot, MAX_ACTUATOR_NOISE, MAX_NOISE,
    MAX_SUBSTEPS,
};
pub use spatial::Pose;

/// Everything an operational space controller reads, in one call: kinematics (`ee_pos`,
/// `ee_vel`, `jdot_qd`), the Jacobian `jac`, the mass matrix `mass`, gravity `g` and the
/// non-inertial torques `h` (friction included, `friction` separately).
///
/// Fails on a wrong length or a non-finite entry; never allocates.
pub fn compute_all(model: &Model, data: &mut Data, q: &[f64], qd: &[f64]) -> Result<()> {
    kinematics(model, data, q, qd)?;
    jacobian_from_fk(model, data);
    crba::crba_pass(model, data);
    rnea::rnea_passes(model, data, None, None, true);
    data.g.copy_from(&data.tau);
    rnea::rnea_passes(model, data, Some(qd), None, true);
    model.friction(qd, data.friction.as_mut_slice());
    data.h.copy_from(&data.tau);
    data.h += &data.friction;
    Ok(())
}

/// The README's example compiles and runs (`cargo test --doc`).
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
