//! The forward model `ẍ = f(q, q̇, u)`: LWPR with the kernel on `(q, q̇)` (eq. 33), local
//! regression on `(q̇, u)` (eq. 32) and one set of receptive fields for all task dimensions. Its
//! receptive fields are the partition the local controllers live on.

use crate::error::Result;
use lwpr::{Activation, Lwpr, LwprConfig, Norm, RfEvent, RfId};
use serde::{Deserialize, Serialize};

/// The forward model and the input buffer of its queries.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ForwardModel {
    #[serde(with = "crate::io::lwpr_bytes")]
    lwpr: Lwpr,
    n: usize,
    m: usize,
    #[serde(skip)]
    x: Vec<f64>,
}

impl ForwardModel {
    /// A model for `n` joints and `m` task dimensions; velocities scaled by `velocity_scale`
    /// (rad/s), torques by `torque_scale` (N·m per joint), accelerations by `acc_scale` (m/s²).
    pub fn new(
        n: usize,
        m: usize,
        cfg: &LwprConfig,
        velocity_scale: f64,
        torque_scale: &[f64],
        acc_scale: f64,
        with_q: bool,
    ) -> Result<Self> {
        // With `with_q` the local regression also uses `q`: inside a receptive field `ẍ` varies
        // with `q` through `h(q)`, and without `q` that variation (correlated with the gravity
        // compensation in `u`) biases the slope `∂ẍ/∂u` towards zero.
        let mut cfg = cfg.clone();
        cfg.shared_rfs = true;
        cfg.kernel_dims = Some((0..2 * n).collect());
        cfg.regression_dims = Some(((if with_q { 0 } else { n })..3 * n).collect());
        let mut norm = vec![1.0; n];
        norm.extend(std::iter::repeat_n(velocity_scale, n));
        norm.extend_from_slice(torque_scale);
        cfg.norm_in = Norm::List(norm);
        cfg.norm_out = Norm::List(vec![acc_scale; m]);
        Ok(Self {
            lwpr: Lwpr::new(3 * n, m, &cfg)?,
            n,
            m,
            x: vec![0.0; 3 * n],
        })
    }

    fn load(&mut self, q: &[f64], qd: &[f64], u: Option<&[f64]>) {
        let n = self.n;
        self.x.resize(3 * n, 0.0);
        self.x[..n].copy_from_slice(q);
        self.x[n..2 * n].copy_from_slice(qd);
        match u {
            Some(u) => self.x[2 * n..].copy_from_slice(u),
            None => self.x[2 * n..].fill(0.0),
        }
    }

    /// Learns `ẍ` measured under command `u` at `(q, q̇)`; partition changes are queued as events.
    pub fn learn(&mut self, q: &[f64], qd: &[f64], u: &[f64], xdd: &[f64]) -> Result<()> {
        self.load(q, qd, Some(u));
        self.lwpr.update(&self.x, xdd)?;
        Ok(())
    }

    /// Removes a receptive field (queues its `Pruned` event); `false` if there is none.
    pub fn remove(&mut self, id: RfId) -> Result<bool> {
        Ok(self.lwpr.remove_rf(0, id)?)
    }

    /// Takes the queued partition events (RFs added or pruned).
    pub fn drain_events(&mut self, out: &mut Vec<RfEvent>) {
        out.extend(self.lwpr.drain_events());
    }

    /// Activations `w^i(q, q̇) > cutoff` of all receptive fields (eq. 33) into `out`.
    pub fn activations(
        &mut self,
        q: &[f64],
        qd: &[f64],
        cutoff: f64,
        out: &mut Vec<Activation>,
    ) -> Result<()> {
        self.load(q, qd, None);
        self.lwpr.activations(0, &self.x, cutoff, out)?;
        Ok(())
    }

    /// Re-creates the skipped query buffers after deserialisation.
    pub(crate) fn restore_buffers(&mut self) {
        self.x = vec![0.0; 3 * self.n];
    }

    /// Centre of a receptive field in `(q, q̇)`.
    pub fn center(&self, id: RfId) -> Option<Vec<f64>> {
        self.lwpr.rf(0, id).map(|v| v.center())
    }

    pub fn n_rfs(&self) -> usize {
        self.lwpr.n_rfs_total()
    }

    /// The underlying LWPR model (read only).
    pub fn lwpr(&self) -> &Lwpr {
        &self.lwpr
    }
}
