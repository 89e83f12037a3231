//! The learning-safety figure (E3/E5): the largest on-policy command step per bin of simulated
//! training time, one line per seed, next to the analytical controller's level.

use crate::plot::{Figure, Panel, Series, PALETTE};
use osrl_experiments::results::SafetyRow;

/// Command steps over training time of each seed's run; `eq7` is the largest step of the
/// analytical `u*` in the final evaluations, drawn flat from 0 to `t_max` simulated minutes.
pub fn command_steps(
    robot: &str,
    runs: &[SafetyRow],
    seeds: &[u64],
    eq7: f64,
    dt: f64,
    t_max: f64,
) -> Figure {
    let mut step = Panel::new(
        "largest command step per 15 s of training",
        "simulated training [min]",
        "max |Δu| between commands [N·m]",
    );
    let mut rate = Panel::new(
        "as a torque rate",
        "simulated training [min]",
        "max |Δu| / dt [N·m/s]",
    );
    for (i, r) in runs.iter().enumerate() {
        let pts: Vec<(f64, f64)> = (r.step_curve.iter())
            .map(|p| (p.minutes, p.max_command_step.max(1e-6)))
            .collect();
        let color = PALETTE[i % PALETTE.len()];
        let label = seeds
            .get(i)
            .map_or_else(|| format!("run {i}"), |s| format!("seed {s}"));
        step = step.with(Series::line(&label, pts.clone()).color(color));
        let rates = pts.iter().map(|&(t, s)| (t, s / dt)).collect();
        rate = rate.with(Series::line(&label, rates).color(color));
    }
    for (p, scale) in [(&mut step, 1.0), (&mut rate, 1.0 / dt)] {
        let level = (eq7 * scale).max(1e-6);
        *p = std::mem::replace(p, Panel::new("", "", "")).with(
            Series::line("analytical eq. 7", vec![(0.0, level), (t_max, level)])
                .color(PALETTE[7])
                .dashed(),
        );
        p.log_y = true;
    }
    let mut fig = Figure::grid(vec![step, rate], 2);
    fig.title = Some(format!("{robot}: command steps while learning on-policy"));
    fig
}
