//! The learned gravity compensation `ĝ(q)` of the nominal behaviour: an LWPR joint-space
//! inverse-dynamics model `[q, q̇, q̈, (q̇ᵢq̇ⱼ)] → u`, localised in `q`, evaluated at `q̇ = q̈ = 0`.
//!
//! Inverse dynamics is linear in `q̈` and quadratic in `q̇` (`M(q) q̈ + C(q, q̇) q̇ + g(q)`); a local
//! model linear in `q̇` alone would fold the mean centripetal torque of its samples into its
//! intercept, i.e. into `ĝ`. The products `q̇ᵢq̇ⱼ` (i ≤ j) as extra regressors remove that bias.
//!
//! The static variant ([`GravityModel::new_static`]) learns only from still samples (`|q̇|`, `|q̈|`
//! below a [`StaticGate`] on every joint), where `u = g(q)` up to the gate, and regresses on `q`
//! alone: its local models need no PLS directions for `q̇, q̈` (sarcos7 after 4 minutes of
//! babbling, seeds 0/1/2: 0.08–0.10 N·m RMS error inside the babbling region against 0.47–0.50
//! N·m for the dynamic model).

mod budget;
mod gate;

pub use gate::StaticGate;

use crate::error::{LearnError, Result};
use budget::PostureBudget;
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
    /// Static variant: learn only from still samples, regress on `q` alone.
    gate: Option<StaticGate>,
    /// Static variant: the still samples learned per posture so far
    /// (`StaticGate::max_samples_per_posture`).
    budget: PostureBudget,
    /// The budget is lifted (not saved): every still sample counts, as while the null-space
    /// correction re-adapts (`learner/null_gravity.rs`).
    #[serde(skip)]
    unbudgeted: bool,
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
        let regression = (0..n_inputs(n, products)).collect();
        Self::build(
            n,
            cfg,
            products,
            regression,
            velocity_scale,
            acceleration_scale,
            torque_scale,
        )
    }

    /// The model with the kernel on `q` and the regression on the inputs `regression`.
    fn build(
        n: usize,
        cfg: &LwprConfig,
        products: bool,
        regression: Vec<usize>,
        velocity_scale: f64,
        acceleration_scale: f64,
        torque_scale: &[f64],
    ) -> Result<Self> {
        let d = n_inputs(n, products);
        let mut cfg = cfg.clone();
        cfg.shared_rfs = true;
        cfg.kernel_dims = Some((0..n).collect());
        cfg.regression_dims = Some(regression);
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
            gate: None,
            budget: PostureBudget::default(),
            unbudgeted: false,
            x: vec![0.0; d],
        })
    }

    /// The static variant for `n` joints: the same inputs (so the same queries), but the
    /// regression uses `q` only and [`learn`](Self::learn) keeps only samples that pass `gate`.
    pub fn new_static(
        n: usize,
        cfg: &LwprConfig,
        gate: StaticGate,
        velocity_scale: f64,
        acceleration_scale: f64,
        torque_scale: &[f64],
    ) -> Result<Self> {
        let regression = (0..n).collect();
        let mut g = Self::build(
            n,
            cfg,
            false,
            regression,
            velocity_scale,
            acceleration_scale,
            torque_scale,
        )?;
        g.gate = Some(gate);
        Ok(g)
    }

    /// Whether this is the static variant.
    pub fn is_static(&self) -> bool {
        self.gate.is_some()
    }

    /// Learns from one transition: the command `u` held while the state went from `(q0, q̇0)` to
    /// `(q1, q̇1)` over `dt` seconds; the sample is the midpoint state with `q̈ = Δq̇ / dt`. The
    /// static variant ignores samples that are not still, and those of a posture whose budget
    /// is spent ([`StaticGate::max_samples_per_posture`]).
    ///
    /// # Errors
    /// The LWPR update's error (non-finite or out-of-range input or torque); the model, and the
    /// static variant's budget, are then unchanged.
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
        let mut slot = None;
        if let Some(g) = self.gate {
            let still = g.is_still(qd0, qd1, dt);
            if !still {
                return Ok(());
            }
            if g.max_samples_per_posture > 0 && !self.unbudgeted {
                match self
                    .budget
                    .slot(&self.x[..n], g.posture_radius, g.max_samples_per_posture)
                {
                    Some(s) => slot = Some(s),
                    None => return Ok(()),
                }
            }
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
        if let Some(s) = slot {
            self.budget.count(s, &self.x[..n]);
        }
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

    /// `ĝ(q)` into `g` from every trustworthy field, without LWPR's cutoff
    /// ([`Lwpr::predict_everywhere`]): continuous in `q`, and defined far from the data (the
    /// nearest fields' models at the edge of their support). Returns `ln Σ w`, the log of the
    /// model's total activation at `q`, or `None` (and `g` zeros) while no field is trustworthy.
    pub fn predict_everywhere(&mut self, q: &[f64], g: &mut [f64]) -> Result<Option<f64>> {
        let n = self.n;
        self.x[..n].copy_from_slice(q);
        self.x[n..].fill(0.0);
        match self.lwpr.predict_everywhere(&self.x, g) {
            Ok(ln_sum) => Ok(Some(ln_sum)),
            Err(LwprError::NoActiveRf { .. }) => {
                g.fill(0.0);
                Ok(None)
            }
            Err(e) => Err(e.into()),
        }
    }

    /// Lifts the static variant's budget per posture (`true`) or restores it: while lifted,
    /// every still sample is learned and none is counted.
    pub(crate) fn set_unbudgeted(&mut self, lifted: bool) {
        self.unbudgeted = lifted;
    }

    /// Re-creates the skipped query buffers after deserialisation.
    pub(crate) fn restore_buffers(&mut self) {
        self.x = vec![0.0; n_inputs(self.n, self.products)];
    }

    /// Checks what a loaded file says beyond its LWPR model: the static gate's ranges and the
    /// budget's postures (`n` values each, finite).
    ///
    /// # Errors
    /// [`LearnError::Load`] naming what is inconsistent.
    pub(crate) fn check_loaded(&self) -> Result<()> {
        if let Some(g) = &self.gate {
            g.validate()
                .map_err(|e| LearnError::Load(format!("static gravity gate: {e}")))?;
        }
        self.budget
            .check(self.n)
            .map_err(|why| LearnError::Load(format!("static gravity model's postures: {why}")))
    }

    /// The LWPR model (read access: its receptive fields and their local regressions).
    pub fn lwpr(&self) -> &Lwpr {
        &self.lwpr
    }

    /// Number of receptive fields.
    pub fn n_rfs(&self) -> usize {
        self.lwpr.n_rfs_total()
    }

    /// Static variant: the number of postures its still samples came from (0 for the dynamic
    /// model, or with no budget).
    pub fn n_postures(&self) -> usize {
        self.budget.len()
    }
}

#[cfg(test)]
mod tests;
