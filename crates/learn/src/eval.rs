//! The evaluation harness: runs the learned controller without exploration on a simulated robot
//! and compares it with the analytical optimum `u*` (eq. 7, `N = I`, the true model, the same
//! `u0` form with the true gravity) at the same states and reference accelerations.
//!
//! This is the one place that reads a robot model — the simulator's, to compute `u*` — and it
//! sits outside the learner: the learner only receives the commands' measurements.

use crate::error::Result;
use crate::learner::{CommandSource, Learner};
use osrl_control::{Osc, OscConfig, TaskGains, Trajectory};
use osrl_dynamics::{Robot, SimConfig, SimRobot};
use serde::{Deserialize, Serialize};

/// Metrics of one evaluation run (definitions of issue 6).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EvalResult {
    /// RMS of `‖x − x_d‖` over whole periods after the first (mm).
    pub tracking_rms_mm: f64,
    pub tracking_max_mm: f64,
    /// Mean `‖u − u*‖²` over the summed per-joint variance of `u*`.
    pub command_nmse: f64,
    /// Mean `‖u − u0‖²` of the learned commands over that of `u*`.
    pub command_cost_ratio: f64,
    /// Share of steps where no trained local controller was active (fallback to `u0`).
    pub fallback_share: f64,
    /// Largest change of the command between consecutive steps (N·m), learned and analytical.
    pub max_command_step: f64,
    pub max_command_step_analytical: f64,
    /// Whether the run was cut short by a tracking error above 0.2 m (metrics then cover the
    /// steps before).
    pub diverged: bool,
}

/// The time series of one evaluation (for plots).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EvalSeries {
    pub t: Vec<f64>,
    /// Task position, desired and actual (row-major, `m` per step).
    pub x_d: Vec<f64>,
    pub x: Vec<f64>,
    /// Learned and optimal commands (row-major, `n` per step).
    pub u: Vec<f64>,
    pub u_star: Vec<f64>,
    pub q: Vec<f64>,
}

/// Evaluation on its own simulated robot with the true model.
pub struct Evaluator {
    sim: SimRobot,
    osc: Osc,
    traj: Trajectory,
    home: Vec<f64>,
    gains: TaskGains,
    /// Simulated seconds per evaluation (whole periods; the first is warm-up).
    pub seconds: f64,
    /// Keep the last run's time series.
    pub keep_series: bool,
    pub series: EvalSeries,
}

impl Evaluator {
    /// An evaluator for `model` (the true robot) along `traj`, starting at rest at `home`.
    pub fn new(
        model: osrl_dynamics::Model,
        sim_cfg: SimConfig,
        traj: Trajectory,
        home: Vec<f64>,
        gains: TaskGains,
        periods: usize,
    ) -> Result<Self> {
        let osc = Osc::new(
            model.clone(),
            OscConfig {
                gains,
                ..OscConfig::default()
            },
        )?;
        let sim = SimRobot::new(
            model,
            SimConfig {
                sensor_noise: Default::default(),
                actuator_noise: 0.0,
                ..sim_cfg
            },
        )?;
        let seconds = traj.period() * (periods.max(1) + 1) as f64;
        Ok(Self {
            sim,
            osc,
            traj,
            home,
            gains,
            seconds,
            keep_series: false,
            series: EvalSeries::default(),
        })
    }

    /// Runs `learner` (no exploration, no learning) from home for `self.seconds`.
    pub fn evaluate(&mut self, learner: &mut Learner) -> Result<EvalResult> {
        let (n, m) = learner.dims();
        let zeros = vec![0.0; n];
        self.sim.reset(&self.home, &zeros)?;
        let axes = self.sim.model().task_axes().to_vec();
        let dt = self.sim.control_period();
        let steps = (self.seconds / dt).round() as usize;
        let warm = (self.traj.period() / dt).round() as usize;
        let (mut u, mut u_star, mut u0) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut xdd_ref = vec![0.0; m];
        let (mut e2, mut emax, mut du2, mut c_l, mut c_s, mut fall, mut count) =
            (0.0, 0.0f64, 0.0, 0.0, 0.0, 0usize, 0usize);
        let (mut s1, mut s2) = (vec![0.0; n], vec![0.0; n]);
        let (mut prev_u, mut prev_us): (Option<Vec<f64>>, Option<Vec<f64>>) = (None, None);
        let (mut step_l, mut step_a) = (0.0f64, 0.0f64);
        let mut diverged = false;
        self.series = EvalSeries::default();
        for k in 0..steps {
            let meas = self.sim.measurement().clone();
            let t = meas.t;
            let target = self.traj.sample(t);
            osrl_control::reference_acceleration(
                &self.gains,
                &target,
                &axes,
                meas.x.as_slice(),
                meas.xd.as_slice(),
                &mut xdd_ref,
            );
            let src = learner.command::<rand_chacha::ChaCha8Rng>(
                meas.q.as_slice(),
                meas.qd.as_slice(),
                &xdd_ref,
                None,
                &mut u,
            )?;
            self.osc
                .nominal(meas.q.as_slice(), meas.qd.as_slice(), &mut u0)?;
            self.osc.solve(
                meas.q.as_slice(),
                meas.qd.as_slice(),
                &xdd_ref,
                &u0,
                &mut u_star,
            )?;
            let e = axes
                .iter()
                .enumerate()
                .map(|(j, &a)| (meas.x[j] - target.x[a]).powi(2))
                .sum::<f64>()
                .sqrt();
            if let (Some(pu), Some(ps)) = (&prev_u, &prev_us) {
                step_l = step_l.max(
                    pu.iter()
                        .zip(&u)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max),
                );
                step_a = step_a.max(
                    ps.iter()
                        .zip(&u_star)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max),
                );
            }
            prev_u = Some(u.clone());
            prev_us = Some(u_star.clone());
            if self.keep_series {
                self.series.t.push(t);
                self.series.x_d.extend(axes.iter().map(|&a| target.x[a]));
                self.series.x.extend(meas.x.iter());
                self.series.u.extend(&u);
                self.series.u_star.extend(&u_star);
                self.series.q.extend(meas.q.iter());
            }
            if k >= warm {
                count += 1;
                e2 += e * e;
                emax = emax.max(e);
                fall += (src == CommandSource::Fallback) as usize;
                for i in 0..n {
                    du2 += (u[i] - u_star[i]).powi(2);
                    c_l += (u[i] - u0[i]).powi(2);
                    c_s += (u_star[i] - u0[i]).powi(2);
                    s1[i] += u_star[i];
                    s2[i] += u_star[i] * u_star[i];
                }
            }
            if e > 0.2 {
                diverged = true;
                break;
            }
            if self.sim.step(&u).is_err() {
                diverged = true;
                break;
            }
        }
        let c = count.max(1) as f64;
        let var: f64 = (0..n)
            .map(|i| s2[i] / c - (s1[i] / c).powi(2))
            .sum::<f64>()
            .max(1e-12);
        Ok(EvalResult {
            tracking_rms_mm: 1e3 * (e2 / c).sqrt(),
            tracking_max_mm: 1e3 * emax,
            command_nmse: du2 / c / var,
            command_cost_ratio: c_l / c_s.max(1e-12),
            fallback_share: fall as f64 / c,
            max_command_step: step_l,
            max_command_step_analytical: step_a,
            diverged: diverged || count == 0,
        })
    }
}
