//! The 2-D update with every dimension a constant (`rf_update_2d`, `metric_2d`) against the
//! general path, bit for bit: whole saved models after training, for every configuration the
//! 2-D path takes (meta learning on and off, metric learning off, Gaussian and BiSquare
//! kernels, shared RFs with one output, a kernel and a regression on different input pairs,
//! normalised inputs, rates large enough to halve).

use super::const_r::FORCE_DYNAMIC;
use crate::config::{Kernel, LwprConfig, MetricInit, Norm};
use crate::model::Lwpr;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cell::Cell;

thread_local! {
    /// RF updates that took the 2-D path (counted by `rf_update::update_rf`).
    pub(crate) static TAKEN: Cell<u64> = const { Cell::new(0) };
}

/// Trains a model on `n_in` inputs (targets: the cross function of inputs 0 and 1 plus a
/// linear term in the last input, with noise) with the 2-D path on or off; returns the saved
/// model, its predictions on a grid and the number of 2-D updates.
fn train(general: bool, n_in: usize, cfg: &LwprConfig) -> (Vec<u8>, Vec<u64>, u64) {
    FORCE_DYNAMIC.with(|f| f.set(general));
    TAKEN.with(|n| n.set(0));
    let mut m = Lwpr::new(n_in, 1, cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let f = |x: &[f64]| {
        let (a, b) = (x[0], x[1]);
        let cross = (-10.0 * a * a)
            .exp()
            .max((-50.0 * b * b).exp())
            .max(1.25 * (-5.0 * (a * a + b * b)).exp());
        cross + 0.5 * x[n_in - 1]
    };
    for _ in 0..3000 {
        let x: Vec<f64> = (0..n_in).map(|_| rng.random_range(-1.0..1.0)).collect();
        let y = f(&x) + 0.1 * rng.random_range(-1.0..1.0);
        m.update(&x, &[y]).unwrap();
    }
    let mut preds = Vec::new();
    for k in 0..200 {
        let x: Vec<f64> = (0..n_in)
            .map(|i| ((k * (i + 3)) % 41) as f64 / 20.0 - 1.0)
            .collect();
        let mut y = [0.0];
        if m.predict(&x, &mut y).is_ok() {
            preds.push(y[0].to_bits());
        }
    }
    FORCE_DYNAMIC.with(|f| f.set(false));
    (m.to_bytes(), preds, TAKEN.with(|n| n.get()))
}

#[test]
fn the_2d_update_matches_the_general_path() {
    let base = LwprConfig {
        init_d: MetricInit::Scalar(25.0),
        init_alpha: 250.0,
        w_gen: 0.2,
        diag_only: false,
        meta: true,
        meta_rate: 250.0,
        ..Default::default()
    };
    let cases: Vec<(&str, usize, LwprConfig)> = vec![
        ("cross, meta", 2, base.clone()),
        (
            "no meta",
            2,
            LwprConfig {
                meta: false,
                ..base.clone()
            },
        ),
        (
            "no metric learning",
            2,
            LwprConfig {
                update_d: false,
                ..base.clone()
            },
        ),
        (
            "bisquare, large rates",
            2,
            LwprConfig {
                kernel: Kernel::Bisquare,
                init_alpha: 5000.0,
                ..base.clone()
            },
        ),
        (
            "shared RFs",
            2,
            LwprConfig {
                shared_rfs: true,
                ..base.clone()
            },
        ),
        (
            "kernel on (0, 1), regression on (1, 2)",
            3,
            LwprConfig {
                kernel_dims: Some(vec![0, 1]),
                regression_dims: Some(vec![1, 2]),
                ..base.clone()
            },
        ),
        (
            "normalised inputs, fast forgetting",
            2,
            LwprConfig {
                norm_in: Norm::List(vec![0.5, 2.0]),
                init_lambda: 0.99,
                final_lambda: 0.995,
                ..base.clone()
            },
        ),
    ];
    for (name, n_in, cfg) in cases {
        let (fast, fast_pred, taken) = train(false, n_in, &cfg);
        let (general, general_pred, taken_g) = train(true, n_in, &cfg);
        assert!(taken > 5_000, "{name}: the 2-D path ran {taken} times");
        assert_eq!(taken_g, 0, "{name}: the switch did not hold");
        assert!(fast_pred.len() > 150, "{name}: too few predictions");
        assert!(fast == general, "{name}: the saved models differ");
        assert_eq!(fast_pred, general_pred, "{name}: the predictions differ");
    }
}
