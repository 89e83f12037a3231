//! The learned controller: bad measurements, determinism, and learning that helps.

mod common;
use osrl_dynamics::{robots, Robot, SimConfig, SimRobot};
use osrl_learn::LearnError;

#[test]
fn bad_measurements_are_rejected_counted_and_change_nothing() {
    let s = common::planar3();
    let mut learner = common::learner(&s);
    let mut sim = SimRobot::new(robots::planar3(), SimConfig::default()).unwrap();
    let a = sim.measurement().clone();
    let b = sim.step(&[1.0, 1.0, 1.0]).unwrap().clone();
    learner.learn(&a, &b).unwrap();
    let before = learner.stats();
    let mut nan = b.clone();
    nan.xdd[1] = f64::NAN;
    assert!(matches!(
        learner.learn(&a, &nan),
        Err(LearnError::BadMeasurement(_))
    ));
    let mut absurd = b.clone();
    absurd.xdd[0] = 1e9;
    assert!(matches!(
        learner.learn(&a, &absurd),
        Err(LearnError::BadMeasurement(_))
    ));
    let mut short = b.clone();
    short.q = short.q.rows(0, 2).into_owned();
    assert!(matches!(
        learner.learn(&a, &short),
        Err(LearnError::BadMeasurement(_))
    ));
    let after = learner.stats();
    assert_eq!(after.rejected, before.rejected + 3);
    assert_eq!(after.samples, before.samples);
    // And it keeps learning afterwards.
    let c = sim.step(&[1.0, 1.0, 1.0]).unwrap().clone();
    learner.learn(&b, &c).unwrap();
}

#[test]
fn same_seed_same_learning_other_seed_other_learning() {
    let s = common::planar3();
    let curve = |seed| {
        let mut l = common::learner(&s);
        let summary = common::run(&s, &mut l, 0.6, 0.4, 0.3, seed);
        (summary.learning_curve, summary.stats, l.n_local_models())
    };
    let a = curve(1);
    assert_eq!(a, curve(1));
    assert_ne!(a.0, curve(2).0);
}

#[test]
fn training_reduces_the_tracking_error_and_beats_the_nominal_controller() {
    let s = common::planar3();
    let mut learner = common::learner(&s);
    let summary = common::run(&s, &mut learner, 6.0, 4.0, 1.0, 0);
    let curve = &summary.learning_curve;
    let first = &curve[0].1;
    let last = &curve.last().unwrap().1;
    // After one minute of babbling the controller is poor; after six minutes it tracks.
    assert!(
        last.tracking_rms_mm < 0.5 * first.tracking_rms_mm || first.diverged,
        "{first:?} → {last:?}"
    );
    assert!(!last.diverged && last.tracking_rms_mm < 20.0, "{last:?}");
    // The error decomposition is consistent: parts never exceed their wholes, and the learned
    // input gain Â is within 50 % of the true J M⁻¹ along the path.
    assert!(
        last.command_nmse_null <= last.command_nmse * (1.0 + 1e-9),
        "{last:?}"
    );
    assert!(
        last.nominal_nmse_null <= last.nominal_nmse * (1.0 + 1e-9),
        "{last:?}"
    );
    assert!(last.gain_error > 0.0 && last.gain_error < 0.5, "{last:?}");
    // ĝ learns from the babbling only.
    assert!(learner.gravity_frozen());
    // The nominal behaviour alone (PD to rest plus learned gravity) does not track the figure-8:
    // compare with a learner whose local controllers never act (min_ess unreachable).
    let mut cfg = common::config(&s);
    cfg.controllers.trained_ess = 1e12;
    let mut nominal_only = osrl_learn::Learner::new(3, 2, 0.002, cfg).unwrap();
    let nominal = common::run(&s, &mut nominal_only, 4.5, 4.0, 0.0, 0);
    let nom = &nominal.learning_curve.last().unwrap().1;
    assert!(
        nom.diverged || nom.tracking_rms_mm > 5.0 * last.tracking_rms_mm,
        "nominal {nom:?} vs learned {last:?}"
    );
}

#[test]
fn save_load_round_trips_and_bad_files_are_errors() {
    let s = common::planar3();
    let mut learner = common::learner(&s);
    common::run(&s, &mut learner, 0.4, 0.4, 0.0, 5);
    let bytes = learner.to_bytes().unwrap();
    let mut back = osrl_learn::Learner::from_bytes(&bytes).unwrap();
    assert_eq!(
        back.to_bytes().unwrap(),
        bytes,
        "save → load → save is the identity"
    );
    // Same commands from the original and the loaded controller.
    let (q, qd) = (s.q_start.clone(), vec![0.05, -0.02, 0.1]);
    let (mut u1, mut u2) = (vec![0.0; 3], vec![0.0; 3]);
    learner
        .command::<rand_chacha::ChaCha8Rng>(&q, &qd, &[0.3, -0.2], None, &mut u1)
        .unwrap();
    back.command::<rand_chacha::ChaCha8Rng>(&q, &qd, &[0.3, -0.2], None, &mut u2)
        .unwrap();
    assert_eq!(u1, u2);
    // Truncated, corrupted, foreign and other-version files are clear errors.
    let err = |b: &[u8]| osrl_learn::Learner::from_bytes(b).unwrap_err().to_string();
    assert!(err(&bytes[..bytes.len() - 10]).contains("truncated"));
    let mut corrupt = bytes.clone();
    let mid = corrupt.len() / 2;
    corrupt[mid] ^= 0x40;
    assert!(err(&corrupt).contains("checksum"));
    assert!(err(b"hello world, this is not a controller file").contains("not an osrl"));
    let mut version = bytes.clone();
    version[8] = 99;
    assert!(err(&version).contains("version"));
}

#[test]
fn invalid_training_settings_are_refused_with_the_field_named() {
    use osrl_learn::train::TrainConfig;
    assert!(TrainConfig::default().validate().is_ok());
    // Below 0, above a PD error of π rad, NaN.
    for bad in [-0.1, 3.2, 1e300, f64::NAN] {
        let mut cfg = TrainConfig::default();
        cfg.babble.noise = bad;
        let e = cfg.validate().unwrap_err().to_string();
        assert!(e.contains("babble.noise"), "{bad}: {e}");
    }
    for bad in [0.0, 101.0, 1e300] {
        let mut cfg = TrainConfig::default();
        cfg.babble.gain_scale = bad;
        let e = cfg.validate().unwrap_err().to_string();
        assert!(e.contains("babble.gain_scale"), "{bad}: {e}");
    }
    let mut cfg = TrainConfig::default();
    (cfg.babble.noise, cfg.babble.gain_scale) = (std::f64::consts::PI, 100.0);
    assert!(cfg.validate().is_ok(), "the bounds themselves are accepted");
    let mut cfg = TrainConfig::default();
    cfg.babble.move_time = [2.0, 1.0];
    let e = cfg.validate().unwrap_err().to_string();
    assert!(e.contains("babble.move_time"), "{e}");
    let cfg = TrainConfig {
        minutes: f64::NAN,
        ..Default::default()
    };
    assert!(cfg.validate().unwrap_err().to_string().contains("minutes"));
}

#[test]
fn commands_respect_the_torque_limits_and_bad_limits_are_refused() {
    let s = common::planar3();
    let mut cfg = common::config(&s);
    // Limits from the data sheet reach the config; a wrong count or a non-positive limit is refused.
    assert_eq!(cfg.guards.torque_limits, vec![60.0, 40.0, 20.0]);
    for bad in [
        vec![1.0, 1.0],
        vec![1.0, 0.0, 1.0],
        vec![1.0, f64::NAN, 1.0],
        vec![1.0, f64::INFINITY, 1.0],
    ] {
        let mut c = cfg.clone();
        c.guards.torque_limits = bad.clone();
        let err = osrl_learn::Learner::new(3, 2, 0.002, c).err();
        assert!(
            matches!(&err, Some(LearnError::InvalidConfig(m)) if m.contains("torque_limits")),
            "{bad:?}: {err:?}"
        );
    }
    // A velocity scale outside LWPR's normalisation range is refused when the learner is made,
    // not after the warm-up when its models are.
    for bad in [0.0, 1e-101, 1e101, f64::NAN] {
        let mut c = cfg.clone();
        c.partition.velocity_scale = bad;
        let err = osrl_learn::Learner::new(3, 2, 0.002, c).err();
        assert!(
            matches!(&err, Some(LearnError::InvalidConfig(m)) if m.contains("velocity_scale")),
            "{bad}: {err:?}"
        );
    }
    // Limits far below gravity: every command (fallback u0, then the learned blend with
    // exploration) stays inside them, and the clipped commands are counted.
    // A learner without limits gets them set (a bad set changes nothing).
    cfg.guards.torque_limits = vec![0.5, 0.4, 0.3];
    let mut learner = osrl_learn::Learner::new(3, 2, 0.002, {
        let mut c = cfg.clone();
        c.guards.torque_limits = Vec::new();
        c
    })
    .unwrap();
    assert!(learner.set_torque_limits(&[1.0, 2.0]).is_err());
    assert!(learner.config().guards.torque_limits.is_empty());
    learner
        .set_torque_limits(&cfg.guards.torque_limits)
        .unwrap();
    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(3);
    let mut u = vec![0.0; 3];
    let q = s.q_start.clone();
    learner
        .command(&q, &[0.0; 3], &[5.0, -5.0], Some(&mut rng), &mut u)
        .unwrap();
    let within = |u: &[f64]| {
        u.iter()
            .zip(&cfg.guards.torque_limits)
            .all(|(v, l)| v.abs() <= *l)
    };
    assert!(within(&u), "{u:?}");
    common::run(&s, &mut learner, 0.5, 0.4, 0.0, 1);
    let before = learner.stats().clipped;
    for k in 0..20 {
        let qd = [0.1 * k as f64, -0.3, 0.2];
        learner
            .command(&q, &qd, &[50.0, -40.0], Some(&mut rng), &mut u)
            .unwrap();
        assert!(within(&u), "{u:?}");
    }
    assert!(learner.stats().clipped > before, "{:?}", learner.stats());
}

#[test]
fn idle_untrained_fields_are_pruned_with_their_controllers() {
    let s = common::planar3();
    let run = |after: Option<f64>| {
        let mut cfg = common::config(&s);
        cfg.partition.prune_untrained_after = after;
        let mut l = osrl_learn::Learner::new(3, 2, 0.002, cfg).unwrap();
        common::run(&s, &mut l, 0.6, 0.4, 0.0, 2);
        l
    };
    let (kept, pruned) = (run(None), run(Some(3.0)));
    assert_eq!(kept.stats().pruned_untrained, 0);
    assert!(pruned.stats().pruned_untrained > 0, "{:?}", pruned.stats());
    assert!(pruned.n_local_models() < kept.n_local_models());
    // The partition and the controllers still match one to one.
    let ids = |l: &osrl_learn::Learner| {
        let fwd: Vec<u64> = (l.forward_model().unwrap().lwpr().rfs(0).unwrap())
            .map(|v| v.id().0)
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect();
        let locals: Vec<u64> = l.local_summaries().iter().map(|x| x.id).collect();
        (fwd, locals)
    };
    let (fwd, locals) = ids(&pruned);
    assert_eq!(fwd, locals);
    // A bad setting is refused with the field named.
    let mut cfg = common::config(&s);
    cfg.partition.prune_untrained_after = Some(0.0);
    let e = osrl_learn::Learner::new(3, 2, 0.002, cfg)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("prune_untrained_after"), "{e}");
}

/// The cost metric `N = B̂` estimated in the warm-up travels with a saved learner: the loaded
/// one evaluates (eq. 7 with `N = M⁻¹` as `u*`) and learns on exactly as the one in memory.
/// (Before format 10 `N` was not saved and the loaded learner learned on with `N = I`.)
#[test]
fn a_saved_learner_keeps_its_cost_metric_and_learns_on_as_in_memory() {
    use osrl_learn::eval::Evaluator;
    let s = common::planar3();
    let mut cfg = common::config(&s);
    cfg.controllers.metric = Some(osrl_learn::CostMetric::InverseInertia);
    let mut learner = osrl_learn::Learner::new(3, 2, 0.002, cfg.clone()).unwrap();
    common::run(&s, &mut learner, 0.6, 0.4, 0.0, 3);
    let bytes = learner.to_bytes().unwrap();
    let mut back = osrl_learn::Learner::from_bytes(&bytes).unwrap();
    assert_eq!(back.to_bytes().unwrap(), bytes, "save → load → save");
    let n = learner
        .cost_metric()
        .expect("a positive-definite B̂ from the warm-up");
    assert_eq!(back.cost_metric(), Some(n.clone()));
    assert!(
        n.iter().any(|&v| (v - 1.0).abs() > 1e-3),
        "N = B̂ is not I: {n:?}"
    );
    let evaluate = |l: &mut osrl_learn::Learner| {
        let mut ev = Evaluator::new(
            s.model.clone(),
            osrl_dynamics::SimConfig::default(),
            s.traj.clone(),
            s.q_start.clone(),
            osrl_learn::train::TrainConfig::default().gains,
            1,
        )
        .unwrap();
        ev.set_metric(osrl_control::MetricKind::InverseMass)
            .unwrap();
        ev.evaluate(l).unwrap()
    };
    let (e1, e2) = (evaluate(&mut learner), evaluate(&mut back));
    assert!(e1.tracking_rms_mm.is_finite());
    assert_eq!(e1, e2, "the same evaluation");
    // Learning on from the same state with the same seed: the same learner, bit for bit.
    common::run(&s, &mut learner, 0.3, 0.0, 0.0, 4);
    common::run(&s, &mut back, 0.3, 0.0, 0.0, 4);
    let (a, b) = (learner.to_bytes().unwrap(), back.to_bytes().unwrap());
    assert!(a == b, "continued learning differs after loading");
}
