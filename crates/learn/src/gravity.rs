//! The learned gravity compensation `ĝ(q)` of the nominal behaviour: an LWPR joint-space
//! inverse-dynamics model `[q, q̇, q̈, (q̇ᵢq̇ⱼ)] → u`, localised in `q`, evaluated at `q̇ = q̈ = 0`.
//!
//! Inverse dynamics is linear in `q̈` and quadratic in `q̇` (`M(q) q̈ + C(q, q̇) q̇ + g(q)`); a local
//! model linear in `q̇` alone would fold the mean centripetal torque of its samples into its
//! intercept, i.e. into `ĝ`. The products `q̇ᵢq̇ⱼ` (i ≤ j) as extra regressors remove that bias.

use crate::error::Result;
use lwpr::{Lwpr, LwprConfig, LwprError, Norm};
use serde::{Deserialize, Serialize};

/// `ĝ(q)` learned from measured transitions (supervised; no robot model).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct GravityModel {
    #[serde(with = "crate::io::lwpr_bytes")]
    lwpr: Lwpr,
    n: usize,
    /// Whether the regressors include the velocity products `q̇ᵢq̇ⱼ`.
    products: bool,
    velocity_scale: f64,
    #[serde(skip)]
    x: Vec<f64>,
}

/// Number of regressors: `q, q̇, q̈` and, with `products`, the `n(n+1)/2` products `q̇ᵢq̇ⱼ`.
fn n_inputs(n: usize, products: bool) -> usize {
    3 * n + if products { n * (n + 1) / 2 } else { 0 }
}

impl GravityModel {
    /// A model for `n` joints. `cfg` is used with its kernel on `q` and its regression on
    /// `(q, q̇, q̈)` plus, with `products`, the velocity products `q̇ᵢq̇ⱼ`; velocities are scaled by
    /// `velocity_scale` (rad/s) and accelerations by `acceleration_scale` (rad/s²), torques by
    /// `torque_scale` (N·m, per joint).
    pub fn new(
        n: usize,
        cfg: &LwprConfig,
        products: bool,
        velocity_scale: f64,
        acceleration_scale: f64,
        torque_scale: &[f64],
    ) -> Result<Self> {
        let d = n_inputs(n, products);
        let mut cfg = cfg.clone();
        cfg.shared_rfs = true;
        cfg.kernel_dims = Some((0..n).collect());
        cfg.regression_dims = Some((0..d).collect());
        let mut norm = vec![1.0; n];
        norm.extend(std::iter::repeat_n(velocity_scale, n));
        norm.extend(std::iter::repeat_n(acceleration_scale, n));
        // The products are formed from q̇ / velocity_scale: already of unit scale.
        norm.extend(std::iter::repeat_n(1.0, d - 3 * n));
        cfg.norm_in = Norm::List(norm);
        cfg.norm_out = Norm::List(torque_scale.to_vec());
        Ok(Self {
            lwpr: Lwpr::new(d, n, &cfg)?,
            n,
            products,
            velocity_scale,
            x: vec![0.0; d],
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
        for i in 0..n {
            self.x[i] = 0.5 * (q0[i] + q1[i]);
            self.x[n + i] = 0.5 * (qd0[i] + qd1[i]);
            self.x[2 * n + i] = (qd1[i] - qd0[i]) / dt;
        }
        if self.products {
            let s = 1.0 / self.velocity_scale;
            let mut k = 3 * n;
            for i in 0..n {
                for j in i..n {
                    self.x[k] = self.x[n + i] * s * self.x[n + j] * s;
                    k += 1;
                }
            }
        }
        self.lwpr.update(&self.x, u)?;
        Ok(())
    }

    /// `ĝ(q)` into `g`; `false` (and `g` zeros) where the model has no support yet.
    pub fn predict(&mut self, q: &[f64], g: &mut [f64]) -> Result<bool> {
        let n = self.n;
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
        self.x = vec![0.0; n_inputs(self.n, self.products)];
    }

    /// Number of receptive fields.
    pub fn n_rfs(&self) -> usize {
        self.lwpr.n_rfs_total()
    }
}
