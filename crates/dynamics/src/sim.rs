//! The simulated robot and the measurement boundary the learner sees (`docs/architecture.md`, "The measurement boundary").
//!
//! A learner holds a `&mut dyn Robot` (or `impl Robot`): it can send torques and read
//! [`Measurement`]s, nothing else — the trait exposes no model, so the compiler keeps the learner
//! from reading the simulator's dynamics.

use crate::data::Data;
use crate::error::{DynamicsError, Result};
use crate::model::Model;
use nalgebra::DVector;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};

/// What a learner can measure on a robot at one instant. Task-space quantities are the
/// end-effector position's task axes (`Model::task_axes`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Measurement {
    /// Time since reset (s).
    pub t: f64,
    /// Joint positions (rad) and velocities (rad/s).
    pub q: DVector<f64>,
    pub qd: DVector<f64>,
    /// Task-space position (m), velocity (m/s) and acceleration (m/s²) of the end-effector. `xdd`
    /// is the instantaneous acceleration at this state under the command `u` still applied (as an
    /// accelerometer on the hand would read it).
    pub x: DVector<f64>,
    pub xd: DVector<f64>,
    pub xdd: DVector<f64>,
    /// The command being applied (N·m), after torque-limit clipping, without actuator noise.
    pub u: DVector<f64>,
}

impl Measurement {
    /// Copies `other` into `self`: in place, without allocating, when the two have the same
    /// dimensions (a learner's buffer for the next measurement), else as a clone.
    ///
    /// ```
    /// use osrl_dynamics::{robots, Robot, SimConfig, SimRobot};
    /// let mut sim = SimRobot::new(robots::planar3(), SimConfig::default())?;
    /// let mut last = sim.measurement().clone();
    /// last.copy_from(sim.step(&[0.0; 3])?);
    /// assert_eq!(&last, sim.measurement());
    /// # Ok::<(), osrl_dynamics::DynamicsError>(())
    /// ```
    pub fn copy_from(&mut self, other: &Measurement) {
        let pairs = [
            (&mut self.q, &other.q),
            (&mut self.qd, &other.qd),
            (&mut self.x, &other.x),
            (&mut self.xd, &other.xd),
            (&mut self.xdd, &other.xdd),
            (&mut self.u, &other.u),
        ];
        if pairs.iter().any(|(a, b)| a.len() != b.len()) {
            *self = other.clone();
            return;
        }
        for (a, b) in pairs {
            a.copy_from(b);
        }
        self.t = other.t;
    }
}

/// A robot as the learner sees it: commands in, measurements out.
pub trait Robot {
    /// Number of joints.
    fn dof(&self) -> usize;
    /// Task-space dimension.
    fn task_dim(&self) -> usize;
    /// Control period (s).
    fn control_period(&self) -> f64;
    /// Torque limits per joint (N·m), from the robot's data sheet.
    fn torque_limits(&self) -> &[f64];
    /// Joint position limits (rad), from the robot's data sheet.
    fn joint_limits(&self) -> (&[f64], &[f64]);
    /// The latest measurement.
    fn measurement(&self) -> &Measurement;
    /// Applies `u` (N·m, clipped to the torque limits) for one control period; returns the new
    /// measurement. A wrong length or non-finite `u` is an error and changes nothing.
    fn step(&mut self, u: &[f64]) -> Result<&Measurement>;
}

/// Integration scheme inside one control period.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    /// Classical 4th-order Runge–Kutta on `(q, q̇)` with the command held (zero-order hold).
    Rk4,
    /// Semi-implicit (symplectic) Euler: `q̇ ← q̇ + h q̈(q, q̇)`, then `q ← q + h q̇`.
    SemiImplicitEuler,
}

/// How the simulator integrates joint friction (`sim/friction.rs` explains the scheme).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrictionScheme {
    /// The configured integrator while the friction is not stiff for the step (`h λ̂ ≤`
    /// [`STIFF_LIMIT`], checked every control period), implicit otherwise.
    #[default]
    Auto,
    /// Always the configured integrator. A model whose friction is stiff for the step at its
    /// start posture is refused, naming the joint and its friction parameters.
    Explicit,
    /// Always implicit: each substep is semi-implicit Euler with backward-Euler friction
    /// (first order, whatever `integrator` says; a sticking joint stays stuck).
    Implicit,
}

/// Standard deviations of the Gaussian sensor noise (0 = exact).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorNoise {
    /// Joint positions (rad). Default 0.
    pub q: f64,
    /// Joint velocities (rad/s). Default 0.
    pub qd: f64,
    /// Task position (m). Default 0.
    pub x: f64,
    /// Task velocity (m/s). Default 0.
    pub xd: f64,
    /// Task acceleration (m/s²). Default 0.
    pub xdd: f64,
}

/// Simulator settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimConfig {
    /// Control period (s): the command is held for this long. Default 0.002 (500 Hz).
    pub control_period: f64,
    /// Integration steps per control period. Default 2 (1 ms RK4 steps).
    pub substeps: usize,
    /// Integration scheme. Default `rk4`.
    pub integrator: Integrator,
    /// Joint friction: explicit, implicit, or chosen from its stiffness every control period.
    /// Default `auto` (explicit, and bit-identical to it, whenever the friction is not stiff).
    pub friction: FrictionScheme,
    /// Sensor noise. Default none.
    pub sensor_noise: SensorNoise,
    /// Standard deviation of Gaussian noise added to every applied torque (N·m). Default 0.
    pub actuator_noise: f64,
    /// Seed of the noise generator. Default 0.
    pub seed: u64,
    /// Enforce the joint position limits as inelastic hard stops. Default true.
    pub joint_limits: bool,
}

impl Default for SimConfig {
    fn default() -> Self {
        Self {
            control_period: 0.002,
            substeps: 2,
            integrator: Integrator::Rk4,
            friction: FrictionScheme::Auto,
            sensor_noise: SensorNoise::default(),
            actuator_noise: 0.0,
            seed: 0,
            joint_limits: true,
        }
    }
}

/// Most integration steps per control period ([`SimConfig::substeps`]): fine enough for a
/// reference solution (0.2 µs steps at 2 ms); the `osrl` commands accept at most 100.
pub const MAX_SUBSTEPS: usize = 10_000;

impl SimConfig {
    /// Checks ranges: positive period, at least one substep, noise levels within [0, [`MAX_NOISE`]]
    /// and [0, [`MAX_ACTUATOR_NOISE`]].
    pub fn validate(&self) -> Result<()> {
        let bad = |m: &str| Err(DynamicsError::InvalidConfig(m.to_string()));
        if !(self.control_period > 0.0 && self.control_period.is_finite()) {
            return bad("control_period must be a positive number of seconds");
        }
        if !(1..=MAX_SUBSTEPS).contains(&self.substeps) {
            return Err(DynamicsError::InvalidConfig(format!(
                "substeps = {}: accepted range 1–{MAX_SUBSTEPS}",
                self.substeps
            )));
        }
        let n = &self.sensor_noise;
        let noises = [
            ("sensor_noise.q", n.q, MAX_NOISE.q),
            ("sensor_noise.qd", n.qd, MAX_NOISE.qd),
            ("sensor_noise.x", n.x, MAX_NOISE.x),
            ("sensor_noise.xd", n.xd, MAX_NOISE.xd),
            ("sensor_noise.xdd", n.xdd, MAX_NOISE.xdd),
            ("actuator_noise", self.actuator_noise, MAX_ACTUATOR_NOISE),
        ];
        match noises.iter().find(|(_, s, hi)| !(0.0..=*hi).contains(s)) {
            Some((what, s, hi)) => Err(DynamicsError::InvalidConfig(format!(
                "{what} = {s:?}: a noise standard deviation must lie in [0, {hi:?}]"
            ))),
            None => Ok(()),
        }
    }
}

/// Largest sensor noise standard deviations: half a turn in `q`, and for the other signals
/// levels a hundred times any arm's motion (100 rad/s, 10 m, 100 m/s, 10⁴ m/s²); beyond them a
/// signal carries no measurement, and the learner's normalisation overflows.
pub const MAX_NOISE: SensorNoise = SensorNoise {
    q: std::f64::consts::PI,
    qd: 100.0,
    x: 10.0,
    xd: 100.0,
    xdd: 1e4,
};

/// Largest actuator noise standard deviation (N·m): ten kN·m, far beyond the torque limits of any
/// serial arm.
pub const MAX_ACTUATOR_NOISE: f64 = 1e4;

/// Counters of what the simulator had to enforce.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SimStats {
    /// Control periods simulated since reset.
    pub steps: u64,
    /// Control periods in which at least one command was clipped to its torque limit.
    pub torque_saturations: u64,
    /// Control periods in which at least one joint hit a position limit.
    pub limit_hits: u64,
    /// Control periods whose friction was integrated implicitly (stiff for the step).
    #[serde(default)]
    pub implicit_friction: u64,
}

mod friction;
mod robot;
pub use friction::STIFF_LIMIT;
pub use robot::SimRobot;

/// Gaussian noise with standard deviation `std` (0 draws nothing, keeping streams aligned).
#[inline]
pub(crate) fn noise(rng: &mut ChaCha8Rng, std: f64) -> f64 {
    if std > 0.0 {
        std * rng.sample::<f64, _>(StandardNormal)
    } else {
        0.0
    }
}

/// Task-space acceleration `ẍ = J q̈ + J̇ q̇` of the state in `data` (after `kinematics`,
/// `jacobian_from_fk` and a forward-dynamics result `qdd`), on the task axes.
pub(crate) fn task_acceleration(
    model: &Model,
    data: &Data,
    qdd: &DVector<f64>,
    out: &mut DVector<f64>,
) {
    for (k, &axis) in model.task_axes().iter().enumerate() {
        out[k] = (0..qdd.len())
            .map(|j| data.jac[(axis, j)] * qdd[j])
            .sum::<f64>()
            + data.jdot_qd[axis];
    }
}

pub(crate) fn new_rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}
