//! The cross function, its training set and test grid, their embedding in more dimensions and
//! the model configs of the two standard tests.

use crate::{LwprConfig, MetricInit};
use nalgebra::DMatrix;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// `max(exp(−10 x₁²), exp(−50 x₂²), 1.25 exp(−5(x₁² + x₂²)))`.
pub fn cross(x1: f64, x2: f64) -> f64 {
    let a = (-10.0 * x1 * x1).exp();
    let b = (-50.0 * x2 * x2).exp();
    let c = 1.25 * (-5.0 * (x1 * x1 + x2 * x2)).exp();
    a.max(b).max(c)
}

/// A data set: inputs and scalar targets.
pub struct Data {
    /// Inputs, one row per sample.
    pub x: Vec<Vec<f64>>,
    /// Targets.
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

/// The cross test's model config: `init_D = 25·I`, `init_alpha` 250, `w_gen` 0.2, full metric,
/// meta learning with rate 250, the rest default.
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

/// The 21-D test's model config: `init_D = 0.25·I`, `init_alpha` 250, `w_gen` 0.2, full
/// metric, meta learning with rate 250, `w_prune` 0.7, the reference C library's prune rule
/// (see [`crate::PruneRule`]).
pub fn cross21_config() -> LwprConfig {
    LwprConfig {
        init_d: MetricInit::Scalar(0.25),
        init_alpha: 250.0,
        w_gen: 0.2,
        diag_only: false,
        meta: true,
        meta_rate: 250.0,
        w_prune: 0.7,
        ..Default::default()
    }
}

/// How the 21-D cross test puts its 2-D points into 21 dimensions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Embedding {
    /// By one random rotation per seed (the standard test).
    Rotation,
    /// Unrotated: the points in inputs 0 and 1, zeros in the other 19. The same samples as
    /// [`Embedding::Rotation`] with the same seed; LWPR is not rotation-invariant (the metric
    /// is learnt through its Cholesky factor and with a rate per element, PLS starts from the
    /// coordinate axes), so this isolates what the rotation costs.
    Identity,
}

/// The 21-D cross test's data for `seed`: the 500 training points of [`cross_train`] (from a
/// generator seeded with `seed`) and the test grid, both embedded by `e`, and the matrix `R`
/// that embeds them (`x = R · [x₁, x₂, 0, …]`; drawn after the points, so both embeddings of
/// a seed share them; the identity for [`Embedding::Identity`]).
pub fn cross21_data(seed: u64, e: Embedding) -> (Data, Data, DMatrix<f64>) {
    cross_nd_data(seed, 21, e)
}

/// [`cross21_data`] in `d ≥ 2` dimensions (`R` is `d × d`; the 2-D points are the same for
/// every `d`). Panics for `d < 2`.
pub fn cross_nd_data(seed: u64, d: usize, e: Embedding) -> (Data, Data, DMatrix<f64>) {
    assert!(
        d >= 2,
        "the cross test needs at least 2 dimensions, got {d}"
    );
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let train = cross_train(&mut rng, 500);
    let rot = match e {
        Embedding::Rotation => rotation(&mut rng, d),
        Embedding::Identity => DMatrix::identity(d, d),
    };
    (embed(&train, &rot), embed(&cross_grid(), &rot), rot)
}
