//! One run of the Fig. 1 experiment: EM iterations from `θ_0` until `‖θ − θ*‖ < ε`.

use super::{Case, ToyConfig, Variant};
use crate::{BatchRwr, Result, RwrConfig};
use nalgebra::DMatrix;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Result of one run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RunOutcome {
    /// First iteration with `‖θ − θ*‖ < ε` (0 if `θ_0` already is), `None` if none up to
    /// `max_iters`.
    pub iters: Option<usize>,
    /// `‖θ − θ*‖` when the run stopped.
    pub final_dist: f64,
}

/// The policy and transformation at one iteration (`θ_k`, `σ_k`, and the `τ_k` that iteration
/// `k`'s samples are weighted with).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TraceStep {
    /// Iteration `k` (0 = initial policy).
    pub iter: usize,
    /// `(θ1, θ2)`: mean action `θ1 s + θ2`.
    pub theta: [f64; 2],
    /// Exploration `σ_k`.
    pub sigma: f64,
    /// `τ_k`.
    pub tau: f64,
    /// `‖θ_k − θ*‖`.
    pub dist: f64,
}

struct Learner {
    rwr: BatchRwr,
    rng: ChaCha8Rng,
    phi: DMatrix<f64>,
    u: DMatrix<f64>,
    costs: Vec<f64>,
}

impl Learner {
    fn new(cfg: &ToyConfig, case: Case, seed: u64) -> Result<Self> {
        cfg.validate()?;
        let rwr_cfg = RwrConfig {
            tau_init: case.tau0,
            adapt_tau: case.variant == Variant::Adaptive,
            sigma_init: cfg.sigma_init,
            update_sigma: case.sigma_update,
            sigma_min: cfg.sigma_min,
            ..RwrConfig::default()
        };
        let theta = DMatrix::from_column_slice(2, 1, &cfg.theta_init);
        let n = cfg.samples_per_iter;
        Ok(Self {
            rwr: BatchRwr::with_theta(theta, rwr_cfg)?,
            rng: ChaCha8Rng::seed_from_u64(seed),
            phi: DMatrix::zeros(n, 2),
            u: DMatrix::zeros(n, 1),
            costs: vec![0.0; n],
        })
    }

    /// Samples a batch from the current policy and makes one EM step.
    fn step(&mut self, cfg: &ToyConfig) -> Result<()> {
        let mut a = [0.0];
        for i in 0..self.costs.len() {
            let s = self.rng.random_range(-cfg.s_max..=cfg.s_max);
            self.rwr
                .policy()
                .sample_into(&[s, 1.0], &mut self.rng, &mut a)?;
            self.phi[(i, 0)] = s;
            self.phi[(i, 1)] = 1.0;
            self.u[(i, 0)] = a[0];
            self.costs[i] = cfg.cost(s, a[0]);
        }
        self.rwr.em_step(&self.phi, &self.u, &self.costs, None)?;
        Ok(())
    }

    fn snapshot(&self, cfg: &ToyConfig, iter: usize) -> TraceStep {
        let t = self.rwr.theta();
        let theta = [t[(0, 0)], t[(1, 0)]];
        let star = cfg.theta_star();
        let dist = (theta[0] - star[0]).hypot(theta[1] - star[1]);
        TraceStep {
            iter,
            theta,
            sigma: self.rwr.sigma(),
            tau: self.rwr.tau(),
            dist,
        }
    }
}

/// Runs one case with one seed until convergence or `max_iters`. Fails on an invalid config.
pub fn run(cfg: &ToyConfig, case: Case, seed: u64) -> Result<RunOutcome> {
    let mut l = Learner::new(cfg, case, seed)?;
    let mut dist = l.snapshot(cfg, 0).dist;
    if dist < cfg.epsilon {
        return Ok(RunOutcome {
            iters: Some(0),
            final_dist: dist,
        });
    }
    for k in 1..=cfg.max_iters {
        l.step(cfg)?;
        dist = l.snapshot(cfg, k).dist;
        if dist < cfg.epsilon {
            return Ok(RunOutcome {
                iters: Some(k),
                final_dist: dist,
            });
        }
    }
    Ok(RunOutcome {
        iters: None,
        final_dist: dist,
    })
}

/// The first `iters + 1` policies of one run (iteration 0 to `iters`), not stopping at
/// convergence: the data behind a Fig. 1-like plot.
pub fn trace(cfg: &ToyConfig, case: Case, seed: u64, iters: usize) -> Result<Vec<TraceStep>> {
    let mut l = Learner::new(cfg, case, seed)?;
    let mut out = vec![l.snapshot(cfg, 0)];
    for k in 1..=iters {
        l.step(cfg)?;
        out.push(l.snapshot(cfg, k));
    }
    Ok(out)
}
