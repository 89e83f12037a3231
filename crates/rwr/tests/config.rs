//! Config validation, serde, and the optional safeguards (fixed τ, τ cap, ESS floor, σ floor).
#![allow(clippy::needless_range_loop)]

mod common;

use common::random_samples;
use rwr::{BatchRwr, RwrConfig, RwrError};

#[test]
fn defaults_are_valid_and_round_trip_through_json() {
    let cfg = RwrConfig::default();
    cfg.validate().unwrap();
    let back: RwrConfig = serde_json::from_str(&serde_json::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    let partial: RwrConfig = serde_json::from_str(r#"{"tau_init": 0.1, "tau_max": 50.0}"#).unwrap();
    assert_eq!(
        (partial.tau_init, partial.tau_max, partial.ridge),
        (0.1, Some(50.0), cfg.ridge)
    );
    assert!(serde_json::from_str::<RwrConfig>(r#"{"tau": 1.0}"#).is_err());
}

#[test]
fn invalid_configs_are_rejected() {
    let bad = [
        RwrConfig {
            tau_init: 0.0,
            ..Default::default()
        },
        RwrConfig {
            tau_init: f64::NAN,
            ..Default::default()
        },
        RwrConfig {
            tau_max: Some(0.5),
            ..Default::default()
        },
        RwrConfig {
            min_ess: -1.0,
            ..Default::default()
        },
        RwrConfig {
            min_ess_share: 1.5,
            ..Default::default()
        },
        RwrConfig {
            min_ess_share: f64::NAN,
            ..Default::default()
        },
        RwrConfig {
            sigma_init: 0.0,
            ..Default::default()
        },
        RwrConfig {
            sigma_min: 2.0,
            ..Default::default()
        },
        RwrConfig {
            ridge: -1e-3,
            ..Default::default()
        },
        RwrConfig {
            forgetting: 0.0,
            ..Default::default()
        },
        RwrConfig {
            forgetting: 1.01,
            ..Default::default()
        },
    ];
    for cfg in bad {
        assert!(
            matches!(cfg.validate(), Err(RwrError::InvalidConfig(_))),
            "{cfg:?}"
        );
        assert!(BatchRwr::new(2, 1, cfg).is_err());
    }
}

#[test]
fn fixed_tau_stays_fixed_and_sigma_update_can_be_off() {
    let cfg = RwrConfig {
        adapt_tau: false,
        update_sigma: false,
        tau_init: 0.25,
        sigma_init: 0.8,
        ..Default::default()
    };
    let mut rwr = BatchRwr::new(2, 1, cfg).unwrap();
    for seed in 0..3 {
        let (phi, u, costs) = random_samples(seed, 20, 2, 1, 2.0);
        rwr.em_step(&phi, &u, &costs, None).unwrap();
        assert_eq!((rwr.tau(), rwr.sigma()), (0.25, 0.8));
    }
}

#[test]
fn sigma_floor_tau_cap_and_ess_floor_bound_the_updates() {
    // Costs near zero: eq. 28 would give τ ≈ 1e8; the cap holds it at 100.
    let (phi, u, _) = random_samples(2, 20, 2, 1, 1.0);
    let tiny: Vec<f64> = (0..20).map(|i| 1e-8 * (i as f64 + 1.0)).collect();
    let capped = RwrConfig {
        tau_max: Some(100.0),
        ..Default::default()
    };
    let mut rwr = BatchRwr::new(2, 1, capped).unwrap();
    rwr.em_step(&phi, &u, &tiny, None).unwrap();
    assert_eq!(rwr.tau(), 100.0);
    let mut free = BatchRwr::new(2, 1, RwrConfig::default()).unwrap();
    free.em_step(&phi, &u, &tiny, None).unwrap();
    assert!(free.tau() > 9e6); // 1 / mean(1e-8..2e-7) ≈ 9.5e6
                               // Residuals exactly zero (u linear in φ): σ lands on its floor.
    let u_lin = &phi * nalgebra::DMatrix::from_vec(2, 1, vec![0.5, -1.0]);
    let floored = RwrConfig {
        sigma_min: 0.05,
        ..Default::default()
    };
    let mut rwr = BatchRwr::new(2, 1, floored).unwrap();
    rwr.em_step(&phi, &u_lin, &tiny, None).unwrap();
    assert_eq!(rwr.sigma(), 0.05);
    // τ so large that one sample takes all weight: ESS ≈ 1 < 10 pulls τ down to τ·ess/10.
    let (phi, u, costs) = random_samples(4, 50, 2, 1, 10.0);
    let guarded = RwrConfig {
        tau_init: 100.0,
        min_ess: 10.0,
        ..Default::default()
    };
    let mut rwr = BatchRwr::new(2, 1, guarded).unwrap();
    let info = rwr.em_step(&phi, &u, &costs, None).unwrap();
    assert!(info.ess < 2.0);
    assert!((rwr.tau() - 100.0 * info.ess / 10.0).abs() < 1e-9);
}
