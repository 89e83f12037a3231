//! The online form's extra forgetting and its residual, against their definitions.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rwr::{OnlineRwr, RwrConfig};

fn fixed_tau() -> RwrConfig {
    RwrConfig {
        adapt_tau: false,
        update_sigma: false,
        ridge: 1e-9,
        ..RwrConfig::default()
    }
}

fn samples(n: usize, seed: u64) -> Vec<(Vec<f64>, Vec<f64>, f64)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let phi: Vec<f64> = (0..3).map(|_| rng.random_range(-1.0..1.0)).collect();
            let y = vec![
                2.0 * phi[0] - phi[1] + 0.3 + rng.random_range(-0.1..0.1),
                phi[2] + rng.random_range(-0.2..0.2),
            ];
            (phi, y, rng.random_range(0.1..1.0))
        })
        .collect()
}

/// `mean_sq_residual` is `Σ w ‖y − θᵀφ‖² / (d Σ w)` of the current `θ`, computed directly.
#[test]
fn the_residual_matches_its_definition() {
    let data = samples(200, 1);
    let mut r = OnlineRwr::new(3, 2, fixed_tau()).unwrap();
    for (phi, y, a) in &data {
        r.observe(phi, y, 0.0, *a).unwrap();
    }
    r.update().unwrap();
    let theta = r.theta().clone();
    let (mut num, mut sw) = (0.0, 0.0);
    for (phi, y, a) in &data {
        for k in 0..2 {
            let pred: f64 = (0..3).map(|j| theta[(j, k)] * phi[j]).sum();
            num += a * (y[k] - pred).powi(2);
        }
        sw += a;
    }
    let direct = num / (2.0 * sw);
    let fast = r.mean_sq_residual();
    assert!(direct > 1e-4, "{direct}");
    assert!(
        (fast - direct).abs() < 1e-9 * direct.max(1.0),
        "{fast} vs {direct}"
    );
}

/// `decay(f)` between two samples is what forgetting `f` does: the same `θ`, bit for bit; and
/// it shifts the fit towards the later samples.
#[test]
fn decay_is_forgetting_on_demand() {
    let data = samples(100, 2);
    let (first, second) = data.split_at(50);
    let mut a = OnlineRwr::new(3, 2, fixed_tau()).unwrap();
    let mut b = OnlineRwr::new(
        3,
        2,
        RwrConfig {
            forgetting: 0.9,
            ..fixed_tau()
        },
    )
    .unwrap();
    for (phi, y, w) in first.iter().chain(second) {
        a.decay(0.9);
        a.observe(phi, y, 0.0, *w).unwrap();
        b.observe(phi, y, 0.0, *w).unwrap();
    }
    a.update().unwrap();
    b.update().unwrap();
    assert_eq!(a.theta(), b.theta());
    assert_eq!(a.ess(), b.ess());
    // Factors outside (0, 1) change nothing.
    let before = a.clone();
    a.decay(1.0);
    a.decay(0.0);
    a.decay(f64::NAN);
    assert_eq!(a.log_sum_weight(), before.log_sum_weight());
}
