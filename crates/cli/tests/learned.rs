//! `osrl train`, `osrl eval` and `osrl simulate --controller learned:MODEL` end to end on a tiny
//! training run: the JSON keys of issue 6, the saved model, one-line errors; `osrl train
//! --config` uses every section it accepts and refuses the others.

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
    // With --json, stdout is the JSON document alone (the summary goes to stderr).
    assert!(
        serde_json::from_str::<serde_json::Value>(out.trim()).is_ok(),
        "{out}"
    );
    assert!(err.contains("local models"), "{err}");
    for key in [
        "n_local_models",
        "sim_training_minutes",
        "wall_seconds",
        "realtime_factor",
        "learning_curve",
        "max_command_step",
        "max_command_step_analytical",
        "max_torque_rate",
        "rate_limited",
        "minutes_to_1mm",
        "minutes_to_nmse_0.05",
        "aborted_episodes",
        "braked_episodes",
        "braked_on_step",
        "braked_on_step_by_joint",
        "clipped_on_policy",
        "command_step_curve",
        "counters",
    ] {
        assert!(t.get(key).is_some(), "train JSON lacks {key}: {t}");
    }
    assert!((t["sim_training_minutes"].as_f64().unwrap() - 0.2).abs() < 1e-6);
    // All babbling: no on-policy command step, no time to 1 mm (null, not a number).
    assert!(t["minutes_to_1mm"].is_null(), "{t}");
    for k in ["clipped", "fallbacks", "rate_limited"] {
        assert!(t["counters"][k].as_u64().is_some(), "counters.{k}: {t}");
    }
    assert!(!t["learning_curve"].as_array().unwrap().is_empty());
    let saved = osrl_learn::SavedModel::load(&model).unwrap();
    assert_eq!(saved.info().robot, "planar3");
    assert_eq!(saved.info().seed, 3);
    assert_eq!(saved.info().home.len(), 3);
    assert_eq!(saved.info().control_period, 0.002);
    assert!(!dir.join("p3.osrl.json").exists(), "one file, no sidecar");
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
    // Bad input: a too-short evaluation, a corrupted model, a missing model — one-line errors.
    let (ok, _, err) = osrl(&["eval", "--model", m, "--seconds", "3"]);
    assert!(
        !ok && err.contains("two periods") && err.trim().lines().count() == 1,
        "{err}"
    );
    let mut bytes = std::fs::read(&model).unwrap();
    bytes[40] ^= 0x20;
    std::fs::write(&model, &bytes).unwrap();
    let (ok, _, err) = osrl(&["eval", "--model", m]);
    assert!(
        !ok && err.contains("p3.osrl")
            && err.contains("checksum")
            && err.trim().lines().count() == 1,
        "{err}"
    );
    let (ok, _, err) = osrl(&["simulate", "--controller", "learned:/nonexistent/x.osrl"]);
    assert!(!ok && err.trim().lines().count() == 1, "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Trains for `minutes` with the config file `toml`; the saved model, or the one-line error.
fn train_with(
    dir: &std::path::Path,
    name: &str,
    toml: &str,
    minutes: &str,
) -> Result<osrl_learn::SavedModel, String> {
    let cfg = dir.join(format!("{name}.toml"));
    std::fs::write(&cfg, toml).unwrap();
    let out = dir.join(format!("{name}.osrl"));
    let (ok, _, err) = osrl(&[
        "train",
        "--config",
        cfg.to_str().unwrap(),
        "--minutes",
        minutes,
        "--out",
        out.to_str().unwrap(),
    ]);
    if !ok {
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        return Err(err);
    }
    Ok(osrl_learn::SavedModel::load(&out).unwrap())
}

#[test]
fn train_uses_the_sim_section_and_refuses_the_sections_it_cannot_use() {
    let dir = std::env::temp_dir().join(format!("osrl-train-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The [sim] control period is the learner's: it changes the run and is saved with the model.
    let fast = train_with(&dir, "fast", "[sim]\ncontrol_period = 0.002\n", "0.1").unwrap();
    let slow = train_with(&dir, "slow", "[sim]\ncontrol_period = 0.004\n", "0.1").unwrap();
    assert_eq!(fast.info().control_period, 0.002);
    assert_eq!(slow.info().control_period, 0.004);
    // Half the control steps in the same simulated time: half the transitions learned from.
    let (a, b) = (
        fast.learner().stats().samples,
        slow.learner().stats().samples,
    );
    assert!(
        b > 0 && (a as f64 / b as f64 - 2.0).abs() < 0.02,
        "{a} vs {b} transitions learned from"
    );
    // An absurd control period is refused, naming the setting.
    for dt in ["1e-9", "1e6"] {
        let err = train_with(
            &dir,
            "absurd",
            &format!("[sim]\ncontrol_period = {dt}\n"),
            "0.05",
        )
        .unwrap_err();
        assert!(err.contains("control_period"), "{err}");
    }
    // Sections that configure other commands are refused, named.
    for (section, body) in [
        ("controller", "[controller]\nlaw = \"eq4\"\n"),
        ("model_error", "[model_error]\nmass_scale = 1.3\n"),
        ("simulate", "[simulate]\nseconds = 8.0\n"),
    ] {
        let err = train_with(&dir, section, body, "0.05").unwrap_err();
        assert!(
            err.contains(&format!("[{section}]")) && err.contains("osrl train"),
            "{err}"
        );
    }
    let err = train_with(&dir, "seed", "[sim]\nseed = 4\n", "0.05").unwrap_err();
    assert!(
        err.contains("[sim] seed") && err.contains("[train] seed"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `osrl train` takes a robot profile (`[robot]` section) as `osrl simulate` does and saves it
/// with the model: the saved set-up has the given gains and home, and `osrl eval` and `osrl
/// simulate --controller learned:` run from the saved model alone.
#[test]
fn train_accepts_a_robot_profile_and_saves_it_with_the_model() {
    let dir = std::env::temp_dir().join(format!("osrl-train-profile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (ok, urdf, err) = osrl(&["robot", "--robot", "planar3", "--urdf"]);
    assert!(ok, "{err}");
    let file = dir.join("p3.urdf");
    std::fs::write(&file, urdf).unwrap();
    let kd = [5.0, 4.0, 2.0];
    let toml = format!(
        "[robot]\nname = \"{}\"\nkd = [5.0, 4.0, 2.0]\n",
        file.display()
    );
    let saved = train_with(&dir, "profiled", &toml, "0.05").unwrap();
    assert_eq!(saved.info().profile.kd, Some(kd.to_vec()));
    assert_eq!(saved.learner().config().nominal.kd, kd);
    let setup = osrl_experiments::Setup::from_saved(&saved).unwrap();
    assert_eq!(setup.model().spec().kd, kd);
    assert_eq!(setup.home(), saved.info().home);
    let m = dir.join("profiled.osrl");
    let m = m.to_str().unwrap();
    let (ok, _, err) = osrl(&["eval", "--model", m, "--seconds", "8"]);
    assert!(ok, "{err}");
    let learned = format!("learned:{m}");
    let (ok, _, err) = osrl(&["simulate", "--controller", &learned, "--seconds", "8"]);
    assert!(ok, "{err}");
    // A profile given with a learned controller is refused: the model carries its own.
    let (ok, _, err) = osrl(&[
        "simulate",
        "--controller",
        &learned,
        "--tip",
        "ee",
        "--seconds",
        "0.2",
    ]);
    assert!(!ok && err.contains("learned controller"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
