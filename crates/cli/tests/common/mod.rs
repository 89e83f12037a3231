//! Running the `osrl` binary from the integration tests.

use std::process::Command;

/// Runs `osrl args…`: (success, stdout, stderr).
pub fn osrl(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_osrl"))
        .args(args)
        .output()
        .expect("run osrl");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The JSON object on the last stdout line.
#[allow(dead_code)] // not every test binary reads JSON
pub fn last_json(stdout: &str) -> serde_json::Value {
    serde_json::from_str(stdout.lines().last().expect("a last line"))
        .expect("the last line is JSON")
}
