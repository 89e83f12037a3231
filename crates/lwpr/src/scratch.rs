//! Preallocated buffers for the hot paths (update, predict), sized once per model.

use crate::params::Params;
use crate::rf::Activation;
use crate::update::{MetricScratch, PlsScratch};

/// Work buffers; never serialised, rebuilt by [`Scratch::new`] after loading.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    /// Normalised input.
    pub xn: Vec<f64>,
    /// Normalised kernel input.
    pub xk: Vec<f64>,
    /// Normalised regression input.
    pub xr: Vec<f64>,
    /// The regression input with the kernel dimensions pulled onto an RF's support edge
    /// (`predict_everywhere`).
    pub xr_pull: Vec<f64>,
    /// Position of each kernel dimension among the regression inputs (`usize::MAX`: none).
    pub k_to_r: Vec<usize>,
    /// Normalised outputs.
    pub yn: Vec<f64>,
    /// PLS buffers.
    pub pls: PlsScratch,
    /// Metric buffers.
    pub met: MetricScratch,
    /// RFs to update: (index, w, dw/dq, d²w/dq²).
    pub active: Vec<(usize, f64, f64, f64)>,
    /// Ids of the RFs whose state the update found non-finite (numerical guard).
    pub diverged: Vec<u64>,
    /// Per-output accumulators (prediction sums).
    pub yacc: Vec<f64>,
    /// The predictions of the RF being updated, per output (normalised).
    pub rf_yp: Vec<f64>,
    /// Per-output `Σ w ŷ_k²`.
    pub wyy: Vec<f64>,
    /// Per-output `Σ w σ_k²`.
    pub wconf: Vec<f64>,
    /// Results: outputs, confidences (user units).
    pub y: Vec<f64>,
    /// Confidence bounds (user units).
    pub conf: Vec<f64>,
    /// Jacobian accumulators / result, `n_out × n_in` row-major.
    pub jac: Vec<f64>,
    /// `Σ ∂w/∂x` over the kernel dimensions.
    pub dwdx: Vec<f64>,
    /// `D (x − c)`.
    pub ddx: Vec<f64>,
    /// Per-output `Σ w` of the last prediction.
    pub support: Vec<f64>,
    /// Prediction made during the last update (normalised until the end of the update).
    pub last_yp: Vec<f64>,
    /// The last prediction's key (kind, strict) and outcome (`Ok(sum_w)`, the support;
    /// `Err(output)`: no RF active for that output), valid while the model is unchanged; its results are in `y`, `conf`, `jac`
    /// and `support`, its input in `pred_x`. Cleared by every update.
    pub pred_cache: Option<((u8, bool), Result<f64, usize>)>,
    /// Input of the cached prediction.
    pub pred_x: Vec<f64>,
    /// The last activation query's (sub-model, cutoff bits), valid while the model is
    /// unchanged; its input is in `act_x`, its result in `act_out`. Cleared by every update.
    pub act_cache: Option<(usize, u64)>,
    /// Input of the cached activation query.
    pub act_x: Vec<f64>,
    /// Result of the cached activation query.
    pub act_out: Vec<Activation>,
    /// `q_bound(W_UPDATE)` and `q_bound(cutoff)` (a logarithm each, computed once).
    pub qb_update: f64,
    /// See `qb_update`.
    pub qb_cutoff: f64,
    /// All input divisors are 1 (`x / 1 = x` exactly: normalising is a copy).
    pub unit_in: bool,
}

impl Scratch {
    /// Buffers for a model with parameters `p`, room for `n_rf` active RFs.
    pub fn new(p: &Params, n_rf: usize) -> Scratch {
        let (n_in, n_out, nk, nr) = (p.n_in, p.n_out, p.nk(), p.nr());
        Scratch {
            xn: vec![0.0; n_in],
            xk: vec![0.0; nk],
            xr: vec![0.0; nr],
            xr_pull: vec![0.0; nr],
            k_to_r: p
                .kdims
                .iter()
                .map(|i| p.rdims.iter().position(|d| d == i).unwrap_or(usize::MAX))
                .collect(),
            yn: vec![0.0; n_out],
            pls: PlsScratch::new(nr),
            met: MetricScratch::new(nk, p.mlen(), crate::fast::wide::scratch_len(nk, p.mlen())),
            active: Vec::with_capacity(n_rf.max(64)),
            diverged: Vec::with_capacity(n_rf.max(64)),
            yacc: vec![0.0; n_out],
            rf_yp: vec![0.0; n_out],
            wyy: vec![0.0; n_out],
            wconf: vec![0.0; n_out],
            y: vec![0.0; n_out],
            conf: vec![0.0; n_out],
            jac: vec![0.0; n_out * n_in],
            dwdx: vec![0.0; nk],
            ddx: vec![0.0; nk],
            support: vec![0.0; n_out],
            last_yp: vec![f64::NAN; n_out],
            pred_cache: None,
            pred_x: vec![0.0; n_in],
            act_cache: None,
            act_x: vec![0.0; n_in],
            act_out: Vec::with_capacity(n_rf.max(64)),
            qb_update: p.q_bound(crate::params::W_UPDATE),
            qb_cutoff: p.q_bound(p.cfg.cutoff),
            unit_in: p.norm_in.iter().all(|&v| v == 1.0),
        }
    }

    /// Forgets the cached query results (the model changed).
    #[inline]
    pub fn invalidate(&mut self) {
        self.pred_cache = None;
        self.act_cache = None;
    }

    /// Normalises `x` into `xn`, `xk`, `xr`.
    #[inline(always)]
    pub fn load_x(&mut self, p: &Params, x: &[f64]) {
        let xn = &mut self.xn[..p.n_in];
        if self.unit_in {
            xn.copy_from_slice(&x[..p.n_in]);
        } else {
            for (v, (&a, &n)) in xn.iter_mut().zip(x.iter().zip(&p.norm_in)) {
                *v = a / n;
            }
        }
        for (k, &i) in p.kdims.iter().enumerate() {
            self.xk[k] = self.xn[i];
        }
        for (k, &i) in p.rdims.iter().enumerate() {
            self.xr[k] = self.xn[i];
        }
    }
}

/// Whether `a` and `b` hold the same bits (so a query at `a` repeats one at `b` exactly).
#[inline]
pub(crate) fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}
