//! The warm-up's measured inverse inertia (`inertia.rs`) against the true one.

use super::inertia::{inverse_inertia_diagonal, velocity_gain_bounds};
use crate::learner::fixture;

/// On the fixture arm (planar, 3 joints) babbled with torque noise, the measured `(M⁻¹)_jj`
/// matches the true inverse mass matrix at the warm-up's mean posture within 20 %, and
/// the bounds follow it: the discrete-time limit `2 / (Δt B_jj)` halved below `K_D`.
#[test]
fn warm_up_measures_the_inverse_inertia() {
    let (warm, truth) = fixture::warm_up_with_inverse_inertia(1000);
    let b = inverse_inertia_diagonal(&warm, 0.002);
    for j in 0..3 {
        let rel = (b[j] - truth[j]).abs() / truth[j];
        assert!(rel < 0.2, "joint {j}: {} vs {}", b[j], truth[j]);
    }
    let (lo, hi) = velocity_gain_bounds(&[1.0, 2.0, 3.0], &b, 0.002, 0.5);
    assert_eq!(hi, vec![1.0, 2.0, 3.0]);
    assert!((lo[0] - (1.0 - 1.0 / (0.002 * b[0]))).abs() < 1e-9);
    let (lo, _) = velocity_gain_bounds(&[1.0], &[f64::NAN], 0.002, 0.5);
    assert_eq!(lo, vec![f64::NEG_INFINITY]);
}
