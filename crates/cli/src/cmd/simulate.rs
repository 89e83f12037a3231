//! `osrl simulate`: an analytical operational space controller (eq. 4 or eq. 7) on the simulated
//! robot along a task-space trajectory, optionally with a wrong model. Prints the tracking
//! metrics; with `--json` the last stdout line is one JSON object; with `--out DIR` it writes
//! `simulate.csv` (time series), `path.svg/png` (desired vs actual path, error over time),
//! `metrics.json` and the effective `config.toml`.

use crate::config::Config;
use crate::plot::{self, Figure, Panel, Series, PALETTE};
use crate::util::{load_robot, print_json};
use anyhow::{Context, Result};
use osrl_control::{
    check_reachable, run_closed_loop, IkOptions, Law, MetricKind, ModelError, Osc, Run,
    TrajectoryKind,
};
use osrl_dynamics::SimRobot;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `osrl simulate` (flags override the config file).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Robot: `planar3`, `sarcos7` or a URDF file (default: the config's, planar3).
    #[arg(long)]
    pub robot: Option<String>,
    /// Control law: `eq4` or `eq7` (default: the config's, eq7).
    #[arg(long, value_parser = ["eq4", "eq7"])]
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
    /// Directory for simulate.csv, path.svg/png, metrics.json and config.toml.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the result as one JSON object on the last stdout line.
    #[arg(long)]
    pub json: bool,
}

/// The config file with the flags applied, validated.
fn effective_config(a: &Args) -> Result<Config> {
    let mut cfg = Config::load(a.config.as_deref())?;
    if let Some(r) = &a.robot {
        cfg.robot = r.clone();
    }
    if let Some(c) = &a.controller {
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
        cfg.trajectory.kind = match t.as_str() {
            "circle" => TrajectoryKind::Circle,
            "min_jerk" => TrajectoryKind::MinJerk,
            _ => TrajectoryKind::Figure8,
        };
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
    let cfg = effective_config(&a)?;
    let model = load_robot(&cfg.robot)?;
    let traj = cfg.trajectory.build(&model)?;
    let reach = check_reachable(&model, &traj, &IkOptions::default())?;
    let (sim_model, ctrl_model) = cfg.model_error.apply(&model)?;
    let mut sim = SimRobot::new(sim_model, cfg.sim.clone())?;
    sim.reset(&reach.q_start, &vec![0.0; model.nq()])?;
    let mut ctrl = Osc::new(ctrl_model, cfg.controller.clone())?;
    let wall = Instant::now();
    let run = run_closed_loop(
        &mut sim,
        &mut ctrl,
        &traj,
        model.task_axes(),
        cfg.simulate.seconds,
    )
    .context("closed-loop simulation")?;
    let wall = wall.elapsed().as_secs_f64();
    let m = &run.metrics;
    let law = match cfg.controller.law {
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
    obj.insert("q_start".into(), serde_json::to_value(&reach.q_start)?);
    if let Some(dir) = &a.out {
        let files = write_outputs(dir, &cfg, &run, &model, &json)?;
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

/// CSV, plot, metrics and config into `dir`.
fn write_outputs(
    dir: &Path,
    cfg: &Config,
    run: &Run,
    model: &osrl_dynamics::Model,
    metrics: &serde_json::Value,
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let s = &run.series;
    let names = ["x", "y", "z"];
    let axes = model.task_axes();
    let csv = dir.join("simulate.csv");
    let mut w = std::io::BufWriter::new(
        std::fs::File::create(&csv).with_context(|| format!("creating {}", csv.display()))?,
    );
    let mut head = vec!["t".to_string()];
    head.extend(axes.iter().map(|&a| format!("{}_d", names[a])));
    head.extend(axes.iter().map(|&a| names[a].to_string()));
    head.push("error_mm".into());
    head.extend((0..s.n).map(|i| format!("q{i}")));
    head.extend((0..s.n).map(|i| format!("u{i}")));
    writeln!(w, "{}", head.join(","))?;
    for k in 0..s.len() {
        let mut row = vec![s.t[k]];
        row.extend(&s.x_d[k * s.m..(k + 1) * s.m]);
        row.extend(&s.x[k * s.m..(k + 1) * s.m]);
        row.push(1e3 * s.error(k));
        row.extend(&s.q[k * s.n..(k + 1) * s.n]);
        row.extend(&s.u[k * s.n..(k + 1) * s.n]);
        let row: Vec<String> = row.iter().map(|v| format!("{v}")).collect();
        writeln!(w, "{}", row.join(","))?;
    }
    w.flush()?;
    let mut files = vec![csv];
    files.extend(plot::save(&path_figure(s, axes), dir, "path")?);
    let mj = dir.join("metrics.json");
    std::fs::write(&mj, serde_json::to_string_pretty(metrics)?)?;
    let ct = dir.join("config.toml");
    std::fs::write(&ct, toml::to_string(cfg)?)?;
    files.extend([mj, ct]);
    Ok(files)
}

/// Desired vs actual path in the plane of the two task coordinates that move most, and the
/// tracking error over time.
fn path_figure(s: &osrl_control::Series, axes: &[usize]) -> Figure {
    let names = ["x", "y", "z"];
    let span = |c: usize| {
        let v = (0..s.len()).map(|k| s.x_d[k * s.m + c]);
        v.clone().fold(f64::MIN, f64::max) - v.fold(f64::MAX, f64::min)
    };
    let mut cols: Vec<usize> = (0..s.m).collect();
    cols.sort_by(|&a, &b| span(b).total_cmp(&span(a)));
    let (c1, c2) = if s.m >= 2 {
        let (a, b) = (cols[0].min(cols[1]), cols[0].max(cols[1]));
        (a, b)
    } else {
        (0, 0)
    };
    let pts = |v: &Vec<f64>| -> Vec<(f64, f64)> {
        (0..s.len())
            .map(|k| (v[k * s.m + c1], v[k * s.m + c2]))
            .collect()
    };
    let mut path = Panel::new(
        "end-effector path",
        &format!("{} [m]", names[axes[c1]]),
        &format!("{} [m]", names[axes[c2]]),
    )
    .with(
        Series::line("desired", pts(&s.x_d))
            .color(PALETTE[0])
            .width(3),
    )
    .with(Series::line("actual", pts(&s.x)).color(PALETTE[1]).dashed());
    path.equal_axes = true;
    let err: Vec<(f64, f64)> = (0..s.len()).map(|k| (s.t[k], 1e3 * s.error(k))).collect();
    let error = Panel::new("tracking error", "time [s]", "‖x − x_d‖ [mm]")
        .with(Series::line("", err).color(PALETTE[1]));
    Figure::grid(vec![path, error], 2)
}
