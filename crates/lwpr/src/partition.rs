//! Read access to the partition of input space: RF ids, activations, centres, metrics and
//! local linear models, and the events that tell other learners when RFs come and go.
//!
//! Everything returned here is in user units (inputs and outputs before normalisation).

use crate::error::check_vec;
use crate::model::Lwpr;
use crate::rf::{Activation, Rf, RfEvent, RfId, SubModel};
use crate::scratch::same_bits;
use crate::LwprError;
use nalgebra::DMatrix;

/// The local linear model of one output in one RF:
/// `ŷ(x) = offset + slope · (x_R − mean)` over the regression dimensions `x_R`.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalModel {
    /// `β₀`: the RF's weighted mean output.
    pub offset: f64,
    /// The RF's weighted mean of the regression inputs.
    pub mean: Vec<f64>,
    /// `∂ŷ/∂x_R` (the PLS regression, over its predicting directions).
    pub slope: Vec<f64>,
}

/// A read-only view of one RF.
pub struct RfView<'a> {
    model: &'a Lwpr,
    sub: &'a SubModel,
    s: usize,
    i: usize,
    rf: &'a Rf,
}

impl RfView<'_> {
    /// Stable id.
    pub fn id(&self) -> RfId {
        RfId(self.rf.id)
    }

    /// Whether the RF has seen enough data to predict (`n_data > 2·n_reg_dims`).
    pub fn trustworthy(&self) -> bool {
        self.rf.trustworthy
    }

    /// Effective number of samples seen (first PLS direction, forgetting applied).
    pub fn n_data(&self) -> f64 {
        self.rf.outs[0].n_data[0]
    }

    /// Number of PLS directions of each output this RF regresses.
    pub fn n_reg(&self) -> Vec<usize> {
        self.rf.outs.iter().map(|o| o.n_reg).collect()
    }

    /// Centre over the kernel dimensions.
    pub fn center(&self) -> Vec<f64> {
        let p = &self.model.p;
        let nk = p.nk();
        let c = &self.sub.centers[self.i * nk..(self.i + 1) * nk];
        c.iter()
            .zip(&p.kdims)
            .map(|(v, &d)| v * p.norm_in[d])
            .collect()
    }

    /// Distance metric `D` over the kernel dimensions: `w = K((x − c)ᵀ D (x − c))`.
    pub fn metric(&self) -> DMatrix<f64> {
        let p = &self.model.p;
        let (nk, ml) = (p.nk(), p.mlen());
        let d = &self.sub.ds[self.i * ml..(self.i + 1) * ml];
        DMatrix::from_fn(nk, nk, |r, c| {
            let v = if p.cfg.diag_only {
                if r == c {
                    d[r]
                } else {
                    0.0
                }
            } else {
                d[r * nk + c]
            };
            v / (p.norm_in[p.kdims[r]] * p.norm_in[p.kdims[c]])
        })
    }

    /// Learning rates `α` of the metric's factor `M` (`D = MᵀM`, `M` upper-triangular), one
    /// per element, `nk × nk` over the kernel dimensions: the upper triangle (only the
    /// diagonal with `diag_only`), zeros elsewhere; in the normalised input space. A new RF
    /// starts from `init_alpha` (or its template's rates); meta learning (`meta`) adapts them,
    /// and a step that would decrease an element by more than a tenth of `max |M|` halves its
    /// rate instead.
    pub fn learning_rates(&self) -> DMatrix<f64> {
        let nk = self.model.p.nk();
        let alpha = &self.rf.alpha;
        DMatrix::from_fn(nk, nk, |r, c| match self.model.p.cfg.diag_only {
            true if r == c => alpha[r],
            false if c >= r => alpha[r * nk + c],
            _ => 0.0,
        })
    }

    /// The local linear model of local output `o` (0 in per-output mode; the output index
    /// with shared RFs).
    pub fn local_model(&self, o: usize) -> Option<LocalModel> {
        let p = &self.model.p;
        let mut pls = self.rf.outs.get(o)?.clone();
        pls.refresh_slope(p.nr());
        let no = p.norm_out[if p.cfg.shared_rfs { o } else { self.s }];
        Some(LocalModel {
            offset: pls.beta0 * no,
            mean: (self.rf.mean_x.iter().zip(&p.rdims))
                .map(|(m, &d)| m * p.norm_in[d])
                .collect(),
            slope: (pls.slope.iter().zip(&p.rdims))
                .map(|(s, &d)| s * no / p.norm_in[d])
                .collect(),
        })
    }
}

impl Lwpr {
    fn sub(&self, sub: usize) -> Result<&SubModel, LwprError> {
        self.subs.get(sub).ok_or(LwprError::NoSubModel {
            index: sub,
            count: self.subs.len(),
        })
    }

    /// Views of all RFs of sub-model `sub` (in storage order, which pruning may change).
    pub fn rfs(&self, sub: usize) -> Result<impl Iterator<Item = RfView<'_>>, LwprError> {
        let s = self.sub(sub)?;
        Ok(s.rfs.iter().enumerate().map(move |(i, rf)| RfView {
            model: self,
            sub: s,
            s: sub,
            i,
            rf,
        }))
    }

    /// The RF with this id in sub-model `sub`, if it exists.
    pub fn rf(&self, sub: usize, id: RfId) -> Option<RfView<'_>> {
        self.rfs(sub).ok()?.find(|v| v.id() == id)
    }

    /// Removes the RF `id` from sub-model `sub` and queues an [`RfEvent::Pruned`] for it, so
    /// learners that follow the partition drop their per-RF state as on any other pruning.
    /// Returns `Ok(false)` (nothing changed) if there is no such RF; fails on a sub-model index
    /// out of range. The last RF takes the removed one's storage slot, as in LWPR's own pruning.
    ///
    /// ```
    /// use lwpr::{Lwpr, LwprConfig, RfEvent};
    /// let mut m = Lwpr::new(1, 1, &LwprConfig::default()).unwrap();
    /// m.update(&[0.0], &[1.0]).unwrap();
    /// let id = m.rfs(0).unwrap().next().unwrap().id();
    /// m.drain_events().for_each(drop);
    /// assert!(m.remove_rf(0, id).unwrap());
    /// assert_eq!(m.n_rfs_total(), 0);
    /// assert_eq!(m.events(), &[RfEvent::Pruned { sub: 0, id }]);
    /// assert!(!m.remove_rf(0, id).unwrap());
    /// ```
    pub fn remove_rf(&mut self, sub: usize, id: RfId) -> Result<bool, LwprError> {
        self.sub(sub)?;
        let Some(i) = self.subs[sub].rfs.iter().position(|rf| rf.id == id.0) else {
            return Ok(false);
        };
        self.ws.invalidate();
        self.subs[sub].remove(&self.p, i);
        self.events.push(RfEvent::Pruned { sub, id });
        Ok(true)
    }

    /// Writes into `out` (cleared first) the activations `w > cutoff` of every RF of
    /// sub-model `sub` at input `x`, trustworthy or not. Does not allocate once `out` has
    /// capacity for the result.
    pub fn activations(
        &mut self,
        sub: usize,
        x: &[f64],
        cutoff: f64,
        out: &mut Vec<Activation>,
    ) -> Result<(), LwprError> {
        check_vec("x", x, self.p.n_in)?;
        self.sub(sub)?;
        // A repeated query (same sub-model, input and cutoff bits) on an unchanged model.
        let key = (sub, cutoff.to_bits());
        let ws = &mut self.ws;
        if ws.act_cache == Some(key) && same_bits(x, &ws.act_x) {
            out.clear();
            out.extend_from_slice(&ws.act_out);
            return Ok(());
        }
        crate::fast::activations(&self.p, &self.subs[sub], &mut self.ws, x, cutoff, out);
        // Kept for the next query unless that would allocate (the buffer grows with the model).
        let ws = &mut self.ws;
        ws.act_cache = None;
        if ws.act_out.capacity() >= out.len() {
            ws.act_out.clear();
            ws.act_out.extend_from_slice(out);
            ws.act_x.copy_from_slice(x);
            ws.act_cache = Some(key);
        }
        Ok(())
    }
}
