//! `osrl train`, `osrl eval` and `osrl simulate --controller learned:MODEL` end to end on a tiny
//! training run: the JSON keys of issue 6, the saved model and its sidecar, one-line errors.

mod common;
use common::{last_json, osrl};

#[test]
fn train_eval_simulate_round_trip() {
    let dir = std::env::temp_dir().join(format!("osrl-learned-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("p3.osrl");
    let m = model.to_str().unwrap();
    // 0.2 simulated minutes: the warm-up and some babbling, enough for the models to exist.
    let (ok, out, err) = osrl(&[
        "train",
        "--robot",
        "planar3",
        "--trajectory",
        "figure8",
        "--minutes",
        "0.2",
        "--seed",
        "3",
        "--out",
        m,
        "--json",
    ]);
    assert!(ok, "{err}");
    let t = last_json(&out);
    for key in [
        "n_local_models",
        "sim_training_minutes",
        "wall_seconds",
        "realtime_factor",
        "learning_curve",
        "max_command_step",
        "max_command_step_analytical",
        "counters",
    ] {
        assert!(t.get(key).is_some(), "train JSON lacks {key}: {t}");
    }
    assert!((t["sim_training_minutes"].as_f64().unwrap() - 0.2).abs() < 1e-6);
    assert!(!t["learning_curve"].as_array().unwrap().is_empty());
    let side: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("p3.osrl.json")).unwrap()).unwrap();
    assert_eq!(side["robot"], "planar3");
    assert_eq!(side["seed"], 3);
    assert_eq!(side["home"].as_array().unwrap().len(), 3);
    // eval on the training trajectory, with files.
    let evdir = dir.join("eval");
    let (ok, out, err) = osrl(&[
        "eval",
        "--model",
        m,
        "--out",
        evdir.to_str().unwrap(),
        "--json",
    ]);
    assert!(ok, "{err}");
    let e = last_json(&out);
    assert_eq!(e["robot"], "planar3");
    assert!(
        e["evaluated"] == false || e["tracking_rms_mm"].as_f64().unwrap().is_finite(),
        "{e}"
    );
    // The cost of a command on this model, timed at every evaluated step.
    let (med, p99) = (
        e["command_us_median"].as_f64().unwrap(),
        e["command_us_p99"].as_f64().unwrap(),
    );
    assert!(med > 0.0 && p99 >= med, "{e}");
    for f in [
        "eval.csv",
        "path.svg",
        "path.png",
        "commands.svg",
        "commands.png",
        "metrics.json",
    ] {
        assert!(evdir.join(f).exists(), "eval --out lacks {f}");
    }
    // simulate runs the saved controller.
    let (ok, out, err) = osrl(&[
        "simulate",
        "--controller",
        &format!("learned:{m}"),
        "--seconds",
        "8",
        "--json",
    ]);
    assert!(ok, "{err}");
    let s = last_json(&out);
    let steps = ["learned_steps", "extrapolated_steps", "fallback_steps"]
        .iter()
        .map(|k| s[k].as_u64().unwrap())
        .sum::<u64>();
    assert_eq!(steps, 4000, "{s}");
    // Bad input: a too-short evaluation, a corrupted sidecar, a missing model — one-line errors.
    let (ok, _, err) = osrl(&["eval", "--model", m, "--seconds", "3"]);
    assert!(
        !ok && err.contains("two periods") && err.trim().lines().count() == 1,
        "{err}"
    );
    std::fs::write(dir.join("p3.osrl.json"), "{\"version\": 1}").unwrap();
    let (ok, _, err) = osrl(&["eval", "--model", m]);
    assert!(
        !ok && err.contains("p3.osrl.json") && err.trim().lines().count() == 1,
        "{err}"
    );
    let (ok, _, err) = osrl(&["simulate", "--controller", "learned:/nonexistent/x.osrl"]);
    assert!(!ok && err.trim().lines().count() == 1, "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
