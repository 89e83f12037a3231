//! `osrl eval`: runs a saved learned controller without exploration on the simulated robot it
//! was trained for (from the model's sidecar), along its training trajectory or another one, and
//! compares it at every step with the analytical optimum `u*` (eq. 7, `N = I`, true model).
//! With `--out DIR`: `eval.csv`, `path.svg/png`, `commands.svg/png` (learned vs analytical per
//! joint over the last cycle, paper Fig. 2c) and `metrics.json`.

pub mod figures;

use crate::cmd::simulate::path_figure;
use crate::cmd::train::trajectory_kind;
use crate::learned::{eval_json, load_model, Setup};
use crate::plot;
use crate::util::print_json;
use anyhow::{bail, Context, Result};
use serde_json::Value;
use std::path::PathBuf;

/// Arguments of `osrl eval`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A model saved by `osrl train` (`MODEL` and `MODEL.json`).
    #[arg(long)]
    pub model: PathBuf,
    /// Trajectory: `figure8`, `circle` or `min_jerk` (default: the training trajectory).
    #[arg(long, value_parser = ["figure8", "circle", "min_jerk"])]
    pub trajectory: Option<String>,
    /// Simulated seconds, rounded down to whole periods; the first period is the warm-up
    /// (default: 3 periods, 12 s on the default figure-8).
    #[arg(long)]
    pub seconds: Option<f64>,
    /// Directory for eval.csv, path.svg/png, commands.svg/png and metrics.json.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the result as one JSON object on the last stdout line.
    #[arg(long)]
    pub json: bool,
}

/// Evaluates, prints, writes.
pub fn run(a: Args) -> Result<()> {
    let (mut learner, side) = load_model(&a.model)?;
    let mut traj_cfg = side.trajectory.clone();
    if let Some(t) = &a.trajectory {
        traj_cfg.kind = trajectory_kind(t);
    }
    let setup = Setup::for_robot(&side.robot, traj_cfg)?;
    let (n, m) = learner.dims();
    if setup.model.nq() != n || setup.model.task_dim() != m {
        bail!(
            "{} has {} joints and a {}-D task, the learner {n} and {m}",
            side.robot,
            setup.model.nq(),
            setup.model.task_dim()
        );
    }
    let period = setup.traj.period();
    let periods = match a.seconds {
        None => 2,
        Some(s) if s.is_finite() && s >= 2.0 * period => (s / period + 1e-9).floor() as usize - 1,
        Some(s) => bail!(
            "--seconds {s}: need at least two periods of the trajectory ({:.3} s)",
            2.0 * period
        ),
    };
    let mut ev = setup.evaluator(setup.model.clone(), side.gains, periods)?;
    ev.keep_series = true;
    let res = ev.evaluate(&mut learner).context("evaluation")?;
    let mut json = eval_json(&res);
    let o = json.as_object_mut().expect("object");
    o.insert("robot".into(), setup.model.name().into());
    o.insert(
        "trajectory".into(),
        format!("{:?}", setup.traj_cfg.kind).to_lowercase().into(),
    );
    o.insert("eval_seconds".into(), ev.seconds.into());
    o.insert("n_local_models".into(), learner.n_local_models().into());
    o.insert(
        "sim_training_minutes".into(),
        side.sim_training_minutes.into(),
    );
    o.insert("counters".into(), serde_json::to_value(learner.stats())?);
    // What one learned command costs on this model (wall time, no exploration).
    let (us50, us99) = (
        ev.series.command_us_quantile(0.5),
        ev.series.command_us_quantile(0.99),
    );
    o.insert("command_us_median".into(), us50.into());
    o.insert("command_us_p99".into(), us99.into());
    println!(
        "{} · {:?} · {:.1} s · model trained {:.1} simulated minutes · {} local models",
        setup.model.name(),
        setup.traj_cfg.kind,
        ev.seconds,
        side.sim_training_minutes,
        learner.n_local_models()
    );
    if let (Some(a), Some(b)) = (us50, us99) {
        println!("learned command: {a:.2} µs median, {b:.2} µs 99th percentile (wall time)");
    }
    if !crate::learned::measured(&res) {
        println!("the evaluation diverged during its warm-up period: no metrics");
    } else {
        println!(
        "tracking RMS {:.3} mm (max {:.3}), command nMSE {:.4}, cost ratio {:.3}, fallback share {:.3}, \
         largest command step {:.2} N·m (analytical {:.2}){}",
        res.tracking_rms_mm,
        res.tracking_max_mm,
        res.command_nmse,
        res.command_cost_ratio,
        res.fallback_share,
        res.max_command_step,
        res.max_command_step_analytical,
        if res.diverged { " — diverged" } else { "" }
    );
    }
    if let Some(dir) = &a.out {
        write_outputs(dir, &setup, &ev.series, n, &json)?;
        println!("wrote {}", dir.display());
    }
    if a.json {
        print_json(&json);
    }
    Ok(())
}

/// CSV, path and command figures, metrics into `dir`.
fn write_outputs(
    dir: &std::path::Path,
    setup: &Setup,
    es: &osrl_learn::eval::EvalSeries,
    n: usize,
    metrics: &Value,
) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let names = ["x", "y", "z"];
    let axes = setup.model.task_axes();
    let axis_names: Vec<&str> = axes.iter().map(|&a| names[a]).collect();
    figures::write_csv(&dir.join("eval.csv"), es, n, &axis_names)?;
    let s = figures::to_series(es, n, axes.len());
    plot::save(&path_figure(&s, axes), dir, "path")?;
    let per = (setup.traj.period() / osrl_dynamics::SimConfig::default().control_period).round();
    let title = format!(
        "{}: learned vs analytical commands over one cycle",
        setup.model.name()
    );
    plot::save(
        &figures::commands_figure(es, n, per as usize, &title),
        dir,
        "commands",
    )?;
    std::fs::write(
        dir.join("metrics.json"),
        serde_json::to_string_pretty(metrics)?,
    )?;
    Ok(())
}
