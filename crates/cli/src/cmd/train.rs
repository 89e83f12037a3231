//! `osrl train`: trains the learned operational space controller (paper section IV) on the
//! simulated robot — motor babbling, then on-policy RWR along the trajectory with evaluations —
//! and saves it as one model file (`osrl_learn::SavedModel`). A progress bar on stderr shows
//! simulated minutes, the tracking error and the number of local models; with `--json` the last
//! stdout line has the metrics of issue 6 and the learning curve.
//!
//! The robot's profile (`[robot]` section, `--profile F`, `--tip`, `--lock`, `--unlock`) is
//! resolved as for `osrl simulate` and saved with the model (`ModelInfo::profile`), so the saved
//! model finds the same robot and home again.
//!
//! The config file's sections `robot`, `[trajectory]`, `[sim]`, `[learner]` and `[train]` set
//! the run (the `[sim]` control period is the learner's and is saved with it); `[controller]`,
//! `[model_error]` and `[simulate]` configure `osrl simulate` and are refused here.

use crate::config::Config;
use crate::progress;
use crate::robot_entry::ProfileArgs;
use crate::train_json::{rejected, summary_json, MAX_REJECTED_SHARE};
use crate::util::{print_json, trajectory_kind};
use anyhow::{bail, Context, Result};
use osrl_control::RobotChange;
use osrl_experiments::adapt::{train_with_change, ChangeSchedule};
use osrl_experiments::stats::{measured, EvalSummary};
use osrl_experiments::Setup;
use osrl_learn::train::TrainSummary;
use serde_json::json;
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `osrl train` (flags override the config file).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Robot: `planar3`, `sarcos7` or a URDF file (default: the config's, planar3).
    #[arg(long)]
    pub robot: Option<String>,
    #[command(flatten)]
    pub profile: ProfileArgs,
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
    /// Change the simulated robot at this simulated minute of training (with `--change`): the
    /// recovery shows on the learning curve; the learner's re-adaptation is switched on.
    #[arg(long, requires = "change")]
    pub change_at: Option<f64>,
    /// The change (the grammar of `--model-error`, applied to the robot itself):
    /// `mass=1.3`, `payload=0.5`, `friction=2`, `com=0.02,seed=7`, combined with commas.
    #[arg(long, requires = "change_at")]
    pub change: Option<RobotChange>,
    /// Remove the change again at this simulated minute (after `--change-at`).
    #[arg(long, requires = "change_at")]
    pub revert_at: Option<f64>,
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
        if sections.contains_key(name) {
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
    cfg.robot.0 = a.profile.apply(&cfg.robot.0)?;
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
    let robot = crate::util::robot_file(a.robot.as_deref());
    crate::util::check_out_file("--out", &a.out, &[a.config.as_deref(), robot])?;
    let setup = Setup::profiled(cfg.robot.name(), &cfg.robot.0, cfg.trajectory.clone())?
        .with_sim(cfg.sim.clone())?
        .with_learner(cfg.learner.clone())
        .context("[learner]")?
        .with_train(cfg.train.clone())
        .context("[train]")?;
    let model = setup.model().clone();
    let minutes = cfg.train.minutes;
    let bar = progress::train_bar(None, &format!("train {}", model.name()), minutes);
    let schedule = match (&a.change, a.change_at) {
        (Some(change), Some(at)) => {
            if !(at >= 0.0 && at <= minutes)
                || a.revert_at.is_some_and(|r| !(r > at && r <= minutes))
            {
                let revert = a.revert_at.map_or("unset".into(), |r| r.to_string());
                bail!(
                    "--change-at {at} / --revert-at {revert}: need 0 ≤ change-at < revert-at ≤ \
                     the run's {minutes} minutes"
                );
            }
            osrl_experiments::adapt::checked_change(&setup, change)?;
            Some(ChangeSchedule {
                change: change.clone(),
                at,
                revert_at: a.revert_at,
            })
        }
        _ => None,
    };
    let mut observe = |p: &osrl_learn::train::Progress| progress::update(&bar, minutes, p);
    let (learner, summary) = match &schedule {
        None => setup.train(&model, &mut observe),
        Some(s) => train_with_change(&setup, s, cfg.learner.adaptation.clone(), &mut observe),
    }
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
        let mut j = summary_json(&summary, &EvalSummary::from(&last), model.name())?;
        if let (Some(s), Some(o)) = (&schedule, j.as_object_mut()) {
            for (k, v) in change_keys(&summary, s) {
                o.insert(k.into(), v);
            }
        }
        print_json(&j);
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

/// The keys of a run with a change: the change and its schedule, the tracking on the last
/// evaluation before it (the nominal), and the minutes from the change (and from the revert) to
/// 1 mm and to twice the nominal tracking (`null`: never).
fn change_keys(s: &TrainSummary, c: &ChangeSchedule) -> Vec<(&'static str, serde_json::Value)> {
    let curve = &s.learning_curve;
    let nominal = curve
        .iter()
        .rev()
        .find(|(t, _)| *t <= c.at + 1e-9)
        .map(|(_, e)| e.tracking_rms_mm);
    let after = |from: f64, until: f64, pred: &dyn Fn(f64) -> bool| {
        curve
            .iter()
            .find(|(t, e)| {
                *t > from + 1e-9 && *t <= until + 1e-9 && !e.diverged && pred(e.tracking_rms_mm)
            })
            .map(|(t, _)| t - from)
    };
    let end = c.revert_at.unwrap_or(f64::INFINITY);
    let twice = |nom: Option<f64>| move |mm: f64| nom.is_some_and(|n| mm <= 2.0 * n);
    vec![
        ("change", json!(c.change.to_string())),
        ("change_at", json!(c.at)),
        ("revert_at", json!(c.revert_at)),
        ("tracking_rms_mm_before_change", json!(nominal)),
        (
            "minutes_to_1mm_after_change",
            json!(after(c.at, end, &|mm| mm <= 1.0)),
        ),
        (
            "minutes_to_2x_nominal_after_change",
            json!(after(c.at, end, &twice(nominal))),
        ),
        (
            "minutes_to_2x_nominal_after_revert",
            json!(c
                .revert_at
                .and_then(|r| after(r, f64::INFINITY, &twice(nominal)))),
        ),
    ]
}
