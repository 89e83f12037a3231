//! The path figure of a closed-loop run (`osrl simulate`, `osrl eval`, E2, E7): desired vs
//! actual path in the plane of the two task coordinates that move most, and the tracking error
//! over time.

use crate::plot::{Figure, Panel, Series, PALETTE};

/// Names of the world axes.
pub const AXES: [&str; 3] = ["x", "y", "z"];

/// The two task columns of `x_d` (`m` per row) that move most along the path, in column order.
pub fn plane(x_d: &[f64], m: usize) -> (usize, usize) {
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

/// Desired vs actual path and the tracking error over time of `s`; `axes` are the world axes of
/// its task coordinates.
pub fn path_figure(s: &osrl_control::Series, axes: &[usize]) -> Figure {
    let (c1, c2) = plane(&s.x_d, s.m);
    let pts = |v: &Vec<f64>| -> Vec<(f64, f64)> {
        (0..s.len())
            .map(|k| (v[k * s.m + c1], v[k * s.m + c2]))
            .collect()
    };
    let mut path = Panel::new(
        "end-effector path",
        &format!("{} [m]", AXES[axes[c1]]),
        &format!("{} [m]", AXES[axes[c2]]),
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
