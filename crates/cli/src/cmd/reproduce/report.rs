//! `index.html`: one self-contained page — every figure inline as SVG with a one-line caption,
//! a table per experiment, and the whole `results.json`.

use super::Fig;
use anyhow::{Context, Result};
use serde_json::Value;
use std::path::Path;

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A number with 3 significant-ish digits, `—` for anything else.
fn num(v: &Value) -> String {
    match v.as_f64() {
        Some(x) if x.abs() >= 100.0 => format!("{x:.0}"),
        Some(x) if x.abs() >= 1.0 => format!("{x:.2}"),
        Some(x) => format!("{x:.3}"),
        None => "—".into(),
    }
}

/// `mean [min–max]` of a stats object.
fn spread(v: &Value) -> String {
    if v.get("mean").is_none() {
        return num(v);
    }
    if v["min"] == v["max"] {
        return num(&v["mean"]);
    }
    format!(
        "{} [{}–{}]",
        num(&v["mean"]),
        num(&v["min"]),
        num(&v["max"])
    )
}

fn table(head: &[&str], rows: &[Vec<String>]) -> String {
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

fn tables(key: &str, r: &Value) -> String {
    let robots = ["planar3", "sarcos7"];
    let e = &r[key];
    match key {
        "E2" => {
            let rows: Vec<Vec<String>> = e
                .as_object()
                .into_iter()
                .flatten()
                .map(|(k, v)| {
                    vec![
                        k.clone(),
                        num(&v["tracking_rms_mm"]),
                        num(&v["tracking_max_mm"]),
                        num(&v["command_rms"]),
                    ]
                })
                .collect();
            table(
                &[
                    "robot_law",
                    "tracking RMS [mm]",
                    "max [mm]",
                    "command RMS [N·m]",
                ],
                &rows,
            )
        }
        "E3" => {
            let rows: Vec<Vec<String>> = robots
                .iter()
                .map(|&rb| {
                    let v = &e[rb];
                    vec![
                        rb.into(),
                        spread(&v["tracking_rms_mm"]),
                        num(&v["analytical_eq7_tracking_rms_mm"]),
                        spread(&v["command_nmse"]),
                        spread(&v["command_cost_ratio"]),
                        spread(&v["n_local_models"]),
                        num(&v["sim_training_minutes"]["mean"]),
                        spread(&v["realtime_factor"]),
                        format!(
                            "{} (analytical {})",
                            num(&v["max_command_step"]["max"]),
                            num(&v["max_command_step_analytical"]["max"])
                        ),
                    ]
                })
                .collect();
            table(
                &[
                    "robot",
                    "tracking RMS [mm]",
                    "analytical eq. 7 [mm]",
                    "command nMSE",
                    "cost ratio",
                    "local models",
                    "training [sim min]",
                    "real-time factor",
                    "largest command step in training [N·m]",
                ],
                &rows,
            )
        }
        "E6" => {
            let mut rows = Vec::new();
            for rb in robots {
                for (k, v) in e[rb].as_object().into_iter().flatten() {
                    rows.push(vec![
                        rb.into(),
                        v["label"].as_str().unwrap_or(k).into(),
                        num(&v["seeds"]),
                        spread(&v["tracking_rms_mm"]),
                        spread(&v["command_nmse"]),
                        spread(&v["command_cost_ratio"]),
                    ]);
                }
            }
            table(
                &[
                    "robot",
                    "learner",
                    "seeds",
                    "tracking RMS [mm]",
                    "command nMSE",
                    "cost ratio",
                ],
                &rows,
            )
        }
        "E7" => {
            let mut rows = Vec::new();
            for rb in robots {
                for (k, v) in e[rb].as_object().into_iter().flatten() {
                    let learned = spread(&v["learned_tracking_rms_mm"]);
                    let extra = v
                        .get("learned_trained_without_payload")
                        .map_or(String::new(), |w| {
                            format!("; trained without it: {}", num(&w["tracking_rms_mm"]))
                        });
                    rows.push(vec![
                        rb.into(),
                        k.clone(),
                        num(&v["analytical_eq7_tracking_rms_mm"]),
                        learned + &extra,
                    ]);
                }
            }
            table(
                &[
                    "robot",
                    "model error",
                    "analytical eq. 7 [mm]",
                    "learned [mm]",
                ],
                &rows,
            )
        }
        _ => String::new(),
    }
}

/// What each section shows (one line under its heading).
const SECTIONS: [(&str, &str); 7] = [
    ("E1", "RWR on the 1-D linear-policy toy problem: adaptive vs fixed reward transformation (paper Fig. 1)."),
    ("E2", "Analytical operational space control (eq. 4 and eq. 7, N = I) with the true model: the baseline."),
    ("E3", "The learned controller tracking the figure-8 on both robots (paper Fig. 2a/2b, 3b). Final evaluation of each seed, no exploration."),
    ("E4", "Learned vs analytical optimal commands per joint along one cycle (paper Fig. 2c)."),
    ("E5", "Learning curves over simulated training time (paper Sec. V)."),
    ("E6", "Ablation: reward weighting off (supervised inverse learning), RWR as in the paper (full cost ‖u − u0‖², no hindsight null-space shrinkage), a global inverse model."),
    ("E7", "Model errors: analytical eq. 7 with a wrong model vs the learned controller trained on the true robot."),
];

/// Writes `out/index.html`.
pub fn write(out: &Path, results: &Value, figs: &[Fig]) -> Result<()> {
    let mut html = String::from("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>osrl report</title>\
        <style>body{font-family:sans-serif;max-width:1200px;margin:auto;padding:0 1em}figure{margin:1.5em 0}\
        svg{max-width:100%;height:auto}figcaption{color:#333}table{border-collapse:collapse;margin:1em 0}\
        td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}pre{background:#f4f4f4;padding:1em;overflow:auto}</style></head><body>\n\
        <h1>osrl — Reinforcement Learning for Operational Space Control</h1>\n");
    html += &format!(
        "<p>Peters &amp; Schaal (ICRA 2007), reproduced: experiments E1–E7 of DESIGN.md §5{}. Wall time {:.0} s.</p>\n",
        if results["config"]["quick"].as_bool() == Some(true) { " at the <em>quick</em> size (small, for CI: not the paper's training times)" } else { "" },
        results["wall_seconds"].as_f64().unwrap_or(0.0)
    );
    for (key, text) in SECTIONS {
        html += &format!("<h2>{key}</h2><p>{}</p>\n", escape(text));
        html += &tables(key, results);
        for f in figs.iter().filter(|f| f.file.starts_with(key)) {
            let svg = std::fs::read_to_string(out.join(&f.file))
                .with_context(|| format!("reading {}", f.file))?;
            let svg = svg.trim_start_matches(|c| c != '<');
            let svg = svg
                .strip_prefix("<?xml")
                .map_or(svg, |s| &s[s.find("?>").map_or(0, |i| i + 2)..]);
            html += &format!(
                "<figure>{svg}<figcaption>{}</figcaption></figure>\n",
                escape(&f.caption)
            );
        }
    }
    html += &format!(
        "<h2>results.json</h2><details><summary>all numbers</summary><pre>{}</pre></details>\n</body></html>\n",
        escape(&serde_json::to_string_pretty(results)?)
    );
    std::fs::write(out.join("index.html"), html).context("writing index.html")
}
