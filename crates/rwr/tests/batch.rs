//! Batch EM (Algorithm 2) against direct computations of eq. 23, 24, 25 and 28.
#![allow(clippy::needless_range_loop)]

mod common;

use approx::assert_relative_eq;
use common::random_samples;
use nalgebra::DMatrix;
use rwr::weights::normalized_weights;
use rwr::{BatchRwr, RwrConfig, RwrError};

fn cfg() -> RwrConfig {
    RwrConfig {
        ridge: 0.0,
        tau_init: 0.7,
        sigma_min: 0.0,
        ..RwrConfig::default()
    }
}

/// Eq. 25 computed naively (no log space): `U_τ(r_i) / Σ U_τ(r_j)` with `U_τ = τ exp(−τ r)`.
fn naive_weights(tau: f64, costs: &[f64], ext: &[f64]) -> Vec<f64> {
    let u: Vec<f64> = costs
        .iter()
        .zip(ext)
        .map(|(r, a)| a * tau * (-tau * r).exp())
        .collect();
    let s: f64 = u.iter().sum();
    u.iter().map(|x| x / s).collect()
}

#[test]
fn weighted_regression_equals_direct_weighted_least_squares() {
    let (phi, u, costs) = random_samples(3, 40, 3, 2, 4.0);
    let ext: Vec<f64> = (0..40).map(|i| 0.1 + (i % 7) as f64 * 0.3).collect();
    let mut rwr = BatchRwr::new(3, 2, cfg()).unwrap();
    let info = rwr.em_step(&phi, &u, &costs, Some(&ext)).unwrap();
    // Direct solve: least squares on sqrt(W)Φ θ = sqrt(W)Y by SVD (no normal equations).
    let w = naive_weights(0.7, &costs, &ext);
    let sw = DMatrix::from_diagonal(&nalgebra::DVector::from_iterator(
        40,
        w.iter().map(|x| x.sqrt()),
    ));
    let theta = (&sw * &phi)
        .svd(true, true)
        .solve(&(&sw * &u), 1e-14)
        .unwrap();
    assert_relative_eq!(rwr.theta(), &theta, epsilon = 1e-10);
    // Eq. 24 (with 1/d) from the residuals.
    let res = &u - &phi * &theta;
    let s2: f64 = (0..40)
        .map(|i| w[i] * res.row(i).norm_squared())
        .sum::<f64>()
        / 2.0;
    assert_relative_eq!(info.sigma, s2.sqrt(), epsilon = 1e-10);
    // Eq. 28 and the effective sample size.
    let tau = w.iter().sum::<f64>() / w.iter().zip(&costs).map(|(w, r)| w * r).sum::<f64>();
    assert_relative_eq!(info.tau_next, tau, epsilon = 1e-10);
    assert_relative_eq!(rwr.tau(), tau, epsilon = 1e-10);
    assert_relative_eq!(
        info.ess,
        1.0 / w.iter().map(|x| x * x).sum::<f64>(),
        epsilon = 1e-9
    );
}

#[test]
fn tau_update_is_eq_28_with_unnormalised_transformed_rewards() {
    // Eq. 28 literally: Σ U_τ(r_i) / Σ U_τ(r_i) r_i, over several iterations.
    let mut rwr = BatchRwr::new(
        2,
        1,
        RwrConfig {
            tau_init: 0.3,
            ..cfg()
        },
    )
    .unwrap();
    for seed in 0..5 {
        let (phi, u, costs) = random_samples(seed, 30, 2, 1, 3.0);
        let tau = rwr.tau();
        let ut: Vec<f64> = costs.iter().map(|r| tau * (-tau * r).exp()).collect();
        let expect =
            ut.iter().sum::<f64>() / ut.iter().zip(&costs).map(|(a, r)| a * r).sum::<f64>();
        let info = rwr.em_step(&phi, &u, &costs, None).unwrap();
        assert_eq!(info.tau_used, tau);
        assert_relative_eq!(rwr.tau(), expect, max_relative = 1e-12);
    }
}

#[test]
fn ridge_is_added_to_the_normalised_gram_matrix() {
    let (phi, u, costs) = random_samples(5, 20, 3, 1, 1.0);
    let mut rwr = BatchRwr::new(
        3,
        1,
        RwrConfig {
            ridge: 0.5,
            ..cfg()
        },
    )
    .unwrap();
    rwr.em_step(&phi, &u, &costs, None).unwrap();
    let w = naive_weights(0.7, &costs, &[1.0; 20]);
    let wm = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(w));
    let a = phi.transpose() * &wm * &phi + DMatrix::identity(3, 3) * 0.5;
    let theta = a.lu().solve(&(phi.transpose() * &wm * &u)).unwrap();
    assert_relative_eq!(rwr.theta(), &theta, epsilon = 1e-12);
}

#[test]
fn weights_stay_finite_for_huge_costs_and_tau() {
    for &tau in &[1e-3, 1.0, 1e3, 1e6] {
        let costs = [1e6, 0.0, 3.5e5, 1e6 - 1e-3, 12.0];
        let mut w = [0.0; 5];
        let ess = normalized_weights(tau, &costs, None, &mut w).unwrap();
        assert!(
            w.iter().all(|x| x.is_finite() && *x >= 0.0),
            "tau {tau}: {w:?}"
        );
        assert_relative_eq!(w.iter().sum::<f64>(), 1.0, epsilon = 1e-12);
        assert!(w[1] >= w[4] && w[4] >= w[2] && w[2] >= w[3] && ess >= 1.0 && ess.is_finite());
        // Costs all huge (every exp(−τ r) underflows naively): still a distribution.
        let big = [1e6, 1e6 + 1e-6, 2e6 / 3.0 + 5e5];
        let mut w = [0.0; 3];
        normalized_weights(tau, &big, None, &mut w).unwrap();
        assert!(w.iter().all(|x| x.is_finite()) && (w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        let cfg = RwrConfig {
            tau_init: tau,
            tau_max: None,
            ..RwrConfig::default()
        };
        let (phi, u, _) = random_samples(9, 3, 2, 1, 1.0);
        let mut rwr = BatchRwr::new(2, 1, cfg).unwrap();
        let info = rwr.em_step(&phi, &u, &big, None).unwrap();
        assert!(rwr.theta().iter().all(|x| x.is_finite()) && info.sigma.is_finite());
        assert!(info.tau_next.is_finite() && info.tau_next > 0.0);
    }
}

#[test]
fn bad_input_is_rejected_and_changes_nothing() {
    let (phi, u, costs) = random_samples(1, 10, 2, 1, 1.0);
    let mut rwr = BatchRwr::new(2, 1, cfg()).unwrap();
    rwr.em_step(&phi, &u, &costs, None).unwrap();
    let (theta, sigma, tau) = (rwr.theta().clone(), rwr.sigma(), rwr.tau());
    let mut bad_cost = costs.clone();
    for v in [-1e-9, f64::NAN, f64::INFINITY] {
        bad_cost[4] = v;
        assert!(matches!(
            rwr.em_step(&phi, &u, &bad_cost, None),
            Err(RwrError::BadCost(_))
        ));
    }
    let mut bad_phi = phi.clone();
    bad_phi[(2, 1)] = f64::NAN;
    assert_eq!(
        rwr.em_step(&bad_phi, &u, &costs, None),
        Err(RwrError::NonFinite("features"))
    );
    let mut bad_u = u.clone();
    bad_u[(0, 0)] = f64::NEG_INFINITY;
    assert_eq!(
        rwr.em_step(&phi, &bad_u, &costs, None),
        Err(RwrError::NonFinite("actions"))
    );
    let ext = vec![-1.0; 10];
    assert!(matches!(
        rwr.em_step(&phi, &u, &costs, Some(&ext)),
        Err(RwrError::BadWeight(_))
    ));
    assert_eq!(
        rwr.em_step(&phi, &u, &costs, Some(&[0.0; 10])),
        Err(RwrError::NoWeight)
    );
    assert!(matches!(
        rwr.em_step(&phi, &u, &costs[..9], None),
        Err(RwrError::Dimension { .. })
    ));
    let wide = DMatrix::zeros(10, 3);
    assert!(matches!(
        rwr.em_step(&wide, &u, &costs, None),
        Err(RwrError::Dimension { .. })
    ));
    let rank1 = DMatrix::from_element(10, 2, 1.0);
    assert_eq!(
        rwr.em_step(&rank1, &u, &costs, None),
        Err(RwrError::Singular)
    );
    assert_eq!((rwr.theta(), rwr.sigma(), rwr.tau()), (&theta, sigma, tau));
}
