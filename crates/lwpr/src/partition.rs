//! Read access to the partition of input space: RF ids, activations, centres, metrics and
//! local linear models, and the events that tell other learners when RFs come and go.
//!
//! Everything returned here is in user units (inputs and outputs before normalisation).

use crate::error::check_vec;
use crate::model::Lwpr;
use crate::rf::{Rf, SubModel};
use crate::scratch::{quad, same_bits};
use crate::LwprError;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// A receptive field's stable id: unique within a model, never reused, kept by save/load.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct RfId(pub u64);

/// A change of the partition, queued by [`Lwpr::update`]; read with [`Lwpr::drain_events`].
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
        #[cfg(target_arch = "x86_64")]
        if crate::simd::has_avx2() {
            // SAFETY: the CPU supports AVX2 (checked at run time).
            unsafe { self.activations_avx2(sub, x, cutoff, out) };
        } else {
            self.activations_dims(sub, x, cutoff, out);
        }
        #[cfg(not(target_arch = "x86_64"))]
        self.activations_dims(sub, x, cutoff, out);
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

    /// [`Lwpr::activations`] compiled with AVX2 (same results, see `crate::simd`).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn activations_avx2(
        &mut self,
        sub: usize,
        x: &[f64],
        cutoff: f64,
        out: &mut Vec<Activation>,
    ) {
        self.activations_dims(sub, x, cutoff, out)
    }

    /// Kernel spaces of the learned controllers' forward models get a copy with the dimension
    /// as a constant (as the update does).
    #[inline(always)]
    fn activations_dims(&mut self, sub: usize, x: &[f64], cutoff: f64, out: &mut Vec<Activation>) {
        match self.p.nk() {
            14 => self.activations_core::<14>(sub, x, cutoff, out),
            6 => self.activations_core::<6>(sub, x, cutoff, out),
            _ => self.activations_core::<0>(sub, x, cutoff, out),
        }
    }

    /// The activation pass; `NK > 0` fixes the kernel dimension (0: taken from the model).
    #[inline(always)]
    fn activations_core<const NK: usize>(
        &mut self,
        sub: usize,
        x: &[f64],
        cutoff: f64,
        out: &mut Vec<Activation>,
    ) {
        let Lwpr { p, subs, ws, .. } = self;
        ws.load_x(p, x);
        let s = &subs[sub];
        let (ml, diag) = (p.mlen(), p.cfg.diag_only);
        let nk = if NK > 0 { NK } else { p.nk() };
        let kern = if diag { &s.ds } else { &s.ms };
        let qb = p.q_bound(cutoff);
        out.clear();
        let rf_chunks = s.centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
        for (rf, (c, md)) in s.rfs.iter().zip(rf_chunks) {
            let q = quad(diag, c, md, &ws.xk[..nk], &mut ws.met.dx, qb);
            if q < qb {
                let w = p.kernel(q).0;
                if w > cutoff {
                    out.push(Activation { id: RfId(rf.id), w });
                }
            }
        }
    }
}
