//! The nominal behaviour `u0 = ĝ(q) − K_Dq q̇ − K_Pq (q − q_rest)` (eq. 6 with the learned
//! gravity compensation `ĝ`): the command of an untrained region and the origin of the local
//! controllers' residuals.

use super::{Learner, Models};
use crate::config::NominalConfig;
use crate::error::Result;

/// `ĝ(q)` into `g`: the static model where it has support once `ĝ` is frozen, else the dynamic
/// model; zeros and `false` without support (or before the warm-up ends).
pub(crate) fn gravity_into(
    models: Option<&mut Models>,
    frozen: bool,
    q: &[f64],
    g: &mut [f64],
) -> Result<bool> {
    let Some(models) = models else {
        g.fill(0.0);
        return Ok(false);
    };
    let from_static = match models.gravity_static.as_mut() {
        Some(s) if frozen => s.predict(q, g)?,
        _ => false,
    };
    Ok(from_static || models.gravity.predict(q, g)?)
}

/// `u0 ← u0 − K_Dq q̇ − K_Pq (q − q_rest)`: the PD pull towards rest, added to `ĝ` in `u0`.
pub(crate) fn add_rest_pull(nom: &NominalConfig, q: &[f64], qd: &[f64], u0: &mut [f64]) {
    for i in 0..u0.len() {
        u0[i] -= nom.kd[i] * qd[i] + nom.kp[i] * (q[i] - nom.q_rest[i]);
    }
}

/// `u0` into `out` from the parts of a learner (so callers can hold its other parts).
pub(crate) fn nominal_into(
    nom: &NominalConfig,
    models: Option<&mut Models>,
    frozen: bool,
    q: &[f64],
    qd: &[f64],
    out: &mut [f64],
) -> Result<bool> {
    let known = gravity_into(models, frozen, q, out)?;
    add_rest_pull(nom, q, qd, out);
    Ok(known)
}

impl Learner {
    /// The nominal behaviour `u0` at `(q, q̇)` into `u0` (`ĝ = 0` until the gravity model has
    /// support). Returns whether `ĝ` had support.
    ///
    /// # Errors
    /// A model failure (e.g. a non-finite prediction); slices must have `n` entries.
    pub fn nominal(&mut self, q: &[f64], qd: &[f64], u0: &mut [f64]) -> Result<bool> {
        nominal_into(
            &self.cfg.nominal,
            self.state.models_mut(),
            self.gravity_frozen,
            q,
            qd,
            u0,
        )
    }

    /// The learned gravity compensation `ĝ(q)` into `g`; `false` (zeros) without support.
    pub fn gravity(&mut self, q: &[f64], g: &mut [f64]) -> Result<bool> {
        gravity_into(self.state.models_mut(), self.gravity_frozen, q, g)
    }
}

#[cfg(test)]
mod tests {
    use crate::learner::fixture;
    use crate::Learner;

    /// Before the warm-up ends `ĝ = 0` and `u0` is the PD pull to rest; after, `u0 − ĝ` is.
    #[test]
    fn u0_is_the_learned_gravity_minus_the_pull_to_rest() {
        let cfg = fixture::config();
        let nom = cfg.nominal.clone();
        let (q, qd) = ([0.3, -0.2, 0.1], [0.5, 0.0, -1.0]);
        let pull: Vec<f64> = (0..3)
            .map(|i| -(nom.kd[i] * qd[i] + nom.kp[i] * (q[i] - nom.q_rest[i])))
            .collect();
        let mut fresh = Learner::new(3, 2, 0.002, cfg.clone()).unwrap();
        let (mut u0, mut g) = ([0.0; 3], [0.0; 3]);
        assert!(!fresh.nominal(&q, &qd, &mut u0).unwrap());
        assert_eq!(u0.to_vec(), pull);
        let (mut learner, _, last) = fixture::ready(cfg, 300, 0);
        let q = last.q.as_slice();
        assert!(learner.nominal(q, &qd, &mut u0).unwrap());
        assert!(learner.gravity(q, &mut g).unwrap());
        for i in 0..3 {
            let pull = -(nom.kd[i] * qd[i] + nom.kp[i] * (q[i] - nom.q_rest[i]));
            assert!((u0[i] - (g[i] + pull)).abs() < 1e-12);
        }
        // Gravity is learnt: the static pose needs torque, so ĝ is far from zero.
        assert!(g.iter().any(|v| v.abs() > 1.0), "{g:?}");
    }
}
