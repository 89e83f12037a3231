//! Gaussian policy linear in features (eq. 21): `π(u | s) = N(u | θᵀφ(s), σ² I)`.

use crate::error::{Result, RwrError};
use nalgebra::DMatrix;
use rand::{Rng, RngExt};
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};

/// `π(u | s) = N(u | θᵀφ, σ² I)` with `θ` of shape `p × d` (`p` features, `d` action dims).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LinearGaussianPolicy {
    theta: DMatrix<f64>,
    sigma: f64,
}

/// Fails unless `got == expected`.
pub(crate) fn check_len(what: &'static str, expected: usize, got: usize) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(RwrError::Dimension {
            what,
            expected,
            got,
        })
    }
}

/// Fails if any value is NaN or infinite.
pub(crate) fn check_finite(what: &'static str, v: &[f64]) -> Result<()> {
    // Without a branch per value (an OR of the exponent tests, which vectorises): the learner
    // checks every field's features for every sample, and the short-circuiting loop was 2.5 %
    // of a sarcos7 training run. An exponent of all ones is an infinity or a NaN.
    const EXP: u64 = 0x7ff0_0000_0000_0000;
    let bad = v
        .iter()
        .fold(0u64, |a, x| a | (x.to_bits() & EXP == EXP) as u64);
    if bad == 0 {
        Ok(())
    } else {
        Err(RwrError::NonFinite(what))
    }
}

impl LinearGaussianPolicy {
    /// A policy with the given `θ` (`p × d`, `p, d ≥ 1`, finite) and `σ > 0`.
    pub fn new(theta: DMatrix<f64>, sigma: f64) -> Result<Self> {
        if theta.nrows() == 0 || theta.ncols() == 0 {
            return Err(RwrError::Dimension {
                what: "theta",
                expected: 1,
                got: 0,
            });
        }
        check_finite("theta", theta.as_slice())?;
        if !(sigma.is_finite() && sigma > 0.0) {
            return Err(RwrError::InvalidConfig(format!(
                "sigma must be > 0, got {sigma}"
            )));
        }
        Ok(Self { theta, sigma })
    }

    /// `θ = 0` with `p` features, `d` action dimensions and the given `σ`.
    pub fn zeros(p: usize, d: usize, sigma: f64) -> Result<Self> {
        Self::new(DMatrix::zeros(p, d), sigma)
    }

    /// Number of features `p`.
    pub fn n_features(&self) -> usize {
        self.theta.nrows()
    }

    /// Number of action dimensions `d`.
    pub fn n_actions(&self) -> usize {
        self.theta.ncols()
    }

    /// Parameters `θ` (`p × d`): the mean action is `θᵀφ`.
    pub fn theta(&self) -> &DMatrix<f64> {
        &self.theta
    }

    /// Exploration standard deviation `σ` (action units).
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// `θ` to change in place (the caller keeps it finite).
    pub(crate) fn theta_mut(&mut self) -> &mut DMatrix<f64> {
        &mut self.theta
    }

    /// Overwrites `θ` and `σ` in place (no allocation); the caller guarantees shape and values.
    pub(crate) fn set(&mut self, theta: &DMatrix<f64>, sigma: f64) {
        self.theta.copy_from(theta);
        self.sigma = sigma;
    }

    /// Writes the mean action `μ = θᵀφ` into `out` (length `d`). Fails on wrong lengths or
    /// non-finite features. Does not allocate.
    pub fn mean_into(&self, phi: &[f64], out: &mut [f64]) -> Result<()> {
        check_len("features", self.n_features(), phi.len())?;
        check_len("action out", self.n_actions(), out.len())?;
        check_finite("features", phi)?;
        // Feature by feature into all actions at once: the actions' sums are independent
        // chains (a column-by-column dot product is one long dependency chain per action),
        // each still summed in feature order, from −0.0 as `Iterator::sum` does.
        out.fill(-0.0);
        let p = phi.len();
        let theta = self.theta.as_slice();
        for (f, x) in phi.iter().enumerate() {
            for (j, o) in out.iter_mut().enumerate() {
                *o += theta[j * p + f] * x;
            }
        }
        Ok(())
    }

    /// Draws an action `u ~ N(θᵀφ, σ² I)` into `out` from the injected generator. Same
    /// generator state, same action. Fails like [`Self::mean_into`]. Does not allocate.
    pub fn sample_into<R: Rng + ?Sized>(
        &self,
        phi: &[f64],
        rng: &mut R,
        out: &mut [f64],
    ) -> Result<()> {
        self.mean_into(phi, out)?;
        for o in out.iter_mut() {
            let e: f64 = rng.sample(StandardNormal);
            *o += self.sigma * e;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::check_finite;

    /// The branch-free test agrees with `f64::is_finite` on the edge cases, in any position.
    #[test]
    fn check_finite_refuses_exactly_nan_and_infinities() {
        let good = [
            0.0,
            -0.0,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            1.0,
        ];
        assert!(check_finite("v", &good).is_ok());
        assert!(check_finite("v", &[]).is_ok());
        for bad in [f64::NAN, -f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for k in 0..=good.len() {
                let mut v = good.to_vec();
                v.insert(k, bad);
                assert!(check_finite("v", &v).is_err(), "{bad} at {k}");
            }
        }
    }
}
