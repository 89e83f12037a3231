//! `osrl eval`: runs a saved learned controller without exploration on the simulated robot it
//! was trained for (from the model file), or that robot changed (`--change`, as `osrl adapt`),
//! along its training trajectory or another one, and compares it at every step with the
//! analytical optimum `u*` (eq. 7, `N = I`, the true — changed — model).
//! With `--out DIR`: `eval.csv`, `path.svg/png`, `commands.svg/png` (learned vs analytical per
//! joint over the last cycle, paper Fig. 2c) and `metrics.json`.

use crate::config::Config;
use crate::util::{print_json, trajectory_kind};
use anyhow::{bail, Context, Result};
use osrl_control::family::Region;
use osrl_control::{RobotChange, TrajectoryConfig, TrajectoryKind};
use osrl_experiments::stats::{measured, EvalSummary};
use osrl_experiments::Setup;
use osrl_learn::SavedModel;
use std::path::PathBuf;

/// Arguments of `osrl eval`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A model saved by `osrl train`.
    #[arg(long)]
    pub model: PathBuf,
    /// Trajectory: `figure8`, `circle` or `min_jerk` (default: the training trajectory).
    #[arg(long, value_parser = ["figure8", "circle", "min_jerk"])]
    pub trajectory: Option<String>,
    /// TOML file with a `[trajectory]` section: the path to evaluate on (any described path;
    /// unset fields take the robot's defaults; `--trajectory` overrides its kind). No other
    /// section is accepted.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Evaluate on the robot changed by this spec (the grammar of `osrl adapt --change`:
    /// `payload=0.5`, `mass=1.3`, ...): e.g. a controller adapted by `osrl adapt` on the robot
    /// it adapted to. `u*` is eq. 7 on the changed model. Default: the unchanged robot.
    #[arg(long)]
    pub change: Option<RobotChange>,
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

/// A path farther than this outside the trained region (m) is reported on stderr.
const REGION_TOLERANCE: f64 = 1e-3;

/// Below this `support_share` an evaluation warns on stderr.
const LOW_SUPPORT: f64 = 0.9;

/// The `[trajectory]` section of `file`; any other section is refused.
fn trajectory_section(file: &std::path::Path) -> Result<TrajectoryConfig> {
    let (cfg, sections) = Config::load_with_sections(Some(file))?;
    if let Some(other) = sections.keys().find(|s| *s != "trajectory") {
        bail!(
            "{}: [{other}] has no meaning for `osrl eval` (the model brings its robot, learner \
             and training settings): keep only [trajectory]",
            file.display()
        );
    }
    if cfg.trajectory.kind == TrajectoryKind::Family {
        bail!(
            "{}: [trajectory] kind = \"family\" is not one path: describe the path to evaluate",
            file.display()
        );
    }
    Ok(cfg.trajectory)
}

/// Whether the saved model was trained on a family of paths.
fn setup_trained_on_family(saved: &SavedModel) -> bool {
    saved.info().trajectory.kind == TrajectoryKind::Family
}

/// Evaluates, prints, writes.
pub fn run(a: Args) -> Result<()> {
    let saved = SavedModel::load(&a.model)?;
    if let Some(dir) = &a.out {
        let inputs = [Some(a.model.as_path()), a.config.as_deref()];
        crate::util::check_out_dir("--out", dir, &osrl_report::runs::EVAL_FILES, &inputs)?;
    }
    let mut setup = Setup::from_saved(&saved)?;
    // Where training went: the trained path's or family's region.
    let trained = Region::of(setup.model(), setup.trajectory_config())?;
    if a.trajectory.is_some() || a.config.is_some() {
        let mut cfg = match &a.config {
            Some(file) => trajectory_section(file)?,
            None => setup.trajectory_config().clone(),
        };
        if let Some(t) = &a.trajectory {
            cfg.kind = trajectory_kind(t);
        }
        setup = setup
            .with_trajectory(cfg)
            .context("the evaluated trajectory")?;
    }
    let leaves = trained.leaves_by(setup.trajectory());
    if leaves > REGION_TOLERANCE {
        eprintln!(
            "warning: the evaluated path leaves the region the model was trained on by up to \
             {:.1} mm (the {} region: ±{:.3} m × ±{:.3} m around ({:.3}, {:.3}, {:.3}) m in \
             its plane); see support_share",
            leaves * 1e3,
            if setup_trained_on_family(&saved) {
                "family's"
            } else {
                "training path's"
            },
            trained.half[0],
            trained.half[1],
            trained.centre[0],
            trained.centre[1],
            trained.centre[2]
        );
    }
    let period = setup.trajectory().period();
    let dt = setup.sim().control_period;
    let max = osrl_control::MAX_RUN_STEPS as f64 * dt;
    let periods = match a.seconds {
        None => 2,
        Some(s) if s >= 2.0 * period && s <= max => (s / period + 1e-9).floor() as usize - 1,
        Some(s) => bail!(
            "--seconds {s:?}: accepted range {:.3} s (two periods of the trajectory) to {max:?} s \
             ({} control steps of {dt:?} s)",
            2.0 * period,
            osrl_control::MAX_RUN_STEPS
        ),
    };
    let setup = setup.with_eval_periods(periods)?;
    // The truth: the profiled model (its postures, gains, torque limits), the one the training
    // evaluated, or that model changed; the change is checked before anything runs.
    // `--change none` is the unchanged robot, reported as such.
    let change = a.change.filter(|c| !c.is_none());
    let truth = match &change {
        Some(c) => osrl_experiments::adapt::checked_change(&setup, c)?,
        None => setup.model().clone(),
    };
    let (info, mut learner, model) = saved.into_parts();
    let mut ev = setup.evaluator(&truth)?;
    ev.keep_series = true;
    let res = ev.evaluate(&mut learner).context("evaluation")?;
    let kind = format!("{:?}", setup.trajectory_config().kind).to_lowercase();
    let mut json = serde_json::to_value(EvalSummary::from(&res))?;
    let o = json
        .as_object_mut()
        .context("an evaluation is a JSON object")?;
    // What one learned command costs on this model (wall time, no exploration).
    let (us50, us99) = (
        ev.series.command_us_quantile(0.5),
        ev.series.command_us_quantile(0.99),
    );
    for (k, v) in [
        ("robot", model.name().into()),
        ("trajectory", kind.into()),
        ("change", change.as_ref().map(|c| c.to_string()).into()),
        ("eval_seconds", ev.seconds.into()),
        ("n_local_models", learner.n_local_models().into()),
        ("sim_training_minutes", info.sim_training_minutes.into()),
        ("counters", serde_json::to_value(learner.stats())?),
        ("command_us_median", us50.into()),
        ("command_us_p99", us99.into()),
        ("support_share", res.support_share.into()),
        ("leaves_trained_region_mm", (1e3 * leaves).into()),
    ] {
        o.insert(k.into(), v);
    }
    println!(
        "{}{} · {:?} · {:.1} s · model trained {:.1} simulated minutes · {} local models",
        model.name(),
        changed_by(&change),
        setup.trajectory_config().kind,
        ev.seconds,
        info.sim_training_minutes,
        learner.n_local_models()
    );
    if let (Some(a), Some(b)) = (us50, us99) {
        println!("learned command: {a:.2} µs median, {b:.2} µs 99th percentile (wall time)");
    }
    print_metrics(&res);
    println!(
        "support share {:.3} (steps inside trained receptive fields)",
        res.support_share
    );
    if res.support_share < LOW_SUPPORT {
        eprintln!(
            "warning: only {:.1} % of the evaluation ran inside trained receptive fields: the \
             path leaves what the controller was trained on",
            100.0 * res.support_share
        );
    }
    if let Some(dir) = &a.out {
        let title = format!(
            "{}{}: learned vs analytical commands over one cycle",
            model.name(),
            changed_by(&change)
        );
        let (n, axes) = (model.nq(), model.task_axes());
        let per = setup.steps_per_period();
        osrl_report::runs::write_eval(dir, &ev.series, n, axes, per, &title, &json)?;
        println!("wrote {}", dir.display());
    }
    if a.json {
        print_json(&json);
    }
    Ok(())
}

/// ` changed by SPEC`, or nothing for the unchanged robot.
fn changed_by(change: &Option<RobotChange>) -> String {
    change
        .as_ref()
        .map(|c| format!(" changed by {c}"))
        .unwrap_or_default()
}

/// One line of the evaluation's metrics.
fn print_metrics(res: &osrl_learn::eval::EvalResult) {
    if !measured(res) {
        println!("the evaluation diverged during its warm-up period: no metrics");
        return;
    }
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
