//! Trajectories: derivatives against finite differences, start at rest, periodicity, defaults
//! reachable, bad and unreachable descriptions rejected with clear errors.

use nalgebra::Vector3;
use osrl_control::{
    check_reachable, ControlError, IkOptions, Trajectory, TrajectoryConfig, TrajectoryKind,
};
use osrl_dynamics::robots;

fn all_shapes() -> Vec<Trajectory> {
    let c = Vector3::new(0.6, 0.0, 0.2);
    vec![
        Trajectory::figure8(c, Vector3::x(), Vector3::z(), 0.15, 0.1, 4.0, 1.0).unwrap(),
        Trajectory::circle(c, Vector3::x(), Vector3::new(0.0, 0.3, 1.0), 0.1, 3.0, 0.5).unwrap(),
        Trajectory::min_jerk(
            vec![c, c + Vector3::new(0.1, 0.0, 0.0), c + Vector3::z() * 0.1],
            0.8,
        )
        .unwrap(),
        Trajectory::figure8(c, Vector3::x(), Vector3::z(), 0.1, 0.1, 2.0, 0.0).unwrap(),
    ]
}

#[test]
fn velocity_and_acceleration_match_finite_differences() {
    let h = 1e-5;
    for traj in all_shapes() {
        for k in 0..400 {
            let t = 0.013 + k as f64 * 0.0237;
            let s = traj.sample(t);
            let (p, m) = (traj.sample(t + h), traj.sample(t - h));
            let v = (p.x - m.x) / (2.0 * h);
            let a = (p.xd - m.xd) / (2.0 * h);
            assert!(
                (v - s.xd).amax() < 1e-6,
                "ẋ at t = {t}: {v:?} vs {:?}",
                s.xd
            );
            assert!(
                (a - s.xdd).amax() < 1e-4,
                "ẍ at t = {t}: {a:?} vs {:?}",
                s.xdd
            );
        }
    }
}

#[test]
fn smooth_start_at_rest_on_the_path_and_periodic_afterwards() {
    for traj in all_shapes() {
        let s0 = traj.sample(0.0);
        if traj.ramp() > 0.0 || matches!(traj.shape(), osrl_control::Shape::MinJerk { .. }) {
            assert_eq!(s0.xd, Vector3::zeros());
            assert_eq!(s0.xdd, Vector3::zeros());
        }
        assert_eq!(traj.sample(-1.0), s0);
        let t = traj.ramp() + 0.37;
        let (a, b) = (traj.sample(t), traj.sample(t + traj.period()));
        assert!((a.x - b.x).amax() < 1e-12 && (a.xd - b.xd).amax() < 1e-12);
        assert!((a.xdd - b.xdd).amax() < 1e-10);
    }
    // The figure-8 passes through its centre at the start with the documented width and height.
    let f = &all_shapes()[0];
    assert!((f.start() - Vector3::new(0.6, 0.0, 0.2)).norm() < 1e-15);
    let xs: Vec<Vector3<f64>> = (0..4000)
        .map(|k| f.sample(1.0 + k as f64 * 1e-3).x)
        .collect();
    let span = |i: usize| {
        let v: Vec<f64> = xs.iter().map(|p| p[i]).collect();
        v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
    };
    assert!((span(0) - 0.30).abs() < 1e-5 && (span(2) - 0.20).abs() < 1e-5);
}

#[test]
fn default_trajectories_are_reachable_well_inside_the_limits() {
    for model in [robots::planar3(), robots::sarcos7()] {
        for kind in [
            TrajectoryKind::Figure8,
            TrajectoryKind::Circle,
            TrajectoryKind::MinJerk,
        ] {
            let cfg = TrajectoryConfig {
                kind,
                ..TrajectoryConfig::default()
            };
            let traj = cfg.build(&model).unwrap();
            let reach = check_reachable(&model, &traj, &IkOptions::default()).unwrap();
            assert!(reach.max_residual < 1e-5, "{} {kind:?}", model.name());
            assert!(
                reach.min_margin >= 0.05 - 1e-12,
                "{} {kind:?}",
                model.name()
            );
            // The start posture puts the end-effector on the path.
            let mut d = model.data();
            osrl_dynamics::forward_kinematics(&model, &mut d, &reach.q_start).unwrap();
            for &a in model.task_axes() {
                assert!((d.ee_pos[a] - traj.start()[a]).abs() < 1e-5);
            }
        }
    }
    // A random arm gets a figure-8 around its start posture's end-effector.
    let arm = robots::random_arm(6, 5, false);
    assert!(TrajectoryConfig::default().build(&arm).is_ok());
}

#[test]
fn unreachable_and_malformed_trajectories_give_clear_errors() {
    let planar = robots::planar3();
    let far = TrajectoryConfig {
        centre: Some([1.2, 0.0, 0.3]),
        ..TrajectoryConfig::default()
    };
    let traj = far.build(&planar).unwrap();
    let e = check_reachable(&planar, &traj, &IkOptions::default()).unwrap_err();
    assert!(matches!(e, ControlError::Unreachable(_)), "{e}");
    assert!(e.to_string().contains("reaches at most 1.050 m"), "{e}");
    // Within the reach but not inside the joint limits: the elbow cannot fold the hand onto the
    // shoulder.
    let close = TrajectoryConfig {
        centre: Some([0.05, 0.0, 0.05]),
        a: Some(0.02),
        b: Some(0.02),
        ..TrajectoryConfig::default()
    };
    let e = check_reachable(
        &planar,
        &close.build(&planar).unwrap(),
        &IkOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("joint limits"), "{e}");
    // Leaving planar3's x–z task space.
    let out = TrajectoryConfig {
        centre: Some([0.6, 0.1, 0.2]),
        ..TrajectoryConfig::default()
    };
    let e = out.build(&planar).unwrap_err();
    assert!(e.to_string().contains("y component"), "{e}");
    let tilted = TrajectoryConfig {
        e1: Some([1.0, 1.0, 0.0]),
        ..TrajectoryConfig::default()
    };
    assert!(tilted.build(&planar).is_err());
    // Malformed values.
    let c = Vector3::new(0.6, 0.0, 0.2);
    let (x, z) = (Vector3::x(), Vector3::z());
    assert!(Trajectory::figure8(c, x, z, 0.1, 0.1, 0.0, 1.0).is_err());
    assert!(Trajectory::figure8(c, x, z, -0.1, 0.1, 4.0, 1.0).is_err());
    assert!(Trajectory::figure8(c, x, z, 0.1, 0.1, 4.0, -1.0).is_err());
    assert!(Trajectory::figure8(c, x, x * 2.0, 0.1, 0.1, 4.0, 1.0).is_err());
    assert!(Trajectory::figure8(c, Vector3::zeros(), z, 0.1, 0.1, 4.0, 1.0).is_err());
    assert!(Trajectory::figure8(c * f64::NAN, x, z, 0.1, 0.1, 4.0, 1.0).is_err());
    assert!(Trajectory::circle(c, x, z, 0.0, 4.0, 1.0).is_err());
    assert!(Trajectory::min_jerk(vec![c], 1.0).is_err());
    assert!(Trajectory::min_jerk(vec![c, c], f64::INFINITY).is_err());
    // Durations no run could step through (an evaluation with a ramp of 1e300 s never ended).
    let e = Trajectory::figure8(c, x, z, 0.1, 0.1, 4.0, 1e300).unwrap_err();
    assert!(
        e.to_string()
            .contains("ramp must be 0 or between 0.001 and 3600 s, got 1e300"),
        "{e}"
    );
    assert!(Trajectory::circle(c, x, z, 0.1, 1e300, 1.0).is_err());
    assert!(Trajectory::min_jerk(vec![c, c], 1e300).is_err());
    assert!(Trajectory::figure8(c, x, z, 0.1, 0.1, 3600.0, 3600.0).is_ok());
    // Durations whose accelerations overflow (`xdd` was inf at a period of 1e-300 s).
    let e = Trajectory::figure8(c, x, z, 0.1, 0.1, 1e-300, 1.0).unwrap_err();
    assert!(e.to_string().contains("period must be between"), "{e}");
    assert!(Trajectory::figure8(c, x, z, 0.1, 0.1, 4.0, 1e-300).is_err());
    assert!(Trajectory::min_jerk(vec![c, c], 1e-300).is_err());
    let fast = Trajectory::figure8(c, x, z, 0.1, 0.1, 1e-3, 1e-3).unwrap();
    assert!(fast.sample(0.0123).xdd.iter().all(|a| a.is_finite()));
    // Sizes and points beyond a kilometre.
    assert!(Trajectory::circle(c, x, z, 1e300, 4.0, 1.0).is_err());
    assert!(Trajectory::min_jerk(vec![c, c * 1e9], 1.0).is_err());
}

#[test]
fn trajectory_config_round_trips_through_toml_like_serde() {
    // deny_unknown_fields: a typo is an error, not silently ignored.
    let e = serde_json::from_str::<TrajectoryConfig>(r#"{"kind": "circle", "raduis": 0.1}"#);
    assert!(e.is_err());
    let c: TrajectoryConfig =
        serde_json::from_str(r#"{"kind": "min_jerk", "move_time": 0.5}"#).unwrap();
    assert_eq!(c.kind, TrajectoryKind::MinJerk);
    assert_eq!(c.period, 4.0);
}
