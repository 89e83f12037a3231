//! The incremental partial least squares (PLS) regression of one output inside one receptive
//! field: its state ([`Pls`]), a fresh model, and what a prediction computes from it (the
//! projections of an input and the local slope). The update's PLS steps are in
//! `update/regression.rs`.

use crate::numeric::dot;
use crate::params::Params;
use serde::{Deserialize, Serialize};

/// Directions reserved up front per PLS model, so that growth up to this many never allocates.
const RESERVE_DIRS: usize = 6;

/// Incremental PLS regression of one output inside one RF.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Pls {
    /// Number of projection directions `R`.
    pub n_reg: usize,
    /// Weighted mean of the output, `β₀`.
    pub beta0: f64,
    /// Projection directions `u_j` (direction-major, `R × nr`).
    pub u: Vec<f64>,
    /// Input loadings `p_j` (`R × nr`).
    pub p: Vec<f64>,
    /// `SXresYres_j` (`R × nr`).
    pub sxy: Vec<f64>,
    /// `SSXres_j` (`R × nr`).
    pub ssx: Vec<f64>,
    /// Regression coefficients `β_j`.
    pub beta: Vec<f64>,
    /// `SSs2_j`.
    pub ss_s2: Vec<f64>,
    /// `SSYres_j`.
    pub ss_yres: Vec<f64>,
    /// `sum_w_j`.
    pub sum_w: Vec<f64>,
    /// `n_data_j`.
    pub n_data: Vec<f64>,
    /// Forgetting factor `λ_j`.
    pub lambda: Vec<f64>,
    /// `sum_e_cv2_j`.
    pub sum_e_cv2: Vec<f64>,
    /// Metric-gradient memory trace `H_j`.
    pub h_tr: Vec<f64>,
    /// Metric-gradient memory trace `r_j`.
    pub r_tr: Vec<f64>,
    /// `SSp`.
    pub ssp: f64,
    /// `sum_e2`.
    pub sum_e2: f64,
    /// The local model's slope `∂ŷ/∂x_R` (normalised units), recomputed from the PLS state
    /// when a prediction needs it (see `slope_stale`); always current in the saved format.
    pub slope: Vec<f64>,
    /// The model changed since `slope` was computed: an update only sets this flag, and the
    /// slope is recomputed (by [`update_slope`], the same arithmetic on the same
    /// state, so the same bits) by the next prediction that uses it or by serialisation.
    #[serde(skip)]
    pub slope_stale: bool,
}

impl Pls {
    /// Whether the parts a prediction reads — `β₀`, `β`, `u`, `p` — are all finite (what
    /// loading a saved model checks; the update's guard sums the same values as its PLS step
    /// computes them, `pls::RegOut::chk`).
    #[inline(always)]
    pub fn predictors_finite(&self) -> bool {
        // Branch-free (an integer OR over the exponent tests, which vectorises): the update
        // calls this for every RF it touches.
        const EXP: u64 = 0x7ff0_0000_0000_0000;
        let bad = |v: &[f64]| {
            v.iter()
                .fold(0u64, |a, x| a | ((x.to_bits() & EXP == EXP) as u64))
        };
        (bad(&self.u) | bad(&self.p) | bad(&self.beta) | bad(&[self.beta0])) == 0
    }

    /// Recomputes `slope` if it is stale.
    #[inline(always)]
    pub fn refresh_slope(&mut self, nr: usize) {
        if self.slope_stale {
            update_slope(self, nr);
            self.slope_stale = false;
        }
    }
}

/// Serialises the PLS models of an RF with current slopes (stale ones recomputed on a copy).
pub(crate) fn serialize_outs<S: serde::Serializer>(
    outs: &Vec<Pls>,
    s: S,
) -> Result<S::Ok, S::Error> {
    if !outs.iter().any(|o| o.slope_stale) {
        return outs.serialize(s);
    }
    let mut fresh = outs.clone();
    for o in &mut fresh {
        let nr = o.slope.len();
        o.refresh_slope(nr);
    }
    fresh.serialize(s)
}

impl Pls {
    /// A fresh model with `n_reg` directions `u_j = p_j = e_j`.
    pub fn new(p: &Params, n_reg: usize, beta0: f64) -> Pls {
        let nr = p.nr();
        let cap = n_reg.max(RESERVE_DIRS.min(nr));
        let vr = || {
            let mut v = Vec::with_capacity(cap);
            v.resize(n_reg, 0.0);
            v
        };
        let vm = || {
            let mut v = Vec::with_capacity(cap * nr);
            v.resize(n_reg * nr, 0.0);
            v
        };
        let mut s = Pls {
            n_reg,
            beta0,
            u: vm(),
            p: vm(),
            sxy: vm(),
            ssx: vm(),
            beta: vr(),
            ss_s2: vr(),
            ss_yres: vr(),
            sum_w: vr(),
            n_data: vr(),
            lambda: vr(),
            sum_e_cv2: vr(),
            h_tr: vr(),
            r_tr: vr(),
            ssp: 0.0,
            sum_e2: 0.0,
            slope: vec![0.0; nr],
            slope_stale: false,
        };
        for j in 0..n_reg {
            s.u[j * nr + j] = 1.0;
            s.p[j * nr + j] = 1.0;
            s.ss_s2[j] = p.cfg.init_s2;
            s.sum_w[j] = 1e-10;
            s.n_data[j] = 1e-10;
            s.lambda[j] = p.cfg.init_lambda;
        }
        s
    }

    /// Number of directions used for prediction: all but the last while its
    /// `n_data ≤ 2·nr` (so 0 when `R = 1` and that direction is not yet trusted).
    #[inline]
    pub fn n_pred(&self, nr: usize) -> usize {
        let r = self.n_reg;
        if self.n_data[r - 1] > 2.0 * nr as f64 {
            r
        } else {
            r - 1
        }
    }
}

/// Projections `s_j` of `x` on the first `np` directions of `u` (eq. of the PLS recursion
/// `xres_{j+1} = xres_j − p_j s_j`), directions and loadings `R × nr`.
#[inline(always)]
pub(crate) fn project(
    u: &[f64],
    p: &[f64],
    nr: usize,
    np: usize,
    x: &[f64],
    xu: &mut [f64],
    s: &mut [f64],
) {
    let (u, p, xu, s) = (&u[..np * nr], &p[..np * nr], &mut xu[..nr], &mut s[..np]);
    xu.copy_from_slice(&x[..nr]);
    for j in 0..np {
        let sj = dot(&u[j * nr..(j + 1) * nr], xu);
        s[j] = sj;
        if j + 1 < np {
            for (a, &pv) in xu.iter_mut().zip(&p[j * nr..(j + 1) * nr]) {
                *a -= pv * sj;
            }
        }
    }
}

/// Recomputes `pls.slope = ∂(Σ_j β_j s_j)/∂x̃` over the predicting directions, by the adjoint
/// recursion `a_j = β_j u_j + a_{j+1} − u_j (p_j · a_{j+1})`.
#[inline(always)]
pub(crate) fn update_slope(pls: &mut Pls, nr: usize) {
    let np = pls.n_pred(nr);
    let a = &mut pls.slope;
    a.iter_mut().for_each(|v| *v = 0.0);
    for j in (0..np).rev() {
        let u = &pls.u[j * nr..(j + 1) * nr];
        let pa = dot(&pls.p[j * nr..(j + 1) * nr], a);
        let c = pls.beta[j] - pa;
        for i in 0..nr {
            a[i] += c * u[i];
        }
    }
}
