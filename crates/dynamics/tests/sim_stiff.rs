//! Stiff joint friction (issue 28 item 3): the xArm7 and the Z1 as published (damping up to
//! 10 N·m·s/rad and Coulomb friction of 1–2 N·m on light links) simulate at the default settings,
//! close to a fine explicit solution, while robots whose friction is not stiff are integrated
//! exactly as before.

use osrl_dynamics::sim::FrictionScheme;
use osrl_dynamics::urdf::load_urdf;
use osrl_dynamics::{gravity, robots, DynamicsError, Model, Robot, SimConfig, SimRobot};

fn published(file: &str) -> Model {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/example-robot-data");
    load_urdf(&dir.join(file)).unwrap()
}

/// `periods` control periods under half gravity compensation plus a 0.3 N·m wobble per joint;
/// the final `(q, q̇)` and the number of implicit periods.
fn run(
    model: &Model,
    cfg: SimConfig,
    periods: usize,
) -> Result<(Vec<f64>, Vec<f64>, u64), DynamicsError> {
    let mut sim = SimRobot::new(model.clone(), cfg)?;
    let mut data = model.data();
    let mut u = vec![0.0; model.nq()];
    for _ in 0..periods {
        let g = gravity(model, &mut data, sim.state().0.as_slice())?.clone();
        for (i, ui) in u.iter_mut().enumerate() {
            *ui = 0.5 * g[i] + 0.3 * (sim.time() * 7.0 + i as f64).sin();
        }
        sim.step(&u)?;
    }
    let (q, qd) = sim.state();
    Ok((
        q.as_slice().to_vec(),
        qd.as_slice().to_vec(),
        sim.stats().implicit_friction,
    ))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn stiff_published_arms_simulate_at_the_default_settings() {
    for file in ["xarm7.urdf", "z1.urdf"] {
        let model = published(file);
        let (q, qd, implicit) = run(&model, SimConfig::default(), 1000).unwrap();
        assert!(q.iter().chain(&qd).all(|v| v.is_finite()), "{file}");
        assert_eq!(implicit, 1000, "{file}: every period is stiff");
    }
    // The explicit integrator alone would diverge within milliseconds: refused up front, naming
    // the joint and the parameter.
    let explicit = SimConfig {
        friction: FrictionScheme::Explicit,
        ..SimConfig::default()
    };
    match SimRobot::new(published("xarm7.urdf"), explicit) {
        Err(DynamicsError::InvalidConfig(m)) => {
            assert!(
                m.contains("joint7") && m.contains("coulomb_velocity"),
                "{m}"
            )
        }
        other => panic!("expected a refusal, got {:?}", other.err()),
    }
}

#[test]
fn implicit_friction_converges_to_the_fine_explicit_solution() {
    let model = published("xarm7.urdf");
    // Reference: explicit RK4 at 0.5 µs steps (stable: h λ̂ < 1 for these arms).
    let fine = SimConfig {
        friction: FrictionScheme::Explicit,
        substeps: 4000,
        ..SimConfig::default()
    };
    let (q_ref, _, _) = run(&model, fine, 50).unwrap();
    let implicit = |substeps| SimConfig {
        friction: FrictionScheme::Implicit,
        substeps,
        ..SimConfig::default()
    };
    let e2 = max_diff(&run(&model, implicit(2), 50).unwrap().0, &q_ref);
    let e20 = max_diff(&run(&model, implicit(20), 50).unwrap().0, &q_ref);
    eprintln!("xArm7, 0.1 s: |q − q_ref| = {e2:e} rad at 2 substeps, {e20:e} at 20");
    assert!(e2 < 1e-3, "{e2:e}");
    // First order: ten times finer steps, at least five times smaller error.
    assert!(e20 * 5.0 < e2, "{e2:e} → {e20:e}");
}

#[test]
fn robots_without_stiff_friction_are_integrated_as_before() {
    let models = [
        robots::planar3(),
        robots::sarcos7(),
        published("panda.urdf"),
        published("ur5_robot.urdf"),
    ];
    for model in models {
        let explicit = SimConfig {
            friction: FrictionScheme::Explicit,
            ..SimConfig::default()
        };
        let (q0, qd0, _) = run(&model, explicit, 500).unwrap();
        let (q1, qd1, implicit) = run(&model, SimConfig::default(), 500).unwrap();
        assert_eq!(implicit, 0, "{}", model.name());
        assert_eq!((q0, qd0), (q1, qd1), "{}: bit-identical", model.name());
    }
}
