//! The learned vs analytical commands per joint over one cycle (paper Fig. 2c; `osrl eval`,
//! E4).

use crate::plot::{Figure, Panel, Series, PALETTE};
use osrl_experiments::learned::last_cycle;
use osrl_learn::eval::EvalSeries;

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
