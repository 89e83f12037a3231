//! E8's figure: per robot, one panel per change — the tracking of the learned controller
//! re-adapting, the same frozen (and frozen with the disturbance observer, on the changed arm),
//! and eq. 7 with the stale model over the timeline, the change (and its removal) marked.

use crate::plot::{Figure, Panel, Series, Style, PALETTE};
use osrl_experiments::e8::ChangeRow;
use std::collections::BTreeMap;

/// Where a diverged evaluation is marked (mm): its error passed 0.2 m.
const DIVERGED_MM: f64 = 200.0;

/// `ys` against `t`; a missing point is NaN, which splits the line there.
fn points(t: &[f64], ys: &[Option<f64>]) -> Vec<(f64, f64)> {
    (t.iter().zip(ys))
        .map(|(t, y)| (*t, y.unwrap_or(f64::NAN)))
        .collect()
}

/// A controller that does not learn: `before` until the change, `during` until its removal (or
/// the end), `before` again after it, as steps.
fn steps(r: &ChangeRow, t_end: f64, before: Option<f64>, during: Option<f64>) -> Vec<(f64, f64)> {
    let (b, d) = (before.unwrap_or(f64::NAN), during.unwrap_or(f64::NAN));
    let at = r.change_at_minutes;
    let mut v = vec![(0.0, b), (at, b), (at, d)];
    match r.revert_at_minutes {
        Some(x) => v.extend([(x, d), (x, b), (t_end, b)]),
        None => v.push((t_end, d)),
    }
    v
}

/// The timeline figure of one robot's E8 rows (keyed by change).
pub fn timelines(robot: &str, rows: &BTreeMap<String, ChangeRow>) -> Figure {
    let mut panels = Vec::new();
    for (key, r) in rows {
        let tl = &r.timeline;
        let t = &tl.sim_minutes;
        let lines = [
            ("learned, re-adapting", &tl.adapting_mm, PALETTE[1]),
            ("learned, frozen", &tl.frozen_mm, PALETTE[2]),
            ("eq. 7, stale model", &tl.eq7_stale_mm, PALETTE[0]),
        ];
        let t_end = t.last().copied().unwrap_or(0.0);
        let drawn = [
            points(t, &tl.adapting_mm),
            steps(
                r,
                t_end,
                r.nominal_tracking_rms_mm,
                r.frozen_tracking_rms_mm,
            ),
            steps(
                r,
                t_end,
                r.eq7_nominal_tracking_rms_mm,
                r.eq7_stale_tracking_rms_mm,
            ),
        ];
        // The frozen controller with the disturbance observer, measured on the changed arm
        // only (E8 runs it there alone): a step over the change.
        let end_of_change = r.revert_at_minutes.unwrap_or(t_end);
        let observer: Vec<(f64, f64)> = (r.observer_frozen_tracking_rms_mm.into_iter())
            .flat_map(|d| [(r.change_at_minutes, d), (end_of_change, d)])
            .collect();
        let all: Vec<f64> = (drawn.iter().flatten().chain(&observer))
            .map(|p| p.1)
            .filter(|y| y.is_finite() && *y > 0.0)
            .collect();
        let lo = all.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = all.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let title = format!("{robot}: {key} ({})", r.change);
        let mut p = Panel::new(&title, "simulated minutes", "tracking RMS [mm]");
        let mut any_diverged = false;
        for (i, ((label, ys, c), pts)) in lines.into_iter().zip(drawn).enumerate() {
            // The evaluations of the re-adapting controller as markers (a lone one between
            // diverged ones shows); the others are steps.
            let style = if i == 0 {
                Style::LineMarkers
            } else {
                Style::Line
            };
            p = p.with(Series::line(label, pts).color(c).style(style));
            // A diverged evaluation (error above 0.2 m) has no number: marked at 200 mm.
            let diverged: Vec<(f64, f64)> = (t.iter().zip(ys))
                .filter(|(_, y)| y.is_none())
                .map(|(t, _)| (*t, DIVERGED_MM))
                .collect();
            if !diverged.is_empty() {
                any_diverged = true;
                let text = format!("{label}: diverged (> 0.2 m)");
                p = p.with(Series::markers(&text, diverged).color(c));
            }
        }
        if !observer.is_empty() {
            let label = "learned, frozen + observer";
            p = p.with(Series::line(label, observer).color(PALETTE[3]));
        } else if r
            .diverged
            .iter()
            .any(|d| d == "observer_frozen_tracking_rms_mm")
        {
            any_diverged = true;
            let mark = vec![(r.change_at_minutes, DIVERGED_MM)];
            let label = "learned, frozen + observer: diverged (> 0.2 m)";
            p = p.with(Series::markers(label, mark).color(PALETTE[3]));
        }
        let hi = if any_diverged {
            hi.max(DIVERGED_MM)
        } else {
            hi
        };
        if lo.is_finite() && hi.is_finite() {
            let marks = [
                ("change", Some(r.change_at_minutes)),
                ("removed", r.revert_at_minutes),
            ];
            for (label, at) in marks {
                if let Some(x) = at {
                    p = p.with(
                        Series::line(label, vec![(x, lo), (x, hi)])
                            .color(PALETTE[7])
                            .dashed(),
                    );
                }
            }
            if let Some(n) = r.nominal_tracking_rms_mm {
                p = p.with(
                    Series::line("2× nominal", vec![(0.0, 2.0 * n), (t_end, 2.0 * n)])
                        .color(PALETTE[5])
                        .dashed(),
                );
            }
        }
        if lo.is_finite() && hi.is_finite() {
            // The data in the lower half (log scale), the legend above them.
            let (bottom, top) = (lo / 2.0, 2.0 * hi);
            p.y_range = Some((bottom, bottom * (top / bottom).powi(2)));
        }
        p.log_y = true;
        panels.push(p);
    }
    let mut fig = Figure::grid(panels, 3);
    fig.panel_size = (520, 400);
    fig.title = Some(format!(
        "{robot}: a controller trained on the unchanged arm while the robot changes"
    ));
    fig
}
