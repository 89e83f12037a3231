//! The immutable robot model: a serial chain of revolute and prismatic joints with full spatial
//! inertias.

use crate::error::{check_finite, DynamicsError, Result};
use crate::inertia::Inertia;
use crate::spatial::{rotate_about_sc, Force, Motion, Pose};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Largest number of joints a [`Model`] accepts: the workspace holds an `n × n` mass matrix and
/// the controllers factor it, so an absurd size is refused before anything is allocated.
pub const MAX_DOF: usize = 1024;

/// Largest offset of a link's joint, centre of mass or end-effector from its parent (m, per
/// coordinate): a kilometre, far beyond any arm; larger ones overflow the mass matrix.
pub const MAX_LENGTH: f64 = 1e3;
/// Largest mass of a link (kg): a thousand tonnes.
pub const MAX_MASS: f64 = 1e6;

/// Largest joint PD stiffness `K_Pq` (N·m/rad or N/m): a million, above the mechanical stiffness
/// of a geared robot joint, which no position loop can exceed; larger gains only overflow the
/// nominal command.
pub const MAX_JOINT_KP: f64 = 1e6;
/// Largest joint PD damping `K_Dq` (N·m·s/rad or N·s/m).
pub const MAX_JOINT_KD: f64 = 1e4;

/// How a joint moves its link along or about its axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointKind {
    /// Rotation by `q` (rad) about the axis; torques in N·m.
    #[default]
    Revolute,
    /// Translation by `q` (m) along the axis; forces in N.
    Prismatic,
}

/// Joint friction `τ_f(q̇) = viscous·q̇ + coulomb·tanh(q̇ / coulomb_velocity)` (N·m): viscous plus a
/// Coulomb term smoothed over `coulomb_velocity` so that the dynamics stay differentiable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Friction {
    /// Viscous coefficient (N·m·s/rad). Default 0.
    pub viscous: f64,
    /// Coulomb friction level (N·m). Default 0.
    pub coulomb: f64,
    /// Smoothing velocity of the Coulomb term (rad/s). Default 0.01.
    pub coulomb_velocity: f64,
}

impl Default for Friction {
    fn default() -> Self {
        Self {
            viscous: 0.0,
            coulomb: 0.0,
            coulomb_velocity: 0.01,
        }
    }
}

impl Friction {
    /// Friction torque (N·m) at joint velocity `qd` (rad/s); it opposes the motion.
    #[inline]
    pub fn torque(&self, qd: f64) -> f64 {
        let coulomb = if self.coulomb != 0.0 {
            self.coulomb * (qd / self.coulomb_velocity).tanh()
        } else {
            0.0
        };
        self.viscous * qd + coulomb
    }
}

/// Joint limits. Infinite values mean "no limit".
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct JointLimits {
    /// Lower position limit (rad). Default −∞.
    pub q_min: f64,
    /// Upper position limit (rad). Default +∞.
    pub q_max: f64,
    /// Velocity limit (rad/s), informational. Default +∞.
    pub qd_max: f64,
    /// Torque limit (N·m): commands are clipped to ±`tau_max`. Default +∞.
    pub tau_max: f64,
}

impl Default for JointLimits {
    fn default() -> Self {
        Self {
            q_min: f64::NEG_INFINITY,
            q_max: f64::INFINITY,
            qd_max: f64::INFINITY,
            tau_max: f64::INFINITY,
        }
    }
}

/// One link of the chain and the joint that moves it. Units follow the joint's kind: rad, rad/s
/// and N·m for a revolute joint, m, m/s and N for a prismatic one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Link {
    /// Link (body) name.
    pub name: String,
    /// Name of the joint that moves this link.
    pub joint_name: String,
    /// Pose of the joint frame in the parent link's frame at `q = 0` (the parent of link 0 is the
    /// world/base frame).
    pub origin: Pose,
    /// Joint axis in the joint frame (unit vector; normalised when the model is built).
    pub axis: Vector3<f64>,
    /// Revolute or prismatic. Default revolute.
    #[serde(default)]
    pub kind: JointKind,
    /// Inertia of the link in the joint frame.
    pub inertia: Inertia,
    pub friction: Friction,
    pub limits: JointLimits,
}

impl Link {
    /// Pose of the link's joint frame in its parent at joint position `q`:
    /// `origin ∘ Rot(axis, q)` or `origin ∘ Trans(axis q)`.
    /// The sine and cosine are [`crate::sincos::sin_cos`]'s.
    #[inline]
    pub fn joint_pose(&self, q: f64) -> Pose {
        self.joint_pose_sc(q, crate::sincos::sin_cos(q))
    }
    /// [`Link::joint_pose`] given `sc = (sin q, cos q)` (used by revolute joints only).
    #[inline]
    pub(crate) fn joint_pose_sc(&self, q: f64, sc: (f64, f64)) -> Pose {
        match self.kind {
            JointKind::Revolute => Pose::new(
                rotate_about_sc(&self.origin.rot, &self.axis, sc),
                self.origin.trans,
            ),
            JointKind::Prismatic => Pose::new(
                self.origin.rot,
                self.origin.trans + self.origin.rot * (self.axis * q),
            ),
        }
    }
    /// The joint's motion subspace `S` scaled by `s`: `(axis s, 0)` or `(0, axis s)`.
    #[inline]
    pub fn motion(&self, s: f64) -> Motion {
        match self.kind {
            JointKind::Revolute => Motion::new(self.axis * s, Vector3::zeros()),
            JointKind::Prismatic => Motion::new(Vector3::zeros(), self.axis * s),
        }
    }
    /// `Sᵀ f`: the part of the spatial force `f` that the joint transmits (N·m or N).
    #[inline]
    pub fn project(&self, f: &Force) -> f64 {
        match self.kind {
            JointKind::Revolute => self.axis.dot(&f.ang),
            JointKind::Prismatic => self.axis.dot(&f.lin),
        }
    }
}

/// What the URDF loader decided for a model it built ([`crate::urdf`]); `None` for the built-in
/// robots. Tools print it so that no choice is silent.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UrdfImport {
    /// The end-effector link (the tip): the model's end-effector point is its origin.
    pub tip: String,
    /// The rule that chose the tip, in words (e.g. "option tip", "name matches '*tcp*'").
    pub tip_rule: String,
    /// Every movable joint of the file that is not a degree of freedom of the model, held rigid.
    pub locked: Vec<LockedJoint>,
    /// The file declared identified inertial parameters, so the per-link check was skipped.
    pub identified_inertias: bool,
    /// The robot profile the file carries (`<osrl_profile .../>`, written by
    /// [`crate::urdf::to_urdf_with_profile`]), as given: resolved and checked by
    /// `osrl_control::profile`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile: Option<crate::profile::RobotProfile>,
}

/// A movable URDF joint that the loader held rigid, its position and why.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LockedJoint {
    pub name: String,
    /// Position it is held at (rad or m).
    pub value: f64,
    /// The rule that locked it, in words (e.g. "beyond the tip", "finger/gripper name").
    pub reason: String,
}

/// Everything that defines a robot; [`Model::new`] validates it once.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelSpec {
    pub name: String,
    /// Links from base to tip.
    pub links: Vec<Link>,
    /// End-effector point in the last link's frame (m).
    pub ee_offset: Vector3<f64>,
    /// Gravity in the world frame (m/s²). Default `(0, 0, −9.81)`.
    pub gravity: Vector3<f64>,
    /// World axes (0 = x, 1 = y, 2 = z) of the end-effector position that form the task space.
    pub task_axes: Vec<usize>,
    /// Default start posture (rad).
    pub q_start: Vec<f64>,
    /// Rest posture of the nominal null-space behaviour (rad).
    pub q_rest: Vec<f64>,
    /// Joint PD gains: stiffness (N·m/rad) and damping (N·m·s/rad), within [0, [`MAX_JOINT_KP`]]
    /// and [0, [`MAX_JOINT_KD`]].
    pub kp: Vec<f64>,
    pub kd: Vec<f64>,
    /// What the URDF loader chose (tip, locked joints), if the model came from a URDF.
    #[serde(default)]
    pub urdf: Option<UrdfImport>,
}

/// Standard gravity along −z (m/s²), the URDF/ROS convention.
pub const GRAVITY: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

/// An immutable, validated robot model. Build with [`Model::new`]; evaluate with a [`crate::Data`].
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    spec: ModelSpec,
    /// `Some(k)` when every joint is revolute about `±e_k` (the CRBA's unit-axis path).
    revolute_axis: Option<usize>,
}

impl Model {
    /// Validates `spec` (finite values, non-negative masses, symmetric inertias, ordered limits,
    /// consistent lengths) and normalises the joint axes.
    pub fn new(mut spec: ModelSpec) -> Result<Self> {
        let n = spec.links.len();
        let bad = |m: String| Err(DynamicsError::InvalidModel(m));
        if n == 0 {
            return bad("a model needs at least one joint".into());
        }
        if n > MAX_DOF {
            return bad(format!("{n} joints: at most {MAX_DOF} are supported"));
        }
        for (what, v) in [
            ("q_start", &spec.q_start),
            ("q_rest", &spec.q_rest),
            ("kp", &spec.kp),
            ("kd", &spec.kd),
        ] {
            if v.len() != n {
                return bad(format!("{what} has {} entries for {n} joints", v.len()));
            }
            check_finite(what, v)?;
        }
        for (what, v, hi) in [
            ("kp", &spec.kp, MAX_JOINT_KP),
            ("kd", &spec.kd, MAX_JOINT_KD),
        ] {
            if let Some(x) = v.iter().find(|x| !(0.0..=hi).contains(*x)) {
                return bad(format!(
                    "{what} = {x:?}: joint gains must lie in [0, {hi:?}]"
                ));
            }
        }
        check_finite("gravity", spec.gravity.as_slice())?;
        check_finite("ee_offset", spec.ee_offset.as_slice())?;
        if spec.ee_offset.amax() > MAX_LENGTH {
            return bad(format!(
                "ee_offset {:?} m lies beyond ±{MAX_LENGTH:?} m",
                spec.ee_offset.as_slice()
            ));
        }
        if spec.task_axes.is_empty()
            || spec.task_axes.iter().any(|&a| a > 2)
            || (1..spec.task_axes.len()).any(|i| spec.task_axes[..i].contains(&spec.task_axes[i]))
        {
            return bad(format!(
                "task_axes {:?} must be distinct values in 0..=2",
                spec.task_axes
            ));
        }
        for l in spec.links.iter_mut() {
            let ctx = |m: &str| format!("link '{}' (joint '{}'): {m}", l.name, l.joint_name);
            let all = [
                l.origin.rot.as_slice(),
                l.origin.trans.as_slice(),
                l.axis.as_slice(),
            ];
            if all.iter().any(|s| s.iter().any(|x| !x.is_finite())) {
                return bad(ctx("non-finite origin or axis"));
            }
            if l.origin.trans.amax() > MAX_LENGTH {
                return bad(ctx(&format!(
                    "origin {:?} m lies beyond ±{MAX_LENGTH:?} m",
                    l.origin.trans.as_slice()
                )));
            }
            if (l.origin.rot.transpose() * l.origin.rot - nalgebra::Matrix3::identity()).amax()
                > 1e-9
                || l.origin.rot.determinant() < 0.0
            {
                return bad(ctx("origin rotation is not a proper rotation matrix"));
            }
            let norm = l.axis.norm();
            if norm < 1e-12 {
                return bad(ctx("zero joint axis"));
            }
            l.axis /= norm;
            let i = &l.inertia;
            let fin = i.mass.is_finite()
                && i.h.iter().all(|x| x.is_finite())
                && i.inertia.iter().all(|x| x.is_finite());
            if !fin || i.mass < 0.0 {
                return bad(ctx(&format!(
                    "mass {} must be finite and non-negative",
                    i.mass
                )));
            }
            let (h_max, i_max) = (MAX_MASS * MAX_LENGTH, MAX_MASS * MAX_LENGTH * MAX_LENGTH);
            if i.mass > MAX_MASS || i.h.amax() > h_max || i.inertia.amax() > i_max {
                return bad(ctx(&format!(
                    "mass {:?} kg, first moment or inertia beyond the bounds (mass ≤ \
                     {MAX_MASS:?} kg, centre of mass within ±{MAX_LENGTH:?} m, inertia ≤ \
                     {i_max:?} kg·m²)",
                    i.mass
                )));
            }
            if (i.inertia - i.inertia.transpose()).amax() > 1e-12 * (1.0 + i.inertia.amax()) {
                return bad(ctx("inertia matrix is not symmetric"));
            }
            if i.mass == 0.0 && i.h.norm() > 0.0 {
                return bad(ctx("zero mass with a non-zero first moment"));
            }
            let f = &l.friction;
            let friction_ok = f.viscous >= 0.0
                && f.coulomb >= 0.0
                && f.coulomb_velocity > 0.0
                && f.viscous.is_finite()
                && f.coulomb.is_finite()
                && f.coulomb_velocity.is_finite();
            if !friction_ok {
                return bad(ctx(
                    "friction coefficients must be finite, ≥ 0 (coulomb_velocity > 0)",
                ));
            }
            let lim = &l.limits;
            if lim.q_min.is_nan() || lim.q_max.is_nan() || lim.q_min > lim.q_max {
                return bad(ctx(&format!(
                    "joint limits [{}, {}] are not ordered",
                    lim.q_min, lim.q_max
                )));
            }
            if !(lim.tau_max > 0.0) || !(lim.qd_max > 0.0) {
                return bad(ctx("tau_max and qd_max must be > 0"));
            }
        }
        let revolute_axis = (0..3).find(|&k| {
            spec.links.iter().all(|l| {
                l.kind == JointKind::Revolute
                    && l.axis[k].abs() == 1.0
                    && (0..3).all(|c| c == k || l.axis[c] == 0.0)
            })
        });
        Ok(Self {
            spec,
            revolute_axis,
        })
    }

    /// The validated specification (clone and edit it to make a variant of this robot).
    pub fn spec(&self) -> &ModelSpec {
        &self.spec
    }
    pub fn name(&self) -> &str {
        &self.spec.name
    }
    /// Number of joints `n`.
    #[inline]
    pub fn nq(&self) -> usize {
        self.spec.links.len()
    }
    /// `Some(k)` when every joint is revolute about `±e_k` (most arms: the DH and URDF `z`), so
    /// that a joint's motion subspace `S` picks one component and needs no product.
    #[inline]
    pub(crate) fn revolute_axis(&self) -> Option<usize> {
        self.revolute_axis
    }
    /// Task-space dimension `m`.
    #[inline]
    pub fn task_dim(&self) -> usize {
        self.spec.task_axes.len()
    }
    #[inline]
    pub fn links(&self) -> &[Link] {
        &self.spec.links
    }
    #[inline]
    pub fn gravity(&self) -> Vector3<f64> {
        self.spec.gravity
    }
    pub fn task_axes(&self) -> &[usize] {
        &self.spec.task_axes
    }
    /// Friction torques `τ_f(q̇)` (N·m) into `out`.
    pub fn friction(&self, qd: &[f64], out: &mut [f64]) {
        for ((o, l), &v) in out.iter_mut().zip(&self.spec.links).zip(qd) {
            *o = l.friction.torque(v);
        }
    }
    pub fn q_min(&self) -> impl Iterator<Item = f64> + '_ {
        self.spec.links.iter().map(|l| l.limits.q_min)
    }
    pub fn q_max(&self) -> impl Iterator<Item = f64> + '_ {
        self.spec.links.iter().map(|l| l.limits.q_max)
    }
    pub fn tau_max(&self) -> impl Iterator<Item = f64> + '_ {
        self.spec.links.iter().map(|l| l.limits.tau_max)
    }
    /// Total mass (kg).
    pub fn total_mass(&self) -> f64 {
        self.spec.links.iter().map(|l| l.inertia.mass).sum()
    }
    /// A fresh workspace for this model.
    pub fn data(&self) -> crate::Data {
        crate::Data::new(self)
    }
}
