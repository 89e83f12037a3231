//! Seeded train-and-test runs of the cross tests: nMSE, RFs, µs per call.

use super::cross::{cross_grid, cross_nd_data, cross_train, Data, Embedding};
use crate::{Lwpr, LwprConfig, LwprError};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// Result of one run.
#[derive(Debug, Clone, Copy)]
pub struct RunResult {
    /// Test MSE / variance of the test targets.
    pub nmse: f64,
    /// Receptive fields at the end of training.
    pub n_rfs: usize,
    /// Wall-clock µs per update, mean over all epochs.
    pub update_us: f64,
    /// Wall-clock µs per prediction, mean over the test set.
    pub predict_us: f64,
    /// The numerical guards' counts over the training ([`crate::Lwpr::warnings`]).
    pub warnings: crate::Warnings,
}

/// Trains a one-output model on `train` for `epochs` epochs, each in a fresh order shuffled by
/// a generator seeded with `seed`, then tests on `test`; a test point without an active RF
/// predicts 0 (as the reference library would). Times are wall-clock means per call. Fails
/// when `epochs` is 0, a data set is empty, the config is invalid for the data or a sample is
/// not finite.
pub fn run(
    cfg: &LwprConfig,
    train: &Data,
    test: &Data,
    epochs: usize,
    seed: u64,
) -> Result<RunResult, LwprError> {
    if test.x.is_empty() {
        return Err(LwprError::Config(
            "a benchmark run needs samples to test on (0 test samples)".into(),
        ));
    }
    let (mut m, update_us) = fit(cfg, train, epochs, seed)?;
    let t1 = Instant::now();
    let nmse = test_nmse(&mut m, test)?;
    let predict_us = t1.elapsed().as_secs_f64() * 1e6 / test.x.len() as f64;
    Ok(RunResult {
        nmse,
        n_rfs: m.n_rfs_total(),
        update_us,
        predict_us,
        warnings: m.warnings(),
    })
}

/// The training of [`run`]: the model after `epochs` epochs on `train` (each in a fresh order
/// from a generator seeded with `seed ^ 0x5eed`, so that the order is not drawn from the
/// stream that drew the data) and the wall-clock µs per update (mean). Fails when `epochs` is
/// 0, `train` is empty, the config is invalid for the data or a sample is not finite.
pub fn fit(
    cfg: &LwprConfig,
    train: &Data,
    epochs: usize,
    seed: u64,
) -> Result<(Lwpr, f64), LwprError> {
    if epochs == 0 || train.x.is_empty() {
        return Err(LwprError::Config(format!(
            "training needs at least one epoch and samples to train on \
             (epochs {epochs}, {} training samples)",
            train.x.len()
        )));
    }
    let n_in = train.x[0].len();
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let mut m = Lwpr::new(n_in, 1, cfg)?;
    let mut order: Vec<usize> = (0..train.x.len()).collect();
    let t0 = Instant::now();
    for _ in 0..epochs {
        order.shuffle(&mut rng);
        for &i in &order {
            m.update(&train.x[i], &[train.y[i]])?;
        }
    }
    let update_us = t0.elapsed().as_secs_f64() * 1e6 / (epochs * train.x.len()) as f64;
    Ok((m, update_us))
}

/// Median of `v` (the mean of the middle two for an even count; NaN when empty), as the
/// benchmarks report their per-seed results.
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => v[n / 2],
        _ => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// The prediction of a one-output model at `x`, 0 where no RF is active (as the reference
/// library predicts there, and as the benchmarks score it). Fails when `x` does not fit the
/// model (wrong length, not finite) or the model has more than one output.
pub fn predict_or_zero(m: &mut Lwpr, x: &[f64]) -> Result<f64, LwprError> {
    let mut y = [0.0];
    match m.predict(x, &mut y) {
        Ok(_) => Ok(y[0]),
        Err(LwprError::NoActiveRf { .. }) => Ok(0.0),
        Err(e) => Err(e),
    }
}

/// [`predict_or_zero`] with the confidence bound of [`Lwpr::predict_conf`]: `(ŷ, conf)`, and
/// `(0, NaN)` where no RF is active (the reference library reports 1e20 there). Fails as
/// [`predict_or_zero`] does.
pub fn predict_conf_or_nan(m: &mut Lwpr, x: &[f64]) -> Result<(f64, f64), LwprError> {
    let (mut y, mut conf) = ([0.0], [0.0]);
    match m.predict_conf(x, &mut y, &mut conf) {
        Ok(_) => Ok((y[0], conf[0])),
        Err(LwprError::NoActiveRf { .. }) => Ok((0.0, f64::NAN)),
        Err(e) => Err(e),
    }
}

/// Test MSE of `m` on `test` over the variance of its targets; a point without an active RF
/// predicts 0 ([`predict_or_zero`]). NaN for an empty `test`. Fails when a test input does not
/// fit the model (wrong length, not finite).
pub fn test_nmse(m: &mut Lwpr, test: &Data) -> Result<f64, LwprError> {
    let mut se = 0.0;
    for (x, &t) in test.x.iter().zip(&test.y) {
        let p = predict_or_zero(m, x)?;
        se += (p - t) * (p - t);
    }
    let n = test.y.len() as f64;
    let mean = test.y.iter().sum::<f64>() / n;
    let var = test.y.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    Ok(se / n / var)
}

/// The standard cross test with one seed: 500 training points, `epochs` epochs (20 in the
/// standard test), `cfg` (normally [`cross_config`]).
pub fn cross_run(cfg: &LwprConfig, seed: u64, epochs: usize) -> Result<RunResult, LwprError> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let train = cross_train(&mut rng, 500);
    run(cfg, &train, &cross_grid(), epochs, seed)
}

/// The 21-D rotated cross with one seed: the 500 training points and the test grid embedded
/// by one random rotation, `epochs` epochs (25 in the standard test), `cfg` (normally
/// [`cross21_config`]).
pub fn cross21_run(cfg: &LwprConfig, seed: u64, epochs: usize) -> Result<RunResult, LwprError> {
    cross21_embedded_run(cfg, seed, epochs, Embedding::Rotation)
}

/// [`cross21_run`] with the embedding `e`.
pub fn cross21_embedded_run(
    cfg: &LwprConfig,
    seed: u64,
    epochs: usize,
    e: Embedding,
) -> Result<RunResult, LwprError> {
    cross_nd_run(cfg, seed, epochs, 21, e)
}

/// [`cross21_embedded_run`] in `d ≥ 2` dimensions (the reference library's Matlab test
/// `test_lwpr_nD.m` uses 25; issue 4 uses 21). Fails for `d < 2` or a config `cfg` that does
/// not fit `d` inputs.
pub fn cross_nd_run(
    cfg: &LwprConfig,
    seed: u64,
    epochs: usize,
    d: usize,
    e: Embedding,
) -> Result<RunResult, LwprError> {
    if d < 2 {
        return Err(LwprError::Config(format!(
            "the cross test needs at least 2 dimensions, got {d}"
        )));
    }
    let (train, test, _) = cross_nd_data(seed, d, e);
    run(cfg, &train, &test, epochs, seed)
}
