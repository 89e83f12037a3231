//! The hostile inputs of issue 30, one test each: a clear one-line error naming the parameter,
//! the value and the accepted range (no panic, abort or hang), and outputs that are not regular
//! files refused before any work, left as they were (a FIFO and a directory in a temp folder).

mod common;
use common::osrl;
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("osrl-hostile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `osrl args…`, expecting a one-line error containing every one of `needles`.
fn refused(args: &[&str], needles: &[&str]) -> String {
    let (ok, out, err) = osrl(args);
    assert!(!ok, "{args:?} succeeded: {out}");
    assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
    assert!(err.starts_with("error: "), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {err:?} lacks {n:?}");
    }
    err
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn simulate_seconds_1e300_is_refused_from_the_flag_and_the_config() {
    let d = scratch("s300");
    refused(
        &["simulate", "--seconds", "1e300"],
        &["--seconds", "1e300", "accepted range", "1000.0 s"],
    );
    let cfg = write(&d, "s.toml", "[simulate]\nseconds = 1e300\n");
    refused(
        &["simulate", "--config", &cfg],
        &["[simulate] seconds", "1e300", "accepted range"],
    );
}

#[test]
fn simulate_seconds_1e7_is_refused_before_allocating() {
    refused(
        &["simulate", "--seconds", "1e7"],
        &["seconds", "10000000", "500000 control steps"],
    );
}

#[test]
fn a_control_period_of_1e9_is_refused() {
    let d = scratch("cp");
    let cfg = write(&d, "c.toml", "[sim]\ncontrol_period = 1e-9\n");
    refused(
        &["simulate", "--config", &cfg],
        &["control_period", "1e-9", "0.0001–0.1 s"],
    );
}

#[test]
fn a_billion_substeps_are_refused() {
    let d = scratch("sub");
    let cfg = write(&d, "c.toml", "[sim]\nsubsteps = 1000000000\n");
    refused(
        &["simulate", "--config", &cfg],
        &["substeps = 1000000000", "1–100"],
    );
}

#[test]
fn eval_seconds_1e7_is_refused() {
    let d = scratch("eval");
    let model = d.join("m.osrl");
    common::untrained_model().save(&model).unwrap();
    let m = model.to_str().unwrap();
    for s in ["1e7", "1e300", "inf", "NaN"] {
        refused(
            &["eval", "--model", m, "--seconds", s],
            &["--seconds", "accepted range", "500000 control steps"],
        );
    }
}

#[test]
fn huge_training_lengths_and_evaluation_counts_are_refused() {
    let d = scratch("minutes");
    let out = d.join("m.osrl");
    let o = out.to_str().unwrap();
    refused(
        &["train", "--minutes", "1e9", "--out", o],
        &["train.minutes", "1000000000", "accepted range"],
    );
    let cfg = write(&d, "c.toml", "[train]\neval_every_minutes = 1e-9\n");
    refused(
        &["train", "--config", &cfg, "--out", o],
        &["eval_every_minutes", "1e-9", "at most 1000 evaluations"],
    );
    assert!(!out.exists());
}

#[test]
fn dynamics_with_huge_velocities_accelerations_or_torques_is_an_error_not_null() {
    let q = ["dynamics", "--robot", "planar3", "--q", "0,0,0", "--json"];
    for (flag, v, names) in [
        ("--qd", "1e200,1e200,1e200", "h"),
        ("--qdd", "1e308,1e308,1e308", "tau"),
        ("--u", "1e308,-1e308,1e308", "qdd_forward"),
    ] {
        let args: Vec<&str> = q.iter().copied().chain([flag, v]).collect();
        refused(&args, &[names, "not finite"]);
    }
}

#[test]
fn lwpr_fit_on_twenty_thousand_columns_is_refused_before_allocating() {
    let d = scratch("wide");
    let n = 20_000;
    let head: Vec<String> = (0..n).map(|i| format!("c{i}")).collect();
    let row: Vec<String> = (0..n).map(|i| (i % 7).to_string()).collect();
    let text = format!("{}\n{}\n{}\n", head.join(","), row.join(","), row.join(","));
    let csv = write(&d, "wide.csv", &text);
    let k = (n - 1).to_string();
    refused(
        &[
            "lwpr", "fit", "--train", &csv, "--test", &csv, "--inputs", &k,
        ],
        &["19999 inputs", "accepted 1–1000"],
    );
}

/// `osrl … | head -c 1`: a reader that closes the pipe before the output is written ends the
/// process quietly (as `cat`), not with a panic on the broken pipe.
#[cfg(unix)]
#[test]
fn a_closed_stdout_pipe_is_not_a_panic() {
    use std::os::unix::process::ExitStatusExt;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_osrl"))
        .args(["robot", "--robot", "sarcos7", "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run osrl");
    drop(child.stdout.take()); // the reader is gone before anything is printed
    let out = child.wait_with_output().expect("wait for osrl");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_ne!(out.status.code(), Some(101), "exit as a panic: {err}");
    if !out.status.success() {
        assert_eq!(
            out.status.signal(),
            Some(libc::SIGPIPE),
            "{:?} {err}",
            out.status
        );
    }
}
