//! The online form against the batch form, forgetting, bad input, seeded sampling.
#![allow(clippy::needless_range_loop)]

mod common;

use approx::assert_relative_eq;
use common::{random_samples, row};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rwr::{BatchRwr, OnlineRwr, RwrConfig, RwrError};

fn cfg(forgetting: f64) -> RwrConfig {
    RwrConfig {
        tau_init: 0.4,
        ridge: 1e-6,
        forgetting,
        ..RwrConfig::default()
    }
}

#[test]
fn online_with_forgetting_one_equals_batch_over_several_iterations() {
    let mut batch = BatchRwr::new(3, 2, cfg(1.0)).unwrap();
    let mut online = OnlineRwr::new(3, 2, cfg(1.0)).unwrap();
    for seed in 0..4 {
        let (phi, u, costs) = random_samples(seed, 60, 3, 2, 5.0);
        let ext: Vec<f64> = (0..60)
            .map(|i| ((i * 7 % 11) as f64 + 0.5) / 11.0)
            .collect();
        let b = batch.em_step(&phi, &u, &costs, Some(&ext)).unwrap();
        online.clear();
        for i in 0..60 {
            online
                .observe(&row(&phi, i), &row(&u, i), costs[i], ext[i])
                .unwrap();
        }
        let o = online.update().unwrap();
        assert_relative_eq!(online.theta(), batch.theta(), max_relative = 1e-9);
        assert_relative_eq!(o.sigma, b.sigma, max_relative = 1e-9);
        assert_relative_eq!(o.tau_next, b.tau_next, max_relative = 1e-9);
        assert_relative_eq!(o.ess, b.ess, max_relative = 1e-9);
        assert_relative_eq!(online.ess(), batch.ess(), max_relative = 1e-9);
    }
}

#[test]
fn forgetting_equals_batch_with_geometric_external_weights() {
    // λ^(n−1−i) as external weights in the batch form is what forgetting does online.
    let lambda: f64 = 0.97;
    let (phi, u, costs) = random_samples(11, 80, 2, 1, 3.0);
    let ext: Vec<f64> = (0..80).map(|i| lambda.powi(79 - i)).collect();
    let mut batch = BatchRwr::new(2, 1, cfg(1.0)).unwrap();
    batch.em_step(&phi, &u, &costs, Some(&ext)).unwrap();
    let mut online = OnlineRwr::new(2, 1, cfg(lambda)).unwrap();
    for i in 0..80 {
        online
            .observe(&row(&phi, i), &row(&u, i), costs[i], 1.0)
            .unwrap();
    }
    online.update().unwrap();
    assert_relative_eq!(online.theta(), batch.theta(), max_relative = 1e-9);
    assert_relative_eq!(online.sigma(), batch.sigma(), max_relative = 1e-9);
    assert_relative_eq!(online.tau(), batch.tau(), max_relative = 1e-9);
}

#[test]
fn online_weights_stay_finite_for_huge_costs_and_tau() {
    let huge = RwrConfig {
        tau_init: 1e6,
        forgetting: 0.5,
        ..RwrConfig::default()
    };
    let mut online = OnlineRwr::new(2, 1, huge).unwrap();
    let (phi, u, _) = random_samples(3, 200, 2, 1, 1.0);
    for i in 0..200 {
        // Costs alternate between 1e6 and 0: weights exp(−1e12) next to exp(0).
        let r = if i % 2 == 0 { 1e6 } else { (i as f64) * 1e-3 };
        online.observe(&row(&phi, i), &row(&u, i), r, 1.0).unwrap();
        assert!(online.log_sum_weight().is_finite() && online.ess().is_finite());
    }
    let info = online.update().unwrap();
    assert!(online.theta().iter().all(|x| x.is_finite()));
    assert!(info.sigma.is_finite() && info.tau_next.is_finite() && info.ess >= 1.0);
}

#[test]
fn bad_samples_are_rejected_and_change_nothing() {
    let mut online = OnlineRwr::new(2, 1, cfg(0.9)).unwrap();
    let (phi, u, costs) = random_samples(5, 20, 2, 1, 1.0);
    for i in 0..20 {
        online
            .observe(&row(&phi, i), &row(&u, i), costs[i], 1.0)
            .unwrap();
    }
    let mut reference = online.clone();
    let (ok_phi, ok_u) = ([0.3, 1.0], [0.2]);
    assert_eq!(
        online.observe(&ok_phi, &ok_u, -0.1, 1.0),
        Err(RwrError::BadCost(-0.1))
    );
    assert!(online.observe(&ok_phi, &ok_u, f64::NAN, 1.0).is_err());
    assert!(online.observe(&[f64::NAN, 1.0], &ok_u, 0.1, 1.0).is_err());
    assert!(online.observe(&ok_phi, &[f64::INFINITY], 0.1, 1.0).is_err());
    assert!(online.observe(&ok_phi, &ok_u, 0.1, -1.0).is_err());
    assert!(online.observe(&ok_phi, &ok_u, 0.1, f64::NAN).is_err());
    assert!(online.observe(&[1.0], &ok_u, 0.1, 1.0).is_err());
    assert!(online.observe(&ok_phi, &[0.1, 0.2], 0.1, 1.0).is_err());
    assert_eq!(online.ess(), reference.ess());
    assert_eq!(online.update().unwrap(), reference.update().unwrap());
    assert_eq!(online.theta(), reference.theta());
}

#[test]
fn empty_statistics_cannot_update() {
    let mut online = OnlineRwr::new(2, 1, cfg(1.0)).unwrap();
    assert_eq!(online.update(), Err(RwrError::NoWeight));
    online.observe(&[1.0, 1.0], &[0.0], 0.0, 0.0).unwrap(); // zero external weight: no weight
    assert_eq!(online.update(), Err(RwrError::NoWeight));
    assert_eq!(online.tau(), 0.4);
}

#[test]
fn seeded_sampling_is_reproducible_and_has_the_policy_moments() {
    let mut online = OnlineRwr::new(
        2,
        2,
        RwrConfig {
            sigma_init: 0.5,
            update_sigma: false,
            ..cfg(1.0)
        },
    )
    .unwrap();
    let (phi, _, _) = random_samples(6, 50, 2, 2, 1.0);
    let u = &phi * nalgebra::DMatrix::from_vec(2, 2, vec![1.0, -2.0, 0.5, 3.0]);
    for i in 0..50 {
        online
            .observe(&row(&phi, i), &row(&u, i), 0.1, 1.0)
            .unwrap();
    }
    online.update().unwrap();
    let draw = |seed| {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut out = [0.0; 2];
        (0..4000)
            .map(|_| {
                online.sample_into(&[0.5, 1.0], &mut rng, &mut out).unwrap();
                out
            })
            .collect::<Vec<_>>()
    };
    let (a, b) = (draw(7), draw(7));
    assert_eq!(a, b);
    assert_ne!(a, draw(8));
    let mut mean = [0.0; 2];
    online.mean_into(&[0.5, 1.0], &mut mean).unwrap();
    assert_relative_eq!(mean[0], -1.5, epsilon = 1e-4); // ridge 1e-6 biases slightly
    for (k, m) in mean.iter().enumerate() {
        let avg = a.iter().map(|x| x[k]).sum::<f64>() / 4000.0;
        let var = a.iter().map(|x| (x[k] - avg).powi(2)).sum::<f64>() / 4000.0;
        assert!((avg - m).abs() < 0.05, "mean {avg} vs {m}");
        assert!(
            (var.sqrt() - online.sigma()).abs() < 0.02,
            "std {} vs {}",
            var.sqrt(),
            online.sigma()
        );
    }
}

#[test]
fn ridge_to_previous_keeps_unexcited_directions() {
    use nalgebra::DMatrix;
    // Features [x, 1] with x always 0: the slope is not excited by the data. A plain ridge pulls
    // it to 0; the proximal ridge keeps the previous slope.
    let prior = DMatrix::from_row_slice(2, 1, &[3.0, 0.5]);
    let fit = |to_prev: bool| {
        let cfg = rwr::RwrConfig {
            ridge: 1e-3,
            ridge_to_previous: to_prev,
            adapt_tau: false,
            ..Default::default()
        };
        let mut o = rwr::OnlineRwr::with_theta(prior.clone(), cfg).unwrap();
        for k in 0..100 {
            o.observe(&[0.0, 1.0], &[1.0 + 0.01 * (k % 3) as f64], 0.0, 1.0)
                .unwrap();
        }
        o.update().unwrap();
        o.theta().clone()
    };
    let plain = fit(false);
    let prox = fit(true);
    assert!(
        plain[(0, 0)].abs() < 1e-12,
        "plain ridge: slope {}",
        plain[(0, 0)]
    );
    assert!(
        (prox[(0, 0)] - 3.0).abs() < 1e-12,
        "proximal ridge: slope {}",
        prox[(0, 0)]
    );
    // The excited intercept follows the data either way.
    assert!((plain[(1, 0)] - 1.01).abs() < 0.01 && (prox[(1, 0)] - 1.01).abs() < 0.01);
}
