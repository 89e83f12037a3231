//! The gravity models against functions they must learn (`docs/learner.md`, "Gravity").

use super::{GravityModel, StaticGate};
use lwpr::{LwprConfig, MetricInit};

/// A static model of 2 joints with wide fixed kernels and unit scales.
fn static_model(gate: StaticGate) -> GravityModel {
    let cfg = LwprConfig {
        init_d: MetricInit::Scalar(1.0),
        update_d: false,
        ..LwprConfig::default()
    };
    GravityModel::new_static(2, &cfg, gate, 1.0, 1.0, &[1.0, 1.0]).unwrap()
}

/// The static model learns `g(q)` from still samples and ignores moving ones, however wrong
/// their torques.
#[test]
fn static_model_learns_from_still_samples_only() {
    let g = |q: &[f64]| [3.0 + 2.0 * q[0] - q[1], -1.0 + 0.5 * q[0] + 4.0 * q[1]];
    let mut m = static_model(StaticGate::default());
    assert!(m.is_static());
    let dt = 0.002;
    for k in 0..4000 {
        let q = [0.3 * (k as f64 * 0.37).sin(), 0.3 * (k as f64 * 0.23).cos()];
        // Every other sample moves (q̇ = 1 rad/s) and carries a torque far from g(q).
        let moving = k % 2 == 1;
        let v = if moving { 1.0 } else { 0.0 };
        let q1 = [q[0] + v * dt, q[1]];
        let u = if moving { [50.0, -50.0] } else { g(&q) };
        m.learn(&q, &[v, 0.0], &q1, &[v, 0.0], &u, dt).unwrap();
    }
    let mut out = [0.0; 2];
    for q in [[0.1, -0.2], [-0.25, 0.15], [0.0, 0.0]] {
        assert!(m.predict(&q, &mut out).unwrap());
        let want = g(&q);
        for i in 0..2 {
            assert!(
                (out[i] - want[i]).abs() < 1e-2,
                "ĝ({q:?}) = {out:?}, want {want:?}"
            );
        }
    }
}

/// A static model trained at spread postures, then held still at one posture with a torque
/// that is off by the `M q̈` of the gate's jitter.
fn repeated_home(repeats: usize, cap: u32) -> GravityModel {
    let g = |q: &[f64]| [3.0 + 2.0 * q[0] - q[1], -1.0 + 0.5 * q[0] + 4.0 * q[1]];
    let mut m = static_model(StaticGate {
        max_samples_per_posture: cap,
        ..StaticGate::default()
    });
    let dt = 0.002;
    for k in 0..2000 {
        let q = [0.3 * (k as f64 * 0.37).sin(), 0.3 * (k as f64 * 0.23).cos()];
        m.learn(&q, &[0.0; 2], &q, &[0.0; 2], &g(&q), dt).unwrap();
    }
    let home = [0.05, -0.1];
    for k in 0..repeats {
        let j = 1e-3 * ((k % 7) as f64 - 3.0);
        let q = [home[0] + j, home[1] - j];
        let u = g(&q).map(|v| v + 0.4 * (k as f64 * 0.9).sin());
        m.learn(&q, &[0.0; 2], &q, &[0.0; 2], &u, dt).unwrap();
    }
    m
}

/// With the budget, a posture held for 20,000 samples teaches the model what its first 2,000
/// did, bit for bit (the jitter's few postures are full by then); without it, the repeats move
/// the model.
#[test]
fn budget_ignores_the_repeats_of_one_posture() {
    let predict = |mut m: GravityModel| {
        let mut out = [0.0; 2];
        [[0.25, -0.25], [-0.2, 0.2], [0.05, -0.1]].map(|q| {
            m.predict(&q, &mut out).unwrap();
            out
        })
    };
    let (short, long) = (repeated_home(2_000, 250), repeated_home(20_000, 250));
    assert!(short.n_postures() > 1);
    assert_eq!(short.n_postures(), long.n_postures());
    assert_eq!(predict(short), predict(long));
    assert_ne!(
        predict(repeated_home(2_000, 0)),
        predict(repeated_home(20_000, 0)),
        "without a budget the repeats are learned"
    );
}

/// A still sample whose learning fails (a non-finite torque) is not counted: the budget and the
/// model stay as they were.
#[test]
fn a_failed_update_leaves_the_budget_unchanged() {
    let mut m = static_model(StaticGate::default());
    let q = [0.1, 0.2];
    assert!(m
        .learn(&q, &[0.0; 2], &q, &[0.0; 2], &[f64::NAN, 1.0], 0.002)
        .is_err());
    assert_eq!((m.n_postures(), m.n_rfs()), (0, 0));
    m.learn(&q, &[0.0; 2], &q, &[0.0; 2], &[1.0, 1.0], 0.002)
        .unwrap();
    assert_eq!((m.n_postures(), m.n_rfs()), (1, 1));
}

/// The gate's ranges are checked where a configuration is validated, naming the field.
#[test]
fn a_bad_gate_is_refused_naming_the_field() {
    assert!(StaticGate::default().validate().is_ok());
    for radius in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let mut cfg = crate::learner::fixture::config();
        assert!(cfg.validate(3).is_ok());
        cfg.gravity.static_gate = Some(StaticGate {
            posture_radius: radius,
            ..StaticGate::default()
        });
        let e = cfg.validate(3).unwrap_err().to_string();
        assert!(e.contains("static_gate.posture_radius"), "{e}");
    }
    let gate = StaticGate {
        max_acceleration: f64::NAN,
        ..StaticGate::default()
    };
    assert!(gate.validate().unwrap_err().contains("max_acceleration"));
}
