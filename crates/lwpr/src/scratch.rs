//! Preallocated buffers for the hot paths (update, predict), sized once per model.

use crate::metric::MetricScratch;
use crate::params::Params;
use crate::pls::PlsScratch;

/// Work buffers; never serialised, rebuilt by [`Scratch::new`] after loading.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    /// Normalised input.
    pub xn: Vec<f64>,
    /// Normalised kernel input.
    pub xk: Vec<f64>,
    /// Normalised regression input.
    pub xr: Vec<f64>,
    /// Normalised outputs.
    pub yn: Vec<f64>,
    /// PLS buffers.
    pub pls: PlsScratch,
    /// Metric buffers.
    pub met: MetricScratch,
    /// RFs to update: (index, w, dw/dq, d²w/dq²).
    pub active: Vec<(usize, f64, f64, f64)>,
    /// Per-output accumulators (prediction sums).
    pub yacc: Vec<f64>,
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
}

impl Scratch {
    /// Buffers for a model with parameters `p`, room for `n_rf` active RFs.
    pub fn new(p: &Params, n_rf: usize) -> Scratch {
        let (n_in, n_out, nk, nr) = (p.n_in, p.n_out, p.nk(), p.nr());
        Scratch {
            xn: vec![0.0; n_in],
            xk: vec![0.0; nk],
            xr: vec![0.0; nr],
            yn: vec![0.0; n_out],
            pls: PlsScratch::new(nr),
            met: MetricScratch::new(nk, p.mlen()),
            active: Vec::with_capacity(n_rf.max(64)),
            yacc: vec![0.0; n_out],
            wyy: vec![0.0; n_out],
            wconf: vec![0.0; n_out],
            y: vec![0.0; n_out],
            conf: vec![0.0; n_out],
            jac: vec![0.0; n_out * n_in],
            dwdx: vec![0.0; nk],
            ddx: vec![0.0; nk],
            support: vec![0.0; n_out],
            last_yp: vec![f64::NAN; n_out],
        }
    }

    /// Normalises `x` into `xn`, `xk`, `xr`.
    pub fn load_x(&mut self, p: &Params, x: &[f64]) {
        for i in 0..p.n_in {
            self.xn[i] = x[i] / p.norm_in[i];
        }
        for (k, &i) in p.kdims.iter().enumerate() {
            self.xk[k] = self.xn[i];
        }
        for (k, &i) in p.rdims.iter().enumerate() {
            self.xr[k] = self.xn[i];
        }
    }
}

/// `q = (x − c)ᵀ D (x − c)`: from the diagonal of `D`, or as `‖M (x − c)‖²` with the
/// upper-triangular `M` (row-major); `dx` receives `x − c`.
#[inline]
pub(crate) fn quad(diag: bool, c: &[f64], md: &[f64], x: &[f64], dx: &mut [f64]) -> f64 {
    if diag {
        let mut q = 0.0;
        for i in 0..x.len() {
            let d = x[i] - c[i];
            q += md[i] * d * d;
        }
        q
    } else {
        let nk = x.len();
        for i in 0..nk {
            dx[i] = x[i] - c[i];
        }
        let mut q = 0.0;
        for n in 0..nk {
            let row = &md[n * nk + n..(n + 1) * nk];
            let v: f64 = row.iter().zip(&dx[n..]).map(|(a, b)| a * b).sum();
            q += v * v;
        }
        q
    }
}
