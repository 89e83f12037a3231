//! Files of an evaluation run: the time series as CSV, the path figure and the learned vs
//! analytical commands per joint over one cycle (paper Fig. 2c). Shared with `osrl reproduce`.

use crate::plot::{Figure, Panel, Series, PALETTE};
use anyhow::{Context, Result};
use osrl_learn::eval::EvalSeries;
use std::io::Write;
use std::path::Path;

/// The evaluation series as the closed-loop driver's [`osrl_control::Series`] (for the path
/// figure of `osrl simulate`).
pub fn to_series(es: &EvalSeries, n: usize, m: usize) -> osrl_control::Series {
    osrl_control::Series {
        n,
        m,
        t: es.t.clone(),
        x_d: es.x_d.clone(),
        x: es.x.clone(),
        q: es.q.clone(),
        u: es.u.clone(),
    }
}

/// Rows `[start, end)` of the last whole period of the series (`per_period` rows per period).
pub fn last_cycle(len: usize, per_period: usize) -> (usize, usize) {
    let per = per_period.max(1).min(len);
    (len - per, len)
}

/// `t, <axis>_d…, <axis>…, error_mm, q0…, u0…, u_star0…` one row per control step.
pub fn write_csv(path: &Path, es: &EvalSeries, n: usize, axis_names: &[&str]) -> Result<()> {
    let m = axis_names.len();
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    let mut w = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?,
    );
    let mut head = vec!["t".to_string()];
    head.extend(axis_names.iter().map(|a| format!("{a}_d")));
    head.extend(axis_names.iter().map(|a| a.to_string()));
    head.push("error_mm".into());
    head.extend((0..n).map(|i| format!("q{i}")));
    head.extend((0..n).map(|i| format!("u{i}")));
    head.extend((0..n).map(|i| format!("u_star{i}")));
    writeln!(w, "{}", head.join(","))?;
    for k in 0..es.t.len() {
        let (xd, x) = (&es.x_d[k * m..(k + 1) * m], &es.x[k * m..(k + 1) * m]);
        let err: f64 = xd.iter().zip(x).map(|(a, b)| (a - b).powi(2)).sum::<f64>();
        let mut row = vec![es.t[k]];
        row.extend(xd);
        row.extend(x);
        row.push(1e3 * err.sqrt());
        row.extend(&es.q[k * n..(k + 1) * n]);
        row.extend(&es.u[k * n..(k + 1) * n]);
        row.extend(&es.u_star[k * n..(k + 1) * n]);
        let row: Vec<String> = row.iter().map(|v| format!("{v}")).collect();
        writeln!(w, "{}", row.join(","))?;
    }
    w.flush()?;
    Ok(())
}

/// One panel per joint: the learned command and the analytical optimum `u*` (eq. 7, `N = I`,
/// true model) at the same states over the last whole cycle, time from the cycle's start.
pub fn commands_figure(es: &EvalSeries, n: usize, per_period: usize, title: &str) -> Figure {
    let (a, b) = last_cycle(es.t.len(), per_period);
    let t0 = es.t.get(a).copied().unwrap_or(0.0);
    let panels = (0..n)
        .map(|j| {
            let pts = |v: &Vec<f64>| -> Vec<(f64, f64)> {
                (a..b).map(|k| (es.t[k] - t0, v[k * n + j])).collect()
            };
            Panel::new(&format!("joint {}", j + 1), "time in cycle [s]", "u [N·m]")
                .with(Series::line("learned", pts(&es.u)).color(PALETTE[1]))
                .with(
                    Series::line("analytical u* (eq. 7)", pts(&es.u_star))
                        .color(PALETTE[0])
                        .dashed(),
                )
        })
        .collect();
    let mut fig = Figure::grid(panels, if n > 4 { 4 } else { n });
    fig.panel_size = (480, 360);
    fig.title = Some(title.to_string());
    fig
}

/// Per-joint RMS of `u − u*` and RMS of `u*` over the last cycle (N·m).
pub fn per_joint_rms(es: &EvalSeries, n: usize, per_period: usize) -> Vec<(f64, f64)> {
    let (a, b) = last_cycle(es.t.len(), per_period);
    let c = (b - a).max(1) as f64;
    (0..n)
        .map(|j| {
            let (mut d2, mut s2) = (0.0, 0.0);
            for k in a..b {
                d2 += (es.u[k * n + j] - es.u_star[k * n + j]).powi(2);
                s2 += es.u_star[k * n + j].powi(2);
            }
            ((d2 / c).sqrt(), (s2 / c).sqrt())
        })
        .collect()
}
