//! Online reward-weighted regression: weighted sufficient statistics with forgetting.

use crate::batch::StepInfo;
use crate::config::RwrConfig;
use crate::error::Result;
use crate::external::External;
use crate::policy::{check_finite, check_len, LinearGaussianPolicy};
use crate::stats::{Solver, Stats};
use crate::weights::{check_cost, check_ext, log_weight};
use nalgebra::DMatrix;
use rand::Rng;

/// Online form of Algorithm 2, as used by one local controller: every sample is weighted when
/// it arrives, `w = a · exp(−τ r)` with the current `τ` and an external weight `a` (e.g. a
/// receptive field's activation), and accumulated into the sufficient statistics of eq. 23,
/// 24 and 28, which decay by the forgetting factor before each new sample. [`Self::update`] is
/// the M-step from those statistics. With forgetting 1 and `τ` unchanged between the samples,
/// `observe`×n + `update` equals one [`crate::BatchRwr::em_step`] on the same samples.
///
/// The statistics are stored relative to a running log scale (the largest log weight seen,
/// decayed by forgetting), so weights never underflow or overflow however large `τ r` gets.
/// Neither `observe` nor `update` allocates.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct OnlineRwr {
    cfg: RwrConfig,
    policy: LinearGaussianPolicy,
    tau: f64,
    stats: Stats,
    /// True statistics = stored × exp(log_scale); `−∞` while empty.
    log_scale: f64,
    ln_forget: f64,
    /// The external weights alone, decayed as the statistics (`min_ess_share`'s reference).
    external: External,
    solver: Solver,
}

impl OnlineRwr {
    /// `θ = 0` (`p × d`), `σ = sigma_init`, `τ = tau_init`, empty statistics.
    pub fn new(p: usize, d: usize, cfg: RwrConfig) -> Result<Self> {
        cfg.validate()?;
        Self::with_theta(DMatrix::zeros(p, d), cfg)
    }

    /// Starts from a given `θ` (`p × d`).
    pub fn with_theta(theta: DMatrix<f64>, cfg: RwrConfig) -> Result<Self> {
        cfg.validate()?;
        let policy = LinearGaussianPolicy::new(theta, cfg.sigma_init)?;
        let (p, d) = (policy.n_features(), policy.n_actions());
        Ok(Self {
            tau: cfg.tau_init,
            ln_forget: cfg.forgetting.ln(),
            cfg,
            policy,
            stats: Stats::new(p, d),
            log_scale: f64::NEG_INFINITY,
            external: External::default(),
            solver: Solver::new(p, d),
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
    /// `τ` that new samples are weighted with.
    pub fn tau(&self) -> f64 {
        self.tau
    }
    /// Effective sample size `(Σw)²/Σw²` of the (decayed) statistics; 0 when empty.
    pub fn ess(&self) -> f64 {
        self.stats.ess()
    }
    /// `ln Σ w` of the (decayed) statistics, `−∞` when empty (the sum itself may not fit an f64).
    pub fn log_sum_weight(&self) -> f64 {
        self.stats.sw.ln() + self.log_scale
    }

    /// Mean action `θᵀφ` into `out`; see [`LinearGaussianPolicy::mean_into`].
    pub fn mean_into(&self, phi: &[f64], out: &mut [f64]) -> Result<()> {
        self.policy.mean_into(phi, out)
    }

    /// Exploratory action `u ~ N(θᵀφ, σ² I)` into `out` from the injected generator.
    pub fn sample_into<R: Rng + ?Sized>(
        &self,
        phi: &[f64],
        rng: &mut R,
        out: &mut [f64],
    ) -> Result<()> {
        self.policy.sample_into(phi, rng, out)
    }

    /// Effective sample size `(Σa)²/Σa²` of the external weights alone (decayed as the
    /// statistics); 0 when empty.
    pub fn ess_external(&self) -> f64 {
        self.external.ess()
    }

    /// Forgets all samples (keeps `θ`, `σ`, `τ`).
    pub fn clear(&mut self) {
        self.stats.clear();
        self.log_scale = f64::NEG_INFINITY;
        self.external.clear();
    }

    /// E-step for one sample `(φ, u, r)` with external weight `a ≥ 0`: decays the statistics by
    /// the forgetting factor, then adds the sample with weight `a · exp(−τ r)` (eq. 25 before
    /// normalisation). Fails, changing nothing, on wrong lengths, non-finite `φ`/`u`, or a
    /// negative or non-finite `r` or `a`.
    pub fn observe(&mut self, phi: &[f64], u: &[f64], r: f64, a: f64) -> Result<()> {
        check_len("features", self.policy.n_features(), phi.len())?;
        check_len("action", self.policy.n_actions(), u.len())?;
        check_finite("features", phi)?;
        check_finite("action", u)?;
        check_cost(r)?;
        check_ext(a)?;
        self.log_scale += self.ln_forget;
        self.external.forget(self.cfg.forgetting);
        self.external.add(a);
        let l = log_weight(self.tau, r, a);
        if l == f64::NEG_INFINITY {
            return Ok(());
        }
        let mut f = None;
        if l > self.log_scale {
            f = Some((self.log_scale - l).exp());
            self.log_scale = l;
        }
        // `scale` then `add`, the matrix parts held until the next M-step (`Stats::push`).
        self.stats.push(f, (l - self.log_scale).exp(), phi, u, r);
        Ok(())
    }

    /// Clamps one entry `θ[(row, col)]` into `[lo, hi]` (a bound the caller knows, e.g. on a
    /// feedback gain); returns whether it moved. Out-of-range indices change nothing.
    pub fn clamp_theta(&mut self, row: usize, col: usize, lo: f64, hi: f64) -> bool {
        let t = self.policy.theta_mut();
        if row >= t.nrows() || col >= t.ncols() {
            return false;
        }
        let v = t[(row, col)];
        let c = v.max(lo).min(hi);
        t[(row, col)] = c;
        c != v
    }

    /// Extra forgetting: multiplies every weight in the statistics by `factor` (in (0, 1]; other
    /// values change nothing), as `factor` would as the forgetting factor of one sample. The
    /// learner uses it to forget faster while its models no longer fit the robot.
    pub fn decay(&mut self, factor: f64) {
        if factor > 0.0 && factor < 1.0 {
            self.log_scale += factor.ln();
            self.external.forget(factor);
        }
    }

    /// The weighted mean squared residual per output dimension of the current `θ` over the
    /// statistics, `Σ w ‖u − θᵀφ‖² / (d Σw)` (0 when empty). Folds the held samples into the
    /// statistics first (hence `&mut`). Does not allocate.
    pub fn mean_sq_residual(&mut self) -> f64 {
        self.stats.flush();
        let s = &self.stats;
        if s.sw.is_nan() || s.sw <= 0.0 {
            return 0.0;
        }
        let theta = self.policy.theta();
        let (p, d) = (theta.nrows(), theta.ncols());
        let mut total = s.yy;
        for k in 0..d {
            let t = theta.column(k);
            let mut quad = 0.0;
            let mut lin = 0.0;
            for j in 0..p {
                lin += t[j] * s.cross[(j, k)];
                let col = t[j];
                quad += s.gram[(j, j)] * col * col;
                let mut off = 0.0;
                for i in j + 1..p {
                    off += s.gram[(i, j)] * t[i];
                }
                quad += 2.0 * col * off;
            }
            total += quad - 2.0 * lin;
        }
        (total / (d as f64 * s.sw)).max(0.0)
    }

    /// M-step from the statistics: `θ` by eq. 23 (with ridge), `σ` by eq. 24 (floored, unless
    /// off), `τ` by eq. 28 (and safeguards, unless fixed). Fails, changing nothing, when no
    /// sample has weight or the Gram matrix is singular (too few samples and no ridge).
    pub fn update(&mut self) -> Result<StepInfo> {
        self.update_scaled(1.0)
    }

    /// [`Self::update`] with the trust region (if any) widened by `trust_scale` (≥ 1 widens;
    /// the learner's "learning rate" while it re-adapts to a changed robot).
    pub fn update_scaled(&mut self, trust_scale: f64) -> Result<StepInfo> {
        self.stats.flush();
        let prior = self.cfg.ridge_to_previous.then(|| self.policy.theta());
        self.solver
            .solve_with_prior(&self.stats, self.cfg.ridge, prior)?;
        // Eq. 24's residual, of the solution before the trust region shrinks it; only when `σ`
        // follows it.
        let msr = if self.cfg.update_sigma {
            self.solver.residual(&self.stats)
        } else {
            0.0
        };
        let shrink = match self.cfg.trust_region {
            Some(delta) => crate::trust::shrink(
                &self.stats.gram,
                self.stats.sw,
                self.policy.theta(),
                &mut self.solver.theta,
                delta * trust_scale,
            ),
            None => 1.0,
        };
        let sigma = self.cfg.next_sigma(self.policy.sigma(), msr);
        let (ess, mean_cost) = (self.stats.ess(), self.stats.mean_cost());
        let ess_ext = self.external.floor_reference();
        let tau_next = self.cfg.next_tau(self.tau, mean_cost, ess, ess_ext);
        let info = StepInfo {
            tau_used: self.tau,
            tau_next,
            sigma,
            ess,
            mean_cost,
            shrink,
        };
        self.policy.set(&self.solver.theta, sigma);
        self.tau = tau_next;
        Ok(info)
    }
}
