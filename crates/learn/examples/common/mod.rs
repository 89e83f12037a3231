//! What the figure examples share: the command line, the robot set-up, a small training run, an
//! evaluation with its time series, an analytical eq. 7 run, and CSV output.
//!
//! Flags: `--robot planar3|sarcos7` (default planar3), `--minutes M` (simulated training
//! minutes, babbling included; default per example), `--seed S` (0), `--seeds N` (examples over
//! seeds; default per example), `--out DIR` (target/figures).
#![allow(dead_code)] // each example uses its part

use osrl_control::{check_reachable, run_closed_loop, IkOptions, ModelError, Osc, OscConfig};
use osrl_control::{Run, Trajectory, TrajectoryConfig};
use osrl_dynamics::{robots, Model, SimConfig, SimRobot};
use osrl_learn::eval::{EvalResult, EvalSeries, Evaluator};
use osrl_learn::train::{train_simulated, BabbleConfig, TrainConfig, TrainSummary};
use osrl_learn::{Learner, LearnerConfig};
use std::io::Write;
use std::path::PathBuf;

pub type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// The command line.
pub struct Args {
    pub robot: String,
    pub minutes: f64,
    pub seed: u64,
    pub seeds: u64,
    pub out: PathBuf,
}

impl Args {
    /// Parses `--key value` pairs; `minutes` and `seeds` are the example's defaults.
    pub fn parse(minutes: f64, seeds: u64) -> Res<Self> {
        let mut a = Args {
            robot: "planar3".into(),
            minutes,
            seed: 0,
            seeds,
            out: "target/figures".into(),
        };
        let argv: Vec<String> = std::env::args().skip(1).collect();
        for pair in argv.chunks(2) {
            let v = pair.get(1).ok_or(format!("{} needs a value", pair[0]))?;
            match pair[0].as_str() {
                "--robot" => a.robot = v.clone(),
                "--minutes" => a.minutes = v.parse()?,
                "--seed" => a.seed = v.parse()?,
                "--seeds" => a.seeds = v.parse()?,
                "--out" => a.out = v.into(),
                f => {
                    return Err(format!(
                        "unknown flag {f} (--robot --minutes --seed --seeds --out)"
                    )
                    .into())
                }
            }
        }
        std::fs::create_dir_all(&a.out)?;
        Ok(a)
    }
}

/// A robot with the default figure-8 and the home posture at rest on its start.
pub struct Setup {
    pub model: Model,
    pub traj: Trajectory,
    pub home: Vec<f64>,
    /// Control steps per period of the figure-8.
    pub per_period: usize,
}

impl Setup {
    pub fn new(robot: &str) -> Res<Self> {
        let model = robots::by_name(robot)?;
        let traj = TrajectoryConfig::default().build(&model)?;
        let home = check_reachable(&model, &traj, &IkOptions::default())?.q_start;
        let per_period = (traj.period() / SimConfig::default().control_period).round() as usize;
        Ok(Self {
            model,
            traj,
            home,
            per_period,
        })
    }

    /// Trains a learner (`variant` edits the robot's default config) for `minutes` with `seed`,
    /// evaluating every `eval_every` simulated minutes (and at the end).
    pub fn train(
        &self,
        minutes: f64,
        seed: u64,
        eval_every: f64,
        variant: impl FnOnce(&mut LearnerConfig),
    ) -> Res<(Learner, TrainSummary)> {
        let spec = self.model.spec();
        let mut lcfg = LearnerConfig::for_robot(
            &spec.kp,
            &spec.kd,
            &spec.q_rest,
            &self.model.tau_max().collect::<Vec<_>>(),
        );
        variant(&mut lcfg);
        let babble = BabbleConfig::default();
        let tcfg = TrainConfig {
            minutes,
            seed,
            eval_every_minutes: eval_every,
            // Small runs babble for at most 40 % of their time (as `osrl reproduce --quick`).
            babble: BabbleConfig {
                minutes: babble.minutes.min(0.4 * minutes),
                ..babble
            },
            ..TrainConfig::default()
        };
        Ok(train_simulated(
            &self.model,
            &self.traj,
            &self.home,
            lcfg,
            &tcfg,
            1,
            &mut |_| {},
        )?)
    }

    /// Evaluates `learner` on `truth` (without exploration) over `periods` periods after a warm-up
    /// period, keeping the time series.
    pub fn evaluate(
        &self,
        truth: &Model,
        learner: &mut Learner,
        periods: usize,
    ) -> Res<(EvalResult, EvalSeries)> {
        let gains = TrainConfig::default().gains;
        let mut ev = Evaluator::new(
            truth.clone(),
            SimConfig::default(),
            self.traj.clone(),
            self.home.clone(),
            gains,
            periods,
        )?;
        ev.keep_series = true;
        let r = ev.evaluate(learner)?;
        Ok((r, ev.series))
    }

    /// Analytical eq. 7 (`N = I`, the training's task gains) with the model `error` on the true
    /// robot (which carries the error's payload, if any) for `periods` periods after a warm-up.
    pub fn analytical(&self, error: &ModelError, periods: usize) -> Res<Run> {
        let (sim_model, ctrl_model) = error.apply(&self.model)?;
        let cfg = OscConfig {
            gains: TrainConfig::default().gains,
            ..OscConfig::default()
        };
        let mut osc = Osc::new(ctrl_model, cfg)?;
        let mut sim = SimRobot::new(sim_model, SimConfig::default())?;
        sim.reset(&self.home, &vec![0.0; self.model.nq()])?;
        let seconds = self.traj.period() * (periods + 1) as f64;
        Ok(run_closed_loop(
            &mut sim,
            &mut osc,
            &self.traj,
            self.model.task_axes(),
            seconds,
        )?)
    }

    /// Names of the task coordinates (`x`, `z` for planar3).
    pub fn axis_names(&self) -> Vec<&'static str> {
        self.model
            .task_axes()
            .iter()
            .map(|&a| ["x", "y", "z"][a])
            .collect()
    }
}

/// `‖x − x_d‖` (mm) per row of row-major `x` and `x_d` with `m` columns.
pub fn errors_mm(x: &[f64], x_d: &[f64], m: usize) -> Vec<f64> {
    x.chunks(m)
        .zip(x_d.chunks(m))
        .map(|(a, b)| {
            1e3 * a
                .iter()
                .zip(b)
                .map(|(p, q)| (p - q).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect()
}

/// Column `j` of a row-major matrix with `w` columns.
pub fn column(v: &[f64], w: usize, j: usize) -> Vec<f64> {
    v.iter().skip(j).step_by(w).copied().collect()
}

/// Writes `columns` under `header` to `dir/name` (shorter columns leave empty cells).
pub fn write_csv(
    dir: &std::path::Path,
    name: &str,
    header: &[String],
    columns: &[Vec<f64>],
) -> Res<()> {
    let path = dir.join(name);
    let mut w = std::io::BufWriter::new(std::fs::File::create(&path)?);
    writeln!(w, "{}", header.join(","))?;
    for k in 0..columns.iter().map(Vec::len).max().unwrap_or(0) {
        let row: Vec<String> = columns
            .iter()
            .map(|c| c.get(k).map_or(String::new(), |v| v.to_string()))
            .collect();
        writeln!(w, "{}", row.join(","))?;
    }
    w.flush()?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The learning-curve columns of a training run: minutes, tracking, command nMSE, cost ratio,
/// diverged (1/0).
pub fn curve_columns(summary: &TrainSummary) -> Vec<Vec<f64>> {
    // The driver's final evaluation can fall on a scheduled one's minute: keep the last.
    let all = &summary.learning_curve;
    let keep = |i: usize| all.get(i + 1).is_none_or(|n| (n.0 - all[i].0).abs() > 1e-9);
    let c: Vec<_> = (0..all.len())
        .filter(|&i| keep(i))
        .map(|i| &all[i])
        .collect();
    let f = |g: fn(&EvalResult) -> f64| c.iter().map(|(_, e)| g(e)).collect();
    vec![
        c.iter().map(|p| p.0).collect(),
        f(|e| e.tracking_rms_mm),
        f(|e| e.command_nmse),
        f(|e| e.command_cost_ratio),
        f(|e| e.diverged as u8 as f64),
    ]
}

pub const CURVE_HEADER: [&str; 5] = [
    "sim_minutes",
    "tracking_rms_mm",
    "command_nmse",
    "command_cost_ratio",
    "diverged",
];

/// `12.345` or `diverged (12.345)`.
pub fn mm(e: &EvalResult) -> String {
    if e.diverged {
        format!("diverged ({:.3})", e.tracking_rms_mm)
    } else {
        format!("{:.3}", e.tracking_rms_mm)
    }
}
