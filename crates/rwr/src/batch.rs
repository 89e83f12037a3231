//! Batch EM iterations of Algorithm 2 (eq. 23, 24, 25, 28).

use crate::config::RwrConfig;
use crate::error::{Result, RwrError};
use crate::policy::{check_finite, check_len, LinearGaussianPolicy};
use crate::stats::{Solver, Stats};
use crate::weights::{external_ess, normalized_weights};
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// What one M-step did.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepInfo {
    /// `τ` the weights of this step were computed with.
    pub tau_used: f64,
    /// `τ` after the step (eq. 28 and safeguards; `tau_used` when fixed).
    pub tau_next: f64,
    /// `σ` after the step (eq. 24, floored).
    pub sigma: f64,
    /// Effective sample size `(Σw)²/Σw²` of the step's weights.
    pub ess: f64,
    /// Weighted mean cost `Σ w r / Σ w` (so eq. 28 is its inverse).
    pub mean_cost: f64,
    /// Factor by which the trust region shrank the step of `θ` (1: not shrunk; online form).
    #[serde(default = "one")]
    pub shrink: f64,
}

fn one() -> f64 {
    1.0
}

/// Reward-weighted regression on batches of samples (Algorithm 2): each [`BatchRwr::em_step`]
/// is one EM iteration on the samples drawn from the current policy.
#[derive(Debug, Clone)]
pub struct BatchRwr {
    cfg: RwrConfig,
    policy: LinearGaussianPolicy,
    tau: f64,
    ess: f64,
    stats: Stats,
    solver: Solver,
    weights: Vec<f64>,
}

impl BatchRwr {
    /// `θ = 0` (`p × d`), `σ = sigma_init`, `τ = tau_init`. Fails on an invalid config or a
    /// zero dimension.
    pub fn new(p: usize, d: usize, cfg: RwrConfig) -> Result<Self> {
        cfg.validate()?;
        let policy = LinearGaussianPolicy::zeros(p, d, cfg.sigma_init)?;
        Self::with_policy(policy, cfg)
    }

    /// Starts from a given `θ` with `σ = sigma_init` and `τ = tau_init`.
    pub fn with_theta(theta: DMatrix<f64>, cfg: RwrConfig) -> Result<Self> {
        cfg.validate()?;
        Self::with_policy(LinearGaussianPolicy::new(theta, cfg.sigma_init)?, cfg)
    }

    fn with_policy(policy: LinearGaussianPolicy, cfg: RwrConfig) -> Result<Self> {
        let (p, d) = (policy.n_features(), policy.n_actions());
        let tau = cfg.tau_init;
        Ok(Self {
            cfg,
            policy,
            tau,
            ess: 0.0,
            stats: Stats::new(p, d),
            solver: Solver::new(p, d),
            weights: Vec::new(),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &RwrConfig {
        &self.cfg
    }
    /// The current policy `N(u | θᵀφ, σ² I)`.
    pub fn policy(&self) -> &LinearGaussianPolicy {
        &self.policy
    }
    /// `θ` (`p × d`).
    pub fn theta(&self) -> &DMatrix<f64> {
        self.policy.theta()
    }
    /// Exploration `σ`.
    pub fn sigma(&self) -> f64 {
        self.policy.sigma()
    }
    /// The reward transformation's `τ` the next step will use.
    pub fn tau(&self) -> f64 {
        self.tau
    }
    /// Effective sample size of the last step's weights (0 before the first step).
    pub fn ess(&self) -> f64 {
        self.ess
    }

    /// One EM iteration on `n` samples: rows of `phi` (`n × p`, eq. 26) are features `φ(s_i)ᵀ`,
    /// rows of `u` (`n × d`, eq. 27) actions, `costs` the costs `r_i ≥ 0`, `ext` optional
    /// external weights `a_i ≥ 0` (multiplying the transformed reward).
    ///
    /// E-step: `w_i ∝ a_i exp(−τ r_i)` (eq. 25, 29, in log space). M-step: `θ` by eq. 23 with
    /// ridge, `σ² = Σ w_i ‖u_i − θᵀφ_i‖² / (d Σ w_i)` (eq. 24 with the ML `1/d`), floored, and
    /// `τ` by eq. 28 unless fixed. Fails, changing nothing, on wrong shapes, non-finite
    /// features/actions, negative or non-finite costs/weights, no positive weight, or a
    /// singular Gram matrix.
    pub fn em_step(
        &mut self,
        phi: &DMatrix<f64>,
        u: &DMatrix<f64>,
        costs: &[f64],
        ext: Option<&[f64]>,
    ) -> Result<StepInfo> {
        let (p, d, n) = (
            self.policy.n_features(),
            self.policy.n_actions(),
            costs.len(),
        );
        check_len("feature columns", p, phi.ncols())?;
        check_len("action columns", d, u.ncols())?;
        check_len("feature rows", n, phi.nrows())?;
        check_len("action rows", n, u.nrows())?;
        if n == 0 {
            return Err(RwrError::NoWeight);
        }
        check_finite("features", phi.as_slice())?;
        check_finite("actions", u.as_slice())?;
        self.weights.resize(n, 0.0);
        let ess = normalized_weights(self.tau, costs, ext, &mut self.weights)?;
        let (mut phi_i, mut u_i) = (vec![0.0; p], vec![0.0; d]);
        self.stats.clear();
        for i in 0..n {
            phi_i
                .iter_mut()
                .zip(phi.row(i).iter())
                .for_each(|(a, b)| *a = *b);
            u_i.iter_mut()
                .zip(u.row(i).iter())
                .for_each(|(a, b)| *a = *b);
            self.stats.add(self.weights[i], &phi_i, &u_i, costs[i]);
        }
        self.solver.solve(&self.stats, self.cfg.ridge)?;
        // Eq. 24 directly from the residuals (the online form uses the expanded statistics).
        let theta = &self.solver.theta;
        let mut sq = 0.0;
        for i in 0..n {
            let mut res2 = 0.0;
            for k in 0..d {
                let mean: f64 = (0..p).map(|j| phi[(i, j)] * theta[(j, k)]).sum();
                res2 += (u[(i, k)] - mean).powi(2);
            }
            sq += self.weights[i] * res2;
        }
        let sigma = self
            .cfg
            .next_sigma(self.policy.sigma(), sq / (d as f64 * self.stats.sw));
        let mean_cost = self.stats.mean_cost();
        let ess_ext = external_ess(ext, n);
        let tau_next = self.cfg.next_tau(self.tau, mean_cost, ess, ess_ext);
        let info = StepInfo {
            tau_used: self.tau,
            tau_next,
            sigma,
            ess,
            mean_cost,
            shrink: 1.0,
        };
        self.policy.set(&self.solver.theta, sigma);
        self.tau = tau_next;
        self.ess = ess;
        Ok(info)
    }
}
