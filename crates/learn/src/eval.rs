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
    /// The part of `command_nmse` in the null space of the true `A = J M⁻¹` (`‖(I − A⁺A)(u −
    /// u*)‖²`, same normalisation): the redundancy resolution's share of the error.
    #[serde(default)]
    pub command_nmse_null: f64,
    /// The learned nominal behaviour's error, `‖û0 − u0‖²` (learned `ĝ` vs true `g`), with the
    /// same normalisation: a floor of `command_nmse` set by the gravity model.
    #[serde(default)]
    pub nominal_nmse: f64,
    /// Its part in the null space of the true `A` (the part the task cannot correct).
    #[serde(default)]
    pub nominal_nmse_null: f64,
    /// Mean relative error `‖Â − A‖_F / ‖A‖_F` of the learner's blended input gain `Â = ∂ẍ/∂u`
    /// against the true `A = J M⁻¹` (steps where the learner has one).
    #[serde(default)]
    pub gain_error: f64,
    /// The scales behind the ratios: summed per-joint variance of `u*` (N²·m²) and mean
    /// `‖u* − u0‖²` (N²·m²).
    #[serde(default)]
    pub u_star_variance: f64,
    #[serde(default)]
    pub u_star_cost: f64,
    /// Share of steps where no trained local controller was active (fallback to `u0`).
    pub fallback_share: f64,
    /// Largest change of the command between consecutive steps (N·m), learned and analytical.
    pub max_command_step: f64,
    pub max_command_step_analytical: f64,
    /// Whether the run was cut short by a tracking error above 0.2 m, or never reached the
    /// evaluated window; the metrics then cover the steps before (all steps if the window was
    /// never reached).
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
    /// Wall time of each learned command (s): what a controller command costs on this model.
    pub command_seconds: Vec<f64>,
}

impl EvalSeries {
    /// The `p`-quantile (0–1, nearest rank) of the command wall times in µs; `None` if none.
    pub fn command_us_quantile(&self, p: f64) -> Option<f64> {
        let mut v = self.command_seconds.clone();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let k = ((v.len() - 1) as f64 * p.clamp(0.0, 1.0)).round() as usize;
        Some(v[k] * 1e6)
    }
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
        let mut u0_hat = vec![0.0; n];
        let mut a_hat = vec![0.0; n * m];
        let mut xdd_ref = vec![0.0; m];
        let (mut window, mut all) = (Acc::new(n), Acc::new(n));
        // The previous step's commands (for the largest command steps), from the second step on.
        let (mut prev_u, mut prev_us) = (vec![0.0; n], vec![0.0; n]);
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
            let clock = std::time::Instant::now();
            let src = learner.command::<rand_chacha::ChaCha8Rng>(
                meas.q.as_slice(),
                meas.qd.as_slice(),
                &xdd_ref,
                None,
                &mut u,
            )?;
            let command_seconds = clock.elapsed().as_secs_f64();
            self.osc
                .nominal(meas.q.as_slice(), meas.qd.as_slice(), &mut u0)?;
            self.osc.solve(
                meas.q.as_slice(),
                meas.qd.as_slice(),
                &xdd_ref,
                &u0,
                &mut u_star,
            )?;
            learner.nominal(meas.q.as_slice(), meas.qd.as_slice(), &mut u0_hat)?;
            // The error split against the true B = J M⁻¹ at this state (0 where B is singular).
            let truth = TrueGain::new(self.osc.data(), &axes);
            let null2 = truth.as_ref().map_or(0.0, |t| t.null_part2(&u, &u_star));
            let nom_null2 = truth.as_ref().map_or(0.0, |t| t.null_part2(&u0_hat, &u0));
            let has_gain = learner.input_gain(meas.q.as_slice(), meas.qd.as_slice(), &mut a_hat)?;
            let gain_err = truth.filter(|_| has_gain).map(|t| t.gain_error(&a_hat));
            let nom2: f64 = u0_hat.iter().zip(&u0).map(|(a, b)| (a - b).powi(2)).sum();
            let e = axes
                .iter()
                .enumerate()
                .map(|(j, &a)| (meas.x[j] - target.x[a]).powi(2))
                .sum::<f64>()
                .sqrt();
            if k > 0 {
                step_l = step_l.max(max_abs_diff(&prev_u, &u));
                step_a = step_a.max(max_abs_diff(&prev_us, &u_star));
            }
            prev_u.copy_from_slice(&u);
            prev_us.copy_from_slice(&u_star);
            if self.keep_series {
                self.series.t.push(t);
                self.series.x_d.extend(axes.iter().map(|&a| target.x[a]));
                self.series.x.extend(meas.x.iter());
                self.series.u.extend(&u);
                self.series.u_star.extend(&u_star);
                self.series.q.extend(meas.q.iter());
                self.series.command_seconds.push(command_seconds);
            }
            // The window of whole periods after the first; `all` covers every step, for runs that
            // diverge before the window starts.
            for (acc, on) in [(&mut window, k >= warm), (&mut all, true)] {
                if on {
                    acc.add(e, src == CommandSource::Fallback, &u, &u_star, &u0);
                    acc.null2 += null2;
                    acc.nom2 += nom2;
                    acc.nom_null2 += nom_null2;
                    if let Some(g) = gain_err {
                        acc.gain_err += g;
                        acc.gain_count += 1;
                    }
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
        let acc = if window.count > 0 { &window } else { &all };
        Ok(acc.result(step_l, step_a, diverged || window.count == 0))
    }
}

/// Sums of one evaluation window.
struct Acc {
    count: usize,
    e2: f64,
    emax: f64,
    du2: f64,
    c_l: f64,
    c_s: f64,
    null2: f64,
    nom2: f64,
    nom_null2: f64,
    gain_err: f64,
    gain_count: usize,
    fall: usize,
    s1: Vec<f64>,
    s2: Vec<f64>,
}

impl Acc {
    fn new(n: usize) -> Self {
        Self {
            count: 0,
            e2: 0.0,
            emax: 0.0,
            du2: 0.0,
            c_l: 0.0,
            c_s: 0.0,
            null2: 0.0,
            nom2: 0.0,
            nom_null2: 0.0,
            gain_err: 0.0,
            gain_count: 0,
            fall: 0,
            s1: vec![0.0; n],
            s2: vec![0.0; n],
        }
    }

    fn add(&mut self, e: f64, fallback: bool, u: &[f64], u_star: &[f64], u0: &[f64]) {
        self.count += 1;
        self.e2 += e * e;
        self.emax = self.emax.max(e);
        self.fall += fallback as usize;
        for i in 0..u.len() {
            self.du2 += (u[i] - u_star[i]).powi(2);
            self.c_l += (u[i] - u0[i]).powi(2);
            self.c_s += (u_star[i] - u0[i]).powi(2);
            self.s1[i] += u_star[i];
            self.s2[i] += u_star[i] * u_star[i];
        }
    }

    fn result(&self, step_l: f64, step_a: f64, diverged: bool) -> EvalResult {
        let c = self.count.max(1) as f64;
        let var: f64 = (0..self.s1.len())
            .map(|i| self.s2[i] / c - (self.s1[i] / c).powi(2))
            .sum::<f64>()
            .max(1e-12);
        EvalResult {
            tracking_rms_mm: 1e3 * (self.e2 / c).sqrt(),
            tracking_max_mm: 1e3 * self.emax,
            command_nmse: self.du2 / c / var,
            command_cost_ratio: self.c_l / self.c_s.max(1e-12),
            command_nmse_null: self.null2 / c / var,
            nominal_nmse: self.nom2 / c / var,
            nominal_nmse_null: self.nom_null2 / c / var,
            u_star_variance: var,
            u_star_cost: self.c_s / c,
            gain_error: self.gain_err / self.gain_count.max(1) as f64,
            fallback_share: self.fall as f64 / c,
            max_command_step: step_l,
            max_command_step_analytical: step_a,
            diverged,
        }
    }
}

/// The true input gain `B = J M⁻¹` (task rows, m×n) at one state and `(B Bᵀ)⁻¹`, formed once
/// per evaluation step for the error split. Allocates (evaluation only, not a control path).
struct TrueGain {
    b: nalgebra::DMatrix<f64>,
    s_inv: nalgebra::DMatrix<f64>,
}

impl TrueGain {
    /// From the dynamics in `data`; `None` if `M` or `B Bᵀ` does not invert.
    fn new(data: &osrl_dynamics::Data, axes: &[usize]) -> Option<Self> {
        let n = data.mass.nrows();
        let j = nalgebra::DMatrix::from_fn(axes.len(), n, |r, c| data.jac[(axes[r], c)]);
        let b = j * data.mass.clone().try_inverse()?;
        let s_inv = (&b * b.transpose()).try_inverse()?;
        Some(Self { b, s_inv })
    }

    /// `‖Â − B‖_F / ‖B‖_F` for the learner's `Â` (m×n row-major).
    fn gain_error(&self, a_hat: &[f64]) -> f64 {
        let n = self.b.ncols();
        let d = nalgebra::DMatrix::from_fn(self.b.nrows(), n, |r, c| a_hat[r * n + c]) - &self.b;
        d.norm() / self.b.norm().max(1e-300)
    }

    /// `‖(I − B⁺B)(u − v)‖²`, the part of `u − v` in the null space of `B`.
    fn null_part2(&self, u: &[f64], v: &[f64]) -> f64 {
        let e = nalgebra::DVector::from_fn(u.len(), |i, _| u[i] - v[i]);
        let range = self.b.transpose() * (&self.s_inv * (&self.b * &e));
        (e - range).norm_squared()
    }
}

/// The largest per-joint change `max_j |a_j − b_j|` between two commands.
pub(crate) fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
