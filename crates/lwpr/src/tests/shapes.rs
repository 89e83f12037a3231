//! The fast path against the reference, bit for bit, for every shape of the shape table
//! (`fast::SHAPES`) and two shapes outside it, with a full and a diagonal metric: saved models,
//! every update's prediction, and plain predictions after training. The full-metric step above
//! 4 dimensions (`fast/wide.rs`) rounds differently and is switched off here (`wide.rs` tests
//! it against the fused step).

use super::paths::{predict_reference, update_flags, update_reference};
use crate::config::{LwprConfig, MetricInit};
use crate::fast::{ALL, SHAPES, WIDE};
use crate::model::Lwpr;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Trains a model of `nk` kernel and `nr` regression inputs (kernel on the first `nk` of
/// `max(nk, nr)` inputs) on the fast path (`fast`) or the reference; returns the saved model,
/// the predictions and the RF updates.
fn run(fast: bool, nk: usize, nr: usize, diag_only: bool) -> (Vec<u8>, Vec<u64>, usize) {
    let n_in = nk.max(nr);
    let cfg = LwprConfig {
        init_d: MetricInit::Scalar(if n_in > 4 { 0.5 } else { 20.0 }),
        init_alpha: 100.0,
        w_gen: 0.3,
        w_prune: 0.8,
        diag_only,
        meta: true,
        kernel_dims: Some((0..nk).collect()),
        regression_dims: Some((n_in - nr..n_in).collect()),
        ..Default::default()
    };
    let mut m = Lwpr::new(n_in, 1, &cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (mut preds, mut updated) = (Vec::new(), 0);
    for _ in 0..600 {
        let x: Vec<f64> = (0..n_in).map(|_| rng.random_range(-1.0..1.0)).collect();
        let y = (2.0 * x[0]).sin() + x[n_in - 1] * x[0] + 0.05 * rng.random_range(-1.0..1.0);
        let info = if fast {
            update_flags::<{ ALL & !WIDE }>(&mut m, &x, &[y])
        } else {
            update_reference(&mut m, &x, &[y])
        };
        updated += info.updated;
        preds.push(m.last_update_prediction()[0].to_bits());
    }
    for k in 0..50 {
        let x: Vec<f64> = (0..n_in)
            .map(|i| ((k * (i + 5)) % 21) as f64 / 10.0 - 1.0)
            .collect();
        let mut y = [0.0];
        let y = if fast {
            m.predict(&x, &mut y).is_ok().then_some(y.to_vec())
        } else {
            predict_reference(&mut m, &x)
        };
        preds.push(y.map_or(u64::MAX, |y| y[0].to_bits()));
    }
    (m.to_bytes(), preds, updated)
}

#[test]
fn every_shape_gives_the_reference_bits() {
    let others = [(4, 5), (5, 3)];
    for &(nk, nr) in SHAPES.iter().chain(&others) {
        for diag_only in [false, true] {
            let (fast, fp, updated) = run(true, nk, nr, diag_only);
            let (reference, rp, _) = run(false, nk, nr, diag_only);
            let what = format!("shape ({nk}, {nr}), diag_only {diag_only}");
            assert!(updated > 1000, "{what}: {updated} RF updates");
            assert!(fast == reference, "{what}: the saved models differ");
            assert_eq!(fp, rp, "{what}: the predictions differ");
        }
    }
}
