//! The true input gain of the evaluated robot, for the split of the command error into its task
//! and null-space parts and for the error of the learner's `Â`.

/// The true input gain `B = J M⁻¹` (task rows, m×n) at one state and `(B Bᵀ)⁻¹`, formed once
/// per evaluation step for the error split. Allocates (evaluation only, not a control path).
pub(super) struct TrueGain {
    b: nalgebra::DMatrix<f64>,
    s_inv: nalgebra::DMatrix<f64>,
}

impl TrueGain {
    /// From the dynamics in `data`; `None` if `M` or `B Bᵀ` does not invert.
    pub fn new(data: &osrl_dynamics::Data, axes: &[usize]) -> Option<Self> {
        let n = data.mass.nrows();
        let j = nalgebra::DMatrix::from_fn(axes.len(), n, |r, c| data.jac[(axes[r], c)]);
        let b = j * data.mass.clone().try_inverse()?;
        let s_inv = (&b * b.transpose()).try_inverse()?;
        Some(Self { b, s_inv })
    }

    /// `‖Â − B‖_F / ‖B‖_F` for the learner's `Â` (m×n row-major).
    pub fn gain_error(&self, a_hat: &[f64]) -> f64 {
        let n = self.b.ncols();
        let d = nalgebra::DMatrix::from_fn(self.b.nrows(), n, |r, c| a_hat[r * n + c]) - &self.b;
        d.norm() / self.b.norm().max(1e-300)
    }

    /// The null-space error `‖(I − B⁺B)(v + Â⁺Â (u* − v) − u*)‖²` of the command that is
    /// optimal for the learner's `Â` (m×n row-major) and nominal `v = û0`: the smallest
    /// correction of `v` with `Â (u − v) = Â (u* − v)`. A floor of the command's null-space error
    /// set by `Â` and `û0` alone. `None` if `Â Âᵀ` does not invert.
    pub fn floor_null2(&self, a_hat: &[f64], v: &[f64], u_star: &[f64]) -> Option<f64> {
        let (m, n) = (self.b.nrows(), self.b.ncols());
        let a = nalgebra::DMatrix::from_fn(m, n, |r, c| a_hat[r * n + c]);
        let s = (&a * a.transpose()).try_inverse()?;
        let d = nalgebra::DVector::from_fn(n, |i, _| u_star[i] - v[i]);
        let range = a.transpose() * (s * (&a * &d));
        let u: Vec<f64> = (0..n).map(|i| v[i] + range[i]).collect();
        Some(self.null_part2(&u, u_star))
    }

    /// `‖(I − B⁺B)(u − v)‖²`, the part of `u − v` in the null space of `B`.
    pub fn null_part2(&self, u: &[f64], v: &[f64]) -> f64 {
        let e = nalgebra::DVector::from_fn(u.len(), |i, _| u[i] - v[i]);
        let range = self.b.transpose() * (&self.s_inv * (&self.b * &e));
        (e - range).norm_squared()
    }
}

#[cfg(test)]
mod tests {
    use super::TrueGain;
    use osrl_dynamics::{robots, Data};

    /// The true gain has no error against itself, and its null-space part is orthogonal to the
    /// rows of `B`.
    #[test]
    fn the_true_gain_splits_a_command_error() {
        let model = robots::planar3();
        let mut data = Data::new(&model);
        let q = [0.3, 0.5, -0.4];
        osrl_dynamics::crba(&model, &mut data, &q).unwrap();
        osrl_dynamics::jacobian(&model, &mut data, &q).unwrap();
        let axes = model.task_axes().to_vec();
        let t = TrueGain::new(&data, &axes).unwrap();
        let b: Vec<f64> = (0..6).map(|k| t.b[(k / 3, k % 3)]).collect();
        assert!(t.gain_error(&b) < 1e-15);
        let (u, v) = ([1.0, -2.0, 0.5], [0.0; 3]);
        let null = t.null_part2(&u, &v);
        assert!(null > 0.0 && null < 5.25);
    }

    /// The floor of the command's null-space error: with the true gain as `Â` it is the
    /// nominal's null-space error alone; a wrong `Â` raises it even with a perfect nominal.
    #[test]
    fn the_floor_is_the_nominal_error_for_the_true_gain() {
        let model = robots::planar3();
        let mut data = Data::new(&model);
        let q = [0.3, 0.5, -0.4];
        osrl_dynamics::crba(&model, &mut data, &q).unwrap();
        osrl_dynamics::jacobian(&model, &mut data, &q).unwrap();
        let t = TrueGain::new(&data, model.task_axes()).unwrap();
        let b: Vec<f64> = (0..6).map(|k| t.b[(k / 3, k % 3)]).collect();
        let (u_star, v) = ([2.0, -1.0, 0.7], [1.5, -0.2, 0.1]);
        let floor = t.floor_null2(&b, &v, &u_star).unwrap();
        assert!((floor - t.null_part2(&v, &u_star)).abs() < 1e-12, "{floor}");
        let mut wrong = b.clone();
        wrong[2] += 0.3 * b.iter().map(|x| x.abs()).fold(0.0, f64::max);
        assert!(t.floor_null2(&wrong, &u_star, &u_star).unwrap() < 1e-20);
        assert!(t.floor_null2(&wrong, &[0.0; 3], &u_star).unwrap() > 1e-6);
    }
}
