//! `osrl train --trajectory family` and `osrl eval --config F` end to end on a tiny run
//! (`docs/family.md`): the JSON's `support_share`, the warning on stderr when the evaluated path
//! leaves the trained region (and none when it does not), and the refused config files.

mod common;
use common::{last_json, osrl};

#[test]
fn family_training_and_eval_on_any_described_path() {
    let dir = std::env::temp_dir().join(format!("osrl-family-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("p3.osrl");
    let m = model.to_str().unwrap();
    let (ok, out, err) = osrl(&[
        "train",
        "--robot",
        "planar3",
        "--trajectory",
        "family",
        "--minutes",
        "0.2",
        "--out",
        m,
        "--json",
    ]);
    assert!(ok, "{err}");
    // All babbling at this size: no path drawn yet.
    assert_eq!(last_json(&out)["paths_drawn"], 0);
    let file = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    // Inside the family's region (planar3: x 0.425–0.875, z 0.10–0.40 m): no region warning.
    let inside = file(
        "inside.toml",
        "[trajectory]\nkind = \"circle\"\ncentre = [0.6, 0.0, 0.28]\nradius = 0.08\n",
    );
    let (ok, out, err) = osrl(&["eval", "--model", m, "--config", &inside, "--json"]);
    assert!(ok, "{err}");
    assert!(!err.contains("leaves the region"), "{err}");
    let j = last_json(&out);
    let share = j["support_share"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&share), "{j}");
    assert_eq!(j["trajectory"], "circle");
    assert_eq!(j["leaves_trained_region_mm"].as_f64().unwrap(), 0.0);
    // 5 cm above the region: warned, and the JSON says by how much.
    let outside = file(
        "outside.toml",
        "[trajectory]\nkind = \"circle\"\ncentre = [0.6, 0.0, 0.40]\nradius = 0.05\n",
    );
    let (ok, out, err) = osrl(&["eval", "--model", m, "--config", &outside, "--json"]);
    assert!(ok, "{err}");
    assert!(
        err.contains("warning: the evaluated path leaves the region"),
        "{err}"
    );
    let left = last_json(&out)["leaves_trained_region_mm"]
        .as_f64()
        .unwrap();
    assert!((left - 50.0).abs() < 0.5, "{left}");
    // Refused: other sections, and a family instead of one path.
    let train = file("train.toml", "[train]\nminutes = 1.0\n");
    let (ok, _, err) = osrl(&["eval", "--model", m, "--config", &train]);
    assert!(
        !ok && err.contains("[train]") && err.contains("keep only [trajectory]"),
        "{err}"
    );
    let fam = file("fam.toml", "[trajectory]\nkind = \"family\"\n");
    let (ok, _, err) = osrl(&["eval", "--model", m, "--config", &fam]);
    assert!(!ok && err.contains("not one path"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
