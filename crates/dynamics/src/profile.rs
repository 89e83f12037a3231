//! A robot profile: what an arm needs beyond its dynamics to be controlled — the tip and locked
//! joints (how its URDF is read), home and rest postures, joint PD gains, torque limits and where
//! the task path goes. Every field is optional: `osrl_control::profile::resolve` computes the
//! missing ones from the model (or takes a built-in robot's data sheet) and checks them all.
//!
//! This module only holds the values: the config-file form (`[robot]` section or
//! `--profile F`, TOML) and the `<osrl_profile .../>` element of a URDF file
//! ([`crate::urdf::to_urdf_with_profile`] writes it, the loader reads it into
//! [`crate::UrdfImport::profile`]), so that a profile travels with an exported robot.

use crate::error::{DynamicsError, Result};
use crate::urdf::UrdfOptions;
use serde::{Deserialize, Serialize};

/// Where the default task path (figure-8, circle, min-jerk corners) is placed. Unset fields are
/// computed from the model; a `[trajectory]` section's own values take precedence.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PathPlacement {
    /// Centre `c` (m, world frame). Default: the end-effector at the home posture, so that the
    /// path starts where the arm is best conditioned.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub centre: Option<[f64; 3]>,
    /// First plane direction `e1` (world frame). Default: horizontal and perpendicular to the
    /// base→tip direction at home (the path faces the arm), x when the tip is above the base;
    /// the first task axis for a planar arm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub e1: Option<[f64; 3]>,
    /// Second plane direction `e2` (world frame). Default z (vertical); the last task axis for a
    /// planar arm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub e2: Option<[f64; 3]>,
    /// Half-width along `e1` (m). Default `scale` × the arm's reach.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a: Option<f64>,
    /// Half-height along `e2` (m). Default `scale` × the arm's reach.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b: Option<f64>,
    /// Size of the default path as a fraction of the arm's reach (the largest distance of the
    /// tip from the first joint). Default 0.1 (sarcos7's 0.10 m path on its ≈ 1 m reach), halved
    /// up to twice when the path is not reachable or not feasible within the torque limits.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
}

impl PathPlacement {
    /// True when nothing is set.
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }
}

/// The metric `N` of the learner's cost `(u − u0)ᵀ N (u − u0)`, of its null space and of the
/// hindsight shrinkage (`osrl_learn`'s `learner/metric.rs`). A robot profile chooses it
/// (`osrl_control::profile`'s rule); a learner config's `[learner.controllers] metric` wins.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CostMetric {
    /// `N = I`, the paper's choice for learning (eq. 7 with `N = I` is the optimum).
    #[default]
    Identity,
    /// `N = B̂ ≈ M⁻¹`, the inverse inertia measured near home in the warm-up: the dynamically
    /// consistent split (eq. 7 with `N = M⁻¹` is the optimum; the evaluation's `u*` uses it).
    InverseInertia,
}

/// The profile of a robot (module docs). Vectors have one entry per degree of freedom of the
/// model (after tip and locks), in chain order.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RobotProfile {
    /// The robot: a built-in name (`planar3`, `sarcos7`) or a URDF file. Only read from a config
    /// file's `[robot]` section (`--robot` wins); default planar3 there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// End-effector link of a URDF (`--tip`). Default: the loader's documented name rule.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip: Option<String>,
    /// URDF joints held rigid, `JOINT` or `JOINT=VALUE` (rad or m) (`--lock`). Default: the
    /// loader's rule (fingers, joints off the chain).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub lock: Vec<String>,
    /// Gripper joints that should move instead of being locked (`--unlock`). Default none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub unlock: Vec<String>,
    /// Home posture (rad or m): where the default path is centred. Default: a well-conditioned
    /// posture inside the joint limits (maximal manipulability and distance to the limits with
    /// the tip in front of the base at 40–75 % of its reach and gravity within half the torque
    /// limits); a built-in robot's data-sheet start posture.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub home: Option<Vec<f64>>,
    /// Rest posture `q_rest` of the nominal behaviour `u0 = g − K_D q̇ − K_P (q − q_rest)`
    /// (rad or m). Default: home (a built-in robot's data sheet).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rest: Option<Vec<f64>>,
    /// Joint stiffness `K_P` of `u0` (N·m/rad or N/m). Default `m_i ω²` with
    /// `ω = null_space_frequency` and `m_i = 1 / (M⁻¹(home))_ii` (joint `i`'s inertia with the
    /// other joints free), so every joint's null-space motion has the same time scale.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kp: Option<Vec<f64>>,
    /// Joint damping `K_D` of `u0` (N·m·s/rad or N·s/m). Default `2 ζ ω √(m_i M_ii(home))`
    /// with `ζ = null_space_damping`: `M_ii`, the inertia with the other joints locked, also
    /// damps the heavy modes of several joints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kd: Option<Vec<f64>>,
    /// Torque limits (N·m or N): commands are clipped to ± these. Default: the URDF's `effort`
    /// (a built-in robot's data sheet).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub torque_limits: Option<Vec<f64>>,
    /// Natural frequency `ω` of the default joint gains (rad/s). Default 10 (a 0.6 s time
    /// constant, far below the 500 Hz control rate's stability bound).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub null_space_frequency: Option<f64>,
    /// Damping ratio `ζ` of the default joint gains. Default 1 (critically damped: the posture
    /// returns to rest without overshoot).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub null_space_damping: Option<f64>,
    /// Placement of the default task path.
    #[serde(skip_serializing_if = "PathPlacement::is_empty")]
    pub path: PathPlacement,
    /// The learner's cost metric `N` ([`CostMetric`]). Default: `inverse_inertia` when eq. 7
    /// with `N = I` on the true model turns some joint through more than
    /// `osrl_control::profile::METRIC_SWEEP_BOUND` rad along the default path (the light
    /// wrists of the UR5 and the Panda), else `identity` (the paper's; the built-in arms).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub metric: Option<CostMetric>,
}

impl RobotProfile {
    /// True when no field but `name` is set (the robot runs with its defaults).
    pub fn is_empty(&self) -> bool {
        Self {
            name: None,
            ..self.clone()
        } == Self::default()
    }

    /// True when the profile changes how a URDF is read (tip, lock, unlock).
    pub fn changes_structure(&self) -> bool {
        self.tip.is_some() || !self.lock.is_empty() || !self.unlock.is_empty()
    }

    /// The loader options of `tip`, `lock` and `unlock`.
    ///
    /// # Errors
    /// A `lock` entry that is not `JOINT` or `JOINT=VALUE` with a finite value (the error names
    /// the field).
    pub fn urdf_options(&self) -> Result<UrdfOptions> {
        let mut opts = UrdfOptions {
            tip: self.tip.clone(),
            lock: Vec::new(),
            unlock: self.unlock.clone(),
        };
        for l in &self.lock {
            opts.push_lock(l).map_err(|e| match e {
                DynamicsError::Urdf(m) => DynamicsError::InvalidModel(format!("profile lock: {m}")),
                other => other,
            })?;
        }
        Ok(opts)
    }

    /// `self` with the fields of `over` that are set replacing its own (a `--profile` file over
    /// a URDF's embedded profile, a config section over both).
    pub fn overlaid(&self, over: &RobotProfile) -> RobotProfile {
        let pick = |a: &Option<Vec<f64>>, b: &Option<Vec<f64>>| b.clone().or_else(|| a.clone());
        let (p, q) = (&self.path, &over.path);
        RobotProfile {
            name: over.name.clone().or_else(|| self.name.clone()),
            tip: over.tip.clone().or_else(|| self.tip.clone()),
            lock: if over.lock.is_empty() {
                self.lock.clone()
            } else {
                over.lock.clone()
            },
            unlock: if over.unlock.is_empty() {
                self.unlock.clone()
            } else {
                over.unlock.clone()
            },
            home: pick(&self.home, &over.home),
            rest: pick(&self.rest, &over.rest),
            kp: pick(&self.kp, &over.kp),
            kd: pick(&self.kd, &over.kd),
            torque_limits: pick(&self.torque_limits, &over.torque_limits),
            null_space_frequency: over.null_space_frequency.or(self.null_space_frequency),
            null_space_damping: over.null_space_damping.or(self.null_space_damping),
            path: PathPlacement {
                centre: q.centre.or(p.centre),
                e1: q.e1.or(p.e1),
                e2: q.e2.or(p.e2),
                a: q.a.or(p.a),
                b: q.b.or(p.b),
                scale: q.scale.or(p.scale),
            },
            metric: over.metric.or(self.metric),
        }
    }
}
