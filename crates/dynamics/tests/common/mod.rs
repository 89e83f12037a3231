//! Shared fixtures of the cross-check tests: the built-in robots, random arms and random states.

#![allow(dead_code)]

use osrl_dynamics::{robots, Model};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// planar3, sarcos7, four random arms (with and without friction) and two mixing revolute and
/// prismatic joints.
pub fn models() -> Vec<Model> {
    vec![
        robots::random_mixed_arm(5, 6, true),
        robots::random_mixed_arm(8, 7, false),
        robots::planar3(),
        robots::sarcos7(),
        robots::random_arm(2, 1, false),
        robots::random_arm(5, 2, true),
        robots::random_arm(7, 3, false),
        robots::random_arm(9, 4, true),
    ]
}

/// A seeded generator.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A vector of `n` uniform draws in [−scale, scale].
pub fn rand_vec(rng: &mut ChaCha8Rng, n: usize, scale: f64) -> Vec<f64> {
    (0..n).map(|_| rng.random_range(-scale..scale)).collect()
}

/// Largest absolute entry of `a − b`.
pub fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The numbers of a JSON array.
pub fn json_vec(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .expect("a JSON array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// Largest |a − b| relative to the scale max(1, max |b|).
pub fn rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

/// What [`against_pinocchio`] compares, in the order of its result.
pub const PINOCCHIO_QUANTITIES: [&str; 6] = ["M", "g", "RNEA", "ABA", "x and J", "J̇q̇"];

/// The worst relative differences between `model` and the Pinocchio fixture's `states` (written
/// by scripts/pinocchio_fixtures.py): M, g, RNEA, ABA, tip position and Jacobian, J̇q̇.
pub fn against_pinocchio(model: &osrl_dynamics::Model, fx: &serde_json::Value) -> [f64; 6] {
    use osrl_dynamics::{aba, compute_all, crba, gravity, rnea};
    let mut data = model.data();
    let states = fx["states"].as_array().expect("states");
    assert!(states.len() >= 100, "{}: too few states", model.name());
    let mut worst = [0.0f64; 6];
    for s in states {
        let v = |k: &str| json_vec(&s[k]);
        let (q, qd, qdd, u) = (v("q"), v("qd"), v("qdd"), v("u"));
        let matrix =
            |k: &str| -> Vec<f64> { s[k].as_array().unwrap().iter().flat_map(json_vec).collect() };
        let m: Vec<f64> = crba(model, &mut data, &q)
            .unwrap()
            .transpose()
            .iter()
            .copied()
            .collect();
        worst[0] = worst[0].max(rel(&m, &matrix("M")));
        let g = gravity(model, &mut data, &q).unwrap();
        worst[1] = worst[1].max(rel(g.as_slice(), &v("g")));
        let tau = rnea(model, &mut data, &q, &qd, &qdd).unwrap();
        worst[2] = worst[2].max(rel(tau.as_slice(), &v("rnea")));
        let acc = aba(model, &mut data, &q, &qd, &u).unwrap();
        worst[3] = worst[3].max(rel(acc.as_slice(), &v("aba")));
        compute_all(model, &mut data, &q, &qd).unwrap();
        let j: Vec<f64> = data.jac.transpose().iter().copied().collect();
        worst[4] = worst[4]
            .max(rel(&j, &matrix("J")))
            .max(rel(data.ee_pos.as_slice(), &v("x")));
        worst[5] = worst[5].max(rel(data.jdot_qd.as_slice(), &v("jdot_qd")));
    }
    worst
}
