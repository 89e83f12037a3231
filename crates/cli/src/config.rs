//! The TOML config file of the whole tool: robot, trajectory, controller (gains, metric), simulator
//! and model error. Every section and field is optional; a missing one keeps its documented
//! default, an unknown one is an error. Other commands add their sections here.
//!
//! ```toml
//! robot = "sarcos7"       # or a [robot] section: name + robot profile (robot_entry.rs)
//! [trajectory]            # osrl_control::TrajectoryConfig
//! kind = "figure8"
//! period = 4.0
//! [controller]            # osrl_control::OscConfig
//! law = "eq7"
//! metric = "identity"
//! gains = { kp = 900.0, kd = 60.0 }
//! [sim]                   # osrl_dynamics::SimConfig
//! control_period = 0.002
//! [model_error]           # osrl_control::ModelError
//! mass_scale = 1.3
//! [simulate]
//! seconds = 12.0
//! [learner]               # osrl_learn::LearnerConfig (`osrl train`); empty nominal, torque_limits = robot's
//! controllers = { trained_ess = 50.0 }
//! [train]                 # osrl_learn::train::TrainConfig (`osrl train`)
//! minutes = 30.0
//! babble = { minutes = 4.0 }
//! ```

use crate::robot_entry::RobotEntry;
use anyhow::{bail, Context, Result};
use osrl_control::{ModelError, OscConfig, TrajectoryConfig};
use osrl_dynamics::SimConfig;
use osrl_learn::train::TrainConfig;
use osrl_learn::LearnerConfig;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Longest training run (simulated minutes, `train.minutes`, `--minutes`): about a week.
pub const MAX_TRAIN_MINUTES: f64 = 10_000.0;
/// Most integration steps per control period (`[sim] substeps`) of the commands.
pub const MAX_SUBSTEPS: usize = 100;
/// Most evaluations of one training run (`train.eval_every_minutes`).
pub const MAX_EVALUATIONS: usize = 1000;

/// Settings of `osrl simulate`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimulateConfig {
    /// Simulated time (s). Default 12 (three periods of the default figure-8: one warm-up, two
    /// evaluated).
    pub seconds: f64,
}

impl Default for SimulateConfig {
    fn default() -> Self {
        Self { seconds: 12.0 }
    }
}

/// The whole config file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Config {
    /// Built-in robot name (`planar3`, `sarcos7`) or URDF path (`robot = "..."`), or a
    /// `[robot]` section with `name` and a robot profile (`osrl_dynamics::RobotProfile`: tip,
    /// locks, postures, gains, torque limits, path placement; unset values are computed from
    /// the model). Default `planar3` with its data sheet.
    pub robot: RobotEntry,
    /// Task-space trajectory; unset fields take the robot's defaults.
    pub trajectory: TrajectoryConfig,
    /// Analytical controller: law, metric, task gains, nominal scale, damping.
    pub controller: OscConfig,
    /// Simulated robot: control period (default 2 ms), substeps, noise, seed, joint limits.
    pub sim: SimConfig,
    /// How the controller's model differs from the simulated robot. Default none.
    pub model_error: ModelError,
    /// `osrl simulate` settings.
    pub simulate: SimulateConfig,
    /// The learned controller (`osrl train`). The nominal behaviour's gains and rest posture and
    /// the torque limits, when left empty, are the robot's
    /// ([`osrl_experiments::Setup::with_learner`]).
    pub learner: LearnerConfig,
    /// The training run (`osrl train`): minutes, babbling, task gains, evaluation interval, seed.
    pub train: TrainConfig,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            robot: RobotEntry::from(crate::robot_entry::DEFAULT_ROBOT),
            trajectory: TrajectoryConfig::default(),
            controller: OscConfig::default(),
            sim: SimConfig::default(),
            model_error: ModelError::default(),
            simulate: SimulateConfig::default(),
            learner: LearnerConfig::default(),
            train: TrainConfig::default(),
        }
    }
}

impl Config {
    /// Reads a TOML file (missing fields keep their defaults), or the defaults without a file.
    pub fn load(path: Option<&Path>) -> Result<Self> {
        let Some(p) = path else {
            return Ok(Self::default());
        };
        crate::util::read_toml(p)
    }

    /// As [`Config::load`], with the file's TOML table (empty without a file): the top-level
    /// keys and sections it sets, and the tables inside them, so a command can refuse a section
    /// it has no use for.
    pub fn load_with_sections(path: Option<&Path>) -> Result<(Self, toml::Table)> {
        let Some(p) = path else {
            return Ok((Self::default(), toml::Table::new()));
        };
        let text = osrl_files::read_text_limited(p, crate::util::MAX_CONFIG_BYTES)?;
        let cfg: Self = crate::util::parse_toml(p, &text)?;
        let table: toml::Table = crate::util::parse_toml(p, &text)?;
        Ok((cfg, table))
    }

    /// Checks every section that can be checked without the robot (the trajectory is checked when
    /// it is built for the robot).
    pub fn validate(&self) -> Result<()> {
        self.controller.validate()?;
        self.sim.validate()?;
        if self.sim.substeps > MAX_SUBSTEPS {
            bail!(
                "[sim] substeps = {}: accepted range 1–{MAX_SUBSTEPS}",
                self.sim.substeps
            );
        }
        let dt = self.sim.control_period;
        if !osrl_learn::CONTROL_PERIOD_RANGE.contains(&dt) {
            bail!(
                "[sim] control_period = {dt:?} s: accepted range {:?}–{:?} s",
                osrl_learn::CONTROL_PERIOD_RANGE.start(),
                osrl_learn::CONTROL_PERIOD_RANGE.end()
            );
        }
        self.model_error.validate()?;
        let t = &self.train;
        if !(t.minutes > 0.0 && t.minutes <= MAX_TRAIN_MINUTES) {
            bail!(
                "train.minutes (--minutes) = {:?}: accepted range 0 < minutes ≤ {MAX_TRAIN_MINUTES}",
                t.minutes
            );
        }
        let min_every = t.minutes / MAX_EVALUATIONS as f64;
        if !(t.eval_every_minutes == 0.0
            || (t.eval_every_minutes >= min_every && t.eval_every_minutes.is_finite()))
        {
            bail!(
                "train.eval_every_minutes = {:?}: accepted 0 (only at the end) or {min_every:?} to \
                 any finite number (at most {MAX_EVALUATIONS} evaluations in {} minutes)",
                t.eval_every_minutes,
                t.minutes
            );
        }
        if !(t.babble.minutes >= 0.0 && t.babble.minutes <= MAX_TRAIN_MINUTES) {
            bail!(
                "train.babble.minutes = {:?}: accepted range 0–{MAX_TRAIN_MINUTES}",
                t.babble.minutes
            );
        }
        t.gains.validate()?;
        let s = self.simulate.seconds;
        osrl_control::run_steps(s, self.sim.control_period)
            .context("[simulate] seconds (--seconds)")?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_round_trip_and_unknown_fields_are_errors() {
        let text = toml::to_string(&Config::default()).unwrap();
        let back: Config = toml::from_str(&text).unwrap();
        assert_eq!(back, Config::default());
        let partial: Config =
            toml::from_str("robot = \"sarcos7\"\n[controller]\nlaw = \"eq4\"\n").unwrap();
        assert_eq!(partial.robot.name(), "sarcos7");
        let section: Config = toml::from_str(
            "[robot]\nname = \"x.urdf\"\nkp = [1.0, 2.0]\npath = { scale = 0.05 }\n",
        )
        .unwrap();
        assert_eq!(section.robot.name(), "x.urdf");
        assert_eq!(section.robot.0.kp, Some(vec![1.0, 2.0]));
        assert_eq!(section.robot.0.path.scale, Some(0.05));
        let text = toml::to_string(&section).unwrap();
        assert_eq!(toml::from_str::<Config>(&text).unwrap(), section);
        let err = toml::from_str::<Config>("[robot]\nname = \"x\"\nkpp = [1.0]").unwrap_err();
        assert!(err.to_string().contains("kpp"), "{err}");
        assert_eq!(partial.controller.law, osrl_control::Law::Eq4);
        assert_eq!(partial.sim, SimConfig::default());
        assert!(toml::from_str::<Config>("robt = \"x\"").is_err());
        assert!(toml::from_str::<Config>("[controller]\nkp = 3.0").is_err());
        let bad: Config = toml::from_str("[simulate]\nseconds = -1.0").unwrap();
        assert!(bad.validate().is_err());
        let l: Config = toml::from_str(
            "[learner]\ncontrollers = { trained_ess = 20.0 }\n[train]\nminutes = 3.0\nbabble = { minutes = 1.0 }",
        )
        .unwrap();
        assert_eq!(l.learner.controllers.trained_ess, 20.0);
        assert_eq!((l.train.minutes, l.train.babble.minutes), (3.0, 1.0));
        let setup = osrl_experiments::Setup::new("planar3").unwrap();
        let lc = setup.with_learner(l.learner.clone()).unwrap();
        let model = lc.model();
        assert_eq!(lc.learner_config().nominal.kp, model.spec().kp);
        assert_eq!(
            lc.learner_config().guards.torque_limits,
            model.tau_max().collect::<Vec<_>>()
        );
        assert!(toml::from_str::<Config>(
            "[learner]
controllers = { trained_es = 2.0 }"
        )
        .is_err());
        assert!(toml::from_str::<Config>("[train]\nminutes = -2.0")
            .unwrap()
            .validate()
            .is_err());
    }
}
