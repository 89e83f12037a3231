//! The 2-D code with every dimension a constant (the PLS step `rf_update_2d::regression_2d`,
//! the metric step `metric_2d::step_2d`, the activation pass `activation::for_each_q` of the
//! update and of a plain prediction) against
//! the general path, bit for bit: whole saved models and predictions after training, for
//! every configuration the 2-D path takes (meta learning on and off, metric learning off,
//! Gaussian and BiSquare kernels, shared RFs with one and with two outputs, two outputs with
//! an RF list each, a kernel and a regression on different input pairs, pruning, normalised
//! inputs, fast forgetting), and for RFs whose two directions have seen different amounts of
//! data (as a loaded model may have).
//!
//! The general path here is `output_step::<0>` and `scratch::quad` per RF: `FORCE_DYNAMIC`
//! switches off all four shortcuts (the constant two directions are compared with it in
//! `const_r.rs`).

use super::const_r::FORCE_DYNAMIC;
use crate::config::{Kernel, LwprConfig, Norm};
use crate::model::Lwpr;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cell::Cell;

thread_local! {
    /// PLS steps that took the 2-D path (counted by `rf_update_2d::regression_2d`).
    pub(crate) static TAKEN: Cell<u64> = const { Cell::new(0) };
    /// Elements of `M` whose step the 2-D path halved into a rate cut (`metric_2d`).
    pub(crate) static HALVED: Cell<u64> = const { Cell::new(0) };
}

/// What a run gives: the saved model, the predictions of every update and then of the model
/// on a fixed set of inputs, and the counts of 2-D updates, halved steps and pruned RFs.
pub(crate) type Run = (Vec<u8>, Vec<u64>, u64, u64, usize);

/// Trains `m` on `n` samples (seed `seed`) with the 2-D path on or off. Targets: the cross
/// function of inputs 0 and 1 plus a linear term in the last input, with noise; a second
/// output, if any, is its negative plus the first input.
pub(crate) fn train(general: bool, m: &mut Lwpr, seed: u64, n: usize) -> Run {
    let (n_in, n_out) = (m.params().n_in, m.params().n_out);
    FORCE_DYNAMIC.with(|f| f.set(general));
    TAKEN.with(|c| c.set(0));
    HALVED.with(|c| c.set(0));
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut pruned = 0;
    let mut preds = Vec::new();
    let f = |x: &[f64]| {
        let (a, b) = (x[0], x[1]);
        let cross = (-10.0 * a * a)
            .exp()
            .max((-50.0 * b * b).exp())
            .max(1.25 * (-5.0 * (a * a + b * b)).exp());
        cross + 0.5 * x[n_in - 1]
    };
    for _ in 0..n {
        let x: Vec<f64> = (0..n_in).map(|_| rng.random_range(-1.0..1.0)).collect();
        let y0 = f(&x) + 0.1 * rng.random_range(-1.0..1.0);
        let y = [y0, x[0] - y0];
        let info = m.update(&x, &y[..n_out]).unwrap();
        pruned += info.pruned;
        // The update's own prediction (its blend of the updated RFs) and its guard count.
        preds.extend(m.last_update_prediction().iter().map(|v| v.to_bits()));
        preds.push(info.metric_skipped as u64);
    }
    for k in 0..200 {
        let x: Vec<f64> = (0..n_in)
            .map(|i| ((k * (i + 3)) % 41) as f64 / 20.0 - 1.0)
            .collect();
        let mut y = vec![0.0; n_out];
        if m.predict(&x, &mut y).is_ok() {
            preds.extend(y.iter().map(|v| v.to_bits()));
        }
    }
    FORCE_DYNAMIC.with(|f| f.set(false));
    let counts = (TAKEN.with(|c| c.get()), HALVED.with(|c| c.get()));
    (m.to_bytes(), preds, counts.0, counts.1, pruned)
}

/// Asserts that the two paths agree and that the 2-D one ran; returns the halved steps and
/// the pruned RFs.
fn compare(name: &str, fast: Run, general: Run) -> (u64, usize) {
    assert!(fast.2 > 5_000, "{name}: the 2-D path ran {} times", fast.2);
    assert_eq!(general.2, 0, "{name}: the 2-D path ran with the switch on");
    assert!(fast.1.len() > 150, "{name}: too few predictions");
    assert!(fast.0 == general.0, "{name}: the saved models differ");
    assert_eq!(fast.1, general.1, "{name}: the predictions differ");
    (fast.3, fast.4)
}

/// The cross test's config (full metric, meta learning).
fn base() -> LwprConfig {
    crate::datasets::cross_config()
}

/// The configurations the 2-D path takes: (name, inputs, outputs, config).
pub(crate) fn cases() -> Vec<(&'static str, usize, usize, LwprConfig)> {
    let b = base();
    vec![
        ("cross, meta", 2, 1, b.clone()),
        (
            "no meta",
            2,
            1,
            LwprConfig {
                meta: false,
                ..b.clone()
            },
        ),
        (
            "no metric learning",
            2,
            1,
            LwprConfig {
                update_d: false,
                ..b.clone()
            },
        ),
        (
            "bisquare, large rates",
            2,
            1,
            LwprConfig {
                kernel: Kernel::Bisquare,
                init_alpha: 5000.0,
                ..b.clone()
            },
        ),
        (
            "shared RFs",
            2,
            1,
            LwprConfig {
                shared_rfs: true,
                ..b.clone()
            },
        ),
        (
            "shared RFs, two outputs",
            2,
            2,
            LwprConfig {
                shared_rfs: true,
                ..b.clone()
            },
        ),
        ("two outputs, an RF list each", 2, 2, b.clone()),
        (
            "kernel on (0, 1), regression on (1, 2)",
            3,
            1,
            LwprConfig {
                kernel_dims: Some(vec![0, 1]),
                regression_dims: Some(vec![1, 2]),
                ..b.clone()
            },
        ),
        (
            // Pruning: the two nearest RFs of the activation pass decide which one goes.
            "pruning",
            2,
            1,
            LwprConfig {
                w_prune: 0.5,
                ..b.clone()
            },
        ),
        (
            "normalised inputs, fast forgetting",
            2,
            1,
            LwprConfig {
                norm_in: Norm::List(vec![0.5, 2.0]),
                init_lambda: 0.99,
                final_lambda: 0.995,
                ..b.clone()
            },
        ),
        (
            // λ ≈ 0.9: the cost terms and error sums start while the second direction does
            // not predict yet (n_data ≤ 4).
            "very fast forgetting",
            2,
            1,
            LwprConfig {
                init_lambda: 0.9,
                final_lambda: 0.95,
                tau_lambda: 0.99,
                ..b.clone()
            },
        ),
    ]
}

#[test]
fn the_2d_update_matches_the_general_path() {
    let mut halved = 0;
    for (name, n_in, n_out, cfg) in cases() {
        let run = |general| {
            train(
                general,
                &mut Lwpr::new(n_in, n_out, &cfg).unwrap(),
                11,
                3000,
            )
        };
        let (h, pruned) = compare(name, run(false), run(true));
        halved += h;
        assert!(
            name != "pruning" || pruned > 10,
            "{name}: {pruned} RFs pruned, too few to test the choice"
        );
    }
    assert!(
        halved > 0,
        "no case halved a step: the test misses that branch"
    );
}

/// RFs whose second direction has seen less data than the first (`n_data₁ < n_data₀`), so
/// that it is left out of the cost terms (`n_data₁·(1 − λ₀) ≤ 0.1`) or of the prediction
/// (`n_data₁ ≤ 4`) while the first is in: a trained model so edited, then trained on by
/// both paths.
#[test]
fn the_2d_update_matches_with_unequal_directions() {
    let cfg = base();
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    train(false, &mut m, 5, 1500);
    for (k, rf) in m.subs[0].rfs.iter_mut().enumerate() {
        let s = &mut rf.outs[0];
        s.n_data[1] = if k % 2 == 0 { 2.0 } else { 0.05 * s.n_data[0] };
    }
    let bytes = m.to_bytes();
    let run = |general| train(general, &mut Lwpr::from_bytes(&bytes).unwrap(), 6, 1500);
    compare("unequal directions", run(false), run(true));
}
