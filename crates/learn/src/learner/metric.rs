//! The metric `N` of the cost `(u − u0)ᵀ N (u − u0)` and of the null space of `Â`
//! (`controllers.metric`, `docs/decisions.md` D27). `N = I` is the paper's; with
//! `N = B̂ ≈ M⁻¹`, measured in the warm-up (`inertia.rs`, the least-squares fit of `q̈` on
//! `[u, q, q̇, 1]`), the null space of `Â = J M⁻¹` in the `N`-metric is that of `J` in the joint
//! velocities — the dynamically consistent split of eq. 7 with `N = M⁻¹` — so the task is not
//! carried by spinning the light wrist joints, whose torques are the cheapest in `N = I`.
//!
//! With `N = L Lᵀ` (Cholesky), `ũ = Lᵀ u` and `Ã = Â L⁻ᵀ` turn the `N`-metric into the Euclidean
//! one (`ũᵀ ũ = uᵀ N u`, `Ã ũ = Â u`), so the Euclidean null-space algebra (`null_space.rs`)
//! applies unchanged. The measurement only: the robot's model is not read.

use super::inertia::inverse_inertia_matrix;
use super::null_space::{null_space_cost, project_null};
use super::stats::Scratch;
use nalgebra::DMatrix;
use osrl_dynamics::Measurement;
use serde::{Deserialize, Serialize};

/// `N = L Lᵀ` by its lower Cholesky factor `L` (n×n); saved as `N` itself (row-major) and
/// factorised again on loading, which refuses an `N` that is not positive definite.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(into = "SavedMetric", try_from = "SavedMetric")]
pub(crate) struct Metric {
    pub(super) l: DMatrix<f64>,
}

/// The saved form of a [`Metric`]: `L` (n×n, row-major). (`L` rather than `N`: its round trip
/// is exact, so a loaded learner computes what the saved one did to the bit.)
#[derive(Serialize, Deserialize)]
struct SavedMetric {
    n: usize,
    l: Vec<f64>,
}

impl From<Metric> for SavedMetric {
    fn from(m: Metric) -> Self {
        let n = m.l.nrows();
        Self {
            n,
            l: m.l.transpose().as_slice().to_vec(),
        }
    }
}

impl TryFrom<SavedMetric> for Metric {
    type Error = String;
    fn try_from(s: SavedMetric) -> Result<Self, String> {
        let ok = s.l.len() == s.n * s.n && s.l.iter().all(|v| v.is_finite());
        let l = DMatrix::from_row_slice(s.n, s.n, &s.l);
        let lower = (0..s.n).all(|i| l[(i, i)] > 0.0 && (i + 1..s.n).all(|k| l[(i, k)] == 0.0));
        if !(ok && lower) {
            return Err(format!(
                "the cost metric's factor is not a {0}×{0} lower-triangular matrix with a \
                 positive diagonal",
                s.n
            ));
        }
        Ok(Self { l })
    }
}

impl Metric {
    /// `N = (B̂ + B̂ᵀ)/2` from the warm-up `warm` (period `dt`); `None` when the fit fails or
    /// the symmetrised estimate is not positive definite (the learner then uses `N = I`).
    pub fn inverse_inertia(warm: &[Measurement], dt: f64) -> Option<Self> {
        let b = inverse_inertia_matrix(warm, dt)?;
        let sym = (&b + b.transpose()) * 0.5;
        Self::from_matrix(sym)
    }

    /// The metric of a symmetric positive-definite `n` (`None` otherwise).
    pub fn from_matrix(n: DMatrix<f64>) -> Option<Self> {
        if !n.iter().all(|v| v.is_finite()) {
            return None;
        }
        Some(Self {
            l: n.cholesky()?.l(),
        })
    }

    /// `N = L Lᵀ` (n×n, row-major).
    pub fn matrix(&self) -> Vec<f64> {
        (&self.l * self.l.transpose())
            .transpose()
            .as_slice()
            .to_vec()
    }

    /// `uᵀ N u = ‖Lᵀ u‖²`; `v` (n) is scratch.
    pub fn norm_squared(&self, u: &[f64], v: &mut [f64]) -> f64 {
        v.copy_from_slice(u);
        self.lt_mul(v);
        v.iter().map(|x| x * x).sum()
    }

    fn n(&self) -> usize {
        self.l.nrows()
    }

    /// `Â ← Â L⁻ᵀ` in place (`a`: m×n row-major): each row `r` becomes `L⁻¹ r`.
    fn gain(&self, a: &mut [f64]) {
        let n = self.n();
        for row in a.chunks_exact_mut(n) {
            for i in 0..n {
                let v = (0..i).fold(row[i], |v, k| v - self.l[(i, k)] * row[k]);
                row[i] = v / self.l[(i, i)];
            }
        }
    }

    /// `v ← Lᵀ v`.
    fn lt_mul(&self, v: &mut [f64]) {
        let n = self.n();
        for i in 0..n {
            v[i] = (i..n).map(|k| self.l[(k, i)] * v[k]).sum();
        }
    }

    /// `v ← L⁻ᵀ v`.
    fn lt_solve(&self, v: &mut [f64]) {
        let n = self.n();
        for i in (0..n).rev() {
            let s = (i + 1..n).fold(v[i], |s, k| s - self.l[(k, i)] * v[k]);
            v[i] = s / self.l[(i, i)];
        }
    }
}

/// `‖du‖²_N` minus its task part: [`null_space_cost`] in the metric (Euclidean without one).
/// `a_n` (m×n) and `v_n` (n) are scratch.
#[allow(clippy::too_many_arguments)]
pub(crate) fn null_space_cost_in(
    metric: Option<&Metric>,
    a: &[f64],
    du: &[f64],
    m: usize,
    y: &mut [f64],
    s: &mut [f64],
    a_n: &mut [f64],
    v_n: &mut [f64],
) -> Option<f64> {
    let Some(metric) = metric else {
        return null_space_cost(a, du, m, y, s);
    };
    a_n.copy_from_slice(a);
    metric.gain(a_n);
    v_n.copy_from_slice(du);
    metric.lt_mul(v_n);
    null_space_cost(a_n, v_n, m, y, s)
}

/// `ws.z ← (I − Â⁺Â) ws.z` in the metric, with `Â` in `ws.a_hat`: [`project_null_in`] on the
/// scratch; `false` (`ws.z` unchanged up to round-off) if `Â N⁻¹ Âᵀ` is singular.
pub(crate) fn project_scratch_z(metric: Option<&Metric>, ws: &mut Scratch) -> bool {
    let m = ws.y.len();
    project_null_in(
        metric,
        &ws.a_hat,
        &mut ws.z,
        m,
        &mut ws.y,
        &mut ws.s,
        &mut ws.a_n,
    )
}

/// `z ← z − N⁻¹ Âᵀ (Â N⁻¹ Âᵀ)⁻¹ Â z`: [`project_null`] in the metric; `false` (z unchanged up
/// to round-off) if `Â N⁻¹ Âᵀ` is singular. `a_n` (m×n) is scratch.
pub(crate) fn project_null_in(
    metric: Option<&Metric>,
    a: &[f64],
    z: &mut [f64],
    m: usize,
    y: &mut [f64],
    s: &mut [f64],
    a_n: &mut [f64],
) -> bool {
    let Some(metric) = metric else {
        return project_null(a, z, m, y, s);
    };
    a_n.copy_from_slice(a);
    metric.gain(a_n);
    metric.lt_mul(z);
    let ok = project_null(a_n, z, m, y, s);
    metric.lt_solve(z);
    ok
}
