//! A redundant linear problem: `ẍ = A u + b` (2-D `ẍ`, 3-D `u`), cost `‖u − u0‖²`, learning
//! from relabelled samples `φ = [ẍ_observed, 1] → u`. RWR must find the minimum-cost inverse
//! `u*(ẍ) = A⁺(ẍ − b) + (I − A⁺A) u0`; plain regression of the same data must not.
#![allow(clippy::needless_range_loop)]

use nalgebra::{DMatrix, Matrix2x3, Vector2, Vector3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rwr::{BatchRwr, RwrConfig};

struct Problem {
    a: Matrix2x3<f64>,
    b: Vector2<f64>,
    u0: Vector3<f64>,
}

impl Problem {
    fn new() -> Self {
        Self {
            a: Matrix2x3::new(1.0, 0.5, -0.3, 0.2, -0.8, 1.1),
            b: Vector2::new(0.3, -0.2),
            u0: Vector3::new(0.5, -1.0, 0.8),
        }
    }

    fn optimal(&self, xdd: &Vector2<f64>) -> Vector3<f64> {
        let pinv = self.a.transpose() * (self.a * self.a.transpose()).try_inverse().unwrap();
        pinv * (xdd - self.b) + (nalgebra::Matrix3::identity() - pinv * self.a) * self.u0
    }

    /// One on-policy batch: desired `ẍ` uniform in [−2, 2]², `u ~ π(u | [ẍ_d, 1])`, executed,
    /// relabelled with the observed `ẍ`.
    fn batch(
        &self,
        rwr: &BatchRwr,
        n: usize,
        rng: &mut ChaCha8Rng,
    ) -> (DMatrix<f64>, DMatrix<f64>, Vec<f64>) {
        let (mut phi, mut us, mut costs) =
            (DMatrix::zeros(n, 3), DMatrix::zeros(n, 3), vec![0.0; n]);
        let mut u = [0.0; 3];
        for i in 0..n {
            let xd = [
                rng.random_range(-2.0..2.0),
                rng.random_range(-2.0..2.0),
                1.0,
            ];
            rwr.policy().sample_into(&xd, rng, &mut u).unwrap();
            let uv = Vector3::from_column_slice(&u);
            let xdd = self.a * uv + self.b;
            phi.row_mut(i).copy_from_slice(&[xdd[0], xdd[1], 1.0]);
            us.row_mut(i).copy_from_slice(&u);
            costs[i] = (uv - self.u0).norm_squared();
        }
        (phi, us, costs)
    }

    /// Command nMSE of the policy mean against `u*` on a grid of `ẍ` in [−2, 2]².
    fn nmse(&self, theta: &DMatrix<f64>) -> f64 {
        let grid: Vec<Vector2<f64>> = (0..21)
            .flat_map(|i| {
                (0..21).map(move |j| Vector2::new(-2.0 + 0.2 * i as f64, -2.0 + 0.2 * j as f64))
            })
            .collect();
        let opt: Vec<Vector3<f64>> = grid.iter().map(|x| self.optimal(x)).collect();
        let mean = opt.iter().sum::<Vector3<f64>>() / opt.len() as f64;
        let var: f64 = opt.iter().map(|u| (u - mean).norm_squared()).sum();
        let err: f64 = grid
            .iter()
            .zip(&opt)
            .map(|(x, o)| {
                let phi = DMatrix::from_row_slice(1, 3, &[x[0], x[1], 1.0]);
                let u = phi * theta;
                (Vector3::new(u[0], u[1], u[2]) - o).norm_squared()
            })
            .sum();
        err / var
    }
}

fn learn(cfg: RwrConfig, iters: usize, n: usize) -> (f64, Vec<f64>) {
    let p = Problem::new();
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let mut rwr = BatchRwr::new(3, 3, cfg).unwrap();
    let mut curve = Vec::new();
    for _ in 0..iters {
        let (phi, u, costs) = p.batch(&rwr, n, &mut rng);
        rwr.em_step(&phi, &u, &costs, None).unwrap();
        curve.push(p.nmse(rwr.theta()));
    }
    (p.nmse(rwr.theta()), curve)
}

#[test]
fn rwr_converges_to_the_minimum_cost_inverse() {
    // Fixed exploration σ = 0.5, adaptive τ. The cost's unavoidable (range-space) part keeps
    // τ ≈ 0.3, so the null-space error contracts by about 1/(1 + 2τσ²) per iteration and the
    // estimate fluctuates at a level ∝ 1/(τ n): many samples per iteration keep it below 1e-3.
    let cfg = RwrConfig {
        sigma_init: 0.5,
        update_sigma: false,
        ..RwrConfig::default()
    };
    let (nmse, curve) = learn(cfg, 40, 20_000);
    let worst_late = curve[30..].iter().cloned().fold(0.0, f64::max);
    let shown: Vec<String> = curve
        .iter()
        .step_by(5)
        .map(|x| format!("{x:.1e}"))
        .collect();
    assert!(curve[0] > 1e-2, "starts far from optimal: {shown:?}");
    assert!(
        nmse < 1e-3 && worst_late < 1e-3,
        "command nMSE {nmse:.2e}, every 5th iteration {shown:?}"
    );
}

#[test]
fn unweighted_regression_of_the_same_data_does_not() {
    // τ fixed and tiny: all weights equal, i.e. supervised learning of the inverse.
    let cfg = RwrConfig {
        tau_init: 1e-12,
        adapt_tau: false,
        sigma_init: 0.5,
        update_sigma: false,
        ..RwrConfig::default()
    };
    let (nmse, _) = learn(cfg, 40, 20_000);
    assert!(nmse > 0.05, "command nMSE {nmse:.2e}");
}
