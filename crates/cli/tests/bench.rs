//! `osrl bench lwpr`: a small configuration of the LWPR benchmarks.

mod common;
use common::{last_json, osrl};

#[test]
fn bench_lwpr_reports_the_selected_tests() {
    let args = [
        "bench",
        "lwpr",
        "--seeds",
        "2",
        "--only",
        "cross2,sarcos7",
        "--traj",
        "2",
        "--seconds",
        "2",
        "--epochs",
        "1",
        "--json",
    ];
    let (ok, out, err) = osrl(&args);
    assert!(ok, "{err}");
    let v = last_json(&out);
    assert!(v.get("cross_21d").is_none(), "not selected");
    let c = &v["cross_2d"];
    assert_eq!(c["seeds"], 2);
    let nmse: Vec<f64> = serde_json::from_value(c["nmse_all"].clone()).unwrap();
    let rfs: Vec<usize> = serde_json::from_value(c["n_rfs_all"].clone()).unwrap();
    // The cross test's regression guard (as `lwpr/tests/cross.rs`).
    assert!(
        nmse.len() == 2 && nmse.iter().all(|&e| e < 0.06),
        "{nmse:?}"
    );
    assert!(rfs.iter().all(|&n| (20..=45).contains(&n)), "{rfs:?}");
    assert!(c["update_us"].as_f64().unwrap() > 0.0 && c["predict_us"].as_f64().unwrap() > 0.0);
    // The numerical guards' counts: no RF diverges on the standard tests.
    assert!(c["metric_skipped"].is_u64(), "{c}");
    assert_eq!(c["removed_non_finite"], 0, "{c}");
    let s = &v["sarcos7_invdyn"];
    assert_eq!(
        s["train"].as_u64().unwrap() + s["test"].as_u64().unwrap(),
        400
    );
    assert_eq!(s["n_rfs_per_output"].as_array().unwrap().len(), 7);
    let e: Vec<f64> = serde_json::from_value(s["nmse"].clone()).unwrap();
    assert!(e.iter().all(|x| x.is_finite() && *x < 1.0), "{e:?}");
    assert_eq!(s["removed_non_finite"], 0, "{s}");
}

#[test]
fn bench_lwpr_first_seed_selects_the_seeds() {
    // Seeds 0..3 at once, and seed 2 alone: the same numbers for seed 2.
    let run = |extra: &[&str]| {
        let mut args = vec!["bench", "lwpr", "--only", "cross2", "--json"];
        args.extend_from_slice(extra);
        let (ok, out, err) = osrl(&args);
        assert!(ok, "{err}");
        last_json(&out)["cross_2d"].clone()
    };
    let all = run(&["--seeds", "3"]);
    let one = run(&["--seeds", "1", "--first-seed", "2"]);
    assert_eq!(
        (&all["first_seed"], &one["first_seed"]),
        (&0.into(), &2.into())
    );
    assert_eq!(one["nmse_all"][0], all["nmse_all"][2]);
    assert_eq!(one["n_rfs_all"][0], all["n_rfs_all"][2]);
    assert_ne!(all["nmse_all"][0], all["nmse_all"][2], "the seeds differ");
    assert_eq!(all["epochs"], 20);
    // Fewer epochs: another fit, and the count is reported.
    let short = run(&["--seeds", "1", "--first-seed", "2", "--cross2-epochs", "2"]);
    assert_eq!(short["epochs"], 2);
    assert_ne!(short["nmse_all"][0], one["nmse_all"][0]);
    // The last seed there is.
    let last = run(&["--seeds", "1", "--first-seed", "18446744073709551615"]);
    assert_eq!(last["first_seed"], u64::MAX);
    assert!(last["nmse"].as_f64().unwrap().is_finite());
}

#[test]
fn bench_lwpr_cross21_takes_its_seeds_and_epochs() {
    let args = [
        "bench",
        "lwpr",
        "--only",
        "cross21",
        "--seeds",
        "2",
        "--first-seed",
        "3",
        "--cross21-epochs",
        "1",
        "--json",
    ];
    let (ok, out, err) = osrl(&args);
    assert!(ok, "{err}");
    let c = &last_json(&out)["cross_21d"];
    assert_eq!(
        (&c["first_seed"], &c["epochs"], &c["seeds"]),
        (&3.into(), &1.into(), &2.into())
    );
    let nmse: Vec<f64> = serde_json::from_value(c["nmse_all"].clone()).unwrap();
    assert!(
        nmse.len() == 2 && nmse.iter().all(|e| e.is_finite() && *e > 0.0),
        "{nmse:?}"
    );
    assert_ne!(nmse[0], nmse[1], "two seeds, two data sets");
    assert_eq!(c["embedding"], "rotation");
}

/// The `cross_21d` object of a one-seed, one-epoch run of the 21-D test with `flag value`.
fn cross21_with(flag: &str, value: &str) -> serde_json::Value {
    let args = [
        "bench",
        "lwpr",
        "--only",
        "cross21",
        "--seeds",
        "1",
        "--cross21-epochs",
        "1",
        flag,
        value,
        "--json",
    ];
    let (ok, out, err) = osrl(&args);
    assert!(ok, "{err}");
    last_json(&out)["cross_21d"].clone()
}

#[test]
fn bench_lwpr_cross21_embeds_with_or_without_the_rotation() {
    let run = |embedding| cross21_with("--cross21-embedding", embedding);
    let (rot, id) = (run("rotation"), run("identity"));
    assert_eq!(
        (&rot["embedding"], &id["embedding"]),
        (&"rotation".into(), &"identity".into())
    );
    let e = |c: &serde_json::Value| c["nmse"].as_f64().unwrap();
    assert!(e(&id).is_finite() && e(&id) > 0.0);
    assert_ne!(e(&rot), e(&id), "the embedding changes the fit");
    let (ok, _, err) = osrl(&["bench", "lwpr", "--cross21-embedding", "shear"]);
    assert!(!ok && err.contains("shear"), "{err}");
}

/// `--cross21-dim` embeds the same points in another dimension (the Matlab test's 25) and
/// reports it as `dim`.
#[test]
fn bench_lwpr_cross21_dim() {
    let run = |dim| cross21_with("--cross21-dim", dim);
    let (d21, d25) = (run("21"), run("25"));
    assert_eq!(
        (d21["dim"].as_u64(), d25["dim"].as_u64()),
        (Some(21), Some(25))
    );
    let e = |c: &serde_json::Value| c["nmse"].as_f64().unwrap();
    assert!(e(&d25).is_finite() && e(&d25) > 0.0);
    assert_ne!(e(&d21), e(&d25), "another rotation, another fit");
}

#[test]
fn bench_lwpr_rejects_bad_arguments() {
    for (args, says) in [
        (&["bench", "lwpr", "--seeds", "0", "--json"][..], "--seeds"),
        (&["bench", "lwpr", "--only", "cross3"], "cross3"),
        (
            &[
                "bench",
                "lwpr",
                "--only",
                "cross21",
                "--cross21-epochs",
                "0",
            ],
            "--cross21-epochs",
        ),
        (
            &["bench", "lwpr", "--only", "cross2", "--cross2-epochs", "0"],
            "--cross2-epochs",
        ),
        (
            &["bench", "lwpr", "--only", "cross21", "--cross21-dim", "1"],
            "--cross21-dim",
        ),
        (
            &[
                "bench",
                "lwpr",
                "--only",
                "cross2",
                "--first-seed",
                "18446744073709551615",
            ],
            "--first-seed",
        ),
        (
            &["bench", "lwpr", "--only", "sarcos7", "--traj", "0"],
            "--traj",
        ),
        (&["bench", "lwpr", "--seconds", "inf"], "--seconds"),
        (
            &[
                "bench",
                "lwpr",
                "--only",
                "sarcos7",
                "--traj",
                "1",
                "--seconds",
                "0.1",
            ],
            "test samples",
        ),
    ] {
        let (ok, out, err) = osrl(args);
        assert!(!ok && out.is_empty(), "{args:?}: {out}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}
