//! The closed-loop driver: a [`TaskController`] on a [`Robot`] following a [`Trajectory`] for a
//! given time, with the time series and the tracking metrics.

use crate::controller::TaskController;
use crate::error::{ControlError, Result};
use crate::trajectory::{Target, Trajectory};
use osrl_dynamics::{Measurement, Robot};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// Most control steps of one recorded run ([`run_closed_loop`], an evaluation): the series is
/// kept in memory (about 170 bytes a step for 7 joints), so a run's length is bounded.
pub const MAX_RUN_STEPS: usize = 500_000;

/// The number of control steps of `seconds` at control period `dt`, checked: `seconds` must be
/// positive, finite and at most [`MAX_RUN_STEPS`] steps long.
///
/// # Errors
/// [`ControlError::InvalidConfig`] naming the value and the accepted range.
pub fn run_steps(seconds: f64, dt: f64) -> Result<usize> {
    let max = MAX_RUN_STEPS as f64 * dt;
    let steps = (seconds / dt).round();
    if !(seconds > 0.0 && steps <= MAX_RUN_STEPS as f64 && dt.is_finite()) || dt <= 0.0 {
        return Err(ControlError::InvalidConfig(format!(
            "seconds = {seconds:?}: accepted range 0 < seconds ≤ {max:?} s (at most {MAX_RUN_STEPS} \
             control steps of {dt:?} s)"
        )));
    }
    Ok(steps as usize)
}

/// Time series of one run, one row per control step (row-major flat vectors).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// Joints `n` and task dimension `m`.
    pub n: usize,
    pub m: usize,
    /// Time of the measurement (s).
    pub t: Vec<f64>,
    /// Desired task position (m), `m` per row.
    pub x_d: Vec<f64>,
    /// Measured task position (m), `m` per row.
    pub x: Vec<f64>,
    /// Measured joint positions (rad), `n` per row.
    pub q: Vec<f64>,
    /// Command sent (N·m, before the robot's torque-limit clipping), `n` per row.
    pub u: Vec<f64>,
}

impl Series {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.t.len()
    }
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
    /// Tracking error `‖x − x_d‖` (m) of row `k`.
    pub fn error(&self, k: usize) -> f64 {
        let r = k * self.m..(k + 1) * self.m;
        self.x[r.clone()]
            .iter()
            .zip(&self.x_d[r])
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt()
    }
}

/// Metrics of one run. Tracking and command metrics cover the evaluation window: whole periods
/// of the trajectory after the first (the first period, with the start ramp, is the warm-up).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// RMS of `‖x − x_d‖` over the window (mm).
    pub tracking_rms_mm: f64,
    /// Largest `‖x − x_d‖` in the window (mm).
    pub tracking_max_mm: f64,
    /// RMS of all joint commands in the window (N·m).
    pub command_rms: f64,
    /// Simulated time (s).
    pub sim_seconds: f64,
    /// Start (s) and number of whole periods of the window.
    pub window_start_s: f64,
    pub window_periods: usize,
    /// Posture drift per period: `max_i |q_i(end) − q_i(start)|` over the window divided by the
    /// number of periods (rad). Zero for a motion that repeats every period.
    pub joint_drift_rad: f64,
    /// Largest distance of any joint from its start position during the run (rad).
    pub max_joint_excursion_rad: f64,
    /// Smallest distance of any joint to its position limits during the run (rad); ≤ 0 means a
    /// joint reached a limit.
    pub min_limit_margin_rad: f64,
    /// Control steps in which some joint was at or beyond a position limit.
    pub limit_steps: usize,
    /// Time (s) a joint first reached a position limit, if one did.
    pub first_limit_s: Option<f64>,
    /// Control steps in which some command exceeded its torque limit (and was clipped).
    pub torque_saturation_steps: usize,
}

/// A run's series, metrics and final joint positions.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub series: Series,
    pub metrics: Metrics,
    pub q_final: Vec<f64>,
}

/// One control step as the driver shows it to a [`StepObserver`]: the measurement at time `t`,
/// the target `traj.sample(t)` and the command about to be applied for one control period.
#[derive(Clone, Copy, Debug)]
pub struct StepView<'a> {
    /// Index of the step (0 for the first).
    pub k: usize,
    pub meas: &'a Measurement,
    pub target: &'a Target,
    pub u: &'a [f64],
}

/// Watches a closed-loop run step by step; may stop it. It also sees the controller, so it can
/// ask it (or the model behind it) about the step it just commanded.
pub trait StepObserver<C: ?Sized> {
    /// Called after the command of each step and before it is applied.
    /// `ControlFlow::Break` ends the run before this step's command is applied.
    ///
    /// # Errors
    /// Any error ends the run and is returned by [`drive`].
    fn observe(&mut self, ctrl: &mut C, step: &StepView) -> Result<ControlFlow<()>>;
}

/// How a run driven by [`drive`] ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Ended {
    /// All steps were applied.
    Completed,
    /// The observer stopped it at step `k` (not applied).
    Stopped { k: usize },
    /// The robot refused the command of step `k` (e.g. a diverged simulation).
    RobotFailed { k: usize, error: ControlError },
}

/// Runs `ctrl` on `robot` along `traj` for `steps` control periods from the robot's current
/// state: each step reads the measurement at time `t`, asks for the command for
/// `traj.sample(t)`, shows the step to `obs` and applies the command for one period.
///
/// # Errors
/// The first controller or observer error; a robot that refuses a command ends the run with
/// [`Ended::RobotFailed`] instead.
pub fn drive<R, C, O>(
    robot: &mut R,
    ctrl: &mut C,
    traj: &Trajectory,
    steps: usize,
    obs: &mut O,
) -> Result<Ended>
where
    R: Robot + ?Sized,
    C: TaskController + ?Sized,
    O: StepObserver<C> + ?Sized,
{
    let mut u = vec![0.0; robot.dof()];
    for k in 0..steps {
        let meas = robot.measurement();
        let target = traj.sample(meas.t);
        ctrl.command(meas, &target, &mut u)?;
        let view = StepView {
            k,
            meas,
            target: &target,
            u: &u,
        };
        if obs.observe(ctrl, &view)?.is_break() {
            return Ok(Ended::Stopped { k });
        }
        if let Err(e) = robot.step(&u) {
            return Ok(Ended::RobotFailed { k, error: e.into() });
        }
    }
    Ok(Ended::Completed)
}

/// Distance (rad or m) from a position limit within which a joint counts as at the limit.
pub(crate) const AT_LIMIT: f64 = 1e-9;

/// Records the series of a run and counts limits and saturation (the observer of
/// [`run_closed_loop`]).
struct Recorder {
    s: Series,
    task_axes: Vec<usize>,
    q_min: Vec<f64>,
    q_max: Vec<f64>,
    tau_max: Vec<f64>,
    limit_steps: usize,
    sat_steps: usize,
    margin: f64,
    first_limit: Option<f64>,
}

impl<C: ?Sized> StepObserver<C> for Recorder {
    fn observe(&mut self, _: &mut C, step: &StepView) -> Result<ControlFlow<()>> {
        let (meas, u, s) = (step.meas, step.u, &mut self.s);
        s.t.push(meas.t);
        s.x_d
            .extend(self.task_axes.iter().map(|&a| step.target.x[a]));
        s.x.extend(meas.x.iter());
        s.q.extend(meas.q.iter());
        s.u.extend(u);
        let mut at_limit = false;
        for i in 0..s.n {
            let d = (meas.q[i] - self.q_min[i]).min(self.q_max[i] - meas.q[i]);
            self.margin = self.margin.min(d);
            at_limit |= d <= AT_LIMIT;
        }
        self.limit_steps += at_limit as usize;
        if at_limit && self.first_limit.is_none() {
            self.first_limit = Some(meas.t);
        }
        self.sat_steps += u.iter().zip(&self.tau_max).any(|(v, l)| v.abs() > *l) as usize;
        Ok(ControlFlow::Continue(()))
    }
}

/// Runs `ctrl` on `robot` along `traj` for `seconds` of simulated time (rounded to whole control
/// periods), from the robot's current state (reset it at rest on the path first, e.g. at
/// [`crate::Reach::q_start`]), recording the series and measuring the tracking ([`drive`] with a
/// recorder). `task_axes` are the world axes of the measured task coordinates.
///
/// # Errors
/// If `seconds` does not cover at least two periods (one warm-up, one evaluated), or the first
/// controller or robot error.
pub fn run_closed_loop<R, C>(
    robot: &mut R,
    ctrl: &mut C,
    traj: &Trajectory,
    task_axes: &[usize],
    seconds: f64,
) -> Result<Run>
where
    R: Robot + ?Sized,
    C: TaskController + ?Sized,
{
    let (n, m, dt) = (robot.dof(), robot.task_dim(), robot.control_period());
    if task_axes.len() != m {
        return Err(ControlError::Dimension {
            what: "task_axes",
            expected: m,
            got: task_axes.len(),
        });
    }
    let period = traj.period();
    run_steps(seconds, dt)?;
    let steps = (seconds / dt).round();
    let per_period = traj.steps_per_period(dt);
    let periods = if steps.is_finite() && steps >= 0.0 {
        (steps as usize).saturating_sub(per_period) / per_period.max(1)
    } else {
        0
    };
    if periods == 0 || per_period == 0 {
        return Err(ControlError::InvalidConfig(format!(
            "run for at least two periods of the trajectory ({:.3} s) to evaluate whole periods \
             after the first; got {seconds} s",
            2.0 * period
        )));
    }
    let steps = steps as usize;
    let (q_min, q_max) = robot.joint_limits();
    let mut rec = Recorder {
        s: Series {
            n,
            m,
            ..Series::default()
        },
        task_axes: task_axes.to_vec(),
        q_min: q_min.to_vec(),
        q_max: q_max.to_vec(),
        tau_max: robot.torque_limits().to_vec(),
        limit_steps: 0,
        sat_steps: 0,
        margin: f64::INFINITY,
        first_limit: None,
    };
    let s = &mut rec.s;
    s.t.reserve(steps);
    s.x_d.reserve(steps * m);
    s.x.reserve(steps * m);
    s.q.reserve(steps * n);
    s.u.reserve(steps * n);
    if let Ended::RobotFailed { error, .. } = drive(robot, ctrl, traj, steps, &mut rec)? {
        return Err(error);
    }
    let q_final = robot.measurement().q.as_slice().to_vec();
    let metrics = evaluate(&rec.s, &q_final, per_period, periods, steps as f64 * dt);
    Ok(Run {
        metrics: Metrics {
            min_limit_margin_rad: rec.margin,
            limit_steps: rec.limit_steps,
            first_limit_s: rec.first_limit,
            torque_saturation_steps: rec.sat_steps,
            ..metrics
        },
        series: rec.s,
        q_final,
    })
}

/// Window metrics of a series: rows `[per_period, per_period·(1 + periods))`.
fn evaluate(s: &Series, q_final: &[f64], per_period: usize, periods: usize, sim: f64) -> Metrics {
    let (a, b) = (per_period, per_period * (1 + periods));
    let n = s.n;
    let (mut e2, mut emax, mut u2) = (0.0, 0.0f64, 0.0);
    for k in a..b {
        let e = s.error(k);
        e2 += e * e;
        emax = emax.max(e);
        u2 += s.u[k * n..(k + 1) * n].iter().map(|v| v * v).sum::<f64>();
    }
    let count = (b - a) as f64;
    let q_at = |k: usize| -> &[f64] {
        if k < s.len() {
            &s.q[k * n..(k + 1) * n]
        } else {
            q_final
        }
    };
    let (qa, qb) = (q_at(a), q_at(b));
    let drift = (0..n).map(|i| (qb[i] - qa[i]).abs()).fold(0.0, f64::max) / periods as f64;
    let q0 = q_at(0);
    let mut excursion = 0.0f64;
    for k in 0..s.len() {
        let q = q_at(k);
        for i in 0..n {
            excursion = excursion.max((q[i] - q0[i]).abs());
        }
    }
    Metrics {
        tracking_rms_mm: 1e3 * (e2 / count).sqrt(),
        tracking_max_mm: 1e3 * emax,
        command_rms: (u2 / (count * n as f64)).sqrt(),
        sim_seconds: sim,
        window_start_s: s.t[a],
        window_periods: periods,
        joint_drift_rad: drift,
        max_joint_excursion_rad: excursion,
        min_limit_margin_rad: f64::INFINITY,
        limit_steps: 0,
        first_limit_s: None,
        torque_saturation_steps: 0,
    }
}
