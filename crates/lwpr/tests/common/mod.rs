//! Shared data sets for tests and the `cross` example: the reference library's 2-D "cross"
//! and its 21-D rotated version (`shared/LWPR.md`, issue 4).
#![allow(dead_code)]

use lwpr::{Lwpr, LwprConfig, MetricInit};
use nalgebra::DMatrix;
use rand::seq::SliceRandom;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use std::time::Instant;

/// `max(exp(−10 x₁²), exp(−50 x₂²), 1.25 exp(−5(x₁² + x₂²)))`.
pub fn cross(x1: f64, x2: f64) -> f64 {
    let a = (-10.0 * x1 * x1).exp();
    let b = (-50.0 * x2 * x2).exp();
    let c = 1.25 * (-5.0 * (x1 * x1 + x2 * x2)).exp();
    a.max(b).max(c)
}

/// A data set: inputs and scalar targets.
pub struct Data {
    pub x: Vec<Vec<f64>>,
    pub y: Vec<f64>,
}

/// 500 points `x ~ U[−1,1]²`, targets with N(0, 0.1²) noise.
pub fn cross_train(rng: &mut ChaCha8Rng, n: usize) -> Data {
    let noise = Normal::new(0.0, 0.1).unwrap();
    let mut d = Data {
        x: vec![],
        y: vec![],
    };
    for _ in 0..n {
        let (a, b) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
        d.x.push(vec![a, b]);
        d.y.push(cross(a, b) + noise.sample(rng));
    }
    d
}

/// The noiseless 41×41 grid on [−1, 1]².
pub fn cross_grid() -> Data {
    let mut d = Data {
        x: vec![],
        y: vec![],
    };
    for i in 0..41 {
        for j in 0..41 {
            let (a, b) = (-1.0 + 0.05 * i as f64, -1.0 + 0.05 * j as f64);
            d.x.push(vec![a, b]);
            d.y.push(cross(a, b));
        }
    }
    d
}

/// A random `n × n` rotation (QR of a Gaussian matrix, signs fixed).
pub fn rotation(rng: &mut ChaCha8Rng, n: usize) -> DMatrix<f64> {
    let g = DMatrix::from_fn(n, n, |_, _| Normal::new(0.0, 1.0).unwrap().sample(rng));
    let qr = g.qr();
    let (mut q, r) = (qr.q(), qr.r());
    for j in 0..n {
        if r[(j, j)] < 0.0 {
            q.column_mut(j).neg_mut();
        }
    }
    q
}

/// Embeds 2-D points in `n` dimensions: `R · [x₁, x₂, 0, …]`.
pub fn embed(d: &Data, rot: &DMatrix<f64>) -> Data {
    let n = rot.nrows();
    let x =
        d.x.iter()
            .map(|p| {
                (0..n)
                    .map(|i| rot[(i, 0)] * p[0] + rot[(i, 1)] * p[1])
                    .collect()
            })
            .collect();
    Data { x, y: d.y.clone() }
}

/// The cross test's model config.
pub fn cross_config() -> LwprConfig {
    LwprConfig {
        init_d: MetricInit::Scalar(25.0),
        init_alpha: 250.0,
        w_gen: 0.2,
        diag_only: false,
        meta: true,
        meta_rate: 250.0,
        ..Default::default()
    }
}

/// `LWPR_PRUNE=narrower` selects `shared/LWPR.md`'s prune rule (for the benchmark example);
/// the default is the reference C library's (remove the wider RF).
pub fn prune_rule() -> lwpr::PruneRule {
    match std::env::var("LWPR_PRUNE").as_deref() {
        Ok("narrower") => lwpr::PruneRule::Narrower,
        _ => lwpr::PruneRule::Wider,
    }
}

/// The 21-D test's model config (issue 4).
pub fn cross21_config() -> LwprConfig {
    LwprConfig {
        init_d: MetricInit::Scalar(0.25),
        init_alpha: 250.0,
        w_gen: 0.2,
        diag_only: false,
        meta: true,
        meta_rate: 250.0,
        w_prune: 0.7,
        prune_rule: prune_rule(),
        ..Default::default()
    }
}

/// Result of one run.
#[derive(Debug, Clone, Copy)]
pub struct RunResult {
    pub nmse: f64,
    pub n_rfs: usize,
    pub update_us: f64,
    pub predict_us: f64,
}

/// Trains for `epochs` shuffled epochs, tests on `test`; unsupported test points predict 0
/// (as the reference library would).
pub fn run(cfg: &LwprConfig, train: &Data, test: &Data, epochs: usize, seed: u64) -> RunResult {
    let n_in = train.x[0].len();
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let mut m = Lwpr::new(n_in, 1, cfg).unwrap();
    let mut order: Vec<usize> = (0..train.x.len()).collect();
    let t0 = Instant::now();
    for _ in 0..epochs {
        order.shuffle(&mut rng);
        for &i in &order {
            m.update(&train.x[i], &[train.y[i]]).unwrap();
        }
    }
    let update_us = t0.elapsed().as_secs_f64() * 1e6 / (epochs * train.x.len()) as f64;
    let t1 = Instant::now();
    let mut y = [0.0];
    let mut se = 0.0;
    for (x, &t) in test.x.iter().zip(&test.y) {
        let p = match m.predict(x, &mut y) {
            Ok(_) => y[0],
            Err(_) => 0.0,
        };
        se += (p - t) * (p - t);
    }
    let predict_us = t1.elapsed().as_secs_f64() * 1e6 / test.x.len() as f64;
    let n = test.y.len() as f64;
    let mean = test.y.iter().sum::<f64>() / n;
    let var = test.y.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    RunResult {
        nmse: se / n / var,
        n_rfs: m.n_rfs_total(),
        update_us,
        predict_us,
    }
}

/// The standard cross test with one seed.
pub fn cross_run(seed: u64, epochs: usize) -> RunResult {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let train = cross_train(&mut rng, 500);
    run(&cross_config(), &train, &cross_grid(), epochs, seed)
}

/// The 21-D rotated cross with one seed.
pub fn cross21_run(seed: u64, epochs: usize) -> RunResult {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let train = cross_train(&mut rng, 500);
    let rot = rotation(&mut rng, 21);
    run(
        &cross21_config(),
        &embed(&train, &rot),
        &embed(&cross_grid(), &rot),
        epochs,
        seed,
    )
}
