//! Shared helpers of the integration tests: random states and metrics, literal formulas.
#![allow(dead_code)]

use nalgebra::{DMatrix, DVector};
use osrl_dynamics::{compute_all, robots, Model};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// planar3, sarcos7 and two random arms (one with Coulomb friction).
pub fn models() -> Vec<Model> {
    vec![
        robots::planar3(),
        robots::sarcos7(),
        robots::random_arm(6, 11, true),
        robots::random_arm(5, 3, false),
    ]
}

pub fn uniform(r: &mut ChaCha8Rng, n: usize, lo: f64, hi: f64) -> Vec<f64> {
    (0..n).map(|_| r.random_range(lo..hi)).collect()
}

/// A random state inside the joint limits (or ±2 rad without limits).
pub fn random_state(model: &Model, r: &mut ChaCha8Rng) -> (Vec<f64>, Vec<f64>) {
    let q = model
        .q_min()
        .zip(model.q_max())
        .map(|(a, b)| {
            let (a, b) = (a.max(-2.0), b.min(2.0));
            r.random_range(a..b)
        })
        .collect();
    (q, uniform(r, model.nq(), -1.0, 1.0))
}

/// A random symmetric positive-definite n×n matrix with a spread of eigenvalues.
pub fn random_spd(n: usize, r: &mut ChaCha8Rng) -> DMatrix<f64> {
    let a = DMatrix::from_fn(n, n, |_, _| r.random_range(-1.0..1.0));
    &a * a.transpose() + DMatrix::identity(n, n) * 0.1
}

pub fn rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|i| m.row(i).iter().copied().collect())
        .collect()
}

/// Task Jacobian J (m×n), J̇q̇ (m), M, h of the model at a state.
pub struct Dyn {
    pub j: DMatrix<f64>,
    pub jdqd: DVector<f64>,
    pub m: DMatrix<f64>,
    pub h: DVector<f64>,
}

pub fn dynamics(model: &Model, q: &[f64], qd: &[f64]) -> Dyn {
    let mut d = model.data();
    compute_all(model, &mut d, q, qd).unwrap();
    let axes = model.task_axes();
    Dyn {
        j: DMatrix::from_fn(axes.len(), model.nq(), |r, c| d.jac[(axes[r], c)]),
        jdqd: DVector::from_fn(axes.len(), |r, _| d.jdot_qd[axes[r]]),
        m: d.mass.clone(),
        h: d.h.clone(),
    }
}

/// Symmetric square root of an SPD matrix by eigen-decomposition.
pub fn sqrtm(n: &DMatrix<f64>) -> DMatrix<f64> {
    let e = n.clone().symmetric_eigen();
    let d = DMatrix::from_diagonal(&e.eigenvalues.map(f64::sqrt));
    &e.eigenvectors * d * e.eigenvectors.transpose()
}

/// Eq. 7 in its printed form (corrected; the crate README, "Choices"), with the symmetric square root and nalgebra's own
/// inverses: `u* = N^(−1/2) A⁺ b + N^(−1/2)(I − A⁺A) N^(1/2) u0`, `A = J M⁻¹ N^(−1/2)`.
pub fn eq7_literal(
    d: &Dyn,
    n: &DMatrix<f64>,
    xdd_ref: &DVector<f64>,
    u0: &DVector<f64>,
) -> DVector<f64> {
    let nq = d.m.nrows();
    let minv = d.m.clone().try_inverse().unwrap();
    let nh = sqrtm(n);
    let nmh = nh.clone().try_inverse().unwrap();
    let a = &d.j * &minv * &nmh;
    let aplus = a.transpose() * (&a * a.transpose()).try_inverse().unwrap();
    let b = xdd_ref - &d.jdqd + &d.j * &minv * &d.h;
    &nmh * &aplus * b + &nmh * (DMatrix::identity(nq, nq) - &aplus * &a) * &nh * u0
}

/// Eq. 4 as printed: `u = Jᵀ (J M⁻¹ Jᵀ)⁻¹ b`.
pub fn eq4_literal(d: &Dyn, xdd_ref: &DVector<f64>) -> DVector<f64> {
    let minv = d.m.clone().try_inverse().unwrap();
    let b = xdd_ref - &d.jdqd + &d.j * &minv * &d.h;
    d.j.transpose() * (&d.j * &minv * d.j.transpose()).try_inverse().unwrap() * b
}

/// Task acceleration `J q̈ + J̇ q̇` that command `u` produces at a state (true model, friction in).
pub fn task_accel(model: &Model, q: &[f64], qd: &[f64], u: &[f64]) -> DVector<f64> {
    let d = dynamics(model, q, qd);
    let mut data = model.data();
    let qdd = osrl_dynamics::forward_dynamics(model, &mut data, q, qd, u)
        .unwrap()
        .clone();
    &d.j * qdd + &d.jdqd
}
