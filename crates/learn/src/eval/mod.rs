//! The evaluation harness: runs the learned controller without exploration on a simulated robot
//! and compares it with the analytical optimum `u*` (eq. 7, `N = I`, the true model, the same
//! `u0` form with the true gravity) at the same states and reference accelerations.
//!
//! This is the one place that reads a robot model — the simulator's, to compute `u*` — and it
//! sits outside the learner: the learner only receives the commands' measurements.

mod result;
mod true_gain;
mod window;

use crate::controller::observed_command;
use crate::error::{LearnError, Result};
use crate::learner::{CommandSource, Learner};
use osrl_control::{
    drive, ControlError, Ended, Osc, OscConfig, StepObserver, StepView, Target, TaskController,
    TaskGains, Trajectory,
};
use osrl_dynamics::{Measurement, Robot, SimConfig, SimRobot};
use std::ops::ControlFlow;

pub use result::{EvalResult, EvalSeries};
use true_gain::TrueGain;
use window::Acc;

/// Evaluation on its own simulated robot with the true model.
pub struct Evaluator {
    sim: SimRobot,
    osc: Osc,
    traj: Trajectory,
    home: Vec<f64>,
    gains: TaskGains,
    /// Simulated seconds per evaluation (the path's approach, if any, then whole periods; the
    /// approach and the first period are the warm-up).
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
        let seconds = traj.lead() + traj.period() * (periods.max(1) as f64 + 1.0);
        osrl_control::run_steps(seconds, sim.control_period()).map_err(|e| {
            osrl_control::ControlError::InvalidConfig(format!("{periods} evaluated periods: {e}"))
        })?;
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

    /// Compares the commands with eq. 7 under the metric `metric` instead of `N = I` (for a
    /// learner whose cost uses it, `controllers.metric`).
    ///
    /// # Errors
    /// The analytical controller's.
    pub fn set_metric(&mut self, metric: osrl_control::MetricKind) -> Result<()> {
        self.osc = Osc::new(
            self.sim.model().clone(),
            OscConfig {
                gains: self.gains,
                metric,
                ..OscConfig::default()
            },
        )?;
        Ok(())
    }

    /// Runs `learner` (no exploration, no learning) from home for `self.seconds` through
    /// [`osrl_control::drive`], comparing each command with `u*` at the same state.
    ///
    /// # Errors
    /// A learner or model failure; a diverged run is a result (`diverged`), not an error.
    pub fn evaluate(&mut self, learner: &mut Learner) -> Result<EvalResult> {
        // A copy: the evaluation neither learns nor leaves traces in the learner's counters or
        // its command memory (the training episode it interrupts goes on as it was).
        let learner = &mut learner.clone();
        learner.start_episode(None)?;
        let (n, m) = learner.dims();
        self.sim.reset(&self.home, &vec![0.0; n])?;
        let axes = self.sim.model().task_axes().to_vec();
        let dt = self.sim.control_period();
        let steps = (self.seconds / dt).round() as usize;
        let mut ctrl = EvalController {
            dob: learner.observer(),
            learner,
            gains: self.gains,
            axes: axes.clone(),
            xdd_ref: vec![0.0; m],
            source: CommandSource::Fallback,
            seconds: 0.0,
            error: None,
        };
        // The warm-up: the approach (if any) and the first period.
        let warm = self.traj.steps_per_period(dt) + (self.traj.lead() / dt).round() as usize;
        let mut obs = Comparison::new(&mut self.osc, axes, n, m, warm);
        obs.series = self.keep_series.then(EvalSeries::default);
        let ended = drive(&mut self.sim, &mut ctrl, &self.traj, steps, &mut obs);
        if let Some(e) = ctrl.error.take().or_else(|| obs.error.take()) {
            return Err(e);
        }
        let diverged = match ended? {
            Ended::Completed => false,
            Ended::Stopped { .. } | Ended::RobotFailed { .. } => true,
        };
        self.series = obs.series.take().unwrap_or_default();
        Ok(obs.result(diverged))
    }
}

/// The learner as the evaluated controller: `ẍ_ref` of eq. 2, then the command without
/// exploration; keeps the command's source and wall time.
struct EvalController<'a> {
    learner: &'a mut Learner,
    gains: TaskGains,
    axes: Vec<usize>,
    xdd_ref: Vec<f64>,
    /// The task-space disturbance observer (`adaptation.observer_seconds`; off by default).
    dob: crate::Dob,
    source: CommandSource,
    seconds: f64,
    /// The learner's error, if a command failed.
    error: Option<LearnError>,
}

impl TaskController for EvalController<'_> {
    fn command(
        &mut self,
        meas: &Measurement,
        target: &Target,
        u: &mut [f64],
    ) -> osrl_control::Result<()> {
        let clock = std::time::Instant::now();
        self.source = observed_command(
            self.learner,
            &self.gains,
            target,
            &self.axes,
            meas,
            &mut self.dob,
            &mut self.xdd_ref,
            u,
        )
        .map_err(|e| keep(&mut self.error, e))?;
        self.seconds = clock.elapsed().as_secs_f64();
        Ok(())
    }
}

/// Keeps the first learner error of an evaluation (the driver carries only control errors) and
/// returns the control error that stops the run.
fn keep(slot: &mut Option<LearnError>, e: LearnError) -> ControlError {
    let msg = e.to_string();
    slot.get_or_insert(e);
    ControlError::InvalidConfig(format!("learned controller: {msg}"))
}

/// Compares each evaluated command with the analytical optimum `u*` and accumulates the metrics
/// (the observer of the evaluation run).
struct Comparison<'a> {
    osc: &'a mut Osc,
    axes: Vec<usize>,
    /// Steps of the warm-up period (not in the window).
    warm: usize,
    u_star: Vec<f64>,
    u0: Vec<f64>,
    u0_hat: Vec<f64>,
    a_hat: Vec<f64>,
    /// The window of whole periods after the first, and every step (for runs that diverge
    /// before the window starts).
    window: Acc,
    all: Acc,
    /// The previous step's commands (for the largest command steps).
    prev_u: Vec<f64>,
    prev_us: Vec<f64>,
    step_l: f64,
    step_a: f64,
    series: Option<EvalSeries>,
    /// The learner's or the true model's error, if one failed.
    error: Option<LearnError>,
}

impl<'a> Comparison<'a> {
    fn new(osc: &'a mut Osc, axes: Vec<usize>, n: usize, m: usize, warm: usize) -> Self {
        Self {
            osc,
            axes,
            warm,
            u_star: vec![0.0; n],
            u0: vec![0.0; n],
            u0_hat: vec![0.0; n],
            a_hat: vec![0.0; n * m],
            window: Acc::new(n),
            all: Acc::new(n),
            prev_u: vec![0.0; n],
            prev_us: vec![0.0; n],
            step_l: 0.0,
            step_a: 0.0,
            series: None,
            error: None,
        }
    }

    fn result(&self, diverged: bool) -> EvalResult {
        let acc = if self.window.count > 0 {
            &self.window
        } else {
            &self.all
        };
        acc.result(self.step_l, self.step_a, diverged || self.window.count == 0)
    }

    /// `u*` (eq. 7 with the true model) and the true `u0` at the step's state.
    fn optimum(&mut self, meas: &Measurement, xdd_ref: &[f64]) -> Result<()> {
        let (q, qd) = (meas.q.as_slice(), meas.qd.as_slice());
        self.osc.nominal(q, qd, &mut self.u0)?;
        self.osc.solve(q, qd, xdd_ref, &self.u0, &mut self.u_star)?;
        Ok(())
    }

    fn record(&mut self, step: &StepView, seconds: f64) {
        let Some(series) = self.series.as_mut() else {
            return;
        };
        series.t.push(step.meas.t);
        series
            .x_d
            .extend(self.axes.iter().map(|&a| step.target.x[a]));
        series.x.extend(step.meas.x.iter());
        series.u.extend(step.u);
        series.u_star.extend(&self.u_star);
        series.q.extend(step.meas.q.iter());
        series.command_seconds.push(seconds);
    }
}

/// One step's error split against the true `A = J M⁻¹` (0 where `A` is singular): the parts of
/// `u − u*` and of `û0 − u0` in its null space, `‖û0 − u0‖²`, and the error of `Â` (if any).
struct Split {
    null2: f64,
    nom_null2: f64,
    nom2: f64,
    gain_err: Option<f64>,
    floor_null2: Option<f64>,
}

impl Comparison<'_> {
    /// The error split of the learned command `u` at `(q, q̇)` (after [`Comparison::optimum`]).
    fn split(&mut self, learner: &mut Learner, q: &[f64], qd: &[f64], u: &[f64]) -> Result<Split> {
        learner.nominal_in_command(q, qd, &mut self.u0_hat)?;
        let truth = TrueGain::new(self.osc.data(), &self.axes);
        let null2 = truth
            .as_ref()
            .map_or(0.0, |t| t.null_part2(u, &self.u_star));
        let nom_null2 = truth
            .as_ref()
            .map_or(0.0, |t| t.null_part2(&self.u0_hat, &self.u0));
        let has_gain = learner.input_gain(q, qd, &mut self.a_hat)?;
        let floor_null2 = truth
            .as_ref()
            .filter(|_| has_gain)
            .and_then(|t| t.floor_null2(&self.a_hat, &self.u0_hat, &self.u_star));
        let gain_err = truth
            .filter(|_| has_gain)
            .map(|t| t.gain_error(&self.a_hat));
        let nom2: f64 = self
            .u0_hat
            .iter()
            .zip(&self.u0)
            .map(|(a, b)| (a - b).powi(2))
            .sum();
        Ok(Split {
            null2,
            nom_null2,
            nom2,
            gain_err,
            floor_null2,
        })
    }

    /// Adds one step to the window (from step `warm` on) and to the whole run.
    fn accumulate(&mut self, k: usize, e: f64, source: (bool, bool), u: &[f64], split: &Split) {
        for (acc, on) in [(&mut self.window, k >= self.warm), (&mut self.all, true)] {
            if on {
                acc.add(e, source, u, &self.u_star, &self.u0);
                acc.null2 += split.null2;
                acc.nom2 += split.nom2;
                acc.nom_null2 += split.nom_null2;
                if let Some(g) = split.gain_err {
                    acc.gain_err += g;
                    acc.gain_count += 1;
                }
                if let Some(f) = split.floor_null2 {
                    acc.floor_null2 += f;
                    acc.floor_count += 1;
                }
            }
        }
    }
}

impl StepObserver<EvalController<'_>> for Comparison<'_> {
    fn observe(
        &mut self,
        ctrl: &mut EvalController,
        step: &StepView,
    ) -> osrl_control::Result<ControlFlow<()>> {
        let (meas, u) = (step.meas, step.u);
        let (q, qd) = (meas.q.as_slice(), meas.qd.as_slice());
        let split = self
            .optimum(meas, &ctrl.xdd_ref)
            .and_then(|()| self.split(ctrl.learner, q, qd, u));
        let split = match split {
            Ok(split) => split,
            Err(e) => return Err(keep(&mut self.error, e)),
        };
        let e = osrl_control::task_error(step.target, &self.axes, meas.x.as_slice());
        if step.k > 0 {
            self.step_l = self.step_l.max(max_abs_diff(&self.prev_u, u));
            self.step_a = self.step_a.max(max_abs_diff(&self.prev_us, &self.u_star));
        }
        self.prev_u.copy_from_slice(u);
        self.prev_us.copy_from_slice(&self.u_star);
        self.record(step, ctrl.seconds);
        let source = (
            ctrl.source == CommandSource::Fallback,
            ctrl.source == CommandSource::Learned,
        );
        self.accumulate(step.k, e, source, u, &split);
        Ok(if e > 0.2 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        })
    }
}

/// The largest per-joint change `max_j |a_j − b_j|` between two commands.
pub(crate) fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
