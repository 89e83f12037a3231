//! `osrl train`: trains the learned operational space controller (paper section IV) on the
//! simulated robot — motor babbling, then on-policy RWR along the trajectory with evaluations —
//! and saves it as `MODEL` plus the sidecar `MODEL.json` (see `learned.rs`). A progress bar on
//! stderr shows simulated minutes, the tracking error and the number of local models; with
//! `--json` the last stdout line has the metrics of issue 6 and the learning curve.

use crate::config::Config;
use crate::learned::{curve_json, eval_json, save_model, sidecar_path, train_learner, Setup};
use crate::progress;
use crate::util::{load_robot, print_json};
use anyhow::Result;
use osrl_control::TrajectoryKind;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// Arguments of `osrl train` (flags override the config file).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Robot: `planar3`, `sarcos7` or a URDF file (default: the config's, planar3).
    #[arg(long)]
    pub robot: Option<String>,
    /// Trajectory: `figure8`, `circle` or `min_jerk` (default: the config's, figure8).
    #[arg(long, value_parser = ["figure8", "circle", "min_jerk"])]
    pub trajectory: Option<String>,
    /// TOML config file with `[learner]`, `[train]`, `[trajectory]` sections (see `config.rs`).
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Simulated minutes of training, babbling included (default: the config's, 30).
    #[arg(long)]
    pub minutes: Option<f64>,
    /// Seed of the babbling, the exploration noise and the simulator (default: the config's, 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Where to save the learned controller (`MODEL` and `MODEL.json`).
    #[arg(long)]
    pub out: PathBuf,
    /// Print the result as one JSON object on the last stdout line.
    #[arg(long)]
    pub json: bool,
}

/// Parses a trajectory flag value (checked by clap).
pub fn trajectory_kind(t: &str) -> TrajectoryKind {
    match t {
        "circle" => TrajectoryKind::Circle,
        "min_jerk" => TrajectoryKind::MinJerk,
        _ => TrajectoryKind::Figure8,
    }
}

/// The robot as stored in the sidecar: built-in names as they are, files as absolute paths.
fn robot_reference(robot: &str) -> String {
    let p = Path::new(robot);
    if osrl_dynamics::robots::BUILTIN.contains(&robot) {
        return robot.into();
    }
    std::fs::canonicalize(p).map_or(robot.into(), |a| a.display().to_string())
}

/// Trains, saves, reports.
pub fn run(a: Args) -> Result<()> {
    let mut cfg = Config::load(a.config.as_deref())?;
    if let Some(r) = &a.robot {
        cfg.robot = r.clone();
    }
    if let Some(t) = &a.trajectory {
        cfg.trajectory.kind = trajectory_kind(t);
    }
    if let Some(m) = a.minutes {
        cfg.train.minutes = m;
    }
    if let Some(s) = a.seed {
        cfg.train.seed = s;
    }
    cfg.validate()?;
    let model = load_robot(&cfg.robot)?;
    let lcfg = cfg.learner_for(&model)?;
    let setup = Setup::new(model.clone(), cfg.trajectory.clone())?;
    let minutes = cfg.train.minutes;
    let bar = progress::train_bar(None, &format!("train {}", model.name()), minutes);
    let (learner, summary) = train_learner(&setup, &model, lcfg, &cfg.train, 2, &mut |p| {
        progress::update(&bar, minutes, p)
    })?;
    bar.finish_and_clear();
    let sidecar = crate::learned::Sidecar {
        version: crate::learned::SIDECAR_VERSION,
        robot: robot_reference(&cfg.robot),
        trajectory: cfg.trajectory.clone(),
        home: setup.home.clone(),
        gains: cfg.train.gains,
        control_period: osrl_dynamics::SimConfig::default().control_period,
        sim_training_minutes: summary.sim_training_minutes,
        seed: cfg.train.seed,
    };
    save_model(&a.out, &learner, &sidecar)?;
    let last = summary
        .learning_curve
        .last()
        .map(|(_, e)| e.clone())
        .unwrap_or_default();
    let json = summary_json(&summary, &eval_json(&last), model.name());
    println!(
        "{} · {:.1} simulated minutes in {:.1} s ({:.1}× real time) · {} local models · {} episodes ({} aborted)",
        model.name(),
        summary.sim_training_minutes,
        summary.wall_seconds,
        summary.realtime_factor,
        summary.n_local_models,
        summary.episodes,
        summary.aborted_episodes
    );
    if !crate::learned::measured(&last) {
        println!("the evaluation diverged during its warm-up period: no metrics");
    } else {
        println!(
        "final evaluation: tracking RMS {:.3} mm (max {:.3}), command nMSE {:.4}, cost ratio {:.3}, fallback share {:.3}{}",
        last.tracking_rms_mm,
        last.tracking_max_mm,
        last.command_nmse,
        last.command_cost_ratio,
        last.fallback_share,
        if last.diverged { " — diverged" } else { "" }
    );
    }
    println!(
        "largest command step during on-policy learning {:.2} N·m (analytical on the path {:.2})",
        summary.max_command_step, last.max_command_step_analytical
    );
    println!(
        "wrote {} and {}",
        a.out.display(),
        sidecar_path(&a.out).display()
    );
    if a.json {
        print_json(&json);
    }
    Ok(())
}

/// The JSON of a training run: the final evaluation's metrics, the run's numbers, the curve.
pub fn summary_json(s: &osrl_learn::train::TrainSummary, final_eval: &Value, robot: &str) -> Value {
    let mut j = final_eval.clone();
    let o = j.as_object_mut().expect("eval JSON is an object");
    let extra = json!({
        "robot": robot,
        "n_local_models": s.n_local_models,
        "sim_training_minutes": s.sim_training_minutes,
        "wall_seconds": s.wall_seconds,
        "realtime_factor": s.realtime_factor,
        "max_command_step": s.max_command_step,
        "episodes": s.episodes,
        "aborted_episodes": s.aborted_episodes,
        "counters": s.stats,
        "learning_curve": curve_json(&s.learning_curve),
    });
    for (k, v) in extra.as_object().expect("object") {
        o.insert(k.clone(), v.clone());
    }
    j
}
