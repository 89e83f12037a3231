//! `index.html`: one self-contained page — the summary of the headline numbers next to the
//! paper's claims, then per experiment a line on what it shows, its table and its figures
//! (inline SVG, one caption each), and the whole `results.json`.

use crate::error::Result;
use crate::summary::summary;
use osrl_experiments::analytical::ROBOTS;
use osrl_experiments::results::{Results, RunsSummary};
use osrl_experiments::stats::{Outcome, Spread, Stat};
use std::path::Path;

/// A figure of the page: SVG path relative to the report folder and its caption.
#[derive(Clone, Debug, PartialEq)]
pub struct Fig {
    pub file: String,
    pub caption: String,
}

pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A number with 3 significant-ish digits, `—` for none.
pub(crate) fn num(v: Option<f64>) -> String {
    match v {
        Some(x) if x.abs() >= 100.0 => format!("{x:.0}"),
        Some(x) if x.abs() >= 1.0 => format!("{x:.2}"),
        Some(x) => format!("{x:.3}"),
        None => "—".into(),
    }
}

/// `mean [min–max]`, or the mean alone when min and max agree.
pub(crate) fn spread(s: &Spread) -> String {
    if s.min == s.max {
        return num(Some(s.mean));
    }
    format!(
        "{} [{}–{}]",
        num(Some(s.mean)),
        num(Some(s.min)),
        num(Some(s.max))
    )
}

/// [`spread`] of a measured statistic, `—` otherwise.
pub(crate) fn stat(s: &Stat) -> String {
    s.spread().map_or_else(|| num(None), spread)
}

pub(crate) fn table(head: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = String::from("<table><tr>");
    for h in head {
        s += &format!("<th>{}</th>", escape(h));
    }
    s += "</tr>";
    for r in rows {
        s += "<tr>";
        for c in r {
            s += &format!("<td>{}</td>", escape(c));
        }
        s += "</tr>";
    }
    s + "</table>\n"
}

fn e2(r: &Results) -> String {
    let rows: Vec<Vec<String>> = (r.e2.iter())
        .map(|(k, v)| {
            vec![
                k.clone(),
                num(Some(v.tracking_rms_mm)),
                num(Some(v.tracking_max_mm)),
                num(Some(v.command_rms)),
            ]
        })
        .collect();
    let head = [
        "robot_law",
        "tracking RMS [mm]",
        "max [mm]",
        "command RMS [N·m]",
    ];
    table(&head, &rows)
}

/// The cells of a summary of runs, `—` where it failed.
fn cells(s: Option<&RunsSummary>, f: impl Fn(&RunsSummary) -> String) -> String {
    s.map_or_else(|| num(None), f)
}

fn e3(r: &Results) -> String {
    let rows: Vec<Vec<String>> = ROBOTS
        .iter()
        .map(|&rb| {
            let row = r.e3.get(rb).and_then(Outcome::done);
            let s = row.map(|v| &v.summary);
            vec![
                rb.into(),
                cells(s, |s| stat(&s.tracking_rms_mm)),
                num(row.and_then(|v| v.analytical_eq7_tracking_rms_mm)),
                cells(s, |s| stat(&s.command_nmse)),
                cells(s, |s| stat(&s.command_cost_ratio)),
                cells(s, |s| spread(&s.n_local_models)),
                num(s.map(|s| s.sim_training_minutes.mean)),
                cells(s, |s| spread(&s.realtime_factor)),
                format!(
                    "{} (analytical {})",
                    num(s.map(|s| s.max_command_step.max)),
                    num(s.map(|s| s.max_command_step_analytical.max))
                ),
            ]
        })
        .collect();
    let head = [
        "robot",
        "tracking RMS [mm]",
        "analytical eq. 7 [mm]",
        "command nMSE",
        "cost ratio",
        "local models",
        "training [sim min]",
        "real-time factor",
        "largest command step in training [N·m]",
    ];
    table(&head, &rows)
}

fn e6(r: &Results) -> String {
    let mut rows = Vec::new();
    for rb in ROBOTS {
        for (k, v) in r.e6.get(rb).into_iter().flatten() {
            let row = v.done();
            let s = row.map(|v| &v.summary);
            rows.push(vec![
                rb.into(),
                row.map_or(k.clone(), |v| v.label.clone()),
                num(row.map(|v| v.seeds as f64)),
                cells(s, |s| stat(&s.tracking_rms_mm)),
                cells(s, |s| stat(&s.command_nmse)),
                cells(s, |s| stat(&s.command_cost_ratio)),
            ]);
        }
    }
    let head = [
        "robot",
        "learner",
        "seeds",
        "tracking RMS [mm]",
        "command nMSE",
        "cost ratio",
    ];
    table(&head, &rows)
}

fn e7(r: &Results) -> String {
    let mut rows = Vec::new();
    for rb in ROBOTS {
        for (k, v) in r.e7.get(rb).into_iter().flatten() {
            let extra = v
                .learned_trained_without_payload
                .as_ref()
                .map_or(String::new(), |w| {
                    format!("; trained without it: {}", num(w.tracking_rms_mm))
                });
            rows.push(vec![
                rb.into(),
                k.clone(),
                num(v.analytical_eq7_tracking_rms_mm),
                stat(&v.learned_tracking_rms_mm) + &extra,
            ]);
        }
    }
    let head = [
        "robot",
        "model error",
        "analytical eq. 7 [mm]",
        "learned [mm]",
    ];
    table(&head, &rows)
}

/// A section of the page: key, what it shows (one line under its heading), its table.
type Section = (&'static str, &'static str, fn(&Results) -> String);

/// The experiments' sections.
const SECTIONS: [Section; 9] = [
    ("E1", "RWR on the 1-D linear-policy toy problem: adaptive vs fixed reward transformation (paper Fig. 1).", |_| String::new()),
    ("E2", "Analytical operational space control (eq. 4 and eq. 7, N = I) with the true model: the baseline.", e2),
    ("E3", "The learned controller tracking the figure-8 on both robots (paper Fig. 2a/2b, 3b). Final evaluation of each seed, no exploration.", e3),
    ("E4", "Learned vs analytical optimal commands per joint along one cycle (paper Fig. 2c).", |_| String::new()),
    ("E5", "Learning curves over simulated training time (paper Sec. V), and the learning safety of each training run: what a physical arm would have gone through.", crate::safety::table),
    ("E6", "Ablation: reward weighting off (supervised inverse learning), RWR as in the paper (full cost ‖u − u0‖², no hindsight null-space shrinkage), a global inverse model.", e6),
    ("E7", "Model errors: analytical eq. 7 with a wrong model vs the learned controller trained on the true robot.", e7),
    ("E8", "A changing robot (issue 26): a learned controller trained on the unchanged arm while a payload is attached and removed, the masses grow ×1.3 or the friction doubles — re-adapting on-policy, frozen, and eq. 7 with the stale model. Minutes are counted from the change (or its removal); never = not within the timeline.", crate::e8::table),
    ("E9", "Generalisation over the workspace (issue 27): controllers trained on the figure-8 only and on a family of paths over the region around it, on held-out paths drawn with a seed no training used. Bounds per path: tracking ≤ 1.5× and nMSE ≤ 2× the figure-8-only controller's on its own figure-8 (same seed), and ≤ 1 mm, ≤ 0.05.", crate::family::table),
];

const HEAD: &str = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>osrl report</title>\
    <style>body{font-family:sans-serif;max-width:1200px;margin:auto;padding:0 1em}figure{margin:1.5em 0}\
    svg{max-width:100%;height:auto}figcaption{color:#333}table{border-collapse:collapse;margin:1em 0}\
    td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}table.summary td{text-align:left}\
    pre{background:#f4f4f4;padding:1em;overflow:auto}</style></head><body>\n\
    <h1>osrl — Reinforcement Learning for Operational Space Control</h1>\n";

/// An SVG file's text without its XML declaration, to be inlined.
fn inline_svg(out: &Path, file: &str) -> Result<String> {
    let path = out.join(file);
    let svg = crate::error::read_text(&path)?;
    let svg = svg.trim_start_matches(|c| c != '<');
    let svg = svg
        .strip_prefix("<?xml")
        .map_or(svg, |s| &s[s.find("?>").map_or(0, |i| i + 2)..]);
    Ok(svg.to_string())
}

/// The page of `results` with the figures `figs` (already drawn in `out`), as HTML.
///
/// # Errors
/// A figure that cannot be read.
pub fn html(out: &Path, results: &Results, figs: &[Fig]) -> Result<String> {
    let mut html = String::from(HEAD);
    html += &format!(
        "<p>Peters &amp; Schaal (ICRA 2007), reproduced: experiments E1–{}{}. Wall time {:.0} s.</p>\n",
        if results.e9.is_empty() { "E8" } else { "E9" },
        if results.config.quick { " at the <em>quick</em> size (small, for CI: not the paper's training times)" } else { "" },
        results.wall_seconds
    );
    html += &summary(results);
    for (key, text, tables) in SECTIONS {
        if key == "E9" && results.e9.is_empty() {
            continue;
        }
        html += &format!("<h2>{key}</h2><p>{}</p>\n", escape(text));
        html += &tables(results);
        for f in figs.iter().filter(|f| f.file.starts_with(key)) {
            html += &format!(
                "<figure>{}<figcaption>{}</figcaption></figure>\n",
                inline_svg(out, &f.file)?,
                escape(&f.caption)
            );
        }
    }
    html += &format!(
        "<h2>results.json</h2><details><summary>all numbers</summary><pre>{}</pre></details>\n</body></html>\n",
        escape(&results.to_json()?)
    );
    Ok(html)
}
