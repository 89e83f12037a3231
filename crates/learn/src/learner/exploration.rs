//! Exploration noise of the on-policy commands: Gaussian noise of the blended `σ` (eq. 24),
//! capped per joint, plus noise projected onto the null space of `Â` (the redundancy RWR must
//! resolve, without disturbing the task to first order).

use super::null_space::project_null;
use super::stats::Scratch;
use super::{Features, Models};
use crate::config::LearnerConfig;
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

/// Adds the exploration noise of standard deviation `sigma` (N·m) at `q` to `u`: first the
/// null-space part (if configured and `Â` is known), then the capped isotropic part; `n` (or
/// `2n`) draws from `rng`, in that order.
#[allow(clippy::too_many_arguments)]
pub(crate) fn explore<R: Rng + ?Sized>(
    cfg: &LearnerConfig,
    features: &Features,
    models: &Models,
    ws: &mut Scratch,
    q: &[f64],
    sigma: f64,
    rng: &mut R,
    u: &mut [f64],
) {
    let m = ws.y.len();
    if cfg.experimental.null_space_exploration {
        // z ~ N(0, σ² I) projected onto the null space of Â: z − Âᵀ (Â Âᵀ)⁻¹ Â z.
        let known = models.blended_gain(features, &ws.acts, q, &mut ws.a_hat);
        let ns_cap = cfg.experimental.null_space_cap.unwrap_or(f64::INFINITY);
        for (z, scale) in ws.du.iter_mut().zip(&models.torque_scale) {
            let s: f64 = StandardNormal.sample(rng);
            *z = sigma.min(ns_cap * scale) * s;
        }
        if known && project_null(&ws.a_hat, &mut ws.du, m, &mut ws.y, &mut ws.s) {
            for (v, z) in u.iter_mut().zip(&ws.du) {
                *v += z;
            }
        }
    }
    let cap = cfg.exploration.cap;
    for (v, s) in u.iter_mut().zip(&models.torque_scale) {
        let z: f64 = StandardNormal.sample(rng);
        *v += sigma.min(cap * s) * z;
    }
}
