//! Shared fixtures of the cross-check tests: the built-in robots, random arms and random states.

#![allow(dead_code)]

use osrl_dynamics::{robots, Model};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// planar3, sarcos7 and four random arms (with and without friction).
pub fn models() -> Vec<Model> {
    vec![
        robots::planar3(),
        robots::sarcos7(),
        robots::random_arm(2, 1, false),
        robots::random_arm(5, 2, true),
        robots::random_arm(7, 3, false),
        robots::random_arm(9, 4, true),
    ]
}

/// A seeded generator.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A vector of `n` uniform draws in [−scale, scale].
pub fn rand_vec(rng: &mut ChaCha8Rng, n: usize, scale: f64) -> Vec<f64> {
    (0..n).map(|_| rng.random_range(-scale..scale)).collect()
}

/// Largest absolute entry of `a − b`.
pub fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
