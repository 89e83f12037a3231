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

#[allow(dead_code)]
/// An untrained planar3 model (the library's checks pass).
pub fn untrained_model() -> osrl_learn::SavedModel {
    let model = osrl_dynamics::robots::planar3();
    let spec = model.spec();
    let tau: Vec<f64> = model.tau_max().collect();
    let cfg = osrl_learn::LearnerConfig::for_robot(&spec.kp, &spec.kd, &spec.q_rest, &tau);
    let learner = osrl_learn::Learner::new(3, 2, 0.002, cfg).unwrap();
    let info = osrl_learn::ModelInfo {
        robot: "planar3".into(),
        trajectory: Default::default(),
        home: osrl_experiments::Setup::new("planar3")
            .unwrap()
            .home()
            .to_vec(),
        gains: Default::default(),
        control_period: 0.002,
        sim_training_minutes: 0.0,
        seed: 0,
        profile: Default::default(),
    };
    osrl_learn::SavedModel::new(info, learner).unwrap()
}

/// A fresh scratch folder for one test (`tag`: the test's name; the process id keeps runs
/// apart).
#[allow(dead_code)]
pub fn scratch(tag: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("osrl-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `osrl args…` fails at once (nothing on stdout: no work done) with one line naming `what`.
#[allow(dead_code)]
pub fn refused_before_work(args: &[&str], what: &str) {
    let (ok, out, err) = osrl(args);
    assert!(!ok, "{args:?}: {out}");
    assert!(out.is_empty(), "{args:?} did work first: {out}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains(what), "{args:?}: {err}");
}
