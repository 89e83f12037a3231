//! Figures of `osrl reproduce` beyond those of `osrl simulate`/`osrl eval`: figure-8 tracking
//! learned vs analytical (Fig. 2b/3b), learning curves over seeds (E5), the ablation's curves
//! (E6) and the arm drawn at several instants along the figure-8 (Fig. 2a).

use crate::learned::Setup;
use crate::plot::{Figure, Legend, Panel, Series, PALETTE};
use anyhow::Result;
use osrl_learn::eval::{EvalResult, EvalSeries};

const AXES: [&str; 3] = ["x", "y", "z"];

/// One run's learning curve: `(simulated minutes, evaluation)`.
pub type Curve = Vec<(f64, EvalResult)>;

/// A labelled set of runs' curves (one learner over its seeds).
pub type Runs<'a> = (&'a str, Vec<Curve>);

/// The two task columns that move most along the desired path (in column order).
fn plane(x_d: &[f64], m: usize) -> (usize, usize) {
    if m < 2 {
        return (0, 0);
    }
    let len = x_d.len() / m;
    let span = |c: usize| {
        let v = (0..len).map(|k| x_d[k * m + c]);
        v.clone().fold(f64::MIN, f64::max) - v.fold(f64::MAX, f64::min)
    };
    let mut cols: Vec<usize> = (0..m).collect();
    cols.sort_by(|&a, &b| span(b).total_cmp(&span(a)));
    (cols[0].min(cols[1]), cols[0].max(cols[1]))
}

/// Desired, analytical (eq. 7) and learned paths, and both tracking errors over time.
pub fn tracking(setup: &Setup, learned: &EvalSeries, analytical: &osrl_control::Series) -> Figure {
    let axes = setup.model.task_axes();
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
    let name = setup.model.name();
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

/// Mean and (min, max) over seeds of `f` at each evaluation of the learning curves, over the
/// seeds whose evaluation there did not diverge (points where all diverged are left out).
pub fn spread(curves: &[Curve], f: impl Fn(&EvalResult) -> f64) -> Vec<(f64, f64, f64, f64)> {
    let len = curves.iter().map(Vec::len).min().unwrap_or(0);
    (0..len)
        .filter(|&i| curves.iter().any(|c| !c[i].1.diverged))
        .map(|i| {
            let v: Vec<f64> = curves
                .iter()
                .filter(|c| !c[i].1.diverged)
                .map(|c| f(&c[i].1))
                .collect();
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (curves[0][i].0, mean, lo, hi)
        })
        .collect()
}

fn curve_series(label: &str, s: &[(f64, f64, f64, f64)], color: usize) -> Series {
    Series::line(label, s.iter().map(|p| (p.0, p.1)).collect())
        .errors(s.iter().map(|p| (p.2, p.3)).collect())
        .color(PALETTE[color % PALETTE.len()])
        .style(crate::plot::Style::LineMarkers)
}

/// Learning curves of several learners (one colour each, mean over seeds with min–max bars):
/// tracking error, command nMSE against `u*`, command cost ratio; `reference` draws the
/// analytical tracking error as a flat line.
pub fn curves(title: &str, runs: &[Runs], reference_mm: Option<f64>) -> Figure {
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
        track = track.with(curve_series(label, &spread(c, |e| e.tracking_rms_mm), i));
        nmse = nmse.with(curve_series(label, &spread(c, |e| e.command_nmse), i));
        cost = cost.with(curve_series(label, &spread(c, |e| e.command_cost_ratio), i));
    }
    let t_max = runs
        .iter()
        .flat_map(|(_, c)| c.iter().flat_map(|s| s.last().map(|p| p.0)))
        .fold(0.0, f64::max);
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

/// The arm's links (joint frames to the end-effector, from forward kinematics) at `k` instants
/// of the last cycle of `s`, over the desired path; planar arms in their plane, 3-D arms in the
/// two planes spanned by the path's main axis and each other axis.
pub fn arm(setup: &Setup, s: &ArmSeries, per_period: usize, k: usize) -> Result<Figure> {
    let model = &setup.model;
    let (n, axes) = (model.nq(), model.task_axes());
    let m = axes.len();
    let len = s.t.len();
    let start = len.saturating_sub(per_period.max(1));
    let mut data = model.data();
    let mut chains = Vec::new();
    for i in 0..k.max(1) {
        let row = start + i * (len - start) / k.max(1);
        osrl_dynamics::forward_kinematics(model, &mut data, &s.q[row * n..(row + 1) * n])?;
        let mut pts: Vec<[f64; 3]> = data.world_pose.iter().map(|p| p.trans.into()).collect();
        pts.push(data.ee_pos.into());
        chains.push((s.t[row] - s.t[start], pts));
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
            if let (Some(ca), Some(cb)) = (col(a), col(b)) {
                let path = (start..len)
                    .map(|r| (s.x_d[r * m + ca], s.x_d[r * m + cb]))
                    .collect();
                p = p.with(
                    Series::line("desired path", path)
                        .color(PALETTE[7])
                        .width(1),
                );
            }
            for (i, (t, pts)) in chains.iter().enumerate() {
                let line = pts.iter().map(|v| (v[a], v[b])).collect();
                p = p.with(
                    Series::line(&format!("t = {t:.1} s"), line)
                        .color(PALETTE[i % 7])
                        .style(crate::plot::Style::LineMarkers),
                );
            }
            p.equal_axes = true;
            p.legend = Legend::UpperLeft;
            p
        })
        .collect();
    Ok(Figure::grid(panels, 2))
}
