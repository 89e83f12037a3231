//! The Markdown tables of `osrl bench references --markdown`, drawn from its JSON object alone.

use serde_json::Value;
use std::fmt::Write as _;

fn num(v: &Value, p: &str) -> f64 {
    v.pointer(p).and_then(Value::as_f64).unwrap_or(f64::NAN)
}

/// `median [min–max]` of the nMSE at `p`.
fn nmse(v: &Value, p: &str) -> String {
    let f = |k: &str| num(v, &format!("{p}/nmse/{k}"));
    format!("{:.4} [{:.4}–{:.4}]", f("median"), f("min"), f("max"))
}

/// The tables of `out` (the command's JSON object).
pub fn render(out: &Value) -> String {
    let m = &out["machine"];
    let s = |v: &Value| v.as_str().unwrap_or("unknown").to_string();
    let mut t = format!(
        "Measured {} on {} ({} cores), load average {} (1/5/15 min) at the start.\n\n",
        s(&m["date"]),
        s(&m["cpu"]),
        m["cores"],
        s(&m["loadavg"])
    );
    t += "| data set | seeds × epochs | nMSE crate | nMSE C -O2 | RFs crate / C | update µs crate / C -O2 / C -O3 native | predict µs crate / C -O2 / C -O3 native | C / crate update (O2, O3n) | C / crate predict (O2, O3n) |\n";
    t += "|---|---|---|---|---|---|---|---|---|\n";
    for (k, v) in out["lwpr"].as_object().into_iter().flatten() {
        if let Some(why) = v.get("skipped") {
            let _ = writeln!(t, "| {k} | skipped: {} | | | | | | | |", s(why));
            continue;
        }
        let us = |c: &str| times(v, c);
        let r = |c: &str| ratios(v, c);
        let _ = writeln!(
            t,
            "| {k} | {} × {} | {} | {} | {} / {} | {} | {} | {} | {} |",
            v["seeds"],
            v["epochs"],
            nmse(v, "/rust"),
            nmse(v, "/c_o2"),
            num(v, "/rust/n_rfs"),
            num(v, "/c_o2/n_rfs"),
            us("update_us"),
            us("predict_us"),
            r("update_us"),
            r("predict_us"),
        );
    }
    t += &loops(out);
    match out.get("dynamics") {
        Some(d) if d.get("skipped").is_some() => {
            let _ = writeln!(
                t,
                "\nDynamics against Pinocchio's C++ library: skipped ({}).",
                s(&d["skipped"])
            );
        }
        Some(d) => {
            t +=
                "\n| dynamics | crate ns | Pinocchio ns | Pinocchio / crate |\n|---|---|---|---|\n";
            for (k, r) in d["rust_ns"].as_object().into_iter().flatten() {
                let p = num(d, &format!("/pinocchio_ns/{}", k.replace('/', "~1")));
                let _ = writeln!(
                    t,
                    "| {k} | {:.1} | {p:.1} | {:.2}× |",
                    r.as_f64().unwrap_or(f64::NAN),
                    p / r.as_f64().unwrap_or(f64::NAN)
                );
            }
        }
        None => {}
    }
    t
}

/// "crate / C -O2 / C -O3 native" µs of the timing `c` (`update_us`, `predict_us_batch`, ...).
fn times(v: &Value, c: &str) -> String {
    let f = |i: &str| num(v, &format!("/{i}/{c}"));
    format!(
        "{:.2} / {:.2} / {:.2}",
        f("rust"),
        f("c_o2"),
        f("c_o3_native")
    )
}

/// "C -O2 / crate, C -O3 native / crate" of the timing `c`.
fn ratios(v: &Value, c: &str) -> String {
    let f = |i: &str| num(v, &format!("/ratio_{c}_{i}"));
    format!("{:.2}× / {:.2}×", f("c_o2"), f("c_o3_native"))
}

/// The table of the timings of whole loops (`*_us_batch`), where `out` has them (outputs of
/// the command from before they were added have not).
fn loops(out: &Value) -> String {
    let sets: Vec<_> = out["lwpr"]
        .as_object()
        .into_iter()
        .flatten()
        .filter(|(_, v)| v.pointer("/rust/update_us_batch").is_some())
        .collect();
    if sets.is_empty() {
        return String::new();
    }
    let mut t =
        "\nThe same runs timed as whole loops (each training loop and test pass timed once, \
        run a second time for it; the table above times every call on its own):\n\n"
            .to_string();
    t += "| data set | update µs crate / C -O2 / C -O3 native | predict µs crate / C -O2 / C -O3 native | C / crate update (O2, O3n) | C / crate predict (O2, O3n) |\n";
    t += "|---|---|---|---|---|\n";
    for (k, v) in sets {
        let us = |c: &str| times(v, c);
        let r = |c: &str| ratios(v, c);
        let _ = writeln!(
            t,
            "| {k} | {} | {} | {} | {} |",
            us("update_us_batch"),
            us("predict_us_batch"),
            r("update_us_batch"),
            r("predict_us_batch"),
        );
    }
    t
}
