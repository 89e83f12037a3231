//! `osrl train`: trains the learned operational space controller (paper section IV) on the
//! simulated robot — motor babbling, then on-policy RWR along the trajectory with evaluations —
//! and saves it as one model file (`osrl_learn::SavedModel`). A progress bar on stderr shows
//! simulated minutes, the tracking error and the number of local models; with `--json` the last
//! stdout line has the metrics of issue 6 and the learning curve.
//!
//! The config file's sections `robot`, `[trajectory]`, `[sim]`, `[learner]` and `[train]` set
//! the run (the `[sim]` control period is the learner's and is saved with it); `[controller]`,
//! `[model_error]` and `[simulate]` configure `osrl simulate` and are refused here.

use crate::config::Config;
use crate::progress;
use crate::util::{print_json, trajectory_kind};
use anyhow::{bail, Context, Result};
use osrl_experiments::stats::{curve_points, measured, EvalSummary};
use osrl_experiments::Setup;
use osrl_learn::train::TrainSummary;
use serde_json::{json, Value};
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `osrl train` (flags override the config file).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Robot: `planar3`, `sarcos7` or a URDF file (default: the config's, planar3).
    #[arg(long)]
    pub robot: Option<String>,
    /// Trajectory: `figure8`, `circle`, `min_jerk`, or `family` (one path per episode drawn
    /// from the family of `[trajectory.family]`, `docs/family.md`) (default: the config's,
    /// figure8).
    #[arg(long, value_parser = ["figure8", "circle", "min_jerk", "family"])]
    pub trajectory: Option<String>,
    /// TOML config file with `[trajectory]`, `[sim]`, `[learner]` and `[train]` sections (see
    /// `config.rs`).
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Simulated minutes of training, babbling included (default: the config's, 30).
    #[arg(long)]
    pub minutes: Option<f64>,
    /// Seed of the babbling, the exploration noise and the simulator (default: the config's, 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Where to save the learned controller.
    #[arg(long)]
    pub out: PathBuf,
    /// Print the result as one JSON object on the last stdout line.
    #[arg(long)]
    pub json: bool,
}

/// Sections of the config file that configure other commands.
const NOT_FOR_TRAIN: [(&str, &str); 3] = [
    ("controller", "the analytical controller of `osrl simulate`; the task gains of training are [train] gains"),
    ("model_error", "the analytical controller's model (`osrl simulate`); the learner has no model"),
    ("simulate", "`osrl simulate`'s run length; training runs [train] minutes"),
];

/// The config file with the flags applied; refuses sections `osrl train` has no use for.
fn config(a: &Args) -> Result<Config> {
    let (mut cfg, sections) = Config::load_with_sections(a.config.as_deref())?;
    let file = a.config.as_deref().map(|p| p.display().to_string());
    for (name, what) in NOT_FOR_TRAIN {
        if sections.iter().any(|s| s == name) {
            bail!(
                "{}: [{name}] has no meaning for `osrl train` (it configures {what}): remove it",
                file.as_deref().unwrap_or("config")
            );
        }
    }
    if cfg.sim.seed != 0 {
        bail!(
            "{}: [sim] seed = {}: training seeds the simulator with [train] seed (--seed): set that instead",
            file.as_deref().unwrap_or("config"),
            cfg.sim.seed
        );
    }
    if let Some(r) = &a.robot {
        cfg.robot.set_name(r);
    }
    if !cfg.robot.0.is_empty() {
        bail!(
            "a robot profile ([robot] section) cannot be saved with a trained model yet: export \
             the profiled robot with `osrl robot --robot {} --profile F --urdf > G.urdf` (the \
             profile travels in the file) and train on G.urdf",
            cfg.robot.name()
        );
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
    Ok(cfg)
}

/// Trains, saves, reports.
pub fn run(a: Args) -> Result<()> {
    let cfg = config(&a)?;
    crate::util::check_out_file("--out", &a.out)?;
    let setup = Setup::along(cfg.robot.name(), cfg.trajectory.clone())?
        .with_sim(cfg.sim.clone())?
        .with_learner(cfg.learner.clone())
        .context("[learner]")?
        .with_train(cfg.train.clone())
        .context("[train]")?;
    let model = setup.model().clone();
    let minutes = cfg.train.minutes;
    let bar = progress::train_bar(None, &format!("train {}", model.name()), minutes);
    let (learner, summary) = setup
        .train(&model, &mut |p| progress::update(&bar, minutes, p))
        .context("training")?;
    bar.finish_and_clear();
    let bytes = setup.saved(learner, &summary)?.to_bytes()?;
    let saved = crate::util::save_result("trained model", &a.out, &bytes);
    let last = summary
        .learning_curve
        .last()
        .map(|(_, e)| e.clone())
        .unwrap_or_default();
    // With --json, stdout carries the JSON alone; the summary goes to stderr.
    let mut text: Box<dyn std::io::Write> = if a.json {
        Box::new(std::io::stderr())
    } else {
        Box::new(std::io::stdout())
    };
    print_summary(
        &mut text,
        &summary,
        &last,
        model.name(),
        setup.sim().control_period,
    )?;
    let (rejected, share) = rejected(&summary);
    if share > MAX_REJECTED_SHARE {
        eprintln!(
            "warning: the learner rejected {rejected} samples as absurd ({:.2} % of all, more \
             than {} %): check the robot, the [sim] noise and the torque limits",
            100.0 * share,
            100.0 * MAX_REJECTED_SHARE
        );
    }
    if saved.is_ok() {
        writeln!(text, "wrote {}", a.out.display())?;
    }
    if a.json {
        print_json(&summary_json(
            &summary,
            &EvalSummary::from(&last),
            model.name(),
        )?);
    }
    saved
}

fn print_summary(
    out: &mut dyn std::io::Write,
    s: &TrainSummary,
    last: &osrl_learn::eval::EvalResult,
    robot: &str,
    dt: f64,
) -> std::io::Result<()> {
    writeln!(
        out,
        "{robot} · {:.1} simulated minutes at {:.1} ms in {:.1} s ({:.1}× real time) · {} local models · {} episodes ({} aborted, {} braked)",
        s.sim_training_minutes,
        1e3 * dt,
        s.wall_seconds,
        s.realtime_factor,
        s.n_local_models,
        s.episodes,
        s.aborted_episodes,
        s.braked_episodes
    )?;
    if !measured(last) {
        writeln!(
            out,
            "the evaluation diverged during its warm-up period: no metrics"
        )?;
    } else {
        writeln!(
            out,
            "final evaluation: tracking RMS {:.3} mm (max {:.3}), command nMSE {:.4}, cost ratio {:.3}, fallback share {:.3}{}",
            last.tracking_rms_mm,
            last.tracking_max_mm,
            last.command_nmse,
            last.command_cost_ratio,
            last.fallback_share,
            if last.diverged { " — diverged" } else { "" }
        )?;
    }
    writeln!(
        out,
        "largest command step during on-policy learning {:.3} N·m = {:.0} N·m/s (analytical on \
         the path {:.3}), {} commands rate-limited, {} clipped on-policy",
        s.max_command_step,
        s.max_torque_rate,
        last.max_command_step_analytical,
        s.rate_limited(),
        s.clipped_on_policy
    )?;
    Ok(())
}

/// Above this share of rejected samples a training run warns.
const MAX_REJECTED_SHARE: f64 = 0.01;

/// Samples the learner rejected as absurd, and their share of all it saw (0 without any).
fn rejected(s: &TrainSummary) -> (u64, f64) {
    let (r, n) = (s.stats.rejected, s.stats.samples + s.stats.rejected);
    (r, if n == 0 { 0.0 } else { r as f64 / n as f64 })
}

/// The JSON of a training run: the final evaluation's metrics, the run's numbers, the curve.
fn summary_json(s: &TrainSummary, final_eval: &EvalSummary, robot: &str) -> Result<Value> {
    let mut j = serde_json::to_value(final_eval)?;
    let o = j
        .as_object_mut()
        .context("an evaluation is a JSON object")?;
    let extra = json!({
        "robot": robot,
        "n_local_models": s.n_local_models,
        "sim_training_minutes": s.sim_training_minutes,
        "wall_seconds": s.wall_seconds,
        "realtime_factor": s.realtime_factor,
        "max_command_step": s.max_command_step,
        "max_torque_rate": s.max_torque_rate,
        "rate_limited": s.rate_limited(),
        "clipped_on_policy": s.clipped_on_policy,
        "command_step_curve": s.step_curve,
        "minutes_to_1mm": s.minutes_to(|e| e.tracking_rms_mm <= 1.0),
        "minutes_to_nmse_0.05": s.minutes_to(|e| e.command_nmse <= 0.05),
        "episodes": s.episodes,
        "paths_drawn": s.paths_drawn,
        "aborted_episodes": s.aborted_episodes,
        "braked_episodes": s.braked_episodes,
        "counters": s.stats,
        "rejected_samples": rejected(s).0,
        "rejected_share": rejected(s).1,
        "learning_curve": curve_points(&s.learning_curve),
    });
    for (k, v) in extra.as_object().into_iter().flatten() {
        o.insert(k.clone(), v.clone());
    }
    Ok(j)
}
