//! Receptive fields (RFs): their stable ids and the events that announce them, and the
//! sub-model that holds a list of them.
//!
//! All RF state lives in normalised units. Centres and metrics are stored contiguously in the
//! [`SubModel`] (structure of arrays) so the activation pass over all RFs streams through memory;
//! everything else an RF owns is in [`Rf`] and, per output it regresses, in [`Pls`].

use crate::head::{self, Heads};
use crate::params::Params;
use crate::pls::Pls;
use serde::{Deserialize, Serialize};

/// A receptive field's stable id: unique within a model, never reused, kept by save/load.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct RfId(pub u64);

/// A change of the partition, queued by [`crate::Lwpr::update`]; read with
/// [`crate::Lwpr::drain_events`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum RfEvent {
    /// A new RF in sub-model `sub`, possibly copying the metric of RF `copied_from`.
    Added {
        /// Sub-model (the output in per-output mode, 0 with shared RFs).
        sub: usize,
        /// The new RF.
        id: RfId,
        /// The RF whose metric and `β₀` it started from, if any.
        copied_from: Option<RfId>,
    },
    /// An RF was removed from sub-model `sub`.
    Pruned {
        /// Sub-model.
        sub: usize,
        /// The removed RF.
        id: RfId,
    },
}

/// One RF's activation at an input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Activation {
    /// The RF.
    pub id: RfId,
    /// `w ∈ (0, 1]`.
    pub w: f64,
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
    #[serde(serialize_with = "crate::pls::serialize_outs")]
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
    /// Per RF, the first entries of its rows of `centers` and `ds` where the model keeps heads
    /// (`head::in_use`), else empty; rebuilt on loading.
    #[serde(skip)]
    pub heads: Heads,
}

impl SubModel {
    /// An empty sub-model.
    pub fn new() -> SubModel {
        SubModel {
            rfs: Vec::new(),
            centers: Vec::new(),
            ms: Vec::new(),
            ds: Vec::new(),
            heads: Heads::default(),
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
        if head::in_use(p) {
            self.heads.push(c, &d);
        }
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
        if head::in_use(p) {
            self.heads.swap_remove(i);
        }
    }

    /// Copies RF `i`'s row of `ds` into its head, after its metric changed.
    #[inline(always)]
    pub fn sync_head(&mut self, p: &Params, i: usize) {
        if head::in_use(p) {
            let ml = p.mlen();
            self.heads.set_metric(i, &self.ds[i * ml..(i + 1) * ml]);
        }
    }

    /// Builds every RF's head from `centers` and `ds` (after loading).
    pub fn rebuild_heads(&mut self, p: &Params) {
        self.heads.clear();
        if head::in_use(p) {
            let (nk, ml) = (p.nk(), p.mlen());
            let rows = self.centers.chunks_exact(nk).zip(self.ds.chunks_exact(ml));
            for (c, d) in rows {
                self.heads.push(c, d);
            }
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
