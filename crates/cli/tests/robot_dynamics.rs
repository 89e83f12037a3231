//! `osrl robot` and `osrl dynamics` end to end: JSON on the last line, one-line errors.

mod common;
use common::{last_json, osrl};

#[test]
fn dynamics_json_has_the_documented_keys_and_consistent_values() {
    let (ok, out, err) = osrl(&[
        "dynamics",
        "--robot",
        "sarcos7",
        "--q",
        "0,-0.3,0,1.57,0,0,0",
        "--qd",
        "0.1,0,0,0,0,0,0.2",
        "--qdd",
        "0,0,0,0,0,0,0",
        "--u",
        "1,2,3,4,0,0,0",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v = last_json(&out);
    for key in ["x", "J", "M", "g", "h", "tau", "qdd_forward"] {
        assert!(!v[key].is_null(), "missing {key}");
    }
    // The published gravity check of docs/robots.md.
    assert!((v["g"][0].as_f64().unwrap() - 6.335692).abs() < 1e-5);
    assert_eq!(v["M"].as_array().unwrap().len(), 7);
    assert_eq!(v["J"].as_array().unwrap().len(), 3);
    // With q̈ = 0, tau = C q̇ + g = h − friction.
    let (tau, h, f) = (&v["tau"], &v["h"], &v["friction"]);
    for i in 0..7 {
        let d = tau[i].as_f64().unwrap() - (h[i].as_f64().unwrap() - f[i].as_f64().unwrap());
        assert!(d.abs() < 1e-12);
    }
}

#[test]
fn bad_vectors_are_one_line_errors_with_nonzero_exit() {
    for (args, needle) in [
        (
            vec!["dynamics", "--robot", "planar3", "--q", "0.1,x,0.3"],
            "'x' is not a finite number",
        ),
        (
            vec!["dynamics", "--robot", "planar3", "--q", "0.1,0.2"],
            "expected 3",
        ),
        (
            vec!["dynamics", "--robot", "planar3", "--q", "0,0,nan"],
            "not a finite number",
        ),
        (
            vec!["dynamics", "--robot", "nosuchrobot", "--q", "0"],
            "unknown robot",
        ),
    ] {
        let (ok, _, err) = osrl(&args);
        assert!(!ok, "{args:?} should fail");
        assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn exported_urdf_loads_back_as_the_same_robot() {
    let (ok, urdf, err) = osrl(&["robot", "--robot", "planar3", "--urdf"]);
    assert!(ok, "{err}");
    let path = std::env::temp_dir().join(format!("osrl_planar3_{}.urdf", std::process::id()));
    std::fs::write(&path, &urdf).unwrap();
    let p = path.to_str().unwrap();
    let run = |robot: &str| {
        last_json(
            &osrl(&[
                "dynamics",
                "--robot",
                robot,
                "--q",
                "0.3,-0.2,0.5",
                "--qd",
                "1,2,3",
                "--json",
            ])
            .1,
        )
    };
    let (a, b) = (run("planar3"), run(p));
    for key in ["x", "M", "h"] {
        assert_eq!(a[key], b[key], "{key}");
    }
    // A malformed file names the problem.
    std::fs::write(
        &path,
        "<robot name=\"t\"><link name=\"a\"/><joint name=\"j\" type=\"prismatic\"/></robot>",
    )
    .unwrap();
    let (ok, _, err) = osrl(&["robot", "--robot", p, "--urdf"]);
    assert!(
        !ok && err.contains("'j'") && err.contains("prismatic"),
        "{err}"
    );
    std::fs::remove_file(&path).ok();
}

#[test]
fn robot_json_prints_the_resolved_profile_and_urdf_carries_it() {
    let panda = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../dynamics/tests/fixtures/example-robot-data/panda.urdf"
    );
    let (ok, out, err) = osrl(&["robot", "--robot", panda, "--json"]);
    assert!(ok, "{err}");
    let v = last_json(&out);
    let p = &v["profile"];
    assert_eq!(p["tip"], "panda_hand_tcp");
    assert_eq!(p["sources"]["home"], "computed");
    assert_eq!(p["home"], v["q_start"]);
    assert_eq!(p["kp"].as_array().unwrap().len(), 7);
    assert!(p["path"]["a"].as_f64().unwrap() > 0.0);
    // The export embeds the profile; a bad profile flag is refused naming the field.
    let (ok, urdf, err) = osrl(&["robot", "--robot", "planar3", "--urdf"]);
    assert!(
        ok && urdf.contains("<osrl_profile home=\"-1.0 1.4 0.7\""),
        "{err}"
    );
    let dir = std::env::temp_dir().join(format!("osrl-profile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "kd = [1.0, 2.0]\n").unwrap();
    let (ok, _, err) = osrl(&[
        "robot",
        "--robot",
        "planar3",
        "--profile",
        bad.to_str().unwrap(),
    ]);
    assert!(!ok && err.contains("robot profile kd"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
