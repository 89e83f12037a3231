//! [`SimRobot`]: fixed control period, finer integration inside, limits, noise, divergence check.

use super::friction::{FrictionStep, STIFF_LIMIT};
use super::{
    new_rng, noise, task_acceleration, FrictionScheme, Integrator, Measurement, Robot, SimConfig,
    SimStats,
};
use crate::aba::{aba, forward_dynamics as fd};
use crate::data::Data;
use crate::error::check_vec as check;
use crate::error::{DynamicsError, Result};
use crate::jacobian::jacobian_from_fk as jac_fk;
use crate::kinematics::kinematics as kin;
use crate::model::Model;
use nalgebra::DVector;
use rand_chacha::ChaCha8Rng;

/// A simulated robot: integrates `M q̈ + h = u` with the command held over each control period.
pub struct SimRobot {
    model: Model,
    data: Data,
    cfg: SimConfig,
    rng: ChaCha8Rng,
    q: DVector<f64>,
    qd: DVector<f64>,
    t: f64,
    /// Command after clipping (without noise) and the torque actually applied.
    u_cmd: DVector<f64>,
    u_applied: DVector<f64>,
    tau_max: Vec<f64>,
    q_min: Vec<f64>,
    q_max: Vec<f64>,
    meas: Measurement,
    stats: SimStats,
    // Integration scratch: saved state and RK4 stages.
    q0: DVector<f64>,
    qd0: DVector<f64>,
    qt: DVector<f64>,
    kq: [DVector<f64>; 4],
    kv: [DVector<f64>; 4],
    qdd: DVector<f64>,
    friction: FrictionStep,
}

impl SimRobot {
    /// A robot at `model.spec().q_start`, at rest, with zero command. Fails on an invalid config
    /// or a model the simulation cannot follow: a ball joint written as three angles whose gimbal
    /// lock lies inside the limits ([`crate::gimbal::check`]), or friction too stiff for an
    /// explicit integrator.
    pub fn new(model: Model, cfg: SimConfig) -> Result<Self> {
        cfg.validate()?;
        crate::gimbal::check(&model)?;
        let (n, m) = (model.nq(), model.task_dim());
        let z = DVector::zeros(n);
        let meas = Measurement {
            t: 0.0,
            q: z.clone(),
            qd: z.clone(),
            x: DVector::zeros(m),
            xd: DVector::zeros(m),
            xdd: DVector::zeros(m),
            u: z.clone(),
        };
        let q_start = model.spec().q_start.clone();
        let mut sim = Self {
            data: model.data(),
            rng: new_rng(cfg.seed),
            q: z.clone(),
            qd: z.clone(),
            t: 0.0,
            u_cmd: z.clone(),
            u_applied: z.clone(),
            tau_max: model.tau_max().collect(),
            q_min: model.q_min().collect(),
            q_max: model.q_max().collect(),
            meas,
            stats: SimStats::default(),
            q0: z.clone(),
            qd0: z.clone(),
            qt: z.clone(),
            kq: [z.clone(), z.clone(), z.clone(), z.clone()],
            kv: [z.clone(), z.clone(), z.clone(), z.clone()],
            qdd: z,
            friction: FrictionStep::new(&model),
            model,
            cfg,
        };
        let zeros = vec![0.0; n];
        sim.reset(&q_start, &zeros)?;
        sim.check_explicit_friction()?;
        Ok(sim)
    }

    /// Puts the robot at `(q, q̇)` with zero command, time 0, counters cleared and the noise
    /// generator re-seeded. Fails (changing nothing) on a wrong length or non-finite entry.
    pub fn reset(&mut self, q: &[f64], qd: &[f64]) -> Result<&Measurement> {
        let n = self.model.nq();
        check("q", q, n)?;
        check("qd", qd, n)?;
        self.q.copy_from_slice(q);
        self.qd.copy_from_slice(qd);
        self.t = 0.0;
        self.u_cmd.fill(0.0);
        self.u_applied.fill(0.0);
        self.stats = SimStats::default();
        self.rng = new_rng(self.cfg.seed);
        self.measure()?;
        Ok(&self.meas)
    }

    /// Replaces the simulated robot's model — a payload picked up or put down, other masses,
    /// worn joints — keeping its state, time, command, counters and noise generator: the robot
    /// changes under its controller between two control periods. The next step measures the new
    /// robot.
    ///
    /// # Errors
    /// A model with another number of joints or task dimensions, a gimbal inside its limits
    /// ([`crate::gimbal`]), or friction too stiff for an explicit integrator; nothing is changed.
    pub fn set_model(&mut self, model: Model) -> Result<()> {
        if model.nq() != self.model.nq() || model.task_dim() != self.model.task_dim() {
            return Err(DynamicsError::InvalidModel(format!(
                "set_model: {} joints and a {}-D task, the robot has {} and {}",
                model.nq(),
                model.task_dim(),
                self.model.nq(),
                self.model.task_dim()
            )));
        }
        crate::gimbal::check(&model)?;
        let old = (
            std::mem::replace(&mut self.data, model.data()),
            std::mem::replace(&mut self.friction, FrictionStep::new(&model)),
            std::mem::replace(&mut self.model, model),
        );
        if let Err(e) = self.check_explicit_friction() {
            (self.data, self.friction, self.model) = old;
            return Err(e);
        }
        self.tau_max = self.model.tau_max().collect();
        self.q_min = self.model.q_min().collect();
        self.q_max = self.model.q_max().collect();
        Ok(())
    }

    /// The simulated robot's model (for baselines and evaluation only — never hand it to a learner).
    pub fn model(&self) -> &Model {
        &self.model
    }
    pub fn config(&self) -> &SimConfig {
        &self.cfg
    }
    /// The exact (noise-free) joint state.
    pub fn state(&self) -> (&DVector<f64>, &DVector<f64>) {
        (&self.q, &self.qd)
    }
    pub fn stats(&self) -> SimStats {
        self.stats
    }
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Fills the measurement from the exact state, adding sensor noise: kinematics, Jacobian and
    /// `ẍ = J q̈ + J̇ q̇` under the applied torque.
    fn measure(&mut self) -> Result<()> {
        accel(
            &self.model,
            &mut self.data,
            &self.u_applied,
            &self.q,
            &self.qd,
            &mut self.qdd,
        )?;
        kin(
            &self.model,
            &mut self.data,
            self.q.as_slice(),
            self.qd.as_slice(),
        )?;
        jac_fk(&self.model, &mut self.data);
        task_acceleration(&self.model, &self.data, &self.qdd, &mut self.meas.xdd);
        let sn = self.cfg.sensor_noise;
        let rng = &mut self.rng;
        let m = &mut self.meas;
        m.t = self.t;
        m.u.copy_from(&self.u_cmd);
        for i in 0..self.q.len() {
            m.q[i] = self.q[i] + noise(rng, sn.q);
            m.qd[i] = self.qd[i] + noise(rng, sn.qd);
        }
        for (k, &axis) in self.model.task_axes().iter().enumerate() {
            m.x[k] = self.data.ee_pos[axis] + noise(rng, sn.x);
            m.xd[k] = self.data.ee_vel[axis] + noise(rng, sn.xd);
            m.xdd[k] += noise(rng, sn.xdd);
        }
        Ok(())
    }

    /// With `FrictionScheme::Explicit`, refuses friction that is stiff for the step at the start
    /// posture (the explicit integrator would diverge), naming the joint and its parameters.
    fn check_explicit_friction(&mut self) -> Result<()> {
        if self.cfg.friction != FrictionScheme::Explicit || !self.friction.any() {
            return Ok(());
        }
        let h = self.cfg.control_period / self.cfg.substeps as f64;
        let rate = self
            .friction
            .rate(&self.model, &mut self.data, self.q.as_slice())?;
        if h * rate <= STIFF_LIMIT {
            return Ok(());
        }
        let l = &self.model.links()[self.friction.stiffest()];
        let f = &l.friction;
        Err(DynamicsError::InvalidConfig(format!(
            "friction = \"explicit\": joint '{}' has friction (viscous {}, coulomb {} over \
             coulomb_velocity {}) too stiff for the step of {h:e} s (h·λ̂ = {:.3} > {STIFF_LIMIT}); \
             use friction = \"auto\" or \"implicit\", or at least {} substeps",
            l.joint_name,
            f.viscous,
            f.coulomb,
            f.coulomb_velocity,
            h * rate,
            (self.cfg.control_period * rate / STIFF_LIMIT).ceil()
        )))
    }

    /// Whether this control period integrates the friction implicitly (`FrictionScheme`).
    fn implicit_friction(&mut self, h: f64) -> Result<bool> {
        if !self.friction.any() {
            return Ok(false);
        }
        Ok(match self.cfg.friction {
            FrictionScheme::Explicit => false,
            FrictionScheme::Implicit => true,
            FrictionScheme::Auto => {
                let rate = self
                    .friction
                    .rate(&self.model, &mut self.data, self.q.as_slice())?;
                h * rate > STIFF_LIMIT
            }
        })
    }

    /// One substep with implicit friction (semi-implicit Euler): the rigid-body acceleration at
    /// the current state gives `v* = q̇ + h q̈_rigid`, the new velocity solves
    /// `M (v − v*) + h τ_f(v) = 0` (backward Euler on the friction), and `q ← q + h v`. Applied
    /// torque and friction balance in one solve, so a joint that sticks stays stuck.
    fn implicit_substep(&mut self, h: f64) -> Result<()> {
        let (model, data) = (&self.model, &mut self.data);
        accel_rigid(
            model,
            data,
            &self.u_applied,
            &self.q,
            &self.qd,
            &mut self.qdd,
        )?;
        self.qd.axpy(h, &self.qdd, 1.0);
        self.friction.rate(model, data, self.q.as_slice())?;
        self.friction.step(model, &mut self.qd, h)?;
        self.q.axpy(h, &self.qd, 1.0);
        Ok(())
    }

    /// One integration step of length `h` of `(q, q̇)` in place, with or without friction.
    fn integrate(&mut self, h: f64, friction: bool) -> Result<()> {
        let (model, data, u) = (&self.model, &mut self.data, &self.u_applied);
        let accel = if friction { accel } else { accel_rigid };
        match self.cfg.integrator {
            Integrator::SemiImplicitEuler => {
                accel(model, data, u, &self.q, &self.qd, &mut self.qdd)?;
                self.qd.axpy(h, &self.qdd, 1.0);
                self.q.axpy(h, &self.qd, 1.0);
            }
            Integrator::Rk4 => {
                let [k1q, k2q, k3q, k4q] = &mut self.kq;
                let [k1v, k2v, k3v, k4v] = &mut self.kv;
                let (q0, qd0, qt) = (&self.q, &self.qd, &mut self.qt);
                // k1 at the start, k2 and k3 at the midpoint, k4 at the end.
                k1q.copy_from(qd0);
                accel(model, data, u, q0, qd0, k1v)?;
                stage(q0, k1q, 0.5 * h, qt);
                stage(qd0, k1v, 0.5 * h, k2q);
                accel(model, data, u, qt, k2q, k2v)?;
                stage(q0, k2q, 0.5 * h, qt);
                stage(qd0, k2v, 0.5 * h, k3q);
                accel(model, data, u, qt, k3q, k3v)?;
                stage(q0, k3q, h, qt);
                stage(qd0, k3v, h, k4q);
                accel(model, data, u, qt, k4q, k4v)?;
                let w = h / 6.0;
                for i in 0..self.q.len() {
                    self.q[i] += w * (k1q[i] + 2.0 * k2q[i] + 2.0 * k3q[i] + k4q[i]);
                    self.qd[i] += w * (k1v[i] + 2.0 * k2v[i] + 2.0 * k3v[i] + k4v[i]);
                }
            }
        }
        Ok(())
    }

    /// Inelastic hard stops: a joint beyond a limit is put on it and its outward velocity removed.
    /// Returns whether any joint hit a limit.
    fn enforce_limits(&mut self) -> bool {
        let mut hit = false;
        for i in 0..self.q.len() {
            if self.q[i] < self.q_min[i] {
                self.q[i] = self.q_min[i];
                self.qd[i] = self.qd[i].max(0.0);
                hit = true;
            } else if self.q[i] > self.q_max[i] {
                self.q[i] = self.q_max[i];
                self.qd[i] = self.qd[i].min(0.0);
                hit = true;
            }
        }
        hit
    }
}

/// `out = x + h k`.
#[inline]
fn stage(x: &DVector<f64>, k: &DVector<f64>, h: f64, out: &mut DVector<f64>) {
    for i in 0..x.len() {
        out[i] = x[i] + h * k[i];
    }
}

/// Rigid-body forward dynamics (no friction) into `out`.
#[inline]
fn accel_rigid(
    model: &Model,
    data: &mut Data,
    u: &DVector<f64>,
    q: &DVector<f64>,
    qd: &DVector<f64>,
    out: &mut DVector<f64>,
) -> Result<()> {
    let qdd = aba(model, data, q.as_slice(), qd.as_slice(), u.as_slice())?;
    out.copy_from(qdd);
    Ok(())
}

/// Forward dynamics with friction into `out`.
#[inline]
fn accel(
    model: &Model,
    data: &mut Data,
    u: &DVector<f64>,
    q: &DVector<f64>,
    qd: &DVector<f64>,
    out: &mut DVector<f64>,
) -> Result<()> {
    let qdd = fd(model, data, q.as_slice(), qd.as_slice(), u.as_slice())?;
    out.copy_from(qdd);
    Ok(())
}

impl Robot for SimRobot {
    fn dof(&self) -> usize {
        self.model.nq()
    }
    fn task_dim(&self) -> usize {
        self.model.task_dim()
    }
    fn control_period(&self) -> f64 {
        self.cfg.control_period
    }
    fn torque_limits(&self) -> &[f64] {
        &self.tau_max
    }
    fn joint_limits(&self) -> (&[f64], &[f64]) {
        (&self.q_min, &self.q_max)
    }
    fn measurement(&self) -> &Measurement {
        &self.meas
    }

    fn step(&mut self, u: &[f64]) -> Result<&Measurement> {
        check("u", u, self.model.nq())?;
        self.q0.copy_from(&self.q);
        self.qd0.copy_from(&self.qd);
        // Clip to the torque limits, then add actuator noise.
        let mut saturated = false;
        for (i, &ui) in u.iter().enumerate() {
            let clipped = ui.clamp(-self.tau_max[i], self.tau_max[i]);
            saturated |= clipped != ui;
            self.u_cmd[i] = clipped;
            self.u_applied[i] = clipped + noise(&mut self.rng, self.cfg.actuator_noise);
        }
        let h = self.cfg.control_period / self.cfg.substeps as f64;
        let mut hit = false;
        let mut result = self.implicit_friction(h);
        let implicit = *result.as_ref().unwrap_or(&false);
        for _ in 0..self.cfg.substeps {
            if result.is_err() {
                break;
            }
            result = if implicit {
                self.implicit_substep(h).map(|_| implicit)
            } else {
                self.integrate(h, true).map(|_| implicit)
            };
            if result.is_err() {
                break;
            }
            if self.cfg.joint_limits {
                hit |= self.enforce_limits();
            }
        }
        let finite = self.q.iter().chain(self.qd.iter()).all(|v| v.is_finite());
        if result.is_err() || !finite {
            // Keep the state from before the step.
            self.q.copy_from(&self.q0);
            self.qd.copy_from(&self.qd0);
            return Err(match result {
                Err(e @ DynamicsError::Singular { .. }) => e,
                Err(DynamicsError::Diverged { what, .. }) => {
                    DynamicsError::Diverged { t: self.t, what }
                }
                _ => DynamicsError::Diverged {
                    t: self.t,
                    what: "joint state",
                },
            });
        }
        self.t += self.cfg.control_period;
        self.stats.steps += 1;
        self.stats.implicit_friction += implicit as u64;
        self.stats.torque_saturations += saturated as u64;
        self.stats.limit_hits += hit as u64;
        self.measure()?;
        Ok(&self.meas)
    }
}
