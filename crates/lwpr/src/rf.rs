//! Receptive fields (RFs) and the sub-model that holds them.
//!
//! All RF state lives in normalised units. Centres and metrics are stored contiguously in the
//! [`SubModel`] (structure of arrays) so the activation pass over all RFs streams through memory;
//! everything else an RF owns is in [`Rf`] and, per output it regresses, in [`Pls`].

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
    /// slope is recomputed (by [`crate::pls::update_slope`], the same arithmetic on the same
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
            crate::pls::update_slope(self, nr);
            self.slope_stale = false;
        }
    }
}

/// Serialises the PLS models of an RF with current slopes (stale ones recomputed on a copy).
fn serialize_outs<S: serde::Serializer>(outs: &Vec<Pls>, s: S) -> Result<S::Ok, S::Error> {
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

    /// PLS growth test and step (e): adds direction `R+1` when the last direction explains
    /// enough more than the one before. Returns whether a direction was added.
    /// (The test is inlined into the update; the growth itself is a separate, cold function.)
    #[inline(always)]
    pub fn check_grow(&mut self, p: &Params) -> bool {
        let r = self.n_reg;
        let nr = p.nr();
        if r >= nr || r < 2 {
            return false;
        }
        let mse_r = self.sum_e_cv2[r - 1] / self.sum_w[r - 1] + 1e-10;
        let mse_r1 = self.sum_e_cv2[r - 2] / self.sum_w[r - 2] + 1e-10;
        if mse_r < p.cfg.add_threshold * mse_r1
            && self.n_data[r - 1] > 0.99 * self.n_data[0]
            && self.n_data[r - 1] * (1.0 - self.lambda[r - 1]) > 0.5
        {
            self.grow(p);
            true
        } else {
            false
        }
    }

    /// Adds direction `R+1` (`u = p = e_{R+1}`).
    #[cold]
    #[inline(never)]
    fn grow(&mut self, p: &Params) {
        let r = self.n_reg;
        let nr = p.nr();
        for v in [&mut self.u, &mut self.p, &mut self.sxy, &mut self.ssx] {
            v.resize((r + 1) * nr, 0.0);
        }
        self.u[r * nr + r] = 1.0;
        self.p[r * nr + r] = 1.0;
        for v in [
            &mut self.beta,
            &mut self.ss_yres,
            &mut self.n_data,
            &mut self.sum_e_cv2,
            &mut self.h_tr,
            &mut self.r_tr,
        ] {
            v.push(0.0);
        }
        self.ss_s2.push(p.cfg.init_s2);
        self.sum_w.push(1e-10);
        self.lambda.push(p.cfg.init_lambda);
        self.n_reg = r + 1;
        self.ssp = 0.0;
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

/// One receptive field: everything but its centre and metric (see [`SubModel`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Rf {
    /// Stable id, unique within the model.
    pub id: u64,
    /// Learning rates of `M` (layout of the metric).
    pub alpha: Vec<f64>,
    /// `ln α` for meta learning.
    pub b: Vec<f64>,
    /// IDBD memory `h` for meta learning.
    pub hm: Vec<f64>,
    /// Weighted mean of the regression inputs.
    pub mean_x: Vec<f64>,
    /// Weighted variance of the regression inputs.
    pub var_x: Vec<f64>,
    /// `n_data[0] > 2·nr` seen at an update.
    pub trustworthy: bool,
    /// One PLS model per output this RF regresses.
    #[serde(serialize_with = "serialize_outs")]
    pub outs: Vec<Pls>,
}

/// A list of receptive fields: one per output (reference mode) or one for all (shared mode).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct SubModel {
    /// The RFs.
    pub rfs: Vec<Rf>,
    /// Centres, `n_rf × nk`.
    pub centers: Vec<f64>,
    /// `M` per RF, `n_rf × mlen` (diagonal, or row-major upper-triangular).
    pub ms: Vec<f64>,
    /// `D = MᵀM` per RF, `n_rf × mlen` (diagonal, or full symmetric).
    pub ds: Vec<f64>,
}

impl SubModel {
    /// An empty sub-model.
    pub fn new() -> SubModel {
        SubModel {
            rfs: Vec::new(),
            centers: Vec::new(),
            ms: Vec::new(),
            ds: Vec::new(),
        }
    }

    /// Adds an RF centred at `c` (normalised kernel input) with outputs `y`; copies metric,
    /// rates, `β₀` and direction counts from RF `template` when given.
    pub fn add(&mut self, p: &Params, id: u64, c: &[f64], y: &[f64], template: Option<usize>) {
        let ml = p.mlen();
        let nr = p.nr();
        let (m, d, alpha, outs) = match template {
            Some(t) => {
                let rt = &self.rfs[t];
                let outs = rt
                    .outs
                    .iter()
                    .map(|o| Pls::new(p, o.n_reg, o.beta0))
                    .collect();
                (
                    self.ms[t * ml..(t + 1) * ml].to_vec(),
                    self.ds[t * ml..(t + 1) * ml].to_vec(),
                    rt.alpha.clone(),
                    outs,
                )
            }
            None => {
                let n_reg = if nr > 1 { 2 } else { 1 };
                let outs = y.iter().map(|&yo| Pls::new(p, n_reg, yo)).collect();
                (
                    p.init_m.clone(),
                    p.init_d.clone(),
                    vec![p.cfg.init_alpha; ml],
                    outs,
                )
            }
        };
        let b = alpha.iter().map(|a| (a + 1e-10).ln()).collect();
        self.centers.extend_from_slice(c);
        self.ms.extend_from_slice(&m);
        self.ds.extend_from_slice(&d);
        self.rfs.push(Rf {
            id,
            alpha,
            b,
            hm: vec![0.0; ml],
            mean_x: vec![0.0; nr],
            var_x: vec![0.0; nr],
            trustworthy: false,
            outs,
        });
    }

    /// Removes RF `i`, moving the last RF into its place (as the reference library does).
    pub fn remove(&mut self, p: &Params, i: usize) {
        let (nk, ml) = (p.nk(), p.mlen());
        let last = self.rfs.len() - 1;
        self.rfs.swap_remove(i);
        for (v, l) in [
            (&mut self.centers, nk),
            (&mut self.ms, ml),
            (&mut self.ds, ml),
        ] {
            if i != last {
                v.copy_within(last * l..(last + 1) * l, i * l);
            }
            v.truncate(last * l);
        }
    }

    /// Trace of RF `i`'s `D`.
    pub fn trace_d(&self, p: &Params, i: usize) -> f64 {
        let (nk, ml) = (p.nk(), p.mlen());
        let d = &self.ds[i * ml..(i + 1) * ml];
        if p.cfg.diag_only {
            d.iter().sum()
        } else {
            (0..nk).map(|k| d[k * nk + k]).sum()
        }
    }
}
