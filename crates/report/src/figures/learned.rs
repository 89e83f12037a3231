//! Figures of the learned controller's experiments: figure-8 tracking learned vs analytical
//! (E3, Fig. 2b/3b), learning curves over seeds (E5) and of the ablation's variants (E6), and
//! the arm drawn at several instants along the figure-8 (E3, Fig. 2a).

use super::path::{plane, AXES};
use crate::error::Result;
use crate::plot::{Figure, Legend, Panel, Series, Style, PALETTE};
use osrl_control::Trajectory;
use osrl_experiments::results::Curves;
use osrl_experiments::stats::SpreadSeries;
use osrl_experiments::Setup;
use osrl_learn::eval::EvalSeries;

/// Desired, analytical (eq. 7) and learned paths, and both tracking errors over time.
pub fn tracking(setup: &Setup, learned: &EvalSeries, analytical: &osrl_control::Series) -> Figure {
    let axes = setup.model().task_axes();
    let m = axes.len();
    let (c1, c2) = plane(&learned.x_d, m);
    let pts = |v: &[f64]| -> Vec<(f64, f64)> {
        (0..v.len() / m)
            .map(|k| (v[k * m + c1], v[k * m + c2]))
            .collect()
    };
    let err = |t: &[f64], x: &[f64], xd: &[f64]| -> Vec<(f64, f64)> {
        (0..t.len())
            .map(|k| {
                let e: f64 = (0..m).map(|j| (x[k * m + j] - xd[k * m + j]).powi(2)).sum();
                (t[k], 1e3 * e.sqrt())
            })
            .collect()
    };
    let name = setup.model().name();
    let mut path = Panel::new(
        &format!("{name}: end-effector path"),
        &format!("{} [m]", AXES[axes[c1]]),
        &format!("{} [m]", AXES[axes[c2]]),
    )
    .with(
        Series::line("desired", pts(&learned.x_d))
            .color(PALETTE[7])
            .width(4),
    )
    .with(
        Series::line("analytical eq. 7", pts(&analytical.x))
            .color(PALETTE[0])
            .dashed(),
    )
    .with(Series::line("learned", pts(&learned.x)).color(PALETTE[1]));
    path.equal_axes = true;
    let mut error = Panel::new(
        &format!("{name}: tracking error"),
        "time [s]",
        "‖x − x_d‖ [mm]",
    )
    .with(
        Series::line(
            "analytical eq. 7",
            err(&analytical.t, &analytical.x, &analytical.x_d),
        )
        .color(PALETTE[0]),
    )
    .with(Series::line("learned", err(&learned.t, &learned.x, &learned.x_d)).color(PALETTE[1]));
    error.log_y = true;
    Figure::grid(vec![path, error], 2)
}

fn curve_series(label: &str, minutes: &[f64], s: &SpreadSeries, color: usize) -> Series {
    let pts = minutes.iter().zip(&s.mean).map(|(&t, &m)| (t, m)).collect();
    let bars = s.min.iter().zip(&s.max).map(|(&a, &b)| (a, b)).collect();
    Series::line(label, pts)
        .errors(bars)
        .color(PALETTE[color % PALETTE.len()])
        .style(Style::LineMarkers)
}

/// Learning curves of several learners (one colour each, mean over seeds with min–max bars):
/// tracking error, command nMSE against `u*`, command cost ratio; `reference_mm` draws the
/// analytical tracking error as a flat line from 0 to `t_max` simulated minutes.
pub fn curves(
    title: &str,
    runs: &[(String, Curves)],
    reference_mm: Option<f64>,
    t_max: f64,
) -> Figure {
    let mut track = Panel::new("tracking error", "simulated training [min]", "RMS [mm]");
    let mut nmse = Panel::new(
        "command error vs u*",
        "simulated training [min]",
        "command nMSE",
    );
    let mut cost = Panel::new(
        "command cost",
        "simulated training [min]",
        "‖u − u0‖² / that of u*",
    );
    for (i, (label, c)) in runs.iter().enumerate() {
        let t = &c.sim_minutes;
        track = track.with(curve_series(label, t, &c.tracking_rms_mm, i));
        nmse = nmse.with(curve_series(label, t, &c.command_nmse, i));
        cost = cost.with(curve_series(label, t, &c.command_cost_ratio, i));
    }
    if let Some(r) = reference_mm {
        track = track.with(
            Series::line("analytical eq. 7", vec![(0.0, r), (t_max, r)])
                .color(PALETTE[7])
                .dashed(),
        );
    }
    for p in [&mut track, &mut nmse, &mut cost] {
        p.log_y = true;
    }
    let mut fig = Figure::grid(vec![track, nmse, cost], 3);
    fig.panel_size = (520, 400);
    fig.title = Some(title.into());
    fig
}

/// Times, joint positions (`n` per row) and desired task positions (`m` per row) of a run.
pub struct ArmSeries<'a> {
    pub t: &'a [f64],
    pub q: &'a [f64],
    pub x_d: &'a [f64],
    /// Whose run it is (title).
    pub who: &'a str,
}

/// Rows of `t` at which to draw the arm: from the last `per_period` steps (the last whole cycle),
/// the step nearest to each of `k` evenly spaced phases of the path `traj`, the first at phase 0
/// (the path's start `x_d(0)`). The phase is that of the warped path time `s(t)`, which lags `t`
/// by half the start ramp, so phase 0 is generally not the first step of the last cycle.
pub fn arm_instants(t: &[f64], traj: &Trajectory, per_period: usize, k: usize) -> Vec<usize> {
    let start = t.len().saturating_sub(per_period.max(1));
    let (period, k) = (traj.period(), k.max(1));
    let warp = osrl_control::TimeWarp { ramp: traj.ramp() };
    let phase: Vec<f64> = t[start..]
        .iter()
        .map(|&ti| warp.eval(ti).0.rem_euclid(period))
        .collect();
    (0..k)
        .filter_map(|i| {
            let target = i as f64 * period / k as f64;
            let dist = |p: f64| {
                let d = (p - target).rem_euclid(period);
                d.min(period - d)
            };
            (0..phase.len())
                .min_by(|&a, &b| dist(phase[a]).total_cmp(&dist(phase[b])))
                .map(|r| start + r)
        })
        .collect()
}

/// The arm's links (joint frames to the end-effector, from forward kinematics) at `k` instants
/// of the last cycle of `s` ([`arm_instants`]: the first at the path's start), over the desired
/// path of that cycle, with the desired point `x_d` of each instant (same step) marked in its
/// colour and its time `t` in the legend; planar arms
/// in their plane, 3-D arms in the two planes spanned by the path's main axis and each other axis.
pub fn arm(setup: &Setup, s: &ArmSeries, per_period: usize, k: usize) -> Result<Figure> {
    let model = setup.model();
    let (n, axes) = (model.nq(), model.task_axes());
    let m = axes.len();
    let rows = arm_instants(s.t, setup.trajectory(), per_period, k);
    let (start, end) = (s.t.len().saturating_sub(per_period.max(1)), s.t.len());
    let mut data = model.data();
    let mut chains = Vec::new();
    for &row in &rows {
        osrl_dynamics::forward_kinematics(model, &mut data, &s.q[row * n..(row + 1) * n])
            .map_err(|e| crate::ReportError::Draw(format!("arm drawing: {e}")))?;
        let mut pts: Vec<[f64; 3]> = data.world_pose.iter().map(|p| p.trans.into()).collect();
        pts.push(data.ee_pos.into());
        chains.push((row, pts));
    }
    let planes: Vec<(usize, usize)> = if m == 2 {
        vec![(axes[0], axes[1])]
    } else {
        vec![(0, 2), (1, 2)]
    };
    let panels = planes
        .iter()
        .map(|&(a, b)| {
            let mut p = Panel::new(
                &format!(
                    "{}, {}: posture along the figure-8 ({}–{})",
                    model.name(),
                    s.who,
                    AXES[a],
                    AXES[b]
                ),
                &format!("{} [m]", AXES[a]),
                &format!("{} [m]", AXES[b]),
            );
            let col = |w: usize| axes.iter().position(|&x| x == w);
            let desired = |r: usize| {
                let (ca, cb) = (col(a)?, col(b)?);
                Some((s.x_d[r * m + ca], s.x_d[r * m + cb]))
            };
            let path: Vec<(f64, f64)> = (start..end).filter_map(desired).collect();
            if !path.is_empty() {
                p = p.with(
                    Series::line("desired path", path)
                        .color(PALETTE[7])
                        .width(1),
                );
            }
            for (i, (row, pts)) in chains.iter().enumerate() {
                let line = pts.iter().map(|v| (v[a], v[b])).collect();
                let color = PALETTE[i % 7];
                p = p.with(
                    Series::line(&format!("t = {:.2} s", s.t[*row]), line)
                        .color(color)
                        .style(Style::LineMarkers),
                );
                if let Some(xd) = desired(*row) {
                    p = p.with(Series::markers("", vec![xd]).color(color).width(6));
                }
            }
            p.equal_axes = true;
            p.legend = Legend::UpperLeft;
            p
        })
        .collect();
    Ok(Figure::grid(panels, 2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use osrl_control::{ModelError, OscConfig};

    /// The arm drawing of an analytical eq. 7 run: each posture is drawn at one step of the last
    /// cycle, its end-effector at the measured `x` of that step, its marked desired point at that
    /// step's `x_d`, its label at that step's time; the first instant is the path's start.
    #[test]
    fn arm_postures_and_desired_points_are_those_of_one_step() {
        for robot in ["planar3", "sarcos7"] {
            let setup = Setup::new(robot).unwrap();
            let model = setup.model();
            let run = setup
                .analytical(&OscConfig::default(), &ModelError::default(), 12.0)
                .unwrap();
            let (axes, m) = (model.task_axes(), model.task_dim());
            let s = &run.series;
            let per = setup.steps_per_period();
            let k = 6;
            let traj = setup.trajectory();
            let rows = arm_instants(&s.t, traj, per, k);
            assert_eq!(rows.len(), k);
            assert!(rows.iter().all(|&r| r >= s.len() - per && r < s.len()));
            // Instant i is at phase i/k of the path: x_d there is the path's point at path time
            // i·T/k (the first: its start), to within half a control step of motion (< 1 mm).
            // After the start ramp the path time is t − ramp/2.
            let (ramp, period) = (traj.ramp(), traj.period());
            for (i, &r) in rows.iter().enumerate() {
                let path_t = ramp / 2.0 + period * (1.0 + i as f64 / k as f64);
                let want = traj.sample(path_t).x;
                for (j, &a) in axes.iter().enumerate() {
                    let d = (s.x_d[r * m + j] - want[a]).abs();
                    assert!(
                        d < 1e-3,
                        "{robot} instant {i}: x_d off the path phase by {d} m"
                    );
                }
            }
            let x0 = traj.start();
            assert!(axes
                .iter()
                .enumerate()
                .all(|(j, &a)| (s.x_d[rows[0] * m + j] - x0[a]).abs() < 1e-3));
            let arm_s = ArmSeries {
                t: &s.t,
                q: &s.q,
                x_d: &s.x_d,
                who: "eq. 7",
            };
            let fig = arm(&setup, &arm_s, per, k).unwrap();
            for panel in &fig.panels {
                // The panel's world axes, from its x-axis label ("x [m]") and y-axis label.
                let world = |l: &str| AXES.iter().position(|a| l.starts_with(a)).unwrap();
                let (wa, wb) = (world(&panel.x_label), world(&panel.y_label));
                let col = |w: usize| axes.iter().position(|&x| x == w).unwrap();
                assert_eq!(
                    panel.series.len(),
                    1 + 2 * k,
                    "path, then chain and marker per instant"
                );
                for (i, &r) in rows.iter().enumerate() {
                    let chain = &panel.series[1 + 2 * i];
                    let marker = &panel.series[2 + 2 * i];
                    assert_eq!(
                        chain.label.as_deref(),
                        Some(&*format!("t = {:.2} s", s.t[r]))
                    );
                    let end = *chain.points.last().unwrap();
                    let x = (s.x[r * m + col(wa)], s.x[r * m + col(wb)]);
                    assert!(
                        (end.0 - x.0).abs() < 1e-9 && (end.1 - x.1).abs() < 1e-9,
                        "{robot} instant {i}: arm ends at {end:?}, x of its step is {x:?}"
                    );
                    let xd = (s.x_d[r * m + col(wa)], s.x_d[r * m + col(wb)]);
                    assert_eq!(marker.points, vec![xd]);
                }
            }
        }
    }
}
