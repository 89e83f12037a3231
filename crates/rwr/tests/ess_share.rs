//! The reward weighting's share of the effective sample size (`min_ess_share`): eq. 28 lets `τ`
//! grow without bound when the statistics forget and the costs are squares of one Gaussian
//! residual (a density that does not vanish at zero); the share floor bounds it, and waits
//! for the statistics to forget.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal, Uniform};
use rwr::{BatchRwr, OnlineRwr, RwrConfig};

/// What a run ends with: `τ`, the weights' ESS, the external weights' ESS, and the smallest
/// ratio of the two after the first 20 M-steps.
struct End {
    tau: f64,
    ess: f64,
    ess_ext: f64,
    worst_ratio: f64,
    theta: Vec<f64>,
}

/// 200 M-steps of 25 samples each: features and actions at random, cost `z²` with `z`
/// standard normal (one degree of freedom), activations in [0.2, 1].
fn run(share: f64, forgetting: f64) -> End {
    let cfg = RwrConfig {
        tau_init: 0.1,
        forgetting,
        min_ess_share: share,
        ridge: 1e-6,
        ..RwrConfig::default()
    };
    let mut r = OnlineRwr::new(2, 1, cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let act = Uniform::new(0.2, 1.0).unwrap();
    let mut worst_ratio = f64::INFINITY;
    for step in 0..200 {
        for _ in 0..25 {
            let phi = [1.0, StandardNormal.sample(&mut rng)];
            let u = [StandardNormal.sample(&mut rng)];
            let z: f64 = StandardNormal.sample(&mut rng);
            r.observe(&phi, &u, z * z, act.sample(&mut rng)).unwrap();
        }
        let info = r.update().unwrap();
        if step >= 20 {
            worst_ratio = worst_ratio.min(info.ess / r.ess_external());
        }
    }
    End {
        tau: r.tau(),
        ess: r.ess(),
        ess_ext: r.ess_external(),
        worst_ratio,
        theta: r.theta().as_slice().to_vec(),
    }
}

#[test]
fn the_share_floor_bounds_tau_where_eq_28_diverges() {
    // Forgetting 0.99 per sample: about 100 samples of memory.
    let free = run(0.0, 0.99);
    assert!(free.tau > 1e4, "eq. 28 alone: τ {}", free.tau);
    assert!(
        free.ess < 0.02 * free.ess_ext,
        "eq. 28 alone: ESS {} of {}",
        free.ess,
        free.ess_ext
    );
    let floored = run(0.1, 0.99);
    assert!(floored.tau < 1e3, "with the floor: τ {}", floored.tau);
    assert!(
        floored.ess > 0.05 * floored.ess_ext,
        "with the floor: ESS {} of {}",
        floored.ess,
        floored.ess_ext
    );
    // The floor acts on the next τ, and the samples weighted with a larger one stay in the
    // memory for a while: the share dips below the floor, within a factor of 5 (eq. 28 alone:
    // 50 times below it).
    assert!(
        floored.worst_ratio > 0.02,
        "with the floor: ESS share {}",
        floored.worst_ratio
    );
}

#[test]
fn without_forgetting_the_floor_waits() {
    // Without forgetting the old samples anchor eq. 28 and the share stays high.
    let free = run(0.0, 1.0);
    assert!(free.worst_ratio > 0.1, "{}", free.worst_ratio);
    let floored = run(0.1, 1.0);
    assert_eq!(floored.tau.to_bits(), free.tau.to_bits());
    assert_eq!(floored.theta, free.theta);
    // One sample far cheaper than the other 39 takes almost all weight at τ = 50 (ESS ≈ 1 of
    // 40): eq. 28 unchanged while nothing was forgotten, the floor after a `decay`.
    let cfg = RwrConfig {
        tau_init: 50.0,
        min_ess_share: 0.5,
        ..RwrConfig::default()
    };
    let fill = |r: &mut OnlineRwr| {
        for i in 0..40 {
            let cost = if i == 0 { 0.0 } else { 1.0 };
            r.observe(&[1.0, i as f64 / 40.0], &[(i as f64).sin()], cost, 1.0)
                .unwrap();
        }
    };
    let mut kept = OnlineRwr::new(2, 1, cfg.clone()).unwrap();
    fill(&mut kept);
    let k = kept.update().unwrap();
    assert!(k.ess < 1.01, "{}", k.ess);
    assert_eq!(k.tau_next, 1.0 / k.mean_cost);
    let mut decayed = OnlineRwr::new(2, 1, cfg).unwrap();
    fill(&mut decayed);
    decayed.decay(0.999);
    let d = decayed.update().unwrap();
    let floor = 50.0 * d.ess / (0.5 * decayed.ess_external());
    assert!(
        (d.tau_next - floor).abs() < 1e-12 * floor,
        "{} {floor}",
        d.tau_next
    );
    assert!(d.tau_next < k.tau_next);
    // `clear` forgets that it forgot: eq. 28 again.
    decayed.clear();
    fill(&mut decayed);
    let c = decayed.update().unwrap();
    assert_eq!(c.tau_next, 1.0 / c.mean_cost);
}

#[test]
fn the_external_ess_is_its_definition() {
    let mut r = OnlineRwr::new(1, 1, RwrConfig::default()).unwrap();
    assert_eq!(r.ess_external(), 0.0);
    let a = [0.5, 1.0, 0.25];
    for x in a {
        r.observe(&[1.0], &[0.0], 1.0, x).unwrap();
    }
    let (s, s2) = (1.75_f64, 0.25 + 1.0 + 0.0625);
    assert!((r.ess_external() - s * s / s2).abs() < 1e-12);
    // Extra forgetting scales every weight alike: the ESS stays; a sample after it counts in
    // full against the decayed ones.
    r.decay(0.5);
    assert!((r.ess_external() - s * s / s2).abs() < 1e-12);
    r.observe(&[1.0], &[0.0], 1.0, 1.0).unwrap();
    let (t, t2) = (0.5 * s + 1.0, 0.25 * s2 + 1.0);
    assert!((r.ess_external() - t * t / t2).abs() < 1e-12);
    r.clear();
    assert_eq!(r.ess_external(), 0.0);
}

#[test]
fn the_batch_form_compares_with_its_external_weights() {
    // One sample far cheaper than the rest takes almost all weight at τ = 50: ESS ≈ 1 of 40.
    let n = 40;
    let phi = nalgebra::DMatrix::from_fn(n, 2, |i, j| if j == 0 { 1.0 } else { i as f64 / 40.0 });
    let u = nalgebra::DMatrix::from_fn(n, 1, |i, _| (i as f64).sin());
    let costs: Vec<f64> = (0..n).map(|i| if i == 0 { 0.0 } else { 1.0 }).collect();
    let cfg = |share| RwrConfig {
        tau_init: 50.0,
        min_ess_share: share,
        ..RwrConfig::default()
    };
    let mut free = BatchRwr::new(2, 1, cfg(0.0)).unwrap();
    let f = free.em_step(&phi, &u, &costs, None).unwrap();
    assert!(f.ess < 1.01, "{}", f.ess);
    assert_eq!(f.tau_next, 1.0 / f.mean_cost);
    // Without external weights the reference is n: τ ≤ τ · ess / (share · n).
    let mut floored = BatchRwr::new(2, 1, cfg(0.5)).unwrap();
    let g = floored.em_step(&phi, &u, &costs, None).unwrap();
    assert!((g.tau_next - 50.0 * g.ess / (0.5 * n as f64)).abs() < 1e-12);
    // With them, their own ESS: half the samples at weight 1, half at 0.1.
    let ext: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 0.1 }).collect();
    let (sa, sa2) = (20.0 * 1.1, 20.0 * 1.01);
    let ess_ext = sa * sa / sa2;
    assert!((rwr::weights::external_ess(Some(&ext), n) - ess_ext).abs() < 1e-12);
    let mut weighted = BatchRwr::new(2, 1, cfg(0.5)).unwrap();
    let h = weighted.em_step(&phi, &u, &costs, Some(&ext)).unwrap();
    assert!((h.tau_next - 50.0 * h.ess / (0.5 * ess_ext)).abs() < 1e-12 * h.tau_next);
}
