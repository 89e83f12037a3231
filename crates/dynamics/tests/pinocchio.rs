//! Cross-check against Pinocchio: fixtures made by `scripts/pinocchio_fixtures.py` from the URDF
//! that `osrl robot --urdf` exports (committed next to them), 100 random states per robot.

use osrl_dynamics::{aba, compute_all, crba, gravity, rnea, robots, urdf::to_urdf, Model};
use serde_json::Value;
use std::path::PathBuf;

fn fixtures(robot: &str) -> (String, Value) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let urdf = std::fs::read_to_string(dir.join(format!("{robot}.urdf"))).expect("fixture URDF");
    let json =
        std::fs::read_to_string(dir.join(format!("{robot}.pinocchio.json"))).expect("fixture JSON");
    (
        urdf,
        serde_json::from_str(&json).expect("fixture JSON parses"),
    )
}

fn vec(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Largest |a − b| relative to the scale max(1, max |b|).
fn rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

fn check(model: Model) {
    let (urdf, fx) = fixtures(model.name());
    assert_eq!(
        to_urdf(&model),
        urdf,
        "{}: the exported URDF changed; rerun scripts/pinocchio_fixtures.py",
        model.name()
    );
    let mut data = model.data();
    let states = fx["states"].as_array().unwrap();
    assert!(states.len() >= 100);
    let mut worst = [0.0f64; 6];
    for s in states {
        let (q, qd, qdd, u) = (vec(&s["q"]), vec(&s["qd"]), vec(&s["qdd"]), vec(&s["u"]));
        let m_ref: Vec<f64> = s["M"].as_array().unwrap().iter().flat_map(vec).collect();
        let m: Vec<f64> = crba(&model, &mut data, &q)
            .unwrap()
            .transpose()
            .iter()
            .copied()
            .collect();
        worst[0] = worst[0].max(rel(&m, &m_ref));
        worst[1] = worst[1].max(rel(
            gravity(&model, &mut data, &q).unwrap().as_slice(),
            &vec(&s["g"]),
        ));
        worst[2] = worst[2].max(rel(
            rnea(&model, &mut data, &q, &qd, &qdd).unwrap().as_slice(),
            &vec(&s["rnea"]),
        ));
        worst[3] = worst[3].max(rel(
            aba(&model, &mut data, &q, &qd, &u).unwrap().as_slice(),
            &vec(&s["aba"]),
        ));
        compute_all(&model, &mut data, &q, &qd).unwrap();
        let j_ref: Vec<f64> = s["J"].as_array().unwrap().iter().flat_map(vec).collect();
        let j: Vec<f64> = data.jac.transpose().iter().copied().collect();
        worst[4] = worst[4]
            .max(rel(&j, &j_ref))
            .max(rel(data.ee_pos.as_slice(), &vec(&s["x"])));
        worst[5] = worst[5].max(rel(data.jdot_qd.as_slice(), &vec(&s["jdot_qd"])));
    }
    let names = ["M", "g", "RNEA", "ABA", "x and J", "J̇q̇"];
    eprintln!(
        "{} vs Pinocchio, worst relative difference: {:?}",
        model.name(),
        names.iter().zip(worst).collect::<Vec<_>>()
    );
    for (name, w) in names.iter().zip(worst) {
        assert!(
            w <= 1e-9,
            "{}: {name} differs from Pinocchio by {w:e} (relative)",
            model.name()
        );
    }
}

#[test]
fn planar3_agrees_with_pinocchio() {
    check(robots::planar3());
}

#[test]
fn sarcos7_agrees_with_pinocchio() {
    check(robots::sarcos7());
}
