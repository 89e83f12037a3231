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
//! The general path here is the reference (`update::reference::Reference`: the code of
//! `update/` and `predict/blend.rs` alone, dimensions from the model); the fast path is the
//! production one (the RF groups of `fast/group.rs` included, compared on their own in
//! `group.rs`).

use super::paths::{predict_reference, update_flags, update_reference};
use crate::config::{Kernel, LwprConfig};
use crate::fast::{ALL, GROUPS};
use crate::model::Lwpr;
use crate::norm::Norm;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// What a run gives: the saved model, the predictions of every update and then of the model
/// on a fixed set of inputs, the RF updates, the rates that a step halved (with meta learning
/// off, where only halving changes a rate: elements of `M` with a rate below `init_alpha`) and
/// the pruned RFs, and the updates whose active RFs form groups of two and of three (if every
/// RF has two directions, as in 2-D models).
pub(crate) type Run = (Vec<u8>, Vec<u64>, u64, u64, usize, [u64; 2]);

/// The paths a test trains on.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Path {
    /// Production.
    Fast,
    /// Production without the RF groups.
    NoGroups,
    /// The reference.
    Reference,
}

/// Trains `m` on `n` samples (seed `seed`) on the fast path or (`general`) the reference. Targets: the cross
/// function of inputs 0 and 1 plus a linear term in the last input, with noise; a second
/// output, if any, is its negative plus the first input.
pub(crate) fn train(general: bool, m: &mut Lwpr, seed: u64, n: usize) -> Run {
    train_on(
        if general { Path::Reference } else { Path::Fast },
        m,
        seed,
        n,
    )
}

/// [`train`] on `path`.
pub(crate) fn train_on(path: Path, m: &mut Lwpr, seed: u64, n: usize) -> Run {
    let general = path == Path::Reference;
    let (n_in, n_out) = (m.params().n_in, m.params().n_out);
    assert_eq!(
        (m.params().nk(), m.params().nr()),
        (2, 2),
        "not the 2-D shape"
    );
    let mut rf_updates = 0;
    let mut sizes = [0; 2];
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
        let info = match path {
            Path::Reference => update_reference(m, &x, &y[..n_out]),
            Path::NoGroups => update_flags::<{ ALL & !GROUPS }>(m, &x, &y[..n_out]),
            Path::Fast => m.update(&x, &y[..n_out]).unwrap(),
        };
        rf_updates += info.updated as u64;
        // The groups `fast/group.rs` forms of `u` active RFs (threes, twos when 2 or 4 are left).
        let u = info.updated;
        sizes[0] += (u >= 2 && u % 3 != 0) as u64;
        sizes[1] += (u == 3 || u >= 5) as u64;
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
        let y = if general {
            predict_reference(m, &x)
        } else {
            m.predict(&x, &mut y).is_ok().then_some(y)
        };
        if let Some(y) = y {
            preds.extend(y.iter().map(|v| v.to_bits()));
        }
    }
    (
        m.to_bytes(),
        preds,
        rf_updates,
        halved_rates(m),
        pruned,
        sizes,
    )
}

/// With meta learning off, the elements of `M` (over all RFs) whose rate is below
/// `init_alpha`: halved by a step at least once (or copied from an RF that was); 0 with meta
/// learning on.
fn halved_rates(m: &Lwpr) -> u64 {
    let cfg = &m.params().cfg;
    if cfg.meta {
        return 0;
    }
    let mut n = 0;
    for s in 0..m.n_sub() {
        for v in m.rfs(s).unwrap() {
            let (r, nk) = (v.learning_rates(), m.params().nk());
            n += (0..nk)
                .flat_map(|i| (i..nk).map(move |j| (i, j)))
                .filter(|&(i, j)| r[(i, j)] < cfg.init_alpha)
                .count() as u64;
        }
    }
    n
}

/// Asserts that the two paths agree and that RFs were updated; returns the halved rates and
/// the pruned RFs.
fn compare(name: &str, fast: Run, general: Run) -> (u64, usize) {
    assert!(fast.2 > 5_000, "{name}: {} RF updates", fast.2);
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
            // Large rates without meta learning: steps that would exceed a tenth of max |M|
            // halve the rate instead.
            "no meta, large rates",
            2,
            1,
            LwprConfig {
                meta: false,
                init_alpha: 5000.0,
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
        "no case without meta learning halved a rate: the test misses that branch"
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
