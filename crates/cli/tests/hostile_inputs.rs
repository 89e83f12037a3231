//! Inputs found to crash, hang or destroy data (a review of 2026-12-07), each refused at once
//! with one line naming what was wrong, and nothing lost: an output that is one of the run's
//! inputs, a special file deep in `reproduce`'s output folder, XML nested 50,000 deep, and
//! configuration values whose work would never end or not fit in memory.

mod common;
use common::refused_before_work as refused;
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    common::scratch(&format!("inputs-{name}"))
}

#[test]
fn an_output_that_is_an_input_is_refused_and_the_input_kept() {
    let d = scratch("same");
    let s = |p: &PathBuf| p.to_str().unwrap().to_string();
    let config = d.join("run.toml");
    let text = "# mine\n[train]\nminutes = 0.05\n";
    std::fs::write(&config, text).unwrap();
    let csv = d.join("data.csv");
    let rows: String = (0..50).map(|i| format!("{},{}\n", i, 2 * i)).collect();
    let data = format!("x,y\n{rows}");
    std::fs::write(&csv, &data).unwrap();
    let also = format!("{}/./run.toml", s(&d));
    refused(
        &["train", "--config", &s(&config), "--out", &also],
        "is also the input",
    );
    let fit = [
        "lwpr",
        "fit",
        "--train",
        &s(&csv),
        "--test",
        &s(&csv),
        "--inputs",
        "1",
    ];
    refused(
        &[&fit[..], &["--save", &s(&csv)]].concat(),
        "is also the input",
    );
    // `simulate --out DIR` writes DIR/config.toml: not over the config it read.
    let sim = d.join("sim");
    std::fs::create_dir(&sim).unwrap();
    let own = sim.join("config.toml");
    std::fs::write(&own, text).unwrap();
    refused(
        &["simulate", "--config", &s(&own), "--out", &s(&sim)],
        "is also the input",
    );
    assert_eq!(std::fs::read_to_string(&config).unwrap(), text);
    assert_eq!(std::fs::read_to_string(&own).unwrap(), text);
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), data);
}

#[test]
fn a_special_file_deep_in_the_report_folder_is_refused_before_the_run() {
    let d = scratch("tree");
    let e9 = d.join("E9");
    std::fs::create_dir(&e9).unwrap();
    let fifo = e9.join("planar3_held_out.png");
    let ok = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(ok.success());
    let out = d.to_str().unwrap();
    refused(
        &["reproduce", "--quick", "--seeds", "1", "--out", out],
        "FIFO",
    );
    std::fs::remove_file(&fifo).unwrap();
    std::fs::create_dir(&fifo).unwrap();
    refused(
        &["reproduce", "--quick", "--seeds", "1", "--out", out],
        "planar3_held_out.png",
    );
}

#[test]
fn deeply_nested_xml_is_refused_without_overflowing_the_stack() {
    let d = scratch("deep");
    let urdf = d.join("deep.urdf");
    let n = 50_000;
    let text = format!(
        "<robot name=\"x\">{}{}</robot>",
        "<a>".repeat(n),
        "</a>".repeat(n)
    );
    std::fs::write(&urdf, text).unwrap();
    refused(
        &["robot", "--robot", urdf.to_str().unwrap()],
        "nested more than 256",
    );
}

#[test]
fn values_that_crashed_or_never_finished_are_refused_by_name() {
    let d = scratch("values");
    let cases = [
        ("[learner.nominal]\nkp = [-1.0, -1.0, -1.0]\n", "nominal.kp"),
        (
            "[learner.guards]\nwarmup_samples = 1000000000000\n",
            "warmup_samples",
        ),
        ("[train]\nepisode_seconds = 1e9\n", "episode_seconds"),
        ("[train.curriculum]\nstop_every = 1e-6\n", "stop_every"),
        ("[trajectory]\nramp = 1e300\n", "ramp"),
        (
            "[trajectory]\nkind = \"family\"\n[trajectory.family]\napproach_speed = 1e-300\n",
            "approach_speed",
        ),
        (
            "[learner.partition.lwpr]\nnorm_in = nan\n",
            "partition.lwpr.norm_in",
        ),
    ];
    for (i, (text, what)) in cases.iter().enumerate() {
        let f = d.join(format!("c{i}.toml"));
        std::fs::write(&f, text).unwrap();
        let out = d.join("m.osrl");
        let (f, out) = (f.to_str().unwrap(), out.to_str().unwrap());
        refused(
            &["train", "--minutes", "0.05", "--config", f, "--out", out],
            what,
        );
    }
}

/// Huge but finite values: each is refused before any work, its key and range named, instead of
/// an error about a quantity it overflowed (a cost, LWPR's `norm_in`, a mass, a singular
/// system) or a run that printed "command RMS inf".
#[test]
fn huge_finite_values_are_refused_naming_their_key() {
    let d = scratch("huge");
    let path = |name: &str| d.join(name).to_str().unwrap().to_string();
    let configs = [
        (
            "train",
            "[learner.nominal]\nkp = [1e300, 20.0, 20.0]\n",
            "nominal.kp must lie in (0, 1000000.0]",
        ),
        (
            "train",
            "[sim.sensor_noise]\nq = 1e300\n",
            "sensor_noise.q = 1e300",
        ),
        (
            "train",
            "[trajectory]\na = 1e300\n",
            "figure-8 width a must be > 0 and at most 1000.0 m, got 1e300",
        ),
        (
            "train",
            "[trajectory]\ncentre = [0.5, 0.0, -1e300]\n",
            "centre [0.5, 0.0, -1e300] lies beyond ±1000.0 m",
        ),
        (
            "train",
            "[learner.nominal]\nq_rest = [0.0, 1e300, 0.0]\n",
            "nominal.q_rest must lie within ±1000.0",
        ),
        (
            "train",
            "[learner.partition.lwpr]\ninit_d = 0\n",
            "partition.lwpr: invalid LWPR config: init_d",
        ),
        (
            "train",
            "[learner.gravity.lwpr]\nw_gen = 0\n",
            "gravity.lwpr: invalid LWPR config: w_gen = 0",
        ),
        (
            "train",
            "[train.curriculum]\nstop_seconds = 1e300\n",
            "curriculum.stop_seconds = 1e300 is out of range",
        ),
        (
            "simulate",
            "[controller.gains]\nkp = 1e300\n",
            "task gain kp = 1e300",
        ),
        (
            "simulate",
            "[model_error]\nmass_scale = 1e300\n",
            "mass = 1e300: must lie in [0.001, 1000]",
        ),
        (
            "simulate",
            "[sim]\nactuator_noise = 1e300\n",
            "actuator_noise = 1e300",
        ),
    ];
    for (i, (cmd, text, what)) in configs.iter().enumerate() {
        let f = path(&format!("c{i}.toml"));
        std::fs::write(&f, text).unwrap();
        let out = path(&format!("out{i}"));
        let minutes: &[&str] = if *cmd == "train" {
            &["--minutes", "0.05"]
        } else {
            &[]
        };
        let args = [&[*cmd, "--config", &f, "--out", &out][..], minutes].concat();
        refused(&args, what);
    }
    let out = path("s");
    refused(
        &["simulate", "--model-error", "payload=1e9", "--out", &out],
        "payload = 1000000000: must lie in [0, 10000]",
    );
    // A command-line value: clap's error adds its usage hint below the line.
    let model = path("m.osrl");
    let args = [
        "adapt",
        "--model",
        &model,
        "--change",
        "com=1e300",
        "--out",
        &out,
    ];
    let (ok, stdout, err) = common::osrl(&args);
    assert!(!ok && stdout.is_empty(), "{stdout}");
    assert!(err.contains("com = 1e300: must lie in [0, 10]"), "{err}");
    let profile = path("p.toml");
    std::fs::write(&profile, "kd = [1e300, 1, 1, 1, 1, 1, 1]\n").unwrap();
    refused(
        &["robot", "--robot", "sarcos7", "--profile", &profile],
        "kd: joint 0 ('SFE_joint') is 1e300; at most 10000.0",
    );
}
