//! Robot profiles (`osrl_control::profile`): computed defaults on published arms, eq. 7 on the
//! Panda with them, the URDF export round trip, and bad values refused naming the field.

use osrl_control::profile::{load_robot, resolve, Profiled};
use osrl_control::{
    check_reachable, run_closed_loop, ControlError, IkOptions, Osc, OscConfig, TrajectoryConfig,
};
use osrl_dynamics::urdf::{parse_urdf, to_urdf_with_profile};
use osrl_dynamics::{robots, Model, PathPlacement, RobotProfile, SimConfig, SimRobot};

fn fixture(file: &str) -> String {
    format!(
        "{}/../dynamics/tests/fixtures/example-robot-data/{file}",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn profiled(file: &str) -> Profiled {
    let given = RobotProfile::default();
    let model = load_robot(&fixture(file), &given).unwrap();
    resolve(&model, &given).unwrap()
}

fn inside(model: &Model, q: &[f64]) -> bool {
    q.iter()
        .zip(model.q_min().zip(model.q_max()))
        .all(|(&v, (lo, hi))| v > lo && v < hi)
}

/// Eq. 7 with the default config for two periods of the profile's default path (mm RMS).
fn eq7_rms(p: &Profiled) -> (f64, usize) {
    let traj = p
        .trajectory(&TrajectoryConfig::default())
        .build(&p.model)
        .unwrap();
    let start = check_reachable(&p.model, &traj, &IkOptions::default())
        .unwrap()
        .q_start;
    let mut sim = SimRobot::new(p.model.clone(), SimConfig::default()).unwrap();
    sim.reset(&start, &vec![0.0; p.model.nq()]).unwrap();
    let mut osc = Osc::new(p.model.clone(), OscConfig::default()).unwrap();
    let run = run_closed_loop(&mut sim, &mut osc, &traj, p.model.task_axes(), 8.0).unwrap();
    (
        run.metrics.tracking_rms_mm,
        run.metrics.torque_saturation_steps,
    )
}

#[test]
fn defaults_of_the_panda_and_the_ur5_are_inside_the_limits_reachable_and_scaled() {
    for file in ["panda.urdf", "ur5_robot.urdf"] {
        let p = profiled(file);
        let (m, r) = (&p.model, &p.profile);
        assert!(inside(m, &r.home) && inside(m, &r.rest), "{file}: {r:?}");
        assert_eq!(m.spec().q_start, r.home);
        assert_eq!(m.spec().kp, r.kp);
        assert!(r.kp.iter().chain(&r.kd).all(|&g| g > 0.0), "{file}: {r:?}");
        // kp = ω² m_i and kd = 2 ζ ω √(m_i M_ii): m_i = 1/(M⁻¹)_ii, M_ii from the mass matrix.
        let mm = osrl_dynamics::crba(m, &mut m.data(), &r.home)
            .unwrap()
            .clone_owned();
        let inv = mm.clone().cholesky().unwrap().inverse();
        let (w, z) = (r.null_space_frequency, r.null_space_damping);
        for (i, (kp, kd)) in r.kp.iter().zip(&r.kd).enumerate() {
            let m_i = 1.0 / inv[(i, i)];
            assert!((kp - w * w * m_i).abs() < 1e-9 * kp, "{file}: joint {i}");
            let want = 2.0 * z * w * (m_i * mm[(i, i)]).sqrt();
            assert!((kd - want).abs() < 1e-9 * want, "{file}: joint {i}");
            assert!(*kd >= 2.0 * z * w * m_i, "{file}: joint {i}");
        }
        assert!(
            r.path.a > 0.02 && r.path.a <= 0.1 * r.reach + 1e-12,
            "{file}: {r:?}"
        );
        assert!(
            r.min_limit_margin > 0.05 && r.peak_torque_ratio < 0.8,
            "{file}: {r:?}"
        );
        assert_eq!(r.sources["home"], osrl_control::profile::Source::Computed);
        assert_eq!(
            r.sources["torque_limits"],
            osrl_control::profile::Source::Urdf
        );
        // The path is centred at the tip at home and reachable over a whole cycle.
        let traj = p.trajectory(&TrajectoryConfig::default()).build(m).unwrap();
        let reach = check_reachable(m, &traj, &IkOptions::default()).unwrap();
        let mut data = m.data();
        osrl_dynamics::forward_kinematics(m, &mut data, &r.home).unwrap();
        assert!((traj.start() - data.ee_pos).norm() < 1e-12, "{file}");
        assert!(reach.min_margin > 0.05, "{file}");
    }
}

#[test]
fn eq7_tracks_the_panda_on_its_default_path() {
    let (rms, saturated) = eq7_rms(&profiled("panda.urdf"));
    assert!(rms < 0.05, "Panda eq. 7: {rms} mm");
    assert_eq!(saturated, 0);
}

#[test]
fn built_in_robots_keep_their_data_sheet() {
    for model in [robots::planar3(), robots::sarcos7()] {
        let p = resolve(&model, &RobotProfile::default()).unwrap();
        assert_eq!(p.model, model, "{}", model.name());
        let cfg = TrajectoryConfig::default();
        assert_eq!(p.trajectory(&cfg), cfg);
        let s = model.spec();
        assert_eq!((&p.profile.home, &p.profile.kp), (&s.q_start, &s.kp));
    }
}

#[test]
fn the_export_round_trip_gives_the_same_profile_and_tracking() {
    for model in [robots::planar3(), robots::sarcos7()] {
        let built_in = resolve(&model, &RobotProfile::default()).unwrap();
        let text = to_urdf_with_profile(&built_in.model, Some(&built_in.as_given()));
        let back = parse_urdf(&text).unwrap();
        let loaded = resolve(&back, &RobotProfile::default()).unwrap();
        let (a, b) = (&built_in.profile, &loaded.profile);
        assert_eq!(
            (&a.home, &a.rest, &a.kp, &a.kd),
            (&b.home, &b.rest, &b.kp, &b.kd)
        );
        assert_eq!((&a.path, &a.torque_limits), (&b.path, &b.torque_limits));
        assert_eq!(b.sources["home"], osrl_control::profile::Source::File);
        assert_eq!(back.task_axes(), model.task_axes());
        let (rms_a, _) = eq7_rms(&built_in);
        let (rms_b, _) = eq7_rms(&loaded);
        assert!((rms_a - rms_b).abs() < 1e-6 * rms_a, "{rms_a} vs {rms_b}");
    }
}

#[test]
fn a_computed_profile_travels_with_the_exported_panda() {
    let p = profiled("panda.urdf");
    let text = to_urdf_with_profile(&p.model, Some(&p.as_given()));
    let back = resolve(&parse_urdf(&text).unwrap(), &RobotProfile::default()).unwrap();
    let (a, b) = (&p.profile, &back.profile);
    assert_eq!(
        (&a.home, &a.rest, &a.kp, &a.kd),
        (&b.home, &b.rest, &b.kp, &b.kd)
    );
    assert_eq!((&a.path, &a.torque_limits), (&b.path, &b.torque_limits));
    assert_eq!(b.sources["kp"], osrl_control::profile::Source::File);
}

fn refused(model: &Model, given: RobotProfile, field: &str) {
    match resolve(model, &given) {
        Err(ControlError::Profile { field: f, reason }) => {
            assert_eq!(f, field, "{reason}");
        }
        other => panic!(
            "{field}: expected a profile error, got {:?}",
            other.map(|p| p.profile)
        ),
    }
}

#[test]
fn bad_values_are_refused_naming_the_field() {
    let planar = robots::planar3();
    let p = RobotProfile::default;
    refused(
        &planar,
        RobotProfile {
            kp: Some(vec![1.0; 2]),
            ..p()
        },
        "kp",
    );
    refused(
        &planar,
        RobotProfile {
            kd: Some(vec![1.0, f64::NAN, 1.0]),
            ..p()
        },
        "kd",
    );
    refused(
        &planar,
        RobotProfile {
            home: Some(vec![0.0, 3.0, 0.0]),
            ..p()
        },
        "home",
    );
    refused(
        &planar,
        RobotProfile {
            rest: Some(vec![f64::INFINITY, 0.0, 0.0]),
            ..p()
        },
        "rest",
    );
    refused(
        &planar,
        RobotProfile {
            torque_limits: Some(vec![1.0, 0.0, 1.0]),
            ..p()
        },
        "torque_limits",
    );
    refused(
        &planar,
        RobotProfile {
            null_space_frequency: Some(-1.0),
            ..p()
        },
        "null_space_frequency",
    );
    // Huge but finite: refused by name, not as the infinite gains they would compute.
    refused(
        &planar,
        RobotProfile {
            kp: Some(vec![1.0, 1e300, 1.0]),
            ..p()
        },
        "kp",
    );
    refused(
        &planar,
        RobotProfile {
            null_space_frequency: Some(1e300),
            ..p()
        },
        "null_space_frequency",
    );
    refused(
        &planar,
        RobotProfile {
            null_space_damping: Some(1e300),
            ..p()
        },
        "null_space_damping",
    );
    let far = PathPlacement {
        centre: Some([3.0, 0.0, 0.0]),
        ..PathPlacement::default()
    };
    refused(&planar, RobotProfile { path: far, ..p() }, "path");
    let flat = PathPlacement {
        e1: Some([0.0; 3]),
        ..PathPlacement::default()
    };
    refused(&planar, RobotProfile { path: flat, ..p() }, "path.e1");
    let tip = RobotProfile {
        tip: Some("x".into()),
        ..p()
    };
    assert!(matches!(
        load_robot("planar3", &tip),
        Err(ControlError::Profile { .. })
    ));
    // A profile the file carries is checked the same way, and says where it came from.
    let text = osrl_dynamics::urdf::to_urdf(&planar).replace(
        "<link name=\"base_link\"/>",
        "<osrl_profile kp=\"1 2\"/>\n  <link name=\"base_link\"/>",
    );
    let m = parse_urdf(&text).unwrap();
    match resolve(&m, &RobotProfile::default()) {
        Err(ControlError::Profile { field, reason }) => {
            assert_eq!(field, "kp");
            assert!(reason.contains("osrl_profile"), "{reason}");
        }
        other => panic!("{:?}", other.map(|p| p.profile)),
    }
    let bad = osrl_dynamics::urdf::to_urdf(&planar).replace(
        "<link name=\"base_link\"/>",
        "<osrl_profile kq=\"1 2\"/>\n  <link name=\"base_link\"/>",
    );
    assert!(parse_urdf(&bad).unwrap_err().to_string().contains("kq"));
}

#[test]
fn an_arm_that_cannot_be_profiled_is_refused_with_the_reason() {
    // TwoDofs: its tip stays at a fixed distance from the first joint (no posture has it at
    // 40–75 % of its reach).
    let given = RobotProfile::default();
    let model = load_robot(&fixture("TwoDofs.urdf"), &given).unwrap();
    match resolve(&model, &given) {
        Err(ControlError::Profile { field, reason }) => {
            assert_eq!(field, "home");
            assert!(reason.contains("reach"), "{reason}");
        }
        other => panic!("{:?}", other.map(|p| p.profile)),
    }
}
