//! The damping rule of the pseudo-inverse near singularities.

use nalgebra::{Matrix3, Vector3};

/// Damping `λ²` for the task-space system `(A Aᵀ + λ² I) y = r` of eq. 7.
///
/// `G = A Aᵀ` (m×m, m ≤ 3, in the upper-left block of `g`) has eigenvalues `σ_i²`, the squared
/// singular values of `A`. With `ε = threshold` the rule is
///
/// `λ² = max(0, (ε σ_max)² − σ_min²)`
///
/// so nothing changes while `σ_min ≥ ε σ_max` (condition number of `A` below `1/ε`), and below that
/// the smallest eigenvalue of `G + λ²I` is held at `(ε σ_max)²`: the damping switches on
/// continuously and the command stays bounded at and through a singularity (the task acceleration
/// along the lost direction is then only approximately achieved). `ε = 0` switches damping off.
/// The rule is scale-invariant, so it behaves the same for any metric `N`.
///
/// Returns `(λ², σ_min / σ_max)` (the ratio is 0 when `G = 0`).
pub fn damping(g: &Matrix3<f64>, m: usize, threshold: f64) -> (f64, f64) {
    let mut padded = *g;
    // Pad the unused block with an existing diagonal entry: it lies between the block's smallest
    // and largest eigenvalue, so the extremes are unchanged.
    for k in m..3 {
        for l in 0..3 {
            padded[(k, l)] = 0.0;
            padded[(l, k)] = 0.0;
        }
        padded[(k, k)] = g[(0, 0)];
    }
    let ev: Vector3<f64> = padded.symmetric_eigenvalues();
    let (lo, hi) = (ev.min().max(0.0), ev.max().max(0.0));
    let ratio = if hi > 0.0 { (lo / hi).sqrt() } else { 0.0 };
    let lambda2 = (threshold * threshold * hi - lo).max(0.0);
    (lambda2, ratio)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_damping_when_well_conditioned_and_floor_when_singular() {
        let g = Matrix3::from_diagonal(&Vector3::new(4.0, 1.0, 0.0));
        let (l2, r) = damping(&g, 2, 1e-2);
        assert_eq!(l2, 0.0);
        assert!((r - 0.5).abs() < 1e-12);
        // Singular 2×2 block: λ² lifts the zero eigenvalue to (ε σ_max)².
        let s = Matrix3::new(1.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0);
        let (l2, r) = damping(&s, 2, 0.1);
        assert!((l2 - 0.01 * 2.0).abs() < 1e-12, "{l2}");
        assert!(r < 1e-7);
        assert_eq!(damping(&Matrix3::zeros(), 3, 0.1), (0.0, 0.0));
    }
}
