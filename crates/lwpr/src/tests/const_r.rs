//! The update with two PLS directions as a constant (`rf_update::output_step::<2>`, used when
//! the dimensions are compile-time constants) against the general path, bit for bit, including
//! updates where a third direction is added.

use crate::config::{LwprConfig, MetricInit};
use crate::model::Lwpr;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cell::Cell;

thread_local! {
    /// Set: every output takes the general path (see `rf_update::force_dynamic`).
    pub(crate) static FORCE_DYNAMIC: Cell<bool> = const { Cell::new(false) };
    /// Outputs that took the constant-direction path (counted when it is not switched off;
    /// 2-D RFs updated in groups, `rf_update_group`, are not counted).
    pub(crate) static FAST_PATH_TAKEN: Cell<u64> = const { Cell::new(0) };
}

/// Trains a 21-input model (a shape compiled with constant dimensions) on a linear function of
/// three inputs of very different spreads, which PLS needs three directions for (its first
/// direction follows the covariance, nearly the widest input alone); returns the saved model
/// and the number of RFs with more than two directions.
fn train(force_dynamic: bool, cfg: &LwprConfig) -> (Vec<u8>, usize) {
    FORCE_DYNAMIC.with(|f| f.set(force_dynamic));
    let mut m = Lwpr::new(21, 1, cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let spread = |i: usize| [1.0, 0.1, 0.01].get(i).copied().unwrap_or(0.0);
    for _ in 0..1500 {
        let x: Vec<f64> = (0..21)
            .map(|i| spread(i) * rng.random_range(-1.0..1.0))
            .collect();
        let y = x[0] + 10.0 * x[1] + 100.0 * x[2];
        m.update(&x, &[y]).unwrap();
    }
    FORCE_DYNAMIC.with(|f| f.set(false));
    let grown = m.rfs(0).unwrap().filter(|r| r.n_reg()[0] > 2).count();
    (m.to_bytes(), grown)
}

#[test]
fn constant_two_directions_match_the_general_path() {
    for (diag_only, meta) in [(true, false), (false, true)] {
        let cfg = LwprConfig {
            init_d: MetricInit::Scalar(0.05),
            diag_only,
            meta,
            init_lambda: 0.99,
            final_lambda: 0.995,
            ..Default::default()
        };
        FAST_PATH_TAKEN.with(|n| n.set(0));
        let (fast, grown) = train(false, &cfg);
        let taken = FAST_PATH_TAKEN.with(|n| n.get());
        let (general, grown_g) = train(true, &cfg);
        assert!(
            taken > 1000,
            "the constant path ran {taken} times: the test misses its case"
        );
        assert_eq!(
            FAST_PATH_TAKEN.with(|n| n.get()),
            taken,
            "the switch did not hold"
        );
        assert!(
            grown > 0,
            "no RF grew a third direction: the test misses its case"
        );
        assert_eq!(grown, grown_g);
        assert!(fast == general, "diag_only {diag_only}: the models differ");
    }
}
