//! The trust region of the online M-step: a step never moves the mean action by more than its
//! bound (weighted RMS over the step's samples), a small step is untouched, and a shrunk step
//! keeps its direction.
#![allow(clippy::needless_range_loop)]

mod common;

use common::{random_samples, row};
use rwr::{OnlineRwr, RwrConfig};

/// Weighted RMS of `‖(b − a)ᵀφ‖` over the samples with weights `w`.
fn rms(
    a: &nalgebra::DMatrix<f64>,
    b: &nalgebra::DMatrix<f64>,
    phi: &nalgebra::DMatrix<f64>,
    w: &[f64],
) -> f64 {
    let d = b - a;
    let (mut s, mut sw) = (0.0, 0.0);
    for i in 0..phi.nrows() {
        let f = row(phi, i);
        let mut e2 = 0.0;
        for k in 0..d.ncols() {
            let v: f64 = (0..f.len()).map(|j| d[(j, k)] * f[j]).sum();
            e2 += v * v;
        }
        s += w[i] * e2;
        sw += w[i];
    }
    (s / sw).sqrt()
}

#[test]
fn a_trust_region_step_never_moves_the_mean_action_by_more_than_its_bound() {
    let base = RwrConfig {
        tau_init: 0.3,
        adapt_tau: false,
        ridge: 1e-6,
        ..RwrConfig::default()
    };
    let (phi, u, costs) = random_samples(7, 80, 4, 3, 5.0);
    let theta0 = nalgebra::DMatrix::from_fn(4, 3, |r, c| 0.2 * r as f64 - 0.1 * c as f64);
    // The sample weights of the step, as the online form computes them (fixed τ, unit a).
    let w: Vec<f64> = costs.iter().map(|r| (-base.tau_init * r).exp()).collect();
    let step = |delta: Option<f64>| {
        let cfg = RwrConfig {
            trust_region: delta,
            ..base.clone()
        };
        let mut o = OnlineRwr::with_theta(theta0.clone(), cfg).unwrap();
        for i in 0..80 {
            o.observe(&row(&phi, i), &row(&u, i), costs[i], 1.0)
                .unwrap();
        }
        let info = o.update().unwrap();
        (o.theta().clone(), info.shrink)
    };
    let (free, f) = step(None);
    assert_eq!(f, 1.0);
    let full = rms(&theta0, &free, &phi, &w);
    for delta in [0.01, 0.1, 0.5 * full] {
        assert!(
            full > delta,
            "the test needs a step larger than {delta}: {full}"
        );
        let (limited, f) = step(Some(delta));
        let moved = rms(&theta0, &limited, &phi, &w);
        assert!(moved <= delta * (1.0 + 1e-9), "{moved} > {delta}");
        assert!(
            (moved - delta).abs() < 1e-9 * delta,
            "shrunk onto the bound: {moved}"
        );
        assert!((f - delta / full).abs() < 1e-9, "{f}");
        // Same direction: limited − θ0 = f (free − θ0).
        for (l, (fr, t0)) in limited.iter().zip(free.iter().zip(theta0.iter())) {
            assert!((l - t0 - f * (fr - t0)).abs() < 1e-12);
        }
    }
    // A bound above the step leaves it as it is, bit for bit.
    let (loose, f) = step(Some(2.0 * full));
    assert_eq!(f, 1.0);
    assert_eq!(loose, free);
    // A bad bound is refused.
    let bad = RwrConfig {
        trust_region: Some(0.0),
        ..base
    };
    assert!(OnlineRwr::new(4, 3, bad).is_err());
}
