//! [`Results`]: the typed schema of `results.json`, the numbers of experiments E1–E7 of an
//! `osrl reproduce` run. Maps are keyed by robot (`planar3`, `sarcos7`) and, below, by case;
//! every key of the file is a field here. [`Results::to_json`] writes the keys of every
//! object in sorted order, as the file has always been written.

use crate::error::{ExperimentError, Result};
use crate::sizes::Sizes;
use crate::stats::{EvalSummary, Outcome, Spread, SpreadSeries, Stat};
use osrl_learn::train::TrainConfig;
use osrl_learn::LearnerConfig;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// Per robot.
pub type ByRobot<T> = BTreeMap<String, T>;

/// The whole of `results.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// E1 (paper Fig. 1): RWR with adaptive vs fixed reward transformation on the toy problem.
    #[serde(rename = "E1")]
    pub e1: rwr::toy::Report,
    /// E2: the analytical controllers with the true model, keyed `<robot>_<eq4|eq7>`.
    #[serde(rename = "E2")]
    pub e2: BTreeMap<String, AnalyticalRow>,
    /// E3 (Fig. 2a/2b, 3b): the learned controller's final evaluation over its seeds.
    #[serde(rename = "E3")]
    pub e3: ByRobot<Outcome<LearnedRow>>,
    /// E4 (Fig. 2c): learned vs analytical commands per joint (seed 0).
    #[serde(rename = "E4")]
    pub e4: ByRobot<Outcome<Commands>>,
    /// E5 (Sec. V): learning curves over the seeds.
    #[serde(rename = "E5")]
    pub e5: ByRobot<Outcome<Curves>>,
    /// E6 (Sec. II, IV): the ablation, keyed by [`osrl_learn::Variant::key`].
    #[serde(rename = "E6")]
    pub e6: ByRobot<BTreeMap<String, Outcome<AblationRow>>>,
    /// E7 (Sec. I): eq. 7 with a wrong model vs the learned controller, keyed by model error.
    #[serde(rename = "E7")]
    pub e7: ByRobot<BTreeMap<String, ModelErrorRow>>,
    /// E8 (issue 26): the robot changes under a controller trained on the unchanged arm —
    /// re-adapting, frozen, eq. 7 with the stale model — keyed by change (absent in files
    /// written before E8).
    #[serde(rename = "E8", default)]
    pub e8: ByRobot<BTreeMap<String, crate::e8::ChangeRow>>,
    /// E9 (issue 27): controllers trained on the figure-8 only and on the family of paths,
    /// on held-out paths ([`crate::e9`]); absent for runs without it.
    #[serde(rename = "E9", default, skip_serializing_if = "BTreeMap::is_empty")]
    pub e9: ByRobot<crate::e9::E9Row>,
    /// The settings of the run.
    pub config: RunConfig,
    /// Training seeds of the learned controller (E3, E5).
    pub seeds: Vec<u64>,
    /// Wall time of the whole run (s).
    pub wall_seconds: f64,
}

/// The settings of a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunConfig {
    /// Whether the sizes are `--quick`'s.
    pub quick: bool,
    pub sizes: Sizes,
    /// Threads the training runs shared.
    pub threads: usize,
    /// The learner's defaults (each robot fills in its data sheet: gains, rest posture, limits).
    pub learner_defaults: LearnerConfig,
    /// The training run's defaults (the sizes set minutes, babbling, evaluation interval, seed).
    pub train_defaults: TrainConfig,
}

/// One analytical run (`osrl simulate`'s metrics).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AnalyticalRow {
    pub robot: String,
    /// `eq4` or `eq7`.
    pub controller: String,
    /// The controller's model error (`none`, or its spec).
    pub model_error: String,
    pub tracking_rms_mm: f64,
    pub tracking_max_mm: f64,
    pub command_rms: f64,
    pub sim_seconds: f64,
    pub window_start_s: f64,
    pub window_periods: usize,
    pub joint_drift_rad: f64,
    pub max_joint_excursion_rad: f64,
    pub min_limit_margin_rad: f64,
    pub limit_steps: usize,
    /// When a joint first reached a position limit (absent if none did).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_limit_s: Option<f64>,
    pub torque_saturation_steps: usize,
}

impl AnalyticalRow {
    /// The metrics of a run of `controller` on `robot` with `model_error`.
    pub fn new(
        m: &osrl_control::Metrics,
        robot: &str,
        controller: &str,
        model_error: String,
    ) -> Self {
        Self {
            robot: robot.into(),
            controller: controller.into(),
            model_error,
            tracking_rms_mm: m.tracking_rms_mm,
            tracking_max_mm: m.tracking_max_mm,
            command_rms: m.command_rms,
            sim_seconds: m.sim_seconds,
            window_start_s: m.window_start_s,
            window_periods: m.window_periods,
            joint_drift_rad: m.joint_drift_rad,
            max_joint_excursion_rad: m.max_joint_excursion_rad,
            min_limit_margin_rad: m.min_limit_margin_rad,
            limit_steps: m.limit_steps,
            first_limit_s: m.first_limit_s,
            torque_saturation_steps: m.torque_saturation_steps,
        }
    }
}

/// The final evaluations of a set of training runs (one learner over its seeds): mean, min
/// and max of each metric over the runs whose evaluation did not diverge, and each run's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunsSummary {
    pub runs: usize,
    pub tracking_rms_mm: Stat,
    pub command_nmse: Stat,
    pub command_cost_ratio: Stat,
    pub fallback_share: Stat,
    /// Over all runs, diverged or not.
    pub n_local_models: Spread,
    pub sim_training_minutes: Spread,
    pub wall_seconds: Spread,
    pub realtime_factor: Spread,
    /// Largest on-policy command step of training (N·m).
    pub max_command_step: Spread,
    /// Largest step of `u*` in the final evaluation (N·m).
    pub max_command_step_analytical: Spread,
    pub diverged_runs: usize,
    pub per_seed: Vec<EvalSummary>,
    /// Each run's learning safety, in the order of `per_seed`.
    #[serde(default)]
    pub safety: Vec<SafetyRow>,
}

/// The learning safety of one training run: what a physical robot would have gone through.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SafetyRow {
    /// On-policy episodes stopped at the reset error (the arm taken home).
    pub aborted_episodes: u64,
    /// Episodes ended early (braked) on a growing error or a command jump.
    pub braked_episodes: u64,
    /// On-policy commands clipped to the torque limits.
    pub clipped_on_policy: u64,
    /// Learned commands that fell back to `u0` (no trained field near).
    pub fallbacks: u64,
    /// Commands held to the torque-rate limit.
    pub rate_limited: u64,
    /// Largest on-policy command step (N·m) and torque rate (N·m/s).
    pub max_command_step: f64,
    pub max_torque_rate: f64,
    /// Largest step of eq. 7's `u*` in the final evaluation (N·m).
    pub max_command_step_analytical: f64,
    /// First evaluation at or below 1 mm tracking / 0.05 command nMSE (simulated minutes).
    pub minutes_to_1mm: Option<f64>,
    pub minutes_to_nmse_0_05: Option<f64>,
    /// The largest on-policy command step per bin of simulated time.
    pub step_curve: Vec<osrl_learn::train::StepPoint>,
}

/// E3 for one robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LearnedRow {
    #[serde(flatten)]
    pub summary: RunsSummary,
    /// Eq. 7 with the true model on the same path (E2), for comparison.
    pub analytical_eq7_tracking_rms_mm: Option<f64>,
    /// The seeds that failed, with their errors.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub failed_seeds: Vec<String>,
}

/// E6 for one robot and learner variant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AblationRow {
    #[serde(flatten)]
    pub summary: RunsSummary,
    /// Legend text ([`osrl_learn::Variant::label`]).
    pub label: String,
    /// Seeds that finished.
    pub seeds: usize,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub failed_seeds: Vec<String>,
}

/// E4 for one robot: the learned commands against `u*` over the last evaluated cycle.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Commands {
    pub command_nmse: f64,
    pub command_cost_ratio: f64,
    /// Per joint, RMS of `u − u*` and of `u*` (N·m).
    pub per_joint_rms_difference_nm: Vec<f64>,
    pub per_joint_rms_u_star_nm: Vec<f64>,
    pub seed: u64,
}

/// Learning curves over seeds (E5; also each E6 variant's, in the figure inputs): at each
/// evaluation where some seed did not diverge, mean/min/max over those seeds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Curves {
    pub seeds: usize,
    pub sim_minutes: Vec<f64>,
    pub tracking_rms_mm: SpreadSeries,
    pub command_nmse: SpreadSeries,
    pub command_cost_ratio: SpreadSeries,
}

/// E7 for one robot and model error.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelErrorRow {
    pub analytical_eq7_tracking_rms_mm: Option<f64>,
    pub analytical_eq7_tracking_max_mm: Option<f64>,
    /// The error's spec (`none` for the true model).
    pub model_error: Option<String>,
    /// The learned controller on the robot: trained on the true one (it has no model to be
    /// wrong), or, for the payload, trained on the robot carrying it.
    pub learned_tracking_rms_mm: Stat,
    /// Payload only: the runs trained with the payload.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub learned_trained_with_payload: Option<RunsSummary>,
    /// Payload only: seed 0 trained without the payload, evaluated with it (not retrained).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub learned_trained_without_payload: Option<EvalSummary>,
}

impl Results {
    /// As `results.json` holds it: pretty JSON, the keys of every object sorted.
    ///
    /// # Errors
    /// Only for a value serde cannot represent (none here).
    pub fn to_json(&self) -> Result<String> {
        let json = |e| ExperimentError::Json {
            path: "results".into(),
            source: e,
        };
        // Through `Value` (a sorted map): the layout `results.json` has always had.
        let v = serde_json::to_value(self).map_err(json)?;
        serde_json::to_string_pretty(&v).map_err(json)
    }

    /// Writes [`Results::to_json`] to `path`.
    ///
    /// # Errors
    /// [`ExperimentError::File`].
    pub fn save(&self, path: &Path) -> Result<()> {
        Ok(osrl_files::write_atomic(path, self.to_json()?.as_bytes())?)
    }

    /// Reads a `results.json`.
    ///
    /// # Errors
    /// [`ExperimentError::File`], or [`ExperimentError::Json`] for a file of another layout (a
    /// number written as `null` — a NaN — included).
    pub fn load(path: &Path) -> Result<Self> {
        // At most 256 MiB, a regular file (a FIFO would block).
        let text = osrl_files::read_text_limited(path, 256 << 20)?;
        serde_json::from_str(&text).map_err(|source| ExperimentError::Json {
            path: path.display().to_string(),
            source,
        })
    }
}
