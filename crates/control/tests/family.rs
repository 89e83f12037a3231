//! The family sampler (`docs/family.md`): seeded, and every drawn path inside the region,
//! reachable by IK inside the joint limits, and followed by eq. 7 inside the torque limits.

use osrl_control::family::{FamilyPath, FamilySampler, Region};
use osrl_control::{
    check_reachable, IkOptions, Osc, OscConfig, TaskController, TrajectoryConfig, TrajectoryKind,
};
use osrl_dynamics::{robots, Model, Robot, SimConfig, SimRobot};

fn family() -> TrajectoryConfig {
    TrajectoryConfig {
        kind: TrajectoryKind::Family,
        ..TrajectoryConfig::default()
    }
}

fn sampler(model: &Model, seed: u64) -> FamilySampler {
    let cfg = family();
    let base = cfg.build(model).unwrap();
    let home = check_reachable(model, &base, &IkOptions::default())
        .unwrap()
        .q_start;
    FamilySampler::new(model, &cfg, &home, seed).unwrap()
}

/// Eq. 7 from home along the approached path: the largest share of a torque limit and the
/// smallest joint margin (rad), measured independently of the sampler's own check.
fn replay(model: &Model, home: &[f64], p: &FamilyPath) -> (f64, f64) {
    let mut sim = SimRobot::new(model.clone(), SimConfig::default()).unwrap();
    sim.reset(home, &vec![0.0; model.nq()]).unwrap();
    let mut osc = Osc::new(model.clone(), OscConfig::default()).unwrap();
    let tau: Vec<f64> = model.tau_max().collect();
    let (lo, hi): (Vec<f64>, Vec<f64>) = (model.q_min().collect(), model.q_max().collect());
    let t = &p.approached;
    let dt = sim.control_period();
    let (mut share, mut margin) = (0.0f64, f64::INFINITY);
    let mut u = vec![0.0; model.nq()];
    for k in 0..((t.lead() + t.ramp() + t.period()) / dt).ceil() as usize {
        osc.command(sim.measurement(), &t.sample(k as f64 * dt), &mut u)
            .unwrap();
        for (v, m) in u.iter().zip(&tau) {
            share = share.max(v.abs() / m);
        }
        let q = sim.step(&u).unwrap().q.clone();
        for i in 0..q.len() {
            margin = margin.min(q[i] - lo[i]).min(hi[i] - q[i]);
        }
    }
    (share, margin)
}

#[test]
fn the_same_seed_draws_the_same_paths_and_another_seed_others() {
    let model = robots::planar3();
    let (mut a, mut b, mut c) = (sampler(&model, 7), sampler(&model, 7), sampler(&model, 8));
    for _ in 0..4 {
        let (pa, pb, pc) = (a.draw().unwrap(), b.draw().unwrap(), c.draw().unwrap());
        assert_eq!(pa, pb);
        assert_ne!(pa.config, pc.config);
    }
    assert_eq!(a.rejections, b.rejections);
}

#[test]
fn every_drawn_path_is_in_the_region_reachable_and_within_the_limits() {
    for (model, n) in [(robots::planar3(), 12), (robots::sarcos7(), 4)] {
        let cfg = family();
        let region = Region::of(&model, &cfg).unwrap();
        // The default region: the base figure-8's box grown by 50 %.
        let [a, b] = cfg.base(&model).unwrap();
        assert!(
            (region.half[0] - 1.5 * a).abs() < 1e-12 && (region.half[1] - 1.5 * b).abs() < 1e-12
        );
        let mut s = sampler(&model, 3);
        let base = cfg.build(&model).unwrap();
        let home = check_reachable(&model, &base, &IkOptions::default())
            .unwrap()
            .q_start;
        let mut kinds = Vec::new();
        for _ in 0..n {
            let p = s.draw().unwrap();
            kinds.push(p.config.kind);
            assert!(region.leaves_by(&p.path) < 1e-9, "{:?}", p.config);
            // It starts from home's task point and continues smoothly into the path.
            assert!((p.approached.start() - base.start()).norm() < 1e-12);
            let t0 = p.approached.lead();
            let (x0, x1) = (p.approached.sample(t0 - 1e-9), p.path.sample(0.0));
            assert!((x0.x - x1.x).norm() < 1e-9 && x0.xd.norm() < 1e-6);
            // Reachable by IK (again, from scratch), and its own home is the sampler's.
            let r = check_reachable(&model, &p.path, &IkOptions::default()).unwrap();
            assert_eq!(r.q_start, p.home);
            check_reachable(&model, &p.approached, &IkOptions::default()).unwrap();
            let (share, margin) = replay(&model, &home, &p);
            assert!(
                share <= 0.8 && (share - p.torque_share).abs() < 1e-12,
                "{share} vs {}",
                p.torque_share
            );
            assert!(margin >= 0.05, "{}: margin {margin}", model.name());
        }
        if model.name().starts_with("planar3") {
            for k in [
                TrajectoryKind::Figure8,
                TrajectoryKind::Circle,
                TrajectoryKind::MinJerk,
            ] {
                assert!(kinds.contains(&k), "{kinds:?}");
            }
        }
    }
}

#[test]
fn a_family_config_out_of_range_is_refused_with_its_field_and_value() {
    let model = robots::planar3();
    let mut cfg = family();
    cfg.family.size = [0.5, 1.5];
    let e = cfg.build(&model).unwrap_err().to_string();
    assert!(e.contains("size = [0.5, 1.5]: accepted"), "{e}");
    cfg.family.size = [0.3, 0.8];
    cfg.family.kinds = vec![TrajectoryKind::Family];
    assert!(cfg.build(&model).unwrap_err().to_string().contains("kinds"));
    // Durations and speeds whose reachability check would not fit in memory (these panicked).
    let mut slow = family();
    slow.family.approach_speed = 1e-300;
    let e = slow.build(&model).unwrap_err().to_string();
    assert!(
        e.contains("approach_speed = 1e-300: accepted within"),
        "{e}"
    );
    let mut short = family();
    short.family.move_time = [1e-300, 1e-300];
    let e = short.build(&model).unwrap_err().to_string();
    assert!(e.contains("move_time"), "{e}");
    let mut long = family();
    long.family.period = [1e300, 1e300];
    assert!(long
        .build(&model)
        .unwrap_err()
        .to_string()
        .contains("period"));
    // A family no path can belong to (slower than any): a clear error after max_draws.
    let mut tiny = family();
    tiny.family.max_acceleration_ratio = 1e-9;
    tiny.family.max_draws = 20;
    let base = tiny.build(&model).unwrap();
    let home = check_reachable(&model, &base, &IkOptions::default())
        .unwrap()
        .q_start;
    let mut s = FamilySampler::new(&model, &tiny, &home, 0).unwrap();
    let e = s.draw().unwrap_err().to_string();
    assert!(e.contains("20 draws"), "{e}");
}

#[test]
fn base_every_interleaves_the_base_figure8_without_changing_the_drawn_paths() {
    let model = robots::planar3();
    let with = |k: usize| {
        let mut cfg = family();
        cfg.family.base_every = k;
        let base = cfg.build(&model).unwrap();
        let home = check_reachable(&model, &base, &IkOptions::default())
            .unwrap()
            .q_start;
        (FamilySampler::new(&model, &cfg, &home, 5).unwrap(), base)
    };
    // The drawn sequence on its own.
    let (mut plain, base) = with(0);
    let drawn: Vec<_> = (0..4).map(|_| plain.draw().unwrap().approached).collect();
    // base_every = 0: the training paths are exactly the drawn ones.
    let (mut off, _) = with(0);
    for d in &drawn {
        assert_eq!(&off.next_training_path().unwrap(), d);
    }
    // base_every = 3: episodes 0, 3, 6 run the base figure-8, the others the drawn sequence in
    // order.
    let (mut on, _) = with(3);
    let mut next = drawn.iter();
    for episode in 0..7 {
        let p = on.next_training_path().unwrap();
        if episode % 3 == 0 {
            assert_eq!(p, base, "episode {episode}");
        } else {
            assert_eq!(&p, next.next().unwrap(), "episode {episode}");
            assert_ne!(p, base);
        }
    }
    assert!(next.next().is_none());
}
