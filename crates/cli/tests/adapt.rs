//! `osrl adapt` refuses bad changes before anything runs, naming what is wrong.

use std::process::Command;

fn osrl() -> Command {
    Command::new(env!("CARGO_BIN_EXE_osrl"))
}

/// A fresh directory `NAME-PID` and a planar3 controller trained there for 0.1 simulated
/// minutes (`p3.osrl`).
fn tiny_controller(name: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let dir = std::env::temp_dir().join(format!("{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("p3.osrl");
    let st = osrl()
        .args(["train", "--robot", "planar3", "--minutes", "0.1", "--out"])
        .arg(&model)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    (dir, model)
}

/// Unknown fields and a negative mass factor are refused while the arguments are parsed; a
/// payload beyond the torque limits once the model is loaded; a config that sets the saved
/// learner's settings too; no output file is written.
#[test]
fn bad_changes_are_refused_before_anything_runs() {
    let (dir, model) = tiny_controller("osrl-adapt-test");
    let out = dir.join("adapted.osrl");
    for (spec, word) in [
        ("weight=2", "unknown key 'weight'"),
        ("mass=-1.3", "mass"),
        ("payload=500", "cannot hold itself"),
    ] {
        let o = osrl()
            .args(["adapt", "--model"])
            .arg(&model)
            .args(["--change", spec, "--minutes", "0.1", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{spec}");
        assert!(err.contains(word), "{spec}: {err}");
        assert!(!out.exists(), "{spec}");
    }
    // A learner setting other than [learner.adaptation] would be ignored (the saved
    // controller's settings hold): refused, naming the table; [learner.adaptation] is read.
    let cfg = dir.join("adapt.toml");
    for (text, word) in [
        (
            "[learner.controllers]\ncommand_projection = 0.0\n",
            "[learner] controllers would be ignored",
        ),
        ("[learner.adaptation]\nenabled = false\n", ""),
    ] {
        std::fs::write(&cfg, text).unwrap();
        let o = osrl()
            .args(["adapt", "--model"])
            .arg(&model)
            .args(["--change", "none", "--minutes", "0.05", "--config"])
            .arg(&cfg)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        if word.is_empty() {
            assert!(o.status.success(), "{text}: {err}");
            assert!(out.exists(), "{text}");
        } else {
            assert!(!o.status.success() && err.contains(word), "{text}: {err}");
            assert!(!out.exists(), "{text}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The last line of stdout as JSON.
fn last_json(out: &std::process::Output) -> serde_json::Value {
    let text = String::from_utf8_lossy(&out.stdout);
    serde_json::from_str(text.lines().last().unwrap()).unwrap()
}

/// `osrl eval --change` evaluates on the changed robot: `none` gives the unchanged robot's
/// numbers, a payload other ones (its `u*` is eq. 7 on the loaded arm), and a payload the arm
/// cannot hold is refused before anything runs.
#[test]
fn eval_measures_on_the_changed_robot() {
    let (dir, model) = tiny_controller("osrl-eval-change");
    let eval = |change: Option<&str>| {
        let mut c = osrl();
        c.args(["eval", "--json", "--model"]).arg(&model);
        if let Some(ch) = change {
            c.args(["--change", ch]);
        }
        c.output().unwrap()
    };
    let plain = eval(None);
    assert!(
        plain.status.success(),
        "{}",
        String::from_utf8_lossy(&plain.stderr)
    );
    let (plain, none) = (last_json(&plain), last_json(&eval(Some("none"))));
    let loaded = last_json(&eval(Some("payload=0.5")));
    assert_eq!(plain["change"], serde_json::Value::Null);
    assert_eq!(none["change"], serde_json::Value::Null);
    assert_eq!(loaded["change"], "payload=0.5");
    for key in [
        "tracking_rms_mm",
        "command_nmse",
        "max_command_step_analytical",
    ] {
        assert_eq!(plain[key], none[key], "{key}");
        assert_ne!(plain[key], loaded[key], "{key}");
    }
    let o = eval(Some("payload=500"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("cannot hold itself"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
