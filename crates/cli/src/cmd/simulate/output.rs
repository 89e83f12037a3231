//! Files of `osrl simulate`: the time series as CSV, the path figure, metrics and config.

use crate::config::Config;
use crate::plot::{self, Figure, Panel, Series, PALETTE};
use anyhow::{Context, Result};
use osrl_control::Run;
use std::io::Write;
use std::path::{Path, PathBuf};

/// CSV, plot, metrics and config into `dir`.
pub fn write_outputs(
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
pub fn path_figure(s: &osrl_control::Series, axes: &[usize]) -> Figure {
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
