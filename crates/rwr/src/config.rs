//! Configuration shared by the batch ([`crate::BatchRwr`]) and online ([`crate::OnlineRwr`]) forms.

use crate::error::{Result, RwrError};
use serde::{Deserialize, Serialize};

/// Settings of reward-weighted regression (Algorithm 2). Units: "cost" is the unit of `r`,
/// "action" the unit of `u`. Defaults are the paper's algorithm with no safeguards switched on
/// (faithful); switch on `tau_max` or `min_ess` when costs can approach zero.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RwrConfig {
    /// Initial reward-transformation parameter `τ_0` (1/cost). Must be > 0. Default 1.0.
    pub tau_init: f64,
    /// Update `τ` by eq. 28 after every M-step (`true`), or keep it at `tau_init` (`false`: the
    /// fixed-transformation ablation of Fig. 1). Default `true`.
    pub adapt_tau: bool,
    /// Cap on the adaptive `τ` (1/cost): eq. 28 is clipped to it. `None` = no cap. As costs
    /// approach zero, eq. 28 lets `τ` grow without bound and the weights concentrate on a few
    /// samples; a cap bounds that. Default `None` (faithful).
    pub tau_max: Option<f64>,
    /// Floor on the effective sample size `(Σw)²/Σw²` (samples). When the weights of an M-step
    /// have a smaller effective sample size, the next `τ` is at most `τ·ess/min_ess`, which pulls
    /// `τ` down until the weights spread again (a safeguard not in the paper). `0` = off.
    /// Default 0.
    pub min_ess: f64,
    /// Floor on the reward weighting's share of the effective sample size: when the weights of
    /// an M-step have an effective sample size below this share of the one that the external
    /// weights alone give (`(Σa)²/Σa²`, the activations of a receptive field), the next `τ` is
    /// at most `τ·ess/(share·ess_ext)`. On statistics that forget, eq. 28 lets `τ` grow without
    /// bound where the costs have a density that does not vanish at zero (a squared residual
    /// of one or two dimensions), however many samples arrive; this floor is relative, so it
    /// leaves a controller alone that merely has few samples. The online form applies it only
    /// once its statistics have forgotten (`forgetting < 1` or [`crate::OnlineRwr::decay`]):
    /// without forgetting the old samples anchor eq. 28. In [0, 1]; `0` = off. Default 0.
    pub min_ess_share: f64,
    /// Initial exploration standard deviation `σ_0` (action). Must be > 0. Default 1.0.
    pub sigma_init: f64,
    /// Update `σ` by eq. 24 (`true`) or keep it at `sigma_init` (`false`). Default `true`.
    pub update_sigma: bool,
    /// Floor on `σ` (action): eq. 24 is clipped from below to it. Eq. 24 alone can shrink
    /// exploration to zero before the policy is optimal (premature convergence); the floor keeps
    /// a minimum of exploration. Must be ≥ 0 and ≤ `sigma_init`. Default 1e-6 (nearly faithful).
    pub sigma_min: f64,
    /// Ridge `λ` added to the diagonal of the *normalised* weighted Gram matrix `ΦᵀWΦ` of eq. 23
    /// (weights sum to one, eq. 25, so `λ` is in squared feature units, independent of the
    /// number of samples). Must be ≥ 0. Default 1e-9.
    pub ridge: f64,
    /// Online form only: the ridge pulls `θ` towards its previous value instead of towards zero
    /// (a proximal M-step), so directions the recent samples do not excite keep what was learned
    /// before. Default false (plain ridge).
    pub ridge_to_previous: bool,
    /// Online form only: trust region of an M-step (action units): the new mean action may
    /// differ from the old one by at most this much in weighted RMS (Euclidean norm over the
    /// actions) over the step's samples; a larger step is shrunk towards the old `θ`. `None` =
    /// no limit. Default `None` (faithful).
    #[serde(default)]
    pub trust_region: Option<f64>,
    /// Forgetting factor `λ_f` of the online form, in (0, 1]: before each new sample, the
    /// sufficient statistics are multiplied by it (1 = remember everything; effective memory
    /// about `1/(1−λ_f)` samples). Ignored by the batch form. Default 1.0.
    pub forgetting: f64,
}

impl Default for RwrConfig {
    fn default() -> Self {
        Self {
            tau_init: 1.0,
            adapt_tau: true,
            tau_max: None,
            min_ess: 0.0,
            min_ess_share: 0.0,
            sigma_init: 1.0,
            update_sigma: true,
            sigma_min: 1e-6,
            ridge: 1e-9,
            ridge_to_previous: false,
            trust_region: None,
            forgetting: 1.0,
        }
    }
}

fn check(ok: bool, msg: impl FnOnce() -> String) -> Result<()> {
    if ok {
        Ok(())
    } else {
        Err(RwrError::InvalidConfig(msg()))
    }
}

impl RwrConfig {
    /// Checks every field against its documented range.
    pub fn validate(&self) -> Result<()> {
        let t = self.tau_init;
        check(t.is_finite() && t > 0.0, || {
            format!("tau_init must be finite and > 0, got {t}")
        })?;
        if let Some(c) = self.tau_max {
            check(c.is_finite() && c >= t, || {
                format!("tau_max must be finite and >= tau_init ({t}), got {c}")
            })?;
        }
        let e = self.min_ess;
        check(e.is_finite() && e >= 0.0, || {
            format!("min_ess must be finite and >= 0, got {e}")
        })?;
        let h = self.min_ess_share;
        check((0.0..=1.0).contains(&h), || {
            format!("min_ess_share must be in [0, 1], got {h}")
        })?;
        let s = self.sigma_init;
        check(s.is_finite() && s > 0.0, || {
            format!("sigma_init must be finite and > 0, got {s}")
        })?;
        let m = self.sigma_min;
        check(m.is_finite() && (0.0..=s).contains(&m), || {
            format!("sigma_min must be in [0, sigma_init = {s}], got {m}")
        })?;
        let l = self.ridge;
        check(l.is_finite() && l >= 0.0, || {
            format!("ridge must be finite and >= 0, got {l}")
        })?;
        if let Some(d) = self.trust_region {
            check(d.is_finite() && d > 0.0, || {
                format!("trust_region must be finite and > 0, got {d}")
            })?;
        }
        let f = self.forgetting;
        check(f > 0.0 && f <= 1.0, || {
            format!("forgetting must be in (0, 1], got {f}")
        })
    }

    /// The next `τ` after an M-step: eq. 28, `τ_{k+1} = Σ w_i / Σ w_i r_i`, given the weighted
    /// mean cost `mean_cost = Σ w_i r_i / Σ w_i`, the effective sample size `ess` of the
    /// weights and `ess_ext` of the external weights alone, then the `min_ess`,
    /// `min_ess_share` and `tau_max` safeguards. Returns `tau` unchanged when `τ` is fixed, or
    /// when eq. 28 is not finite (all weighted costs zero).
    pub fn next_tau(&self, tau: f64, mean_cost: f64, ess: f64, ess_ext: f64) -> f64 {
        if !self.adapt_tau {
            return tau;
        }
        let mut next = 1.0 / mean_cost;
        if !next.is_finite() || next <= 0.0 {
            next = tau;
        }
        if self.min_ess > 0.0 && ess < self.min_ess {
            next = next.min(tau * ess / self.min_ess);
        }
        let floor = self.min_ess_share * ess_ext;
        if floor > 0.0 && ess < floor {
            next = next.min(tau * ess / floor);
        }
        if let Some(cap) = self.tau_max {
            next = next.min(cap);
        }
        next
    }

    /// The next `σ` from the weighted mean squared residual per action dimension (eq. 24, with
    /// the `1/d` of the maximum-likelihood estimate), floored at `sigma_min`; `sigma` unchanged
    /// when the σ update is off.
    pub fn next_sigma(&self, sigma: f64, mean_sq_residual_per_dim: f64) -> f64 {
        if !self.update_sigma {
            return sigma;
        }
        mean_sq_residual_per_dim.max(0.0).sqrt().max(self.sigma_min)
    }
}
