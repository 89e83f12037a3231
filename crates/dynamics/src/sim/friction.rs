//! Stiff joint friction in the simulator: a stiffness estimate that decides whether the explicit
//! integrator is stable, and the implicit (backward-Euler) friction step used when it is not.
//!
//! Friction `τ_f(q̇) = D q̇ + c tanh(q̇ / v_c)` acts on the joint velocities with the slope
//! `σ = D + c / v_c` at most. Over a step `h` the friction alone contracts the velocities at the
//! rates of `M⁻¹ diag(σ)`, whose largest eigenvalue is at most `λ̂ = Σ σᵢ (M⁻¹)ᵢᵢ` (the trace of
//! the similar matrix `diag(σ)^½ M⁻¹ diag(σ)^½`). An explicit step is stable for `h λ̂` well below
//! RK4's limit of 2.79 on the negative real axis; beyond [`STIFF_LIMIT`] the friction is instead
//! integrated implicitly (semi-implicit Euler): with `v* = q̇ + h q̈_rigid(q, q̇)` the new velocity
//! `v` solves `M (v − v*) + h τ_f(v) = 0`, the minimum of the strictly convex
//! `Φ(v) = ½ (v − v*)ᵀ M (v − v*) + h Σ φᵢ(vᵢ)`, `φᵢ' = τ_f,ᵢ`, found by Newton's method with a
//! backtracking line search on `Φ` (so it converges from any start, for any stiffness), and
//! `q ← q + h v`.

use crate::crba::crba;
use crate::data::Data;
use crate::error::{DynamicsError, Result};
use crate::model::{Friction, Model};
use nalgebra::{DMatrix, DVector};

/// `h λ̂` above which the friction is integrated implicitly (module docs). The estimate `λ̂`
/// exceeds the true largest rate by up to the number of joints, so this leaves margin for the
/// nonlinearity of the Coulomb term.
pub const STIFF_LIMIT: f64 = 0.5;

/// Newton iterations allowed per friction step: it converges quadratically near the solution
/// and the line search guarantees progress far from it (a few iterations in practice).
const MAX_NEWTON: usize = 60;

/// Preallocated workspace of the friction step.
#[derive(Clone, Debug)]
pub(crate) struct FrictionStep {
    /// Largest friction slope `σᵢ` per joint (N·m·s/rad or N·s/m).
    sigma: Vec<f64>,
    /// The terms `σᵢ (M⁻¹)ᵢᵢ` of the last rate (1/s).
    terms: Vec<f64>,
    mass: DMatrix<f64>,
    chol: DMatrix<f64>,
    v: DVector<f64>,
    grad: DVector<f64>,
    dv: DVector<f64>,
    trial: DVector<f64>,
    diff: DVector<f64>,
}

/// `∫₀^v τ_f`: `D v²/2 + c v_c ln cosh(v / v_c)`, computed without overflow.
fn potential(f: &Friction, v: f64) -> f64 {
    let x = (v / f.coulomb_velocity).abs();
    let ln_cosh = x + (-2.0 * x).exp().ln_1p() - std::f64::consts::LN_2;
    0.5 * f.viscous * v * v + f.coulomb * f.coulomb_velocity * ln_cosh
}

/// `dτ_f/dq̇` at `v`.
fn slope(f: &Friction, v: f64) -> f64 {
    let coulomb = if f.coulomb != 0.0 {
        let t = (v / f.coulomb_velocity).tanh();
        f.coulomb / f.coulomb_velocity * (1.0 - t * t)
    } else {
        0.0
    };
    f.viscous + coulomb
}

/// `Φ(v)` (module docs); `diff` is scratch. Allocation-free.
fn objective(
    model: &Model,
    mass: &DMatrix<f64>,
    diff: &mut DVector<f64>,
    qd: &DVector<f64>,
    v: &DVector<f64>,
    k: f64,
) -> f64 {
    diff.copy_from(v);
    *diff -= qd;
    let n = v.len();
    let mut quad = 0.0;
    for i in 0..n {
        for j in 0..n {
            quad += diff[i] * mass[(i, j)] * diff[j];
        }
    }
    let fric: f64 = model
        .links()
        .iter()
        .zip(v.iter())
        .map(|(l, &x)| potential(&l.friction, x))
        .sum();
    0.5 * quad + k * fric
}

/// In-place Cholesky factor `L` (lower triangle of `a`) of a symmetric positive-definite matrix;
/// `false` if it is not positive definite.
fn cholesky(a: &mut DMatrix<f64>) -> bool {
    let n = a.nrows();
    for j in 0..n {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= a[(j, k)] * a[(j, k)];
        }
        if !(d > 0.0) {
            return false;
        }
        let d = d.sqrt();
        a[(j, j)] = d;
        for i in j + 1..n {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= a[(i, k)] * a[(j, k)];
            }
            a[(i, j)] = s / d;
        }
    }
    true
}

/// Solves `L Lᵀ x = b` in place (`x` holds `b` on entry).
fn solve(l: &DMatrix<f64>, x: &mut DVector<f64>) {
    let n = l.nrows();
    for i in 0..n {
        let mut s = x[i];
        for k in 0..i {
            s -= l[(i, k)] * x[k];
        }
        x[i] = s / l[(i, i)];
    }
    for i in (0..n).rev() {
        let mut s = x[i];
        for k in i + 1..n {
            s -= l[(k, i)] * x[k];
        }
        x[i] = s / l[(i, i)];
    }
}

impl FrictionStep {
    pub fn new(model: &Model) -> Self {
        let n = model.nq();
        let z = DVector::zeros(n);
        Self {
            sigma: model
                .links()
                .iter()
                .map(|l| l.friction.viscous + l.friction.coulomb / l.friction.coulomb_velocity)
                .collect(),
            terms: vec![0.0; n],
            mass: DMatrix::zeros(n, n),
            chol: DMatrix::zeros(n, n),
            v: z.clone(),
            grad: z.clone(),
            dv: z.clone(),
            trial: z.clone(),
            diff: z,
        }
    }

    /// Whether the model has any friction at all.
    pub fn any(&self) -> bool {
        self.sigma.iter().any(|&s| s > 0.0)
    }

    /// The rate bound `λ̂ = Σ σᵢ (M⁻¹)ᵢᵢ` (1/s) at `q`. Leaves `M(q)` in the workspace.
    pub fn rate(&mut self, model: &Model, data: &mut Data, q: &[f64]) -> Result<f64> {
        self.mass.copy_from(crba(model, data, q)?);
        self.chol.copy_from(&self.mass);
        if !cholesky(&mut self.chol) {
            return Err(DynamicsError::Singular {
                joint: 0,
                value: 0.0,
            });
        }
        for (i, &s) in self.sigma.iter().enumerate() {
            self.terms[i] = 0.0;
            if s > 0.0 {
                // (M⁻¹)ᵢᵢ from one solve with the unit vector eᵢ.
                self.dv.fill(0.0);
                self.dv[i] = 1.0;
                solve(&self.chol, &mut self.dv);
                self.terms[i] = s * self.dv[i];
            }
        }
        Ok(self.terms.iter().sum())
    }

    /// The joint with the largest term of the last [`Self::rate`].
    pub fn stiffest(&self) -> usize {
        (0..self.terms.len())
            .max_by(|&a, &b| self.terms[a].total_cmp(&self.terms[b]))
            .unwrap_or(0)
    }

    /// Replaces `qd` by the velocity after an implicit friction step of length `k` (s) at the
    /// configuration whose `M` the last [`Self::rate`] call left. Errors only on a non-finite
    /// value or if Newton's method has not converged in its iteration budget (`qd` unchanged).
    pub fn step(&mut self, model: &Model, qd: &mut DVector<f64>, k: f64) -> Result<()> {
        self.v.copy_from(qd);
        let links = model.links();
        for _ in 0..MAX_NEWTON {
            // Gradient M (v − q̇) + k τ_f(v) and Hessian M + k diag(τ_f'(v)).
            self.diff.copy_from(&self.v);
            self.diff -= &*qd;
            self.grad.gemv(1.0, &self.mass, &self.diff, 0.0);
            self.chol.copy_from(&self.mass);
            for (i, l) in links.iter().enumerate() {
                self.grad[i] += k * l.friction.torque(self.v[i]);
                self.chol[(i, i)] += k * slope(&l.friction, self.v[i]);
            }
            if !cholesky(&mut self.chol) {
                break;
            }
            self.dv.copy_from(&self.grad);
            solve(&self.chol, &mut self.dv);
            let decrement = self.grad.dot(&self.dv);
            if !decrement.is_finite() {
                break;
            }
            if self.dv.amax() <= 1e-11 * (1.0 + self.v.amax()) {
                self.v -= &self.dv;
                qd.copy_from(&self.v);
                return Ok(());
            }
            // Backtracking (Armijo) on Φ along the Newton direction −dv.
            let phi0 = objective(model, &self.mass, &mut self.diff, qd, &self.v, k);
            let mut t = 1.0;
            let stalled = loop {
                self.trial.copy_from(&self.v);
                self.trial.axpy(-t, &self.dv, 1.0);
                let phi = objective(model, &self.mass, &mut self.diff, qd, &self.trial, k);
                if phi <= phi0 - 0.25 * t * decrement {
                    // A shortened step that gains nothing above round-off: at the minimum.
                    break t < 1.0 && phi0 - phi <= 1e-14 * phi0.abs();
                }
                t *= 0.5;
                if t < 1e-12 {
                    break true;
                }
            };
            if stalled {
                qd.copy_from(&self.v);
                return Ok(());
            }
            self.v.copy_from(&self.trial);
        }
        Err(DynamicsError::Diverged {
            t: f64::NAN,
            what: "the implicit friction step (Newton's method did not converge)",
        })
    }
}
