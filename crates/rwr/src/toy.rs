//! The paper's Fig. 1 experiment (experiment E1): a linear policy on a 1-D state, 1-D action
//! problem, learned by batch RWR with adaptive versus fixed reward transformation `τ`.
//!
//! Policy `π(a | s) = N(a | θ1 s + θ2, σ²)` with features `φ = [s, 1]`; cost
//! `r = q1 a² + q2 a s + q3 s²` (`q1 > 0`, `4 q1 q3 ≥ q2²`, so `r ≥ 0`), minimised for every
//! `s` by `a = −q2 s / (2 q1)`: `θ* = (−q2 / (2 q1), 0)`. Each EM iteration draws
//! `samples_per_iter` states uniformly in `[−s_max, s_max]` and actions from the current policy,
//! and makes one [`crate::BatchRwr::em_step`]. A run converges at the first iteration `k` with
//! `‖θ_k − θ*‖ < epsilon`; one that has not by `max_iters` counts as `max_iters`.
//!
//! No plotting or printing here: the `osrl toy` command and `examples/fig1_toy.rs` do that.

mod run;
mod summary;

pub use run::{run, trace, RunOutcome, TraceStep};
pub use summary::{check_claims, summarize, CaseSummary, Claims, Report, Speedup};

use crate::error::{Result, RwrError};
use serde::{Deserialize, Serialize};

/// Most samples a sweep may draw in all (`samples_per_iter × max_iters × seeds × tau0s`).
pub const MAX_TOY_SAMPLES: u64 = 1_000_000_000;

/// Problem constants, sampling and sweep of the Fig. 1 experiment. The defaults are fixed
/// before looking at results: a tilted cost ellipse with an unavoidable state cost
/// (`q = (1, −1, 0.5)`: `r = (a − s/2)² + s²/4`), an initial policy `θ_0 = (−1, 1)` that is
/// wrong in slope and offset (`‖θ_0 − θ*‖ ≈ 1.80`), unit initial exploration, and a
/// tolerance `ε = 0.1` that is about 5% of the initial distance yet several standard errors of
/// the per-iteration estimate (500 samples) wide.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ToyConfig {
    /// Cost coefficients `(q1, q2, q3)` of `r = q1 a² + q2 a s + q3 s²` (cost units; needs
    /// `q1 > 0` and `4 q1 q3 ≥ q2²`). Default `(1, −1, 0.5)`.
    pub q: [f64; 3],
    /// States are uniform in `[−s_max, s_max]` (state units). Default 1.
    pub s_max: f64,
    /// Initial policy parameters `θ_0 = (θ1, θ2)`. Default `(−1, 1)`.
    pub theta_init: [f64; 2],
    /// Initial exploration `σ_0` (action units). Default 1.
    pub sigma_init: f64,
    /// Floor on `σ` when it is updated (action units). Default 1e-3.
    pub sigma_min: f64,
    /// Samples (state–action pairs) per EM iteration. Default 500.
    pub samples_per_iter: usize,
    /// Convergence tolerance `ε` on `‖θ − θ*‖` (Euclidean). Default 0.1.
    pub epsilon: f64,
    /// Iterations after which a run counts as never converged. Default 500.
    pub max_iters: usize,
    /// Initial `τ` values of the sweep (1/cost units). Default `[0.01, 0.1, 1, 10]`.
    pub tau0s: Vec<f64>,
    /// Number of seeds per case (seeds `0..seeds`, the same for every case). Default 30.
    pub seeds: u64,
}

impl Default for ToyConfig {
    fn default() -> Self {
        Self {
            q: [1.0, -1.0, 0.5],
            s_max: 1.0,
            theta_init: [-1.0, 1.0],
            sigma_init: 1.0,
            sigma_min: 1e-3,
            samples_per_iter: 500,
            epsilon: 0.1,
            max_iters: 500,
            tau0s: vec![0.01, 0.1, 1.0, 10.0],
            seeds: 30,
        }
    }
}

/// Reward transformation variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// `τ` updated by eq. 28 after every iteration.
    Adaptive,
    /// `τ` fixed at its initial value.
    Fixed,
}

/// One cell of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Case {
    /// Initial `τ`.
    pub tau0: f64,
    /// Adaptive or fixed `τ`.
    pub variant: Variant,
    /// Whether `σ` is updated by eq. 24.
    pub sigma_update: bool,
}

impl ToyConfig {
    /// Checks every field's documented range.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(RwrError::InvalidConfig(m));
        let [q1, q2, q3] = self.q;
        if !(self.q.iter().all(|x| x.is_finite()) && q1 > 0.0 && 4.0 * q1 * q3 >= q2 * q2) {
            return bad(format!(
                "q must be finite with q1 > 0 and 4 q1 q3 >= q2^2, got {:?}",
                self.q
            ));
        }
        let pos = |x: f64| x.is_finite() && x > 0.0;
        if !(pos(self.s_max) && pos(self.sigma_init) && pos(self.epsilon)) {
            return bad("s_max, sigma_init and epsilon must be finite and > 0".into());
        }
        if !(self.sigma_min >= 0.0 && self.sigma_min <= self.sigma_init) {
            return bad(format!(
                "sigma_min must be in [0, sigma_init], got {}",
                self.sigma_min
            ));
        }
        if !self.theta_init.iter().all(|x| x.is_finite()) {
            return bad("theta_init must be finite".into());
        }
        for (what, v, least) in [
            ("samples_per_iter", self.samples_per_iter as u64, 3),
            ("max_iters", self.max_iters as u64, 1),
            ("seeds", self.seeds, 1),
        ] {
            if v < least {
                return bad(format!("{what} = {v}: at least {least} required"));
            }
        }
        if self.tau0s.is_empty() || !self.tau0s.iter().all(|&t| pos(t)) {
            return bad(format!(
                "tau0s must be non-empty, finite and > 0, got {:?}",
                self.tau0s
            ));
        }
        let sizes = [
            ("samples_per_iter", self.samples_per_iter as u64, 1_000_000),
            ("max_iters", self.max_iters as u64, 100_000),
            ("seeds", self.seeds, 10_000),
            ("tau0s (entries)", self.tau0s.len() as u64, 1000),
        ];
        for (name, v, max) in sizes {
            if v > max {
                return bad(format!("{name} = {v}: accepted at most {max}"));
            }
        }
        let work = sizes.iter().fold(1u64, |w, s| w.saturating_mul(s.1));
        if work > MAX_TOY_SAMPLES {
            return bad(format!(
                "samples_per_iter × max_iters × seeds × tau0s = {work}: accepted at most \
                 {MAX_TOY_SAMPLES} samples in a sweep"
            ));
        }
        Ok(())
    }

    /// The optimal policy parameters `θ* = (−q2 / (2 q1), 0)`.
    pub fn theta_star(&self) -> [f64; 2] {
        [-self.q[1] / (2.0 * self.q[0]), 0.0]
    }

    /// The cost `r(s, a) = q1 a² + q2 a s + q3 s²`.
    pub fn cost(&self, s: f64, a: f64) -> f64 {
        let [q1, q2, q3] = self.q;
        // Clamp rounding below zero when 4 q1 q3 = q2² (the cost is then a perfect square).
        (q1 * a * a + q2 * a * s + q3 * s * s).max(0.0)
    }

    /// Every case of the sweep: each `tau0` × {adaptive, fixed} × σ update {on, off}.
    pub fn cases(&self) -> Vec<Case> {
        let mut out = Vec::new();
        for sigma_update in [false, true] {
            for &tau0 in &self.tau0s {
                for variant in [Variant::Adaptive, Variant::Fixed] {
                    out.push(Case {
                        tau0,
                        variant,
                        sigma_update,
                    });
                }
            }
        }
        out
    }
}
