//! The update with two PLS directions as a constant (`R = 2` in `update/regression.rs`, used
//! where the dimensions are compile-time constants) against the general path, bit for bit,
//! including updates where a third direction is added.

use super::paths::{update_flags, Counting, TWO_DIRECTION_STEPS};
use crate::config::{LwprConfig, MetricInit};
use crate::fast::{Fast, ALL, TWO_DIRS};
use crate::model::Lwpr;
use crate::update::{update_sub, Stages};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Trains a 21-input model (a shape of the shape table) with the stages `S` on a linear
/// function of three inputs of very different spreads, which PLS needs three directions for
/// (its first direction follows the covariance, nearly the widest input alone); returns the
/// saved model and the number of RFs with more than two directions.
fn train<S: Stages>(cfg: &LwprConfig) -> (Vec<u8>, usize) {
    train_by(cfg, |m, x, y| {
        m.update_by(x, y, update_sub::<S>).unwrap();
    })
}

/// [`train`] with each update made by `update`.
fn train_by(cfg: &LwprConfig, update: impl Fn(&mut Lwpr, &[f64], &[f64])) -> (Vec<u8>, usize) {
    let mut m = Lwpr::new(21, 1, cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let spread = |i: usize| [1.0, 0.1, 0.01].get(i).copied().unwrap_or(0.0);
    for _ in 0..1500 {
        let x: Vec<f64> = (0..21)
            .map(|i| spread(i) * rng.random_range(-1.0..1.0))
            .collect();
        let y = x[0] + 10.0 * x[1] + 100.0 * x[2];
        update(&mut m, &x, &[y]);
    }
    let grown = m.rfs(0).unwrap().filter(|r| r.n_reg()[0] > 2).count();
    (m.to_bytes(), grown)
}

#[test]
fn constant_two_directions_match_the_general_path() {
    const GENERAL: u8 = ALL & !TWO_DIRS;
    for (diag_only, meta) in [(true, false), (false, true)] {
        let cfg = LwprConfig {
            init_d: MetricInit::Scalar(0.05),
            diag_only,
            meta,
            init_lambda: 0.99,
            final_lambda: 0.995,
            ..Default::default()
        };
        TWO_DIRECTION_STEPS.with(|n| n.set(0));
        let (fast, grown) = train::<Counting<Fast<21, 21, false, ALL>>>(&cfg);
        let taken = TWO_DIRECTION_STEPS.with(|n| n.get());
        let (general, grown_g) = train::<Fast<21, 21, false, GENERAL>>(&cfg);
        // The production dispatch (AVX2 where the CPU has it) gives the same model.
        let (production, _) = train_by(&cfg, |m, x, y| {
            update_flags::<ALL>(m, x, y);
        });
        assert!(
            taken > 1000,
            "the constant path ran {taken} times: the test misses its case"
        );
        assert!(
            grown > 0,
            "no RF grew a third direction: the test misses its case"
        );
        assert_eq!(grown, grown_g);
        assert!(fast == general, "diag_only {diag_only}: the models differ");
        assert!(fast == production);
    }
}
