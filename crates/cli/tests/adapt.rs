//! `osrl adapt` refuses bad changes before anything runs, naming what is wrong.

use std::process::Command;

fn osrl() -> Command {
    Command::new(env!("CARGO_BIN_EXE_osrl"))
}

/// Unknown fields and a negative mass factor are refused while the arguments are parsed; a
/// payload beyond the torque limits once the model is loaded; a config that sets the saved
/// learner's settings too; no output file is written.
#[test]
fn bad_changes_are_refused_before_anything_runs() {
    let dir = std::env::temp_dir().join(format!("osrl-adapt-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("p3.osrl");
    let out = dir.join("adapted.osrl");
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
