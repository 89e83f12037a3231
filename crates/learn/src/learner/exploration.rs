//! Exploration noise of the on-policy commands: Ornstein–Uhlenbeck noise of the blended `σ`
//! (eq. 24), capped per joint, plus smooth noise projected onto the null space of `Â` (the
//! redundancy RWR must resolve, without disturbing the task to first order). The noise is
//! temporally correlated, so it adds a bounded torque rate rather than a new draw every period.

use super::null_space::project_null;
use super::stats::Scratch;
use super::{Features, Models};
use crate::config::LearnerConfig;
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

/// The state of the noise processes: unit-variance Ornstein–Uhlenbeck processes, one per joint,
/// for the isotropic and the null-space parts.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Noise {
    iso: Vec<f64>,
    null: Vec<f64>,
    /// `a = exp(−dt/τ_c)`, the per-period correlation (0: white noise).
    a: f64,
    /// `sqrt(1 − a²)`, so the stationary variance is 1.
    b: f64,
}

impl Noise {
    /// Processes for `n` joints with correlation time `tau_c` (s) at control period `dt` (s),
    /// starting at 0 (the noise fades in over about `tau_c`).
    pub fn new(n: usize, tau_c: f64, dt: f64) -> Self {
        let a = if tau_c > 0.0 {
            (-dt / tau_c).exp()
        } else {
            0.0
        };
        Self {
            iso: vec![0.0; n],
            null: vec![0.0; n],
            a,
            b: (1.0 - a * a).sqrt(),
        }
    }

    /// Back to 0 (at the start of an episode).
    pub fn reset(&mut self) {
        self.iso.fill(0.0);
        self.null.fill(0.0);
    }

    fn advance<R: Rng + ?Sized>(z: &mut [f64], a: f64, b: f64, rng: &mut R) {
        for v in z.iter_mut() {
            let e: f64 = StandardNormal.sample(rng);
            *v = a * *v + b * e;
        }
    }
}

/// Adds the exploration noise of standard deviation `sigma` (N·m) at `q` to `u`: first the
/// null-space part (if configured and `Â` is known), then the capped isotropic part. Each
/// process advances one period (`n` draws each, null-space first).
#[allow(clippy::too_many_arguments)]
pub(crate) fn explore<R: Rng + ?Sized>(
    cfg: &LearnerConfig,
    features: &Features,
    models: &Models,
    ws: &mut Scratch,
    noise: &mut Noise,
    q: &[f64],
    sigma: f64,
    rng: &mut R,
    u: &mut [f64],
) {
    let m = ws.y.len();
    let (a, b) = (noise.a, noise.b);
    if cfg.experimental.null_space_exploration {
        Noise::advance(&mut noise.null, a, b, rng);
        let known = models.blended_gain(features, &ws.acts, q, &mut ws.a_hat);
        let ns_cap = cfg.experimental.null_space_cap.unwrap_or(f64::INFINITY);
        for ((z, scale), e) in ws.du.iter_mut().zip(&models.torque_scale).zip(&noise.null) {
            *z = sigma.min(ns_cap * scale) * e;
        }
        // z − Âᵀ (Â Âᵀ)⁻¹ Â z: no first-order effect on the task.
        if known && project_null(&ws.a_hat, &mut ws.du, m, &mut ws.y, &mut ws.s) {
            for (v, z) in u.iter_mut().zip(&ws.du) {
                *v += z;
            }
        }
    }
    Noise::advance(&mut noise.iso, a, b, rng);
    let cap = cfg.exploration.cap;
    for ((v, s), e) in u.iter_mut().zip(&models.torque_scale).zip(&noise.iso) {
        *v += sigma.min(cap * s) * e;
    }
}

#[cfg(test)]
mod tests {
    use super::Noise;
    use rand::SeedableRng;

    /// The process has unit variance and its per-period change is `sqrt(2(1 − a))` in RMS:
    /// the torque rate of the noise is bounded by its correlation time, not by chance.
    #[test]
    fn smooth_noise_has_unit_variance_and_a_small_rate() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let (dt, tau) = (0.002, 0.1);
        let mut n = Noise::new(1, tau, dt);
        let (mut s2, mut d2, mut dmax, mut prev) = (0.0, 0.0, 0.0f64, 0.0);
        let k = 200_000;
        for _ in 0..k {
            Noise::advance(&mut n.iso, n.a, n.b, &mut rng);
            let z = n.iso[0];
            s2 += z * z;
            d2 += (z - prev) * (z - prev);
            dmax = dmax.max((z - prev).abs());
            prev = z;
        }
        let var = s2 / k as f64;
        assert!((var - 1.0).abs() < 0.05, "variance {var}");
        let rms_step = (d2 / k as f64).sqrt();
        let want = (2.0 * (1.0 - (-dt / tau).exp())).sqrt();
        assert!(
            (rms_step - want).abs() < 0.02 * want,
            "{rms_step} vs {want}"
        );
        // White noise would step by sqrt(2) in RMS and by ~6 at the worst of 2·10⁵ draws.
        assert!(rms_step < 0.21 && dmax < 1.2, "{rms_step} {dmax}");
    }
}
