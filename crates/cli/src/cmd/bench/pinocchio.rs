//! The dynamics against Pinocchio's C++ library for `osrl bench references`, where the `pin`
//! wheel is importable: `scripts/bench_pinocchio_cpp.sh` and the crate's
//! `crates/dynamics/examples/bench_min.rs` (the same method and states), run from the
//! repository's root.

use serde_json::{json, Map, Value};
use std::process::Command;

/// The dynamics against Pinocchio's C++ library (`scripts/bench_pinocchio_cpp.sh` and
/// `crates/dynamics/examples/bench_min.rs`, same method), or why it is skipped.
pub fn dynamics() -> Value {
    let pin = Command::new("python3").args(["-c", "import pin"]).output();
    if !pin.map(|o| o.status.success()).unwrap_or(false) {
        return json!({"skipped": "the pin wheel is not importable (python3 -c 'import pin' failed)"});
    }
    let json_of = |cmd: &mut Command| -> Result<Map<String, Value>, String> {
        let o = cmd.output().map_err(|e| format!("{cmd:?}: {e}"))?;
        let s = String::from_utf8_lossy(&o.stdout);
        match serde_json::from_str(s.trim()) {
            Ok(Value::Object(m)) if o.status.success() => Ok(m),
            _ => Err(format!(
                "{cmd:?} failed: {}",
                String::from_utf8_lossy(&o.stderr).trim()
            )),
        }
    };
    let pin = json_of(Command::new("bash").arg("scripts/bench_pinocchio_cpp.sh"));
    let rust = json_of(Command::new("cargo").args([
        "run",
        "--release",
        "-q",
        "-p",
        "osrl-dynamics",
        "--example",
        "bench_min",
    ]));
    match (pin, rust) {
        (Ok(p), Ok(r)) => {
            let ratio: Map<String, Value> = r
                .iter()
                .filter_map(|(k, v)| Some((k.clone(), json!(p.get(k)?.as_f64()? / v.as_f64()?))))
                .collect();
            json!({"pinocchio_ns": p, "rust_ns": r, "ratio": ratio})
        }
        (Err(e), _) | (_, Err(e)) => json!({"skipped": e}),
    }
}
