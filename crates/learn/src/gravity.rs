//! The learned gravity compensation `ĝ(q)` of the nominal behaviour: an LWPR joint-space
//! inverse-dynamics model `[q, q̇, q̈] → u`, localised in `q`, evaluated at `q̇ = q̈ = 0`.

use crate::error::Result;
use lwpr::{Lwpr, LwprConfig, LwprError, Norm};
use serde::{Deserialize, Serialize};

/// `ĝ(q)` learned from measured transitions (supervised; no robot model).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct GravityModel {
    #[serde(with = "crate::io::lwpr_bytes")]
    lwpr: Lwpr,
    n: usize,
    #[serde(skip)]
    x: Vec<f64>,
}

impl GravityModel {
    /// A model for `n` joints. `cfg` is used with its kernel on `q` and its regression on
    /// `(q, q̇, q̈)`; velocities are scaled by `velocity_scale` (rad/s) and accelerations by
    /// `acceleration_scale` (rad/s²), torques by `torque_scale` (N·m, per joint).
    pub fn new(
        n: usize,
        cfg: &LwprConfig,
        velocity_scale: f64,
        acceleration_scale: f64,
        torque_scale: &[f64],
    ) -> Result<Self> {
        let mut cfg = cfg.clone();
        cfg.shared_rfs = true;
        cfg.kernel_dims = Some((0..n).collect());
        cfg.regression_dims = Some((0..3 * n).collect());
        let mut norm = vec![1.0; n];
        norm.extend(std::iter::repeat_n(velocity_scale, n));
        norm.extend(std::iter::repeat_n(acceleration_scale, n));
        cfg.norm_in = Norm::List(norm);
        cfg.norm_out = Norm::List(torque_scale.to_vec());
        Ok(Self {
            lwpr: Lwpr::new(3 * n, n, &cfg)?,
            n,
            x: vec![0.0; 3 * n],
        })
    }

    /// Learns from one transition: the command `u` held while the state went from `(q0, q̇0)` to
    /// `(q1, q̇1)` over `dt` seconds; the sample is the midpoint state with `q̈ = Δq̇ / dt`.
    pub fn learn(
        &mut self,
        q0: &[f64],
        qd0: &[f64],
        q1: &[f64],
        qd1: &[f64],
        u: &[f64],
        dt: f64,
    ) -> Result<()> {
        let n = self.n;
        self.x.resize(3 * n, 0.0);
        for i in 0..n {
            self.x[i] = 0.5 * (q0[i] + q1[i]);
            self.x[n + i] = 0.5 * (qd0[i] + qd1[i]);
            self.x[2 * n + i] = (qd1[i] - qd0[i]) / dt;
        }
        self.lwpr.update(&self.x, u)?;
        Ok(())
    }

    /// `ĝ(q)` into `g`; `false` (and `g` zeros) where the model has no support yet.
    pub fn predict(&mut self, q: &[f64], g: &mut [f64]) -> Result<bool> {
        let n = self.n;
        self.x.resize(3 * n, 0.0);
        self.x[..n].copy_from_slice(q);
        self.x[n..].fill(0.0);
        match self.lwpr.predict(&self.x, g) {
            Ok(_) => Ok(true),
            Err(LwprError::NoActiveRf { .. }) => {
                g.fill(0.0);
                Ok(false)
            }
            Err(e) => Err(e.into()),
        }
    }

    /// Re-creates the skipped query buffers after deserialisation.
    pub(crate) fn restore_buffers(&mut self) {
        self.x = vec![0.0; 3 * self.n];
    }

    /// Number of receptive fields.
    pub fn n_rfs(&self) -> usize {
        self.lwpr.n_rfs_total()
    }
}
