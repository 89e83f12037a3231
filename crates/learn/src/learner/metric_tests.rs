//! Tests of `metric.rs`: the metric `N` of the cost and its null-space projection.

use super::metric::{null_space_cost_in, project_null_in, Metric};
use nalgebra::{DMatrix, DVector};

/// The projection in the metric removes exactly the task part (`Â z = 0` after it), leaves
/// a vector `N`-orthogonal to the range of `N⁻¹ Âᵀ`, and its cost is the `N`-norm of that
/// part; with `N = I` both are the Euclidean ones.
#[test]
fn the_metric_projection_and_cost_follow_their_definitions() {
    let (n, m) = (3, 2);
    let a = [1.0, -2.0, 0.5, 0.3, 0.7, -1.7];
    let nm = DMatrix::from_row_slice(3, 3, &[2.0, 0.3, -0.1, 0.3, 1.0, 0.2, -0.1, 0.2, 0.5]);
    let metric = Metric::from_matrix(nm.clone()).unwrap();
    let du = [0.4, -1.1, 2.0];
    let (mut y, mut s, mut an, mut vn) = (vec![0.0; m], vec![0.0; m * m], vec![0.0; 6], [0.0; 3]);
    let mut z = du;
    assert!(project_null_in(
        Some(&metric),
        &a,
        &mut z,
        m,
        &mut y,
        &mut s,
        &mut an
    ));
    let am = DMatrix::from_row_slice(m, n, &a);
    let zv = DVector::from_column_slice(&z);
    assert!((&am * &zv).amax() < 1e-12, "no task part left");
    // The removed part N⁻¹ Âᵀ λ is N-orthogonal to what is left.
    let removed = DVector::from_column_slice(&du) - &zv;
    assert!((zv.transpose() * &nm * &removed)[(0, 0)].abs() < 1e-12);
    let r =
        null_space_cost_in(Some(&metric), &a, &du, m, &mut y, &mut s, &mut an, &mut vn).unwrap();
    let want = (zv.transpose() * &nm * &zv)[(0, 0)];
    assert!((r - want).abs() < 1e-12, "{r} vs {want}");
    // The identity metric is the Euclidean algebra, to the bit.
    let id = Metric::from_matrix(DMatrix::identity(3, 3)).unwrap();
    let (mut z1, mut z2) = (du, du);
    project_null_in(Some(&id), &a, &mut z1, m, &mut y, &mut s, &mut an);
    project_null_in(None, &a, &mut z2, m, &mut y, &mut s, &mut an);
    assert!(z1.iter().zip(&z2).all(|(p, q)| (p - q).abs() < 1e-14));
}

/// From the fixture arm's babbled warm-up, `N = B̂` is positive definite and its diagonal is
/// the measured `(M⁻¹)_jj`, within 20 % of the true one (as the damping bound's).
#[test]
fn the_warm_up_gives_a_positive_definite_inverse_inertia() {
    let (warm, truth) = crate::learner::fixture::warm_up_with_inverse_inertia(1000);
    let metric = Metric::inverse_inertia(&warm, 0.002).expect("positive definite");
    let n = &metric.l * metric.l.transpose();
    let diag = super::inertia::inverse_inertia_diagonal(&warm, 0.002);
    for j in 0..3 {
        assert!((n[(j, j)] - diag[j]).abs() < 1e-9 * diag[j]);
        assert!((n[(j, j)] - truth[j]).abs() < 0.2 * truth[j], "joint {j}");
    }
}
