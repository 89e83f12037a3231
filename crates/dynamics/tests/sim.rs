//! The simulated robot: measurements, limits, noise, seeds, and errors instead of panics.

use osrl_dynamics::sim::SensorNoise;
use osrl_dynamics::{compute_all, robots, DynamicsError, Robot, SimConfig, SimRobot};

#[test]
fn measurement_is_consistent_with_the_model() {
    let model = robots::sarcos7();
    // No hard stops: the uncompensated arm falls, and a stop would make ẋ jump.
    let cfg = SimConfig {
        joint_limits: false,
        ..SimConfig::default()
    };
    let mut sim = SimRobot::new(model.clone(), cfg).unwrap();
    let u = vec![1.0, -2.0, 0.5, 3.0, 0.1, -0.1, 0.05];
    let m = sim.step(&u).unwrap().clone();
    assert!((m.t - 0.002).abs() < 1e-15);
    // x, ẋ from the model at the measured state; ẍ = J q̈ + J̇ q̇ under the held command.
    let mut data = model.data();
    compute_all(&model, &mut data, m.q.as_slice(), m.qd.as_slice()).unwrap();
    assert!((m.x.as_slice()[0] - data.ee_pos.x).abs() < 1e-15);
    let qdd =
        osrl_dynamics::forward_dynamics(&model, &mut data, m.q.as_slice(), m.qd.as_slice(), &u)
            .unwrap()
            .clone();
    compute_all(&model, &mut data, m.q.as_slice(), m.qd.as_slice()).unwrap();
    let xdd = &data.jac * qdd + data.jdot_qd;
    assert!((xdd - &m.xdd).amax() < 1e-12);
    // Over many steps, ẋ is the time integral of ẍ (to integration accuracy).
    let (xd0, mut integral) = (m.xd.clone(), m.xdd.clone() * 0.0);
    let mut prev = m.xdd.clone();
    for _ in 0..100 {
        let m = sim.step(&u).unwrap();
        integral += (&prev + &m.xdd) * 0.001;
        prev = m.xdd.clone();
    }
    let xd = sim.measurement().xd.clone();
    let err = (&xd - &xd0 - &integral).amax();
    assert!(err < 1e-4, "ẋ vs ∫ẍ: {err:e} (ẋ = {xd})");
}

#[test]
fn torque_and_joint_limits_are_enforced_and_counted() {
    let model = robots::planar3();
    let mut sim = SimRobot::new(model.clone(), SimConfig::default()).unwrap();
    // Far beyond the 60/40/20 N·m limits: clipped, and the arm slams into its limits.
    for _ in 0..500 {
        let m = sim.step(&[500.0, 500.0, 500.0]).unwrap();
        assert_eq!(m.u.as_slice(), &[60.0, 40.0, 20.0]);
    }
    let (q, _) = sim.state();
    for (i, l) in model.links().iter().enumerate() {
        assert!(q[i] >= l.limits.q_min && q[i] <= l.limits.q_max);
    }
    let stats = sim.stats();
    assert_eq!(stats.torque_saturations, 500);
    assert!(stats.limit_hits > 0);
}

#[test]
fn same_seed_same_noise_other_seed_other_noise() {
    let noisy = |seed| SimConfig {
        sensor_noise: SensorNoise {
            q: 1e-3,
            xdd: 0.1,
            ..SensorNoise::default()
        },
        actuator_noise: 0.5,
        seed,
        ..SimConfig::default()
    };
    let run = |seed| {
        let mut sim = SimRobot::new(robots::planar3(), noisy(seed)).unwrap();
        (0..50)
            .map(|_| sim.step(&[10.0, 5.0, 1.0]).unwrap().clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(run(7), run(7));
    assert_ne!(run(7), run(8));
}

#[test]
fn bad_commands_and_states_are_errors_that_change_nothing() {
    let mut sim = SimRobot::new(robots::planar3(), SimConfig::default()).unwrap();
    sim.step(&[1.0, 1.0, 1.0]).unwrap();
    let before = sim.measurement().clone();
    assert!(matches!(
        sim.step(&[1.0, f64::NAN, 1.0]),
        Err(DynamicsError::NonFinite {
            what: "u",
            index: 1,
            ..
        })
    ));
    assert!(matches!(
        sim.step(&[1.0, 1.0]),
        Err(DynamicsError::Dimension {
            expected: 3,
            got: 2,
            ..
        })
    ));
    assert!(sim.reset(&[0.0, f64::INFINITY, 0.0], &[0.0; 3]).is_err());
    assert_eq!(sim.measurement(), &before);
    assert!(SimRobot::new(
        robots::planar3(),
        SimConfig {
            substeps: 0,
            ..SimConfig::default()
        }
    )
    .is_err());
    assert!(SimRobot::new(
        robots::planar3(),
        SimConfig {
            control_period: -1.0,
            ..SimConfig::default()
        }
    )
    .is_err());
}

#[test]
fn divergence_is_an_error_not_a_panic() {
    // Unbounded torques on a nearly massless wrist blow the state up to infinity.
    let mut spec = robots::planar3().spec().clone();
    for l in spec.links.iter_mut() {
        l.limits.tau_max = f64::INFINITY;
        l.limits.q_min = f64::NEG_INFINITY;
        l.limits.q_max = f64::INFINITY;
    }
    spec.links[2].inertia = osrl_dynamics::Inertia::from_com(
        1e-9,
        nalgebra::Vector3::new(0.15, 0.0, 0.0),
        nalgebra::Matrix3::identity() * 1e-12,
    );
    let mut sim = SimRobot::new(
        osrl_dynamics::Model::new(spec).unwrap(),
        SimConfig::default(),
    )
    .unwrap();
    let mut failed = None;
    for _ in 0..1000 {
        if let Err(e) = sim.step(&[0.0, 0.0, 1e300]) {
            failed = Some(e);
            break;
        }
    }
    assert!(
        matches!(failed, Some(DynamicsError::Diverged { .. })),
        "{failed:?}"
    );
    let (q, qd) = sim.state();
    assert!(
        q.iter().chain(qd.iter()).all(|v| v.is_finite()),
        "the state before the failed step is kept"
    );
}

#[test]
fn dynamics_reject_wrong_lengths_and_nan() {
    let model = robots::sarcos7();
    let mut data = model.data();
    let e = osrl_dynamics::rnea(&model, &mut data, &[0.0; 6], &[0.0; 7], &[0.0; 7]).unwrap_err();
    assert_eq!(e.to_string(), "q: expected 7 values, got 6");
    let mut qd = [0.0; 7];
    qd[3] = f64::NAN;
    let e = osrl_dynamics::compute_all(&model, &mut data, &[0.0; 7], &qd).unwrap_err();
    assert_eq!(e.to_string(), "qd[3] is not finite (NaN)");
}
