//! The TOML config file of the whole tool: robot, trajectory, controller (gains, metric), simulator
//! and model error. Every section and field is optional; a missing one keeps its documented
//! default, an unknown one is an error. Other commands add their sections here.
//!
//! ```toml
//! robot = "sarcos7"
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
//! ```

use anyhow::{bail, Context, Result};
use osrl_control::{ModelError, OscConfig, TrajectoryConfig};
use osrl_dynamics::SimConfig;
use serde::{Deserialize, Serialize};
use std::path::Path;

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
    /// Built-in robot name (`planar3`, `sarcos7`) or URDF path. Default `planar3`.
    pub robot: String,
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
}

impl Default for Config {
    fn default() -> Self {
        Self {
            robot: "planar3".into(),
            trajectory: TrajectoryConfig::default(),
            controller: OscConfig::default(),
            sim: SimConfig::default(),
            model_error: ModelError::default(),
            simulate: SimulateConfig::default(),
        }
    }
}

impl Config {
    /// Reads a TOML file (missing fields keep their defaults), or the defaults without a file.
    pub fn load(path: Option<&Path>) -> Result<Self> {
        let Some(p) = path else {
            return Ok(Self::default());
        };
        let text =
            std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
        toml::from_str(&text).with_context(|| format!("parsing config {}", p.display()))
    }

    /// Checks every section that can be checked without the robot (the trajectory is checked when
    /// it is built for the robot).
    pub fn validate(&self) -> Result<()> {
        self.controller.validate()?;
        self.sim.validate()?;
        self.model_error.validate()?;
        let s = self.simulate.seconds;
        if !(s > 0.0 && s.is_finite()) {
            bail!("simulate.seconds must be a positive number, got {s}");
        }
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
        assert_eq!(partial.robot, "sarcos7");
        assert_eq!(partial.controller.law, osrl_control::Law::Eq4);
        assert_eq!(partial.sim, SimConfig::default());
        assert!(toml::from_str::<Config>("robt = \"x\"").is_err());
        assert!(toml::from_str::<Config>("[controller]\nkp = 3.0").is_err());
        let bad: Config = toml::from_str("[simulate]\nseconds = -1.0").unwrap();
        assert!(bad.validate().is_err());
    }
}
