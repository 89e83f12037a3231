//! E8's figure: per robot, one panel per change — the tracking of the learned controller
//! re-adapting, the same frozen, and eq. 7 with the stale model over the timeline, the change
//! (and its removal) marked.

use crate::plot::{Figure, Panel, Series, PALETTE};
use osrl_experiments::e8::ChangeRow;
use std::collections::BTreeMap;

/// Where a diverged evaluation is marked (mm): its error passed 0.2 m.
const DIVERGED_MM: f64 = 200.0;

/// The points of `ys` that exist, against `t`.
fn points(t: &[f64], ys: &[Option<f64>]) -> Vec<(f64, f64)> {
    (t.iter().zip(ys))
        .filter_map(|(t, y)| y.filter(|y| *y > 0.0).map(|y| (*t, y)))
        .collect()
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
        let all: Vec<f64> = lines
            .iter()
            .flat_map(|(_, ys, _)| points(t, ys))
            .map(|p| p.1)
            .collect();
        let lo = all.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = all.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let title = format!("{robot}: {key} ({})", r.change);
        let mut p = Panel::new(&title, "simulated minutes", "tracking RMS [mm]");
        let mut any_diverged = false;
        for (label, ys, c) in lines {
            p = p.with(Series::line(label, points(t, ys)).color(c));
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
                let t_max = t.last().copied().unwrap_or(0.0);
                p = p.with(
                    Series::line("2× nominal", vec![(0.0, 2.0 * n), (t_max, 2.0 * n)])
                        .color(PALETTE[5])
                        .dashed(),
                );
            }
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
