//! The joints' inverse inertia `(M⁻¹)_jj` measured in the warm-up, and the bound it sets on a
//! local controller's learned velocity gain (`docs/decisions.md`, D21).
//!
//! Near home, `q̈ ≈ B u + K_q q + K_q̇ q̇ + k` with `B = M⁻¹` (the rest are gravity's and the
//! velocity terms' linearisation): a least-squares fit of the warm-up's `q̈ = Δq̇/dt` on
//! `[u, q, q̇, 1]` gives `B`, identified by the babbling's torque noise and target steps. A joint
//! whose net velocity feedback is `D` (N·m·s/rad) under a command held for `Δt` is stable in
//! discrete time only while `D Δt (M⁻¹)_jj < 2`; the learner keeps a learned loop within half
//! of that and without negative net damping: `0 ≤ K_D,j − β_{q̇_j, j} ≤ share · 2 / (Δt B_jj)`.
//! Measurements only: the robot's model is not read.

use nalgebra::{DMatrix, DVector};
use osrl_dynamics::Measurement;

/// `(M⁻¹)_jj` per joint from the warm-up `warm` (period `dt`); NaN where the fit fails or the
/// estimate is not positive (no bound there).
pub(crate) fn inverse_inertia_diagonal(warm: &[Measurement], dt: f64) -> Vec<f64> {
    let n = warm.first().map_or(0, |w| w.q.len());
    let Some(b) = inverse_inertia_matrix(warm, dt) else {
        return vec![f64::NAN; n];
    };
    (0..n)
        .map(|j| {
            let v = b[(j, j)];
            if v.is_finite() && v > 0.0 {
                v
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// The whole `B = M⁻¹` (n×n, `B_ij = ∂q̈_i/∂u_j`, not symmetrised) from the same fit; `None`
/// where there are too few samples or the fit is singular.
pub(crate) fn inverse_inertia_matrix(warm: &[Measurement], dt: f64) -> Option<DMatrix<f64>> {
    let first = warm.first()?;
    let n = first.q.len();
    let p = 3 * n + 1;
    let k = warm.len().saturating_sub(1);
    if k < 2 * p {
        return None;
    }
    let mut x = DMatrix::zeros(k, p);
    let mut y = DMatrix::zeros(k, n);
    for (r, pair) in warm.windows(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        for j in 0..n {
            x[(r, j)] = b.u[j];
            x[(r, n + j)] = a.q[j];
            x[(r, 2 * n + j)] = a.qd[j];
            y[(r, j)] = (b.qd[j] - a.qd[j]) / dt;
        }
        x[(r, 3 * n)] = 1.0;
    }
    // Columns scaled to unit RMS so that one small ridge suits torques and angles alike.
    let scale = DVector::from_iterator(
        p,
        (0..p).map(|c| (x.column(c).norm_squared() / k as f64).sqrt().max(1e-12)),
    );
    for c in 0..p {
        x.column_mut(c).unscale_mut(scale[c]);
    }
    let mut gram = x.transpose() * &x;
    for c in 0..p {
        gram[(c, c)] += 1e-9 * k as f64;
    }
    let chol = gram.cholesky()?;
    let coef = chol.solve(&(x.transpose() * &y));
    Some(DMatrix::from_fn(n, n, |i, j| coef[(j, i)] / scale[j]))
}

/// Bounds `[lo, hi]` of the learned velocity gain `β_{q̇_j, j}` of each joint: `hi = K_D,j` (no
/// negative net damping), `lo = K_D,j − share · 2 / (Δt B_jj)`; `−∞` where `B_jj` is unknown.
pub(crate) fn velocity_gain_bounds(
    kd: &[f64],
    inv_inertia: &[f64],
    dt: f64,
    share: f64,
) -> (Vec<f64>, Vec<f64>) {
    let lo = kd
        .iter()
        .zip(inv_inertia)
        .map(|(k, b)| {
            if b.is_finite() && *b > 0.0 {
                k - share * 2.0 / (dt * b)
            } else {
                f64::NEG_INFINITY
            }
        })
        .collect();
    (lo, kd.to_vec())
}
