//! Incremental PLS on a linear function.
//!
//! With one regression input the PLS direction is fixed (`u = ±1`) and LWPR's incremental PLS
//! is exact to rounding once the first samples, which entered the sums before `u` turned to the
//! sign of the slope, are forgotten (λ = 0.99 here, so after a few thousand samples). With several inputs the direction `u_j ∝ SXresYres_j` keeps moving with
//! the sample noise of its running sum (by about 1/√(memory)), while `SSs2`, `SSYres`, `SSXres`
//! accumulate projections on past directions; the reference algorithm therefore reproduces a
//! linear function only to about 1e-3 relative, and this test checks that level.

use crate::config::{LwprConfig, MetricInit};
use crate::model::Lwpr;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn wide(add_threshold: f64) -> LwprConfig {
    LwprConfig {
        init_d: MetricInit::Scalar(1e-8),
        update_d: false,
        init_lambda: 0.99,
        final_lambda: 0.99,
        add_threshold,
        ..Default::default()
    }
}

/// One RF, kernel on two inputs, regression on one: exact.
#[test]
fn pls_on_linear_function_is_exact_in_one_regression_dim() {
    let cfg = LwprConfig {
        regression_dims: Some(vec![1]),
        ..wide(0.5)
    };
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..5000 {
        let x = [rng.random_range(-1.0..1.0), rng.random_range(-2.0..2.0)];
        m.update(&x, &[0.5 - 1.75 * x[1]]).unwrap();
    }
    assert_eq!(m.n_rfs_total(), 1);
    let mut y = [0.0];
    let mut jac = [0.0; 2];
    for &x1 in &[-1.9, -0.3, 0.0, 0.8, 1.7] {
        m.predict_jacobian(&[0.2, x1], &mut y, &mut jac).unwrap();
        assert!((y[0] - (0.5 - 1.75 * x1)).abs() < 1e-12, "{}", y[0]);
        assert!((jac[1] + 1.75).abs() < 1e-12);
    }
}

/// One very wide RF fed `y = a·x + b` with anisotropic, correlated 4-D inputs: PLS grows to all
/// four directions and reproduces `a` to the level explained in the module docs.
/// (`add_threshold` 0.95 because here the second direction cuts the error only to 0.6×.)
#[test]
fn pls_on_linear_function_converges_in_four_dims() {
    let mut m = Lwpr::new(4, 1, &wide(0.95)).unwrap();
    let a = [1.5, -2.0, 0.7, 3.0];
    let b = 0.25;
    let f = |x: &[f64]| b + (0..4).map(|i| a[i] * x[i]).sum::<f64>();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut sample = || {
        let z: Vec<f64> = (0..4).map(|_| rng.random_range(-1.0..1.0)).collect();
        vec![z[0], 0.1 * z[1] + z[0], 3.0 * z[2], 0.5 * z[3] - z[2]]
    };
    for _ in 0..30000 {
        let x = sample();
        m.update(&x, &[f(&x)]).unwrap();
    }
    assert_eq!(m.n_rfs_total(), 1);
    let rf = m.rfs(0).unwrap().next().unwrap();
    assert_eq!(rf.n_reg(), vec![4], "PLS grew to all directions");
    let lm = rf.local_model(0).unwrap();
    for i in 0..4 {
        assert!(
            (lm.slope[i] - a[i]).abs() < 0.02 * a[i].abs(),
            "slope {i}: {}",
            lm.slope[i]
        );
    }
    let mut y = [0.0];
    for _ in 0..50 {
        let x = sample();
        m.predict(&x, &mut y).unwrap();
        let scale: f64 = (0..4).map(|i| (a[i] * x[i]).abs()).sum();
        assert!((y[0] - f(&x)).abs() < 0.02 * scale, "{} vs {}", y[0], f(&x));
    }
}
