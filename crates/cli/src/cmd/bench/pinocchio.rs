//! The dynamics against Pinocchio's C++ library for `osrl bench references`, where the `pin`
//! wheel is installed: `scripts/bench_pinocchio_cpp.sh` and the crate's
//! `crates/dynamics/examples/bench_min.rs` (the same method and states), run from the
//! repository's root, interleaved over [`ROUNDS`] rounds (best per call kept for each side).

use serde_json::{json, Map, Value};
use std::path::PathBuf;
use std::process::Command;

/// Rounds of (Pinocchio, crate) runs; each side keeps its best time per call over them, so
/// that both sides see the same phases of a shared machine's load.
const ROUNDS: usize = 2;

/// The venv that `scripts/install_pinocchio.sh` creates (under `$HOME`).
const VENV: &str = ".cache/osrl-pin-venv/bin/python";

/// The Python with the `pin` wheel: `chosen` (`$OSRL_PIN_PYTHON`), else `python3`, else the
/// venv of `scripts/install_pinocchio.sh`; or why there is none.
fn pin_python(chosen: Option<String>) -> Result<String, String> {
    let imports = |py: &str| {
        Command::new(py)
            .args(["-c", "import pinocchio, cmeel"])
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false)
    };
    if let Some(py) = chosen {
        return match imports(&py) {
            true => Ok(py),
            false => Err(format!(
                "OSRL_PIN_PYTHON={py} cannot import pinocchio and cmeel"
            )),
        };
    }
    let venv = std::env::var_os("HOME").map(|h| PathBuf::from(h).join(VENV));
    let venv = venv.map(|p| p.to_string_lossy().into_owned());
    ["python3".to_string()]
        .into_iter()
        .chain(venv)
        .find(|py| imports(py))
        .ok_or_else(|| {
            "the pin wheel is not installed (neither python3 nor ~/".to_string()
                + VENV
                + " imports pinocchio (the pin wheel's module); scripts/install_pinocchio.sh installs it)"
        })
}

/// One JSON object of `cmd`'s standard output, or why not.
fn json_of(cmd: &mut Command) -> Result<Map<String, Value>, String> {
    let o = cmd.output().map_err(|e| format!("{cmd:?}: {e}"))?;
    let s = String::from_utf8_lossy(&o.stdout);
    match serde_json::from_str(s.trim()) {
        Ok(Value::Object(m)) if o.status.success() => Ok(m),
        _ => Err(format!(
            "{cmd:?} failed: {}",
            String::from_utf8_lossy(&o.stderr).trim()
        )),
    }
}

/// Keeps the smaller value per key of `new` in `best`.
fn keep_min(best: &mut Map<String, Value>, new: Map<String, Value>) {
    for (k, v) in new {
        let smaller = match (best.get(&k).and_then(Value::as_f64), v.as_f64()) {
            (Some(b), Some(n)) => n < b,
            _ => true,
        };
        if smaller {
            best.insert(k, v);
        }
    }
}

/// The dynamics against Pinocchio's C++ library (`scripts/bench_pinocchio_cpp.sh` and
/// `crates/dynamics/examples/bench_min.rs`, same method), or why it is skipped.
pub fn dynamics() -> Value {
    match measure() {
        Ok(v) => v,
        Err(why) => json!({ "skipped": why }),
    }
}

fn measure() -> Result<Value, String> {
    let py = pin_python(std::env::var("OSRL_PIN_PYTHON").ok())?;
    let (mut p, mut r) = (Map::new(), Map::new());
    for _ in 0..ROUNDS {
        let mut pin = Command::new("bash");
        pin.arg("scripts/bench_pinocchio_cpp.sh")
            .env("OSRL_PIN_PYTHON", &py);
        keep_min(&mut p, json_of(&mut pin)?);
        let mut rust = Command::new("cargo");
        rust.args(["run", "--release", "-q", "-p", "osrl-dynamics"])
            .args(["--example", "bench_min"]);
        keep_min(&mut r, json_of(&mut rust)?);
    }
    let ratio: Map<String, Value> = r
        .iter()
        .filter_map(|(k, v)| Some((k.clone(), json!(p.get(k)?.as_f64()? / v.as_f64()?))))
        .collect();
    if ratio.len() != r.len() {
        return Err(format!(
            "the two benchmarks measured different calls: {:?} and {:?}",
            p.keys().collect::<Vec<_>>(),
            r.keys().collect::<Vec<_>>()
        ));
    }
    Ok(json!({"pinocchio_ns": p, "rust_ns": r, "ratio": ratio, "rounds": ROUNDS}))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keep_min_keeps_the_smaller_time_per_key() {
        let mut best = Map::new();
        keep_min(
            &mut best,
            json!({"a": 3.0, "b": 1.0}).as_object().unwrap().clone(),
        );
        keep_min(
            &mut best,
            json!({"a": 2.0, "b": 5.0, "c": 7.0})
                .as_object()
                .unwrap()
                .clone(),
        );
        assert_eq!(Value::Object(best), json!({"a": 2.0, "b": 1.0, "c": 7.0}));
    }

    #[test]
    fn a_python_that_lacks_pin_is_named_in_the_reason() {
        // `false` exits 1 for any arguments, as a Python without pin does.
        let why = pin_python(Some("false".into())).unwrap_err();
        assert!(why.contains("OSRL_PIN_PYTHON=false"), "{why}");
    }
}
