//! Issue 30: output paths that exist and are not regular files (a FIFO, a directory) are
//! refused before any work and left as they were; input paths that are not regular files are
//! refused without blocking; a saved model whose home or control period is out of range is
//! refused naming the field; a training run rejecting its samples warns and says so in JSON.

mod common;
use common::{last_json, osrl, refused_before_work};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    common::scratch(&format!("hostile-{name}"))
}

fn mkfifo(p: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(p)
        .status()
        .unwrap();
    assert!(ok.success());
}

fn is_fifo(p: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(p).unwrap().file_type().is_fifo()
}

#[test]
fn train_out_fifo_or_directory_is_refused_before_training_and_left_alone() {
    let d = scratch("train-out");
    let (fifo, dir) = (d.join("fifo"), d.join("dir"));
    mkfifo(&fifo);
    std::fs::create_dir(&dir).unwrap();
    for (p, kind) in [(&fifo, "FIFO"), (&dir, "directory")] {
        let o = p.to_str().unwrap();
        refused_before_work(&["train", "--minutes", "0.05", "--out", o], kind);
    }
    assert!(is_fifo(&fifo) && dir.is_dir());
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        2,
        "no temporary files"
    );
}

#[test]
fn lwpr_fit_save_fifo_is_refused_before_training() {
    let d = scratch("lwpr-save");
    let csv = d.join("t.csv");
    let rows: String = (0..50).map(|i| format!("{},{}\n", i, 2 * i)).collect();
    std::fs::write(&csv, format!("x,y\n{rows}")).unwrap();
    let fifo = d.join("fifo");
    mkfifo(&fifo);
    let c = csv.to_str().unwrap();
    let args = ["lwpr", "fit", "--train", c, "--test", c, "--inputs", "1"];
    let save = ["--save", fifo.to_str().unwrap()];
    refused_before_work(&[&args[..], &save].concat(), "FIFO");
    let save = ["--save", d.to_str().unwrap()];
    refused_before_work(&[&args[..], &save].concat(), "directory");
    assert!(is_fifo(&fifo));
}

#[test]
fn simulate_out_file_inside_a_folder_that_is_a_fifo_is_refused_before_the_run() {
    let d = scratch("sim-out");
    std::fs::create_dir(d.join("run")).unwrap();
    let csv = d.join("run").join("simulate.csv");
    mkfifo(&csv);
    let run = d.join("run");
    refused_before_work(&["simulate", "--out", run.to_str().unwrap()], "FIFO");
    assert!(is_fifo(&csv));
    let fifo = d.join("fifo");
    mkfifo(&fifo);
    refused_before_work(&["simulate", "--out", fifo.to_str().unwrap()], "FIFO");
}

#[test]
fn inputs_that_are_fifos_are_refused_without_blocking() {
    let d = scratch("inputs");
    let fifo = d.join("fifo");
    mkfifo(&fifo);
    let f = fifo.to_str().unwrap();
    refused_before_work(&["simulate", "--config", f], "FIFO");
    refused_before_work(&["eval", "--model", f], "FIFO");
    refused_before_work(&["lwpr", "eval", "--model", f, "--test", f], "FIFO");
    refused_before_work(
        &["lwpr", "fit", "--train", f, "--test", f, "--inputs", "1"],
        "FIFO",
    );
    refused_before_work(&["robot", "--robot", &format!("{f}.urdf")], "");
}

/// A saved planar3 model's bytes with its info JSON edited by `edit` (checksum fixed).
fn with_info(edit: impl Fn(&mut serde_json::Value)) -> Vec<u8> {
    let bytes = common::untrained_model().to_bytes().unwrap();
    let len = u64::from_le_bytes(bytes[12..20].try_into().unwrap()) as usize;
    let mut info: serde_json::Value = serde_json::from_slice(&bytes[28..28 + len]).unwrap();
    edit(&mut info);
    let info = serde_json::to_vec(&info).unwrap();
    let fnv = info.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    });
    let mut out = bytes[..12].to_vec();
    out.extend_from_slice(&(info.len() as u64).to_le_bytes());
    out.extend_from_slice(&fnv.to_le_bytes());
    out.extend_from_slice(&info);
    out.extend_from_slice(&bytes[28 + len..]);
    out
}

#[test]
fn a_saved_home_or_control_period_out_of_range_is_refused_naming_the_field() {
    let d = scratch("fields");
    let p = d.join("m.osrl");
    let m = p.to_str().unwrap();
    std::fs::write(&p, with_info(|_| {})).unwrap();
    assert!(
        osrl(&["eval", "--model", m]).0,
        "the unedited model evaluates"
    );
    for v in [0.0, -1.0, 1e300] {
        std::fs::write(&p, with_info(|i| i["control_period"] = v.into())).unwrap();
        refused_before_work(&["eval", "--model", m], "control_period");
        std::fs::write(&p, with_info(|i| i["home"] = vec![v, v, v].into())).unwrap();
        refused_before_work(&["eval", "--model", m], "home");
    }
}

#[test]
fn a_training_run_that_rejects_its_samples_warns_and_says_so_in_json() {
    let d = scratch("rejected");
    let cfg = d.join("c.toml");
    std::fs::write(
        &cfg,
        "[learner]\nguards = { max_abs_acceleration = 1e-6 }\n",
    )
    .unwrap();
    let out = d.join("m.osrl");
    let (c, o) = (cfg.to_str().unwrap(), out.to_str().unwrap());
    let (ok, stdout, err) = osrl(&[
        "train",
        "--config",
        c,
        "--minutes",
        "0.05",
        "--out",
        o,
        "--json",
    ]);
    assert!(ok, "{err}");
    assert!(err.contains("warning: the learner rejected"), "{err}");
    let j = last_json(&stdout);
    assert!(j["rejected_samples"].as_u64().unwrap() > 0, "{j}");
    assert!(j["rejected_share"].as_f64().unwrap() > 0.01, "{j}");
    assert!(j.get("counters").is_some());
    // Without the guard: no warning, the keys still there.
    let (ok, stdout, err) = osrl(&["train", "--minutes", "0.05", "--out", o, "--json"]);
    assert!(
        ok && !err.contains("warning: the learner rejected"),
        "{err}"
    );
    assert_eq!(last_json(&stdout)["rejected_share"].as_f64(), Some(0.0));
}
