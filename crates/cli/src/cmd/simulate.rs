//! `osrl simulate`: an analytical operational space controller (eq. 4 or eq. 7) on the simulated
//! robot along a task-space trajectory, optionally with a wrong model. Prints the tracking
//! metrics; with `--json` the last stdout line is one JSON object; with `--out DIR` it writes
//! `simulate.csv` (time series), `path.svg/png` (desired vs actual path, error over time),
//! `metrics.json` and the effective `config.toml`.
//!
//! `--controller learned:MODEL` runs a controller saved by `osrl train` instead: the robot, the
//! trajectory and the control period default to the model's, a model error's payload goes on
//! the simulated robot (the other errors concern an analytical model, which it does not have).

use crate::config::Config;
use crate::robot_entry::ProfileArgs;
use crate::util::{print_json, trajectory_kind};
use anyhow::{bail, Context, Result};
use osrl_control::{Law, MetricKind, ModelError, Osc};
use osrl_experiments::Setup;
use osrl_learn::SavedModel;
use std::path::PathBuf;
use std::time::Instant;

/// `eq4`, `eq7` or `learned:MODEL`.
fn parse_controller(s: &str) -> std::result::Result<String, String> {
    match s {
        "eq4" | "eq7" => Ok(s.into()),
        _ if s.strip_prefix("learned:").is_some_and(|p| !p.is_empty()) => Ok(s.into()),
        _ => Err("use eq4, eq7 or learned:MODEL (a file saved by `osrl train`)".into()),
    }
}

/// Arguments of `osrl simulate` (flags override the config file).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Robot: `planar3`, `sarcos7` or a URDF file (default: the config's, planar3).
    #[arg(long)]
    pub robot: Option<String>,
    /// Controller: `eq4`, `eq7` (analytical) or `learned:MODEL` (saved by `osrl train`)
    /// (default: the config's, eq7).
    #[arg(long, value_parser = parse_controller)]
    pub controller: Option<String>,
    /// Metric N of eq. 7: `identity`, `mass`, `inverse_mass` (default: the config's, identity).
    #[arg(long, value_parser = ["identity", "mass", "inverse_mass"])]
    pub metric: Option<String>,
    /// Trajectory: `figure8`, `circle` or `min_jerk` (default: the config's, figure8).
    #[arg(long, value_parser = ["figure8", "circle", "min_jerk"])]
    pub trajectory: Option<String>,
    /// Simulated seconds (default: the config's, 12).
    #[arg(long)]
    pub seconds: Option<f64>,
    /// TOML config file (see `config.rs`); missing fields keep their defaults.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Model error of the controller's model, e.g. `mass=1.3,com=0.02,friction=off,payload=0.5`.
    #[arg(long)]
    pub model_error: Option<String>,
    #[command(flatten)]
    pub profile: ProfileArgs,
    /// Directory for simulate.csv, path.svg/png, metrics.json and config.toml.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the result as one JSON object on the last stdout line.
    #[arg(long)]
    pub json: bool,
}

/// The config file with the flags applied, validated; with a learned controller, its robot,
/// trajectory and control period are the defaults.
fn effective_config(a: &Args, learned: Option<&SavedModel>) -> Result<Config> {
    let mut cfg = Config::load(a.config.as_deref())?;
    if let Some(info) = learned.map(SavedModel::info) {
        cfg.robot.set_name(&info.robot);
        cfg.trajectory = info.trajectory.clone();
        if a.robot.as_ref().is_some_and(|r| *r != info.robot) {
            bail!(
                "--robot {}: the learned controller was trained on {}",
                a.robot.as_deref().unwrap_or(""),
                info.robot
            );
        }
        let dt = cfg.sim.control_period;
        if dt != osrl_dynamics::SimConfig::default().control_period && dt != info.control_period {
            bail!(
                "[sim] control_period = {dt:?} s: the learned controller was trained at {} s",
                info.control_period
            );
        }
        cfg.sim.control_period = info.control_period;
    }
    if let Some(r) = &a.robot {
        cfg.robot.set_name(r);
    }
    cfg.robot.0 = a.profile.apply(&cfg.robot.0)?;
    if let Some(c) = a
        .controller
        .as_deref()
        .filter(|c| !c.starts_with("learned:"))
    {
        cfg.controller.law = if c == "eq4" { Law::Eq4 } else { Law::Eq7 };
    }
    if let Some(m) = &a.metric {
        cfg.controller.metric = match m.as_str() {
            "mass" => MetricKind::Mass,
            "inverse_mass" => MetricKind::InverseMass,
            _ => MetricKind::Identity,
        };
    }
    if let Some(t) = &a.trajectory {
        cfg.trajectory.kind = trajectory_kind(t);
    }
    if let Some(s) = a.seconds {
        cfg.simulate.seconds = s;
    }
    if let Some(spec) = &a.model_error {
        cfg.model_error = spec.parse::<ModelError>()?;
    }
    cfg.validate()?;
    Ok(cfg)
}

/// Runs the closed loop, prints the summary, writes the files.
pub fn run(a: Args) -> Result<()> {
    let model_path = a
        .controller
        .as_deref()
        .and_then(|c| c.strip_prefix("learned:"))
        .map(PathBuf::from);
    let loaded = model_path.as_deref().map(SavedModel::load).transpose()?;
    let cfg = effective_config(&a, loaded.as_ref())?;
    if let Some(dir) = &a.out {
        let robot = crate::util::robot_file(a.robot.as_deref());
        let inputs = [a.config.as_deref(), model_path.as_deref(), robot];
        crate::util::check_out_dir("--out", dir, &osrl_report::runs::SIMULATE_FILES, &inputs)?;
    }
    // A learned controller runs on the robot it was trained on, saved with it (its profile
    // included), not on the file read again.
    let setup = match &loaded {
        Some(saved) if cfg.robot.0.is_empty() => Setup::from_saved(saved)?,
        Some(_) => bail!(
            "a robot profile ([robot] section, --profile, --tip, --lock, --unlock) has no use with \
             a learned controller: it runs on the robot it was trained on, profile included"
        ),
        None => Setup::profiled(cfg.robot.name(), &cfg.robot.0, cfg.trajectory.clone())?,
    }
    .with_sim(cfg.sim.clone())?;
    let model = setup.model().clone();
    let (sim_model, ctrl_model) = cfg.model_error.apply(&model)?;
    let mut learned = loaded.map(SavedModel::controller).transpose()?;
    let mut osc = match learned {
        Some(_) => None,
        None => Some(Osc::new(ctrl_model, cfg.controller.clone())?),
    };
    let wall = Instant::now();
    let run = match (&mut learned, &mut osc) {
        (Some(l), _) => setup.closed_loop(sim_model, l, cfg.simulate.seconds),
        (None, Some(o)) => setup.closed_loop(sim_model, o, cfg.simulate.seconds),
        (None, None) => unreachable!("one controller is built"),
    }
    .context("closed-loop simulation")?;
    let wall = wall.elapsed().as_secs_f64();
    let m = &run.metrics;
    let law = match cfg.controller.law {
        _ if learned.is_some() => format!(
            "learned ({})",
            model_path
                .as_deref()
                .map(|p| p.display().to_string())
                .unwrap_or_default()
        ),
        Law::Eq4 => "eq4".to_string(),
        Law::Eq7 => {
            let n = match cfg.controller.metric {
                MetricKind::Identity => "I",
                MetricKind::Mass => "M",
                MetricKind::InverseMass => "M^-1",
                MetricKind::Matrix => "matrix",
            };
            format!("eq7 (N = {n})")
        }
    };
    println!(
        "{} · {law} · {:?} · model error: {} · {:.1} s simulated in {wall:.2} s",
        model.name(),
        cfg.trajectory.kind,
        cfg.model_error,
        m.sim_seconds
    );
    println!(
        "tracking over {} periods from t = {:.1} s: RMS {:.4} mm, max {:.4} mm; command RMS {:.3} N·m",
        m.window_periods, m.window_start_s, m.tracking_rms_mm, m.tracking_max_mm, m.command_rms
    );
    println!(
        "joints: drift {:.2e} rad/period, max excursion {:.3} rad, min limit margin {:.3} rad, \
         {} steps at a limit (first at {}), {} saturated steps",
        m.joint_drift_rad,
        m.max_joint_excursion_rad,
        m.min_limit_margin_rad,
        m.limit_steps,
        m.first_limit_s.map_or("-".into(), |t| format!("{t:.3} s")),
        m.torque_saturation_steps
    );
    let mut json = serde_json::to_value(m)?;
    let obj = json
        .as_object_mut()
        .expect("metrics serialise to an object");
    obj.insert("robot".into(), model.name().into());
    obj.insert("controller".into(), law.into());
    obj.insert(
        "trajectory".into(),
        format!("{:?}", cfg.trajectory.kind).to_lowercase().into(),
    );
    obj.insert("model_error".into(), cfg.model_error.to_string().into());
    obj.insert("wall_seconds".into(), wall.into());
    obj.insert(
        "real_time_factor".into(),
        (m.sim_seconds / wall.max(1e-9)).into(),
    );
    obj.insert("q_start".into(), serde_json::to_value(setup.home())?);
    obj.insert("profile".into(), serde_json::to_value(setup.profile())?);
    if let Some(l) = &learned {
        let c = l.counts();
        obj.insert("learned_steps".into(), c.learned.into());
        obj.insert("extrapolated_steps".into(), c.extrapolated.into());
        obj.insert("fallback_steps".into(), c.fallback.into());
        println!(
            "learned controller: {} blended, {} extrapolated, {} fallback (u0) steps",
            c.learned, c.extrapolated, c.fallback
        );
    }
    if let Some(dir) = &a.out {
        let axes = model.task_axes();
        let toml = toml::to_string(&cfg)?;
        let files = osrl_report::runs::write_simulate(dir, &run.series, axes, &json, &toml)?;
        println!(
            "wrote {}",
            files
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    if a.json {
        print_json(&json);
    }
    Ok(())
}
