//! The output folder of one run of `osrl simulate --out` or `osrl eval --out`: its time series
//! as CSV, its figures and its metrics.

use crate::error::{create_dir, write, Result};
use crate::figures::{commands, path};
use crate::plot;
use crate::series;
use osrl_learn::eval::EvalSeries;
use std::path::{Path, PathBuf};

/// The files [`write_simulate`] writes into its folder (to check them before a run).
pub const SIMULATE_FILES: [&str; 5] = [
    "simulate.csv",
    "path.svg",
    "path.png",
    "metrics.json",
    "config.toml",
];
/// The files [`write_eval`] writes into its folder.
pub const EVAL_FILES: [&str; 6] = [
    "eval.csv",
    "path.svg",
    "path.png",
    "commands.svg",
    "commands.png",
    "metrics.json",
];

/// `simulate.csv`, `path.svg/png`, `metrics.json` (pretty `metrics`) and `config.toml`
/// (`config_toml`, the effective config) of a closed-loop run into `dir`; `axes` are the world
/// axes of the task coordinates. Returns the files written.
///
/// # Errors
/// An I/O or drawing error.
pub fn write_simulate(
    dir: &Path,
    s: &osrl_control::Series,
    axes: &[usize],
    metrics: &serde_json::Value,
    config_toml: &str,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let csv = dir.join("simulate.csv");
    series::write_run(&csv, s, axes)?;
    let mut files = vec![csv];
    files.extend(plot::save(&path::path_figure(s, axes), dir, "path")?);
    let (mj, ct) = (dir.join("metrics.json"), dir.join("config.toml"));
    write(&mj, &serde_json::to_string_pretty(metrics)?)?;
    write(&ct, config_toml)?;
    files.extend([mj, ct]);
    Ok(files)
}

/// `eval.csv`, `path.svg/png`, `commands.svg/png` (learned vs analytical commands over the
/// last cycle of `per_period` steps, titled `title`) and `metrics.json` of an evaluation of a
/// learned controller on a robot with `n` joints and task axes `axes`. Returns the files.
///
/// # Errors
/// An I/O or drawing error.
pub fn write_eval(
    dir: &Path,
    es: &EvalSeries,
    n: usize,
    axes: &[usize],
    per_period: usize,
    title: &str,
    metrics: &serde_json::Value,
) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let csv = dir.join("eval.csv");
    series::write_eval(&csv, es, n, axes)?;
    let mut files = vec![csv];
    let s = commands::to_series(es, n, axes.len());
    files.extend(plot::save(&path::path_figure(&s, axes), dir, "path")?);
    let fig = commands::commands_figure(es, n, per_period, title);
    files.extend(plot::save(&fig, dir, "commands")?);
    let mj = dir.join("metrics.json");
    write(&mj, &serde_json::to_string_pretty(metrics)?)?;
    files.push(mj);
    Ok(files)
}
