//! The benchmark data sets for tests and examples (re-exported from [`lwpr::datasets`]), and
//! the resting robot of the guard tests.
#![allow(unused_imports, dead_code)]

pub use lwpr::datasets::*;
use lwpr::{Lwpr, LwprConfig, LwprError, RfEvent};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A robot that rests at one point and moves rarely: `x` (in `[-1, 1]^n`) is `0.5` in every
/// dimension 99 % of the time; `y = Σ sin(x_i)` plus uniform noise of ±0.1.
pub fn resting_sample(rng: &mut ChaCha8Rng, n: usize) -> (Vec<f64>, f64) {
    let moving = rng.random_bool(0.01);
    let x: Vec<f64> = (0..n)
        .map(|_| {
            if moving {
                rng.random_range(-1.0..1.0)
            } else {
                0.5
            }
        })
        .collect();
    let y = x.iter().map(|v| v.sin()).sum::<f64>() + 0.1 * rng.random_range(-1.0..1.0);
    (x, y)
}

/// Trains `cfg` on `steps` resting samples in `n` inputs; checks after every update that the
/// reported counts match the queued events, and returns the model.
pub fn train_resting(cfg: &LwprConfig, n: usize, steps: usize, seed: u64) -> Lwpr {
    let mut m = Lwpr::new(n, 1, cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..steps {
        let (x, y) = resting_sample(&mut rng, n);
        let info = m.update(&x, &[y]).unwrap();
        let pruned = m
            .drain_events()
            .filter(|e| matches!(e, RfEvent::Pruned { .. }))
            .count();
        assert_eq!(pruned, info.pruned + info.removed_non_finite);
    }
    m
}

/// Every RF's metric and local model are finite, the model saves and loads, and it predicts
/// finite values (or reports no support) along a line through its data.
pub fn assert_sound(m: &mut Lwpr) {
    let n = m.n_in();
    for v in m.rfs(0).unwrap() {
        assert!(
            v.metric().iter().all(|a| a.is_finite()),
            "metric of {:?}",
            v.id()
        );
        if let Some(lm) = v.local_model(0) {
            assert!(lm.offset.is_finite() && lm.slope.iter().all(|a| a.is_finite()));
        }
    }
    Lwpr::from_bytes(&m.to_bytes()).expect("the model loads again");
    let mut y = [0.0];
    for k in 0..=20 {
        let x = vec![-1.0 + 0.1 * k as f64; n];
        match m.predict_jacobian(&x, &mut y, &mut vec![0.0; n]) {
            Ok(_) => assert!(y[0].is_finite(), "prediction at {x:?}"),
            Err(e) => assert!(matches!(e, LwprError::NoActiveRf { .. })),
        }
    }
}
