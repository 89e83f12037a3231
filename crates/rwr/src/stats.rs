//! Weighted sufficient statistics of eq. 23, 24 and 28, and their allocation-free solve.

use crate::error::{Result, RwrError};
use nalgebra::DMatrix;

/// `Σ w φφᵀ`, `Σ w φ uᵀ`, `Σ w ‖u‖²`, `Σ w`, `Σ w r`, `Σ w²` for some weights `w ≥ 0`
/// (possibly all scaled by one common factor, which cancels everywhere they are used).
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize, PartialEq)]
pub(crate) struct Stats {
    pub gram: DMatrix<f64>,
    pub cross: DMatrix<f64>,
    pub yy: f64,
    pub sw: f64,
    pub swr: f64,
    pub sw2: f64,
}

impl Stats {
    pub fn new(p: usize, d: usize) -> Self {
        Self {
            gram: DMatrix::zeros(p, p),
            cross: DMatrix::zeros(p, d),
            yy: 0.0,
            sw: 0.0,
            swr: 0.0,
            sw2: 0.0,
        }
    }

    pub fn clear(&mut self) {
        self.scale(0.0);
    }

    /// Multiplies every weight by `f` (so `Σ w²` by `f²`).
    pub fn scale(&mut self, f: f64) {
        self.gram *= f;
        self.cross *= f;
        self.yy *= f;
        self.sw *= f;
        self.swr *= f;
        self.sw2 *= f * f;
    }

    /// Adds one sample `(φ, u, r)` with weight `w`. Lengths are the caller's responsibility.
    pub fn add(&mut self, w: f64, phi: &[f64], u: &[f64], r: f64) {
        let p = phi.len();
        for j in 0..p {
            let wj = w * phi[j];
            for i in j..p {
                self.gram[(i, j)] += wj * phi[i];
            }
            for (k, uk) in u.iter().enumerate() {
                self.cross[(j, k)] += wj * uk;
            }
        }
        self.yy += w * u.iter().map(|x| x * x).sum::<f64>();
        self.sw += w;
        self.swr += w * r;
        self.sw2 += w * w;
    }

    /// Effective sample size `(Σw)² / Σw²` (0 with no weight).
    pub fn ess(&self) -> f64 {
        if self.sw2 > 0.0 {
            self.sw * self.sw / self.sw2
        } else {
            0.0
        }
    }

    /// Weighted mean cost `Σ w r / Σ w`, the inverse of eq. 28.
    pub fn mean_cost(&self) -> f64 {
        self.swr / self.sw
    }
}

/// Preallocated buffers for solving eq. 23 from [`Stats`].
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize, PartialEq)]
pub(crate) struct Solver {
    a: DMatrix<f64>,
    pub theta: DMatrix<f64>,
}

impl Solver {
    pub fn new(p: usize, d: usize) -> Self {
        Self {
            a: DMatrix::zeros(p, p),
            theta: DMatrix::zeros(p, d),
        }
    }

    /// Eq. 23 with ridge: `θ = (G/Σw + λI)⁻¹ (C/Σw)` into `self.theta`, and returns the weighted
    /// mean squared residual per action dimension `Σ w ‖u − θᵀφ‖² / (d Σw)` (eq. 24).
    /// Only the lower triangle of `G` is read. Does not allocate.
    pub fn solve(&mut self, s: &Stats, ridge: f64) -> Result<f64> {
        self.solve_with_prior(s, ridge, None)
    }

    /// Like [`Solver::solve`], with the ridge pulling towards `prior` instead of zero:
    /// `θ = (G/Σw + λI)⁻¹ (C/Σw + λ θ_prior)` (a proximal M-step).
    pub fn solve_with_prior(
        &mut self,
        s: &Stats,
        ridge: f64,
        prior: Option<&DMatrix<f64>>,
    ) -> Result<f64> {
        if s.sw.is_nan() || s.sw <= 0.0 {
            return Err(RwrError::NoWeight);
        }
        let p = self.a.nrows();
        let inv = 1.0 / s.sw;
        for j in 0..p {
            for i in j..p {
                self.a[(i, j)] = s.gram[(i, j)] * inv;
            }
            self.a[(j, j)] += ridge;
        }
        self.theta.copy_from(&s.cross);
        self.theta *= inv;
        if let Some(prior) = prior {
            for (t, p) in self.theta.iter_mut().zip(prior.iter()) {
                *t += ridge * p;
            }
        }
        cholesky_solve_lower(&mut self.a, &mut self.theta)?;
        // Σw‖u − θᵀφ‖² = Σw‖u‖² − 2 tr(θᵀC) + tr(θᵀGθ), with G symmetric from its lower triangle.
        let (t, g) = (&self.theta, &s.gram);
        let mut quad = 0.0;
        for k in 0..t.ncols() {
            for j in 0..p {
                let mut gt = 0.0;
                for i in 0..p {
                    let gij = if i >= j { g[(i, j)] } else { g[(j, i)] };
                    gt += gij * t[(i, k)];
                }
                quad += t[(j, k)] * (gt - 2.0 * s.cross[(j, k)]);
            }
        }
        Ok(((s.yy + quad) * inv / t.ncols() as f64).max(0.0))
    }
}

/// Solves `A X = B` for symmetric positive definite `A` given by its lower triangle: overwrites
/// the lower triangle of `A` with its Cholesky factor `L` and `B` with `X`. Fails with
/// [`RwrError::Singular`] (B then holds garbage) when `A` is not numerically positive definite.
fn cholesky_solve_lower(a: &mut DMatrix<f64>, b: &mut DMatrix<f64>) -> Result<()> {
    let p = a.nrows();
    for j in 0..p {
        let diag = a[(j, j)];
        let mut d = diag;
        for k in 0..j {
            d -= a[(j, k)] * a[(j, k)];
        }
        // A pivot lost to rounding (relative to its diagonal) counts as singular.
        if !(d > 1e-13 * diag && d.is_finite()) {
            return Err(RwrError::Singular);
        }
        let d = d.sqrt();
        a[(j, j)] = d;
        for i in j + 1..p {
            let mut v = a[(i, j)];
            for k in 0..j {
                v -= a[(i, k)] * a[(j, k)];
            }
            a[(i, j)] = v / d;
        }
    }
    for c in 0..b.ncols() {
        for i in 0..p {
            let mut v = b[(i, c)];
            for k in 0..i {
                v -= a[(i, k)] * b[(k, c)];
            }
            b[(i, c)] = v / a[(i, i)];
        }
        for i in (0..p).rev() {
            let mut v = b[(i, c)];
            for k in i + 1..p {
                v -= a[(k, i)] * b[(k, c)];
            }
            b[(i, c)] = v / a[(i, i)];
        }
    }
    Ok(())
}
