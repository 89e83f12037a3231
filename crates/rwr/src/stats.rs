//! Weighted sufficient statistics of eq. 23, 24 and 28, and their allocation-free solve.

use crate::error::{Result, RwrError};
use crate::held::Held;
use nalgebra::DMatrix;

/// `Σ w φφᵀ`, `Σ w φ uᵀ`, `Σ w ‖u‖²`, `Σ w`, `Σ w r`, `Σ w²` for some weights `w ≥ 0`
/// (possibly all scaled by one common factor, which cancels everywhere they are used).
///
/// The scalar sums are always current; `gram` and `cross` may lag behind by the samples held
/// by [`Stats::push`] (see `held.rs`), and whoever reads them calls [`Stats::flush`] first. The
/// serialised form is the flushed one.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(into = "Sums", from = "Sums")]
pub(crate) struct Stats {
    pub gram: DMatrix<f64>,
    pub cross: DMatrix<f64>,
    pub yy: f64,
    pub sw: f64,
    pub swr: f64,
    pub sw2: f64,
    pub(crate) held: Held,
}

/// The serialised form of [`Stats`] (its sums, flushed).
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(rename = "Stats")]
struct Sums {
    gram: DMatrix<f64>,
    cross: DMatrix<f64>,
    yy: f64,
    sw: f64,
    swr: f64,
    sw2: f64,
}

impl From<Stats> for Sums {
    fn from(mut s: Stats) -> Self {
        s.flush();
        Sums {
            gram: s.gram,
            cross: s.cross,
            yy: s.yy,
            sw: s.sw,
            swr: s.swr,
            sw2: s.sw2,
        }
    }
}

impl From<Sums> for Stats {
    fn from(s: Sums) -> Self {
        let held = Held::new(s.gram.nrows(), s.cross.ncols());
        Stats {
            gram: s.gram,
            cross: s.cross,
            yy: s.yy,
            sw: s.sw,
            swr: s.swr,
            sw2: s.sw2,
            held,
        }
    }
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
            held: Held::new(p, d),
        }
    }

    pub fn clear(&mut self) {
        self.scale(0.0);
    }

    /// Multiplies every weight by `f` (so `Σ w²` by `f²`).
    pub fn scale(&mut self, f: f64) {
        self.flush();
        self.gram *= f;
        self.cross *= f;
        self.yy *= f;
        self.sw *= f;
        self.swr *= f;
        self.sw2 *= f * f;
    }

    /// Adds one sample `(φ, u, r)` with weight `w`. Lengths are the caller's responsibility.
    /// Runs the AVX2 copy where the CPU has it (the same operations: the same bits).
    pub fn add(&mut self, w: f64, phi: &[f64], u: &[f64], r: f64) {
        self.flush();
        #[cfg(target_arch = "x86_64")]
        if crate::simd::avx2() {
            // SAFETY: the CPU supports AVX2 (checked just above).
            unsafe { self.add_avx2(w, phi, u, r) };
            return;
        }
        self.add_body(w, phi, u, r);
    }

    /// [`Stats::add`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn add_avx2(&mut self, w: f64, phi: &[f64], u: &[f64], r: f64) {
        self.add_body(w, phi, u, r);
    }

    #[inline(always)]
    pub(crate) fn add_body(&mut self, w: f64, phi: &[f64], u: &[f64], r: f64) {
        let p = phi.len();
        // Column j of the lower triangle of G gains w φ_j φ[j..] (contiguous, column-major).
        let gram = self.gram.as_mut_slice();
        for j in 0..p {
            let wj = w * phi[j];
            let col = &mut gram[j * p + j..(j + 1) * p];
            for (g, x) in col.iter_mut().zip(&phi[j..]) {
                *g += wj * x;
            }
        }
        // Column k of C gains (w u_k) φ, in the same order of operations as w φ_j u_k.
        let cross = self.cross.as_mut_slice();
        for (k, uk) in u.iter().enumerate() {
            let col = &mut cross[k * p..(k + 1) * p];
            for (c, x) in col.iter_mut().zip(phi) {
                *c += w * x * uk;
            }
        }
        self.yy += w * u.iter().map(|x| x * x).sum::<f64>();
        self.sw += w;
        self.swr += w * r;
        self.sw2 += w * w;
    }

    /// Effective sample size `(Σw)² / Σw²` (0 with no weight).
    pub fn ess(&self) -> f64 {
        crate::weights::ess_of(self.sw, self.sw2)
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

    /// Eq. 23 with ridge: `θ = (G/Σw + λI)⁻¹ (C/Σw)` into `self.theta`. Only the lower
    /// triangle of `G` is read. Does not allocate.
    pub fn solve(&mut self, s: &Stats, ridge: f64) -> Result<()> {
        self.solve_with_prior(s, ridge, None)
    }

    /// Like [`Solver::solve`], with the ridge pulling towards `prior` instead of zero:
    /// `θ = (G/Σw + λI)⁻¹ (C/Σw + λ θ_prior)` (a proximal M-step).
    pub fn solve_with_prior(
        &mut self,
        s: &Stats,
        ridge: f64,
        prior: Option<&DMatrix<f64>>,
    ) -> Result<()> {
        #[cfg(target_arch = "x86_64")]
        if crate::simd::avx2() {
            // SAFETY: the CPU supports AVX2 (checked just above).
            return unsafe { self.solve_avx2(s, ridge, prior) };
        }
        self.solve_body(s, ridge, prior)
    }

    /// [`Solver::solve_with_prior`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_avx2(&mut self, s: &Stats, ridge: f64, prior: Option<&DMatrix<f64>>) -> Result<()> {
        self.solve_body(s, ridge, prior)
    }

    /// The weighted mean squared residual per action dimension of the `θ` in `self.theta`,
    /// `Σ w ‖u − θᵀφ‖² / (d Σw)` (eq. 24), from the statistics it was solved from. Only an
    /// M-step that updates `σ` needs it (the local dynamics regression does not: `O(d p²)` saved
    /// per solve). Does not allocate.
    pub fn residual(&self, s: &Stats) -> f64 {
        #[cfg(target_arch = "x86_64")]
        if crate::simd::avx2() {
            // SAFETY: the CPU supports AVX2 (checked just above).
            return unsafe { self.residual_avx2(s) };
        }
        self.residual_body(s)
    }

    /// [`Solver::residual`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn residual_avx2(&self, s: &Stats) -> f64 {
        self.residual_body(s)
    }

    #[inline(always)]
    pub(crate) fn solve_body(
        &mut self,
        s: &Stats,
        ridge: f64,
        prior: Option<&DMatrix<f64>>,
    ) -> Result<()> {
        if s.sw.is_nan() || s.sw <= 0.0 {
            return Err(RwrError::NoWeight);
        }
        let p = self.a.nrows();
        let inv = 1.0 / s.sw;
        let (a, g) = (self.a.as_mut_slice(), s.gram.as_slice());
        for j in 0..p {
            let col = j * p + j..(j + 1) * p;
            for (a, g) in a[col.clone()].iter_mut().zip(&g[col]) {
                *a = g * inv;
            }
            a[j * p + j] += ridge;
        }
        self.theta.copy_from(&s.cross);
        self.theta *= inv;
        if let Some(prior) = prior {
            for (t, p) in self.theta.iter_mut().zip(prior.iter()) {
                *t += ridge * p;
            }
        }
        crate::cholesky::solve_lower(&mut self.a, &mut self.theta)
    }

    #[inline(always)]
    pub(crate) fn residual_body(&self, s: &Stats) -> f64 {
        let p = self.a.nrows();
        let inv = 1.0 / s.sw;
        // Σw‖u − θᵀφ‖² = Σw‖u‖² − 2 tr(θᵀC) + tr(θᵀGθ), with G symmetric from its lower
        // triangle: θ_kᵀ G θ_k = Σ_j θ_jk (G_jj θ_jk + 2 Σ_{i>j} G_ij θ_ik), on contiguous columns.
        let (g, c) = (s.gram.as_slice(), s.cross.as_slice());
        let mut quad = 0.0;
        for k in 0..self.theta.ncols() {
            let t = &self.theta.as_slice()[k * p..(k + 1) * p];
            for j in 0..p {
                let below = dot(&g[j * p + j + 1..(j + 1) * p], &t[j + 1..]);
                quad += t[j] * (g[j * p + j] * t[j] + 2.0 * below - 2.0 * c[k * p + j]);
            }
        }
        ((s.yy + quad) * inv / self.theta.ncols() as f64).max(0.0)
    }
}

/// `aᵀb` with four partial sums (vectorisable).
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for l in 0..4 {
            acc[l] += x[l] * y[l];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}
