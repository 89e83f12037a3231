//! Shared test data.
#![allow(dead_code)]

use nalgebra::DMatrix;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `n` random samples: features `n × p`, actions `n × d`, costs in `[0, cost_max)`.
pub fn random_samples(
    seed: u64,
    n: usize,
    p: usize,
    d: usize,
    cost_max: f64,
) -> (DMatrix<f64>, DMatrix<f64>, Vec<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let phi = DMatrix::from_fn(n, p, |_, _| rng.random_range(-2.0..2.0));
    let u = DMatrix::from_fn(n, d, |_, _| rng.random_range(-3.0..3.0));
    let costs = (0..n).map(|_| rng.random_range(0.0..cost_max)).collect();
    (phi, u, costs)
}

/// Row `i` of a matrix as a vector.
pub fn row(m: &DMatrix<f64>, i: usize) -> Vec<f64> {
    m.row(i).iter().copied().collect()
}
