//! The nominal behaviour `u0 = ĝ(q) − K_Dq q̇ − K_Pq (q − q_rest)` (eq. 6 with the learned
//! gravity compensation `ĝ`): the command of an untrained region and the origin of the local
//! controllers' residuals.

use super::{Learner, Models};
use crate::config::{GravityConfig, NominalConfig};
use crate::error::Result;

/// `ĝ(q)` into `g`; zeros and `false` without support (or before the warm-up ends).
/// Continuous (`gravity.continuous`, D21): before `ĝ` is frozen the dynamic model from all its
/// fields; once frozen the blend of both by their total activations `S_s` and `λ S_d`.
/// Otherwise the switch: the static model where it has support once `ĝ` is frozen, else the
/// dynamic model.
/// The last result is kept (`gravity_cache.rs`): the same `q`, settings and model updates
/// give it back, bit for bit.
pub(crate) fn gravity_into(
    gcfg: &GravityConfig,
    models: Option<&mut Models>,
    frozen: bool,
    q: &[f64],
    g: &mut [f64],
) -> Result<bool> {
    let Some(models) = models else {
        g.fill(0.0);
        return Ok(false);
    };
    let key = [
        u64::from(frozen),
        u64::from(gcfg.continuous),
        gcfg.dynamic_weight.to_bits(),
        models.gravity.lwpr().n_updates(),
        (models.gravity_static.as_ref()).map_or(u64::MAX, |s| s.lwpr().n_updates()),
    ];
    if let Some(known) = models.g_cache.get(&key, q, g) {
        return Ok(known);
    }
    let known = gravity_uncached(gcfg, models, frozen, q, g)?;
    models.g_cache.put(key, q, g, known);
    Ok(known)
}

/// [`gravity_into`] without the cache.
fn gravity_uncached(
    gcfg: &GravityConfig,
    models: &mut Models,
    frozen: bool,
    q: &[f64],
    g: &mut [f64],
) -> Result<bool> {
    if !gcfg.continuous {
        let from_static = match models.gravity_static.as_mut() {
            Some(s) if frozen => s.predict(q, g)?,
            _ => false,
        };
        return Ok(from_static || models.gravity.predict(q, g)?);
    }
    let ln_d = models.gravity.predict_everywhere(q, g)?;
    let Some(s) = models.gravity_static.as_mut().filter(|_| frozen) else {
        return Ok(ln_d.is_some());
    };
    let gs = &mut models.g_static;
    gs.resize(g.len(), 0.0);
    let Some(ln_s) = s.predict_everywhere(q, gs)? else {
        return Ok(ln_d.is_some());
    };
    // Share of the static model: S_s / (S_s + λ S_d), from the logarithms (no underflow).
    let share = match ln_d {
        Some(ln_d) if gcfg.dynamic_weight > 0.0 => {
            let t = gcfg.dynamic_weight.ln() + ln_d - ln_s;
            1.0 / (1.0 + t.exp())
        }
        _ => 1.0,
    };
    for (v, s) in g.iter_mut().zip(gs.iter()) {
        *v = share * s + (1.0 - share) * *v;
    }
    Ok(true)
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
    gcfg: &GravityConfig,
    models: Option<&mut Models>,
    frozen: bool,
    q: &[f64],
    qd: &[f64],
    out: &mut [f64],
) -> Result<bool> {
    let known = gravity_into(gcfg, models, frozen, q, out)?;
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
            &self.cfg.gravity,
            self.state.models_mut(),
            self.gravity_frozen,
            q,
            qd,
            u0,
        )
    }

    /// The learned gravity compensation `ĝ(q)` into `g`; `false` (zeros) without support.
    pub fn gravity(&mut self, q: &[f64], g: &mut [f64]) -> Result<bool> {
        gravity_into(
            &self.cfg.gravity,
            self.state.models_mut(),
            self.gravity_frozen,
            q,
            g,
        )
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

    /// The largest change of `ĝ` between neighbours of `steps` equal steps along a straight line
    /// in `q` from the fixture's last posture to 3 rad away on every joint (`ĝ` frozen), and
    /// whether `ĝ` had support at every point.
    fn gravity_walk(continuous: bool, steps: usize) -> (f64, bool) {
        let mut cfg = fixture::config();
        cfg.gravity.continuous = continuous;
        let (mut learner, _, last) = fixture::ready(cfg, 300, 200);
        learner.freeze_gravity(true);
        let q0 = last.q.as_slice().to_vec();
        let (mut g, mut prev) = ([0.0; 3], None::<[f64; 3]>);
        let (mut largest, mut all_known) = (0.0f64, true);
        for k in 0..=steps {
            let s = 3.0 * k as f64 / steps as f64;
            let q: Vec<f64> = q0.iter().map(|v| v + s).collect();
            all_known &= learner.gravity(&q, &mut g).unwrap();
            if let Some(p) = prev {
                for i in 0..3 {
                    largest = largest.max((g[i] - p[i]).abs());
                }
            }
            prev = Some(g);
        }
        (largest, all_known)
    }

    /// Walking out of the data, the switch of before loses `ĝ` at once (a step of the whole
    /// gravity torque, more than 1 N·m); the continuous `ĝ` keeps support everywhere and has no
    /// step: four times finer increments shrink its largest change about fourfold, and it is a
    /// tenth of the old step at most.
    #[test]
    fn the_continuous_gravity_estimate_has_no_step_where_support_ends() {
        let (old, old_known) = gravity_walk(false, 500);
        assert!(
            !old_known && old > 1.0,
            "the old switch: {old}, {old_known}"
        );
        let (coarse, known) = gravity_walk(true, 500);
        let (fine, _) = gravity_walk(true, 2000);
        assert!(known);
        assert!(fine < 0.35 * coarse, "a step: {fine} vs {coarse}");
        assert!(coarse < 0.1 * old, "{coarse} vs {old}");
    }
}
