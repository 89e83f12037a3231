//! E9 on the page (issue 27): the table of tracking and command nMSE per held-out path for the
//! figure-8-only and the family-trained controllers, and its figure.

use crate::page::num;
use crate::plot::{self, Figure, Panel, Series, PALETTE};
use crate::Result;
use osrl_experiments::e9::{E9Point, E9Row};
use osrl_experiments::results::Results;
use std::path::Path;

/// `mean (min–max)` of `f` over the seeds' points (`—` without any).
fn over_seeds(points: &[E9Point], f: impl Fn(&E9Point) -> f64) -> String {
    let v: Vec<f64> = points.iter().map(f).collect();
    if v.is_empty() {
        return "—".into();
    }
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let (lo, hi) = v
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        });
    if v.len() == 1 {
        num(Some(mean))
    } else {
        format!("{} ({}–{})", num(Some(mean)), num(Some(lo)), num(Some(hi)))
    }
}

/// The rows of one robot: its own figure-8, then each held-out path.
fn rows(robot: &str, e: &E9Row) -> Vec<Vec<String>> {
    let mut rows = vec![vec![
        robot.to_string(),
        "default figure-8 (trained on by both)".into(),
        over_seeds(&e.figure8_only_on_figure8, |p| p.tracking_rms_mm),
        over_seeds(&e.family_on_figure8, |p| p.tracking_rms_mm),
        over_seeds(&e.figure8_only_on_figure8, |p| p.command_nmse),
        over_seeds(&e.family_on_figure8, |p| p.command_nmse),
        "—".into(),
        "—".into(),
    ]];
    for p in &e.paths {
        let met = p.family_within_bounds.iter().filter(|b| **b).count();
        rows.push(vec![
            robot.to_string(),
            p.label.clone(),
            over_seeds(&p.figure8_only, |x| x.tracking_rms_mm),
            over_seeds(&p.family, |x| x.tracking_rms_mm),
            over_seeds(&p.figure8_only, |x| x.command_nmse),
            over_seeds(&p.family, |x| x.command_nmse),
            over_seeds(&p.family, |x| x.support_share),
            format!("{met} of {}", p.family_within_bounds.len()),
        ]);
    }
    rows
}

/// The E9 table (empty without E9).
pub(crate) fn table(r: &Results) -> String {
    let rows: Vec<Vec<String>> = r.e9.iter().flat_map(|(rb, e)| rows(rb, e)).collect();
    if rows.is_empty() {
        return String::new();
    }
    let head = [
        "robot",
        "path",
        "tracking RMS [mm], figure-8 only",
        "tracking RMS [mm], family",
        "command nMSE, figure-8 only",
        "command nMSE, family",
        "support share, family",
        "family seeds within the bounds",
    ];
    crate::page::table(&head, &rows)
}

/// The E9 figure of one robot: tracking and nMSE per path (index 0: the default figure-8), one
/// marker per seed and controller.
pub fn figure(robot: &str, e: &E9Row) -> Figure {
    let mut tracking = Panel::new(
        "tracking RMS per path (0: default figure-8)",
        "path",
        "tracking RMS [mm]",
    );
    let mut nmse = Panel::new(
        "command nMSE per path (0: default figure-8)",
        "path",
        "command nMSE against u*",
    );
    let sets = [
        ("figure-8 only", &e.figure8_only_on_figure8, 0usize, -0.1),
        ("family", &e.family_on_figure8, 1, 0.1),
    ];
    for (label, own, k, dx) in sets {
        let mut t = Vec::new();
        let mut n = Vec::new();
        let mut add = |i: usize, pts: &[E9Point]| {
            for p in pts {
                t.push((i as f64 + dx, p.tracking_rms_mm.max(1e-3)));
                n.push((i as f64 + dx, p.command_nmse.max(1e-4)));
            }
        };
        add(0, own);
        for (i, p) in e.paths.iter().enumerate() {
            add(i + 1, if k == 0 { &p.figure8_only } else { &p.family });
        }
        tracking = tracking.with(Series::markers(label, t).color(PALETTE[k]));
        nmse = nmse.with(Series::markers(label, n).color(PALETTE[k]));
    }
    tracking.log_y = true;
    nmse.log_y = true;
    let mut fig = Figure::grid(vec![tracking, nmse], 2);
    fig.title = Some(format!(
        "{robot}: figure-8-only vs family-trained controllers on held-out paths"
    ));
    fig
}

/// Writes the E9 figures into `out/E9`; their files and captions.
pub(crate) fn figures(out: &Path, r: &Results) -> Result<Vec<(String, String)>> {
    let mut figs = Vec::new();
    for (robot, e) in &r.e9 {
        plot::save(
            &figure(robot, e),
            &out.join("E9"),
            &format!("{robot}_held_out"),
        )?;
        let labels: Vec<String> = (e.paths.iter().enumerate())
            .map(|(i, p)| format!("{}: {}", i + 1, p.label))
            .collect();
        figs.push((
            format!("E9/{robot}_held_out.svg"),
            format!(
                "E9 (issue 27): {robot}, tracking RMS and command nMSE of the figure-8-only and the family-trained controllers (seeds {:?}, one marker each) on the default figure-8 (0) and on held-out paths drawn with a seed no training used — {}.",
                e.seeds,
                labels.join("; ")
            ),
        ));
    }
    Ok(figs)
}
