//! The null space of the learned input gain `Â = ∂ẍ/∂u` (m×n, row-major): the part of a command
//! that does not change the task acceleration (to first order). The reward uses the cost of that
//! part, hindsight shrinks it, exploration explores in it (`docs/learner.md`).

/// `r_null = ‖du‖² − duᵀ Âᵀ (Â Âᵀ)⁻¹ Â du`, the part of `‖du‖²` in the null space of `Â`;
/// `None` if `Â Âᵀ` is not positive definite. `y` (m) and `s` (m×m) are scratch.
pub(crate) fn null_space_cost(
    a: &[f64],
    du: &[f64],
    m: usize,
    y: &mut [f64],
    s: &mut [f64],
) -> Option<f64> {
    if !gain_system(a, du, m, y, s) {
        return None;
    }
    // yᵀ S⁻¹ y = ‖L⁻¹ y‖², and y now holds L⁻¹ Â du.
    let quad: f64 = y[..m].iter().map(|v| v * v).sum();
    let full: f64 = du.iter().map(|v| v * v).sum();
    Some((full - quad).max(0.0))
}

/// `z ← z − Âᵀ (Â Âᵀ)⁻¹ Â z`, the projection onto the null space of `Â`; `false` (z unchanged)
/// if `Â Âᵀ` is singular.
pub(crate) fn project_null(
    a: &[f64],
    z: &mut [f64],
    m: usize,
    y: &mut [f64],
    s: &mut [f64],
) -> bool {
    if !gain_system(a, z, m, y, s) {
        return false;
    }
    // Back substitution: y ← L⁻ᵀ L⁻¹ Â z = S⁻¹ Â z.
    for k in (0..m).rev() {
        let mut v = y[k];
        for j in k + 1..m {
            v -= s[j * m + k] * y[j];
        }
        y[k] = v / s[k * m + k];
    }
    let n = z.len();
    for j in 0..n {
        z[j] -= (0..m).map(|k| a[k * n + j] * y[k]).sum::<f64>();
    }
    true
}

/// Forms `S = Â Âᵀ` (m×m) and `y = Â v`, factors `S = L Lᵀ` in place and sets `y ← L⁻¹ y`;
/// `false` if `S` is not positive definite.
fn gain_system(a: &[f64], v: &[f64], m: usize, y: &mut [f64], s: &mut [f64]) -> bool {
    let n = v.len();
    for k in 0..m {
        y[k] = (0..n).map(|j| a[k * n + j] * v[j]).sum();
        for l in 0..m {
            s[k * m + l] = (0..n).map(|j| a[k * n + j] * a[l * n + j]).sum();
        }
    }
    if !cholesky(s, m) {
        return false;
    }
    for k in 0..m {
        let mut w = y[k];
        for j in 0..k {
            w -= s[k * m + j] * y[j];
        }
        y[k] = w / s[k * m + k];
    }
    true
}

/// In-place Cholesky factor (lower triangle) of the small m×m matrix `s`; `false` if not
/// positive definite.
fn cholesky(s: &mut [f64], m: usize) -> bool {
    let scale = (0..m).map(|k| s[k * m + k]).fold(0.0, f64::max);
    for k in 0..m {
        let mut d = s[k * m + k];
        for j in 0..k {
            d -= s[k * m + j] * s[k * m + j];
        }
        if !(d > 1e-12 * scale) {
            return false;
        }
        let d = d.sqrt();
        s[k * m + k] = d;
        for i in k + 1..m {
            let mut v = s[i * m + k];
            for j in 0..k {
                v -= s[i * m + j] * s[k * m + j];
            }
            s[i * m + k] = v / d;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::{null_space_cost, project_null};

    #[test]
    fn projection_removes_the_task_part_and_the_cost_is_its_complement() {
        // Â (2×3) and a vector: after the projection Â z = 0, and r_null(du) = ‖P du‖².
        let a = [1.0, -2.0, 0.5, 0.3, 0.7, -17.0];
        let du = [0.4, -1.1, 2.0];
        let (mut y, mut s) = ([0.0; 2], [0.0; 4]);
        let mut z = du;
        assert!(project_null(&a, &mut z, 2, &mut y, &mut s));
        for k in 0..2 {
            let az: f64 = (0..3).map(|j| a[k * 3 + j] * z[j]).sum();
            assert!(az.abs() < 1e-12, "Â z = {az}");
        }
        let p2: f64 = z.iter().map(|v| v * v).sum();
        let r = null_space_cost(&a, &du, 2, &mut y, &mut s).unwrap();
        assert!((r - p2).abs() < 1e-12, "{r} vs {p2}");
        // Projecting twice changes nothing (a projection).
        let mut z2 = z;
        assert!(project_null(&a, &mut z2, 2, &mut y, &mut s));
        for (x, y) in z.iter().zip(&z2) {
            assert!((x - y).abs() < 1e-12);
        }
        // A rank-deficient Â is refused, leaving z unchanged.
        let flat = [1.0, 2.0, 3.0, 2.0, 4.0, 6.0];
        let mut z3 = du;
        assert!(!project_null(&flat, &mut z3, 2, &mut y, &mut s));
        assert_eq!(z3, du);
        assert!(null_space_cost(&flat, &du, 2, &mut y, &mut s).is_none());
    }
}
