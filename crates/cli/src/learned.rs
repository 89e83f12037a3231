//! The learned controller on the CLI side: the saved model (learner file plus a JSON sidecar),
//! the training set-up shared by `osrl train` and `osrl reproduce`, and a [`TaskController`]
//! wrapper so `osrl simulate --controller learned:MODEL` can run it.
//!
//! A saved model is two files: `MODEL`, the learner itself ([`Learner::save`]: versioned,
//! checksummed), and `MODEL.json`, the [`Sidecar`] with what the learner does not know — which
//! robot it was trained on, the trajectory, the home posture, the task gains and the control
//! period — so `osrl eval --model MODEL` needs no other flag.

use crate::util::load_robot;
use anyhow::{bail, Context, Result};
use osrl_control::{
    check_reachable, reference_acceleration, IkOptions, Target, TaskController, TaskGains,
    Trajectory, TrajectoryConfig,
};
use osrl_dynamics::{Measurement, Model, SimConfig};
use osrl_learn::eval::{EvalResult, Evaluator};
use osrl_learn::train::{Progress, TrainConfig, TrainSummary};
use osrl_learn::{CommandSource, Learner, LearnerConfig};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// Version of the sidecar's layout.
pub const SIDECAR_VERSION: u32 = 1;

/// `MODEL.json`: what `osrl eval` and `osrl simulate` need besides the learner.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sidecar {
    /// [`SIDECAR_VERSION`].
    pub version: u32,
    /// Built-in robot name or URDF path (absolute) the learner was trained on.
    pub robot: String,
    /// The training trajectory (robot defaults for unset fields).
    pub trajectory: TrajectoryConfig,
    /// Home posture (rad): at rest on the start of the training path.
    pub home: Vec<f64>,
    /// Task-space gains of the reference dynamics (eq. 2) used in training.
    pub gains: TaskGains,
    /// Control period (s).
    pub control_period: f64,
    /// Simulated minutes of training and the training seed.
    pub sim_training_minutes: f64,
    pub seed: u64,
}

/// Path of the sidecar of `model`: `MODEL.json` (the suffix appended, not replaced).
pub fn sidecar_path(model: &Path) -> PathBuf {
    let mut s = model.as_os_str().to_owned();
    s.push(".json");
    PathBuf::from(s)
}

/// Writes the learner to `path` and the sidecar to `path.json`.
pub fn save_model(path: &Path, learner: &Learner, sidecar: &Sidecar) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    learner
        .save(path)
        .with_context(|| format!("saving {}", path.display()))?;
    let side = sidecar_path(path);
    // As the learner: a failed write leaves any old sidecar whole.
    let text = serde_json::to_string_pretty(sidecar)? + "\n";
    lwpr::write_atomic(&side, text.as_bytes())
        .with_context(|| format!("writing {}", side.display()))
}

/// Reads a model saved by [`save_model`]; fails if either file is missing or malformed, or if
/// they do not fit together (dimensions).
pub fn load_model(path: &Path) -> Result<(Learner, Sidecar)> {
    let mut learner = Learner::load(path).with_context(|| format!("loading {}", path.display()))?;
    let side = sidecar_path(path);
    let text = std::fs::read_to_string(&side)
        .with_context(|| format!("reading {} (the model's sidecar)", side.display()))?;
    let sc: Sidecar =
        serde_json::from_str(&text).with_context(|| format!("parsing {}", side.display()))?;
    if sc.version != SIDECAR_VERSION {
        bail!(
            "{}: sidecar version {}, this build reads {SIDECAR_VERSION}",
            side.display(),
            sc.version
        );
    }
    let (n, _) = learner.dims();
    if sc.home.len() != n {
        bail!(
            "{}: home posture has {} joints, the learner {n}",
            side.display(),
            sc.home.len()
        );
    }
    // A controller saved without torque limits gets its robot's (data sheet).
    if learner.config().guards.torque_limits.is_empty() {
        let model = load_robot(&sc.robot)?;
        let tau_max: Vec<f64> = model.tau_max().collect();
        learner
            .set_torque_limits(&LearnerConfig::data_sheet_limits(&tau_max))
            .with_context(|| format!("torque limits of {} for {}", sc.robot, path.display()))?;
    }
    Ok((learner, sc))
}

/// A robot with its trajectory and the home posture at rest on the path start.
#[derive(Clone)]
pub struct Setup {
    pub model: Model,
    pub traj: Trajectory,
    pub traj_cfg: TrajectoryConfig,
    pub home: Vec<f64>,
}

impl Setup {
    /// Builds the trajectory for `model` and checks it is reachable.
    pub fn new(model: Model, traj_cfg: TrajectoryConfig) -> Result<Self> {
        let traj = traj_cfg.build(&model)?;
        let home = check_reachable(&model, &traj, &IkOptions::default())?.q_start;
        Ok(Self {
            model,
            traj,
            traj_cfg,
            home,
        })
    }

    /// From a robot spec (name or URDF path).
    pub fn for_robot(robot: &str, traj_cfg: TrajectoryConfig) -> Result<Self> {
        Self::new(load_robot(robot)?, traj_cfg)
    }

    /// An evaluator on `truth` (this robot's model, or one with a payload) over `periods`
    /// evaluated periods after a warm-up period.
    pub fn evaluator(&self, truth: Model, gains: TaskGains, periods: usize) -> Result<Evaluator> {
        Ok(Evaluator::new(
            truth,
            SimConfig::default(),
            self.traj.clone(),
            self.home.clone(),
            gains,
            periods,
        )?)
    }
}

/// Trains a fresh learner with `lcfg` on the simulated `truth` robot (at rest at home), evaluating
/// on the same robot with `eval_periods` periods; `observe` sees each evaluation.
pub fn train_learner(
    setup: &Setup,
    truth: &Model,
    lcfg: LearnerConfig,
    tcfg: &TrainConfig,
    eval_periods: usize,
    observe: &mut dyn FnMut(&Progress),
) -> Result<(Learner, TrainSummary)> {
    osrl_learn::train::train_simulated(
        truth,
        &setup.traj,
        &setup.home,
        lcfg,
        tcfg,
        eval_periods,
        observe,
    )
    .context("training")
}

/// Whether an evaluation measured anything. The library reports, for a run that diverged during
/// its warm-up period, the metrics of the steps before the divergence (flagged `diverged`); only a
/// run that failed at its very first step has zeros, which are not measurements.
pub fn measured(e: &EvalResult) -> bool {
    !(e.diverged && e.tracking_rms_mm == 0.0)
}

/// The metrics of one evaluation as JSON (the keys of issue 6). A run that diverged during the
/// warm-up has only `"diverged": true` and `"evaluated": false` — no invented numbers; one that
/// diverged later has the metrics of the steps before.
pub fn eval_json(e: &EvalResult) -> Value {
    if !measured(e) {
        return json!({"diverged": true, "evaluated": false,
                      "max_command_step_analytical": e.max_command_step_analytical});
    }
    json!({
        "tracking_rms_mm": e.tracking_rms_mm,
        "tracking_max_mm": e.tracking_max_mm,
        "command_nmse": e.command_nmse,
        "command_cost_ratio": e.command_cost_ratio,
        "fallback_share": e.fallback_share,
        "max_command_step_eval": e.max_command_step,
        "max_command_step_analytical": e.max_command_step_analytical,
        "diverged": e.diverged,
        "evaluated": true,
    })
}

/// `[{sim_minutes, tracking_rms_mm, command_nmse, diverged}, ...]` (the metrics left out where
/// the evaluation diverged in its warm-up); an evaluation at the same simulated minute as the
/// previous one (the driver's final evaluation after a scheduled one at the end) is listed once.
pub fn curve_json(curve: &[(f64, EvalResult)]) -> Value {
    dedup_curve(curve)
        .iter()
        .map(|(t, e)| {
            if measured(e) {
                json!({"sim_minutes": t, "tracking_rms_mm": e.tracking_rms_mm,
                       "command_nmse": e.command_nmse, "diverged": e.diverged})
            } else {
                json!({"sim_minutes": t, "diverged": true})
            }
        })
        .collect()
}

/// A saved learner as a task-space controller: `ẍ_ref` from eq. 2 with the training gains, then
/// the learned command (eq. 34) without exploration. Counts where the commands came from.
pub struct LearnedController {
    pub learner: Learner,
    pub gains: TaskGains,
    axes: Vec<usize>,
    xdd_ref: Vec<f64>,
    /// Commands by source: learned blend, extrapolated, fallback to `u0`.
    pub counts: [u64; 3],
}

impl LearnedController {
    /// `axes`: the world axes of the task coordinates (the robot's task axes).
    pub fn new(learner: Learner, gains: TaskGains, axes: &[usize]) -> Self {
        Self {
            learner,
            gains,
            xdd_ref: vec![0.0; axes.len()],
            axes: axes.to_vec(),
            counts: [0; 3],
        }
    }
}

impl TaskController for LearnedController {
    fn command(
        &mut self,
        meas: &Measurement,
        target: &Target,
        u: &mut [f64],
    ) -> osrl_control::Result<()> {
        reference_acceleration(
            &self.gains,
            target,
            &self.axes,
            meas.x.as_slice(),
            meas.xd.as_slice(),
            &mut self.xdd_ref,
        );
        let src = self
            .learner
            .command::<rand_chacha::ChaCha8Rng>(
                meas.q.as_slice(),
                meas.qd.as_slice(),
                &self.xdd_ref,
                None,
                u,
            )
            // The control crate has no variant for a foreign controller's failure.
            .map_err(|e| osrl_control::ControlError::InvalidConfig(format!("learned: {e}")))?;
        self.counts[match src {
            CommandSource::Learned => 0,
            CommandSource::Extrapolated => 1,
            CommandSource::Fallback => 2,
        }] += 1;
        Ok(())
    }
}

/// The curve without repeated evaluations at the same simulated minute (keeps the last).
pub fn dedup_curve(curve: &[(f64, EvalResult)]) -> Vec<(f64, EvalResult)> {
    let mut out: Vec<(f64, EvalResult)> = Vec::with_capacity(curve.len());
    for (t, e) in curve {
        match out.last_mut() {
            Some(last) if (last.0 - t).abs() < 1e-9 => *last = (*t, e.clone()),
            _ => out.push((*t, e.clone())),
        }
    }
    out
}
