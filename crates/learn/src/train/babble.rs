//! Phase 1, motor babbling: random point-to-point joint moves (minimum jerk) around home under
//! PD control with the learned gravity compensation `ĝ`, with torque noise, so the models see
//! commands that vary independently of the state. The same PD moves bring the arm home between
//! on-policy episodes.

use super::Trainer;
use crate::error::Result;
use crate::learner::Learner;
use osrl_dynamics::{Measurement, Robot};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

impl<R: Robot + ?Sized> Trainer<'_, R> {
    /// Babbles for `babble.minutes` (or the whole run if shorter).
    pub(super) fn babble(&mut self) -> Result<()> {
        let b = &self.cfg.babble;
        let babble_steps = (b.minutes * self.per_min as f64).round() as u64;
        let end = babble_steps.min(self.total_steps);
        let spread = b.spread_for(self.home.len());
        let mut target = vec![0.0; self.home.len()];
        while self.steps < end {
            for (i, t) in target.iter_mut().enumerate() {
                let lo = (self.q_min[i] + 0.05).max(self.home[i] - spread);
                let hi = (self.q_max[i] - 0.05).min(self.home[i] + spread);
                *t = uniform(&mut self.rng, lo, hi);
            }
            let b = &self.cfg.babble;
            let (t0, t1, settle, noise) = (b.move_time[0], b.move_time[1], b.settle, b.noise);
            let total = uniform(&mut self.rng, t0, t1);
            self.pd_move(&target, total, settle, noise, end)?;
        }
        Ok(())
    }

    /// A minimum-jerk joint move from the current posture to `target` over `total` seconds, then
    /// `settle` seconds holding it, under PD control with `ĝ`; torque noise of `noise` rad of PD
    /// error while moving; stops early when the step count reaches `limit`.
    pub(super) fn pd_move(
        &mut self,
        target: &[f64],
        total: f64,
        settle: f64,
        noise: f64,
        limit: u64,
    ) -> Result<()> {
        let start: Vec<f64> = self.prev.q.as_slice().to_vec();
        self.pd_move_from(&start, target, total, settle, noise, limit)
    }

    /// [`Self::pd_move`] with the reference starting at `start` instead of the measured
    /// posture: a move that follows a hold at `start` keeps the hold's PD command continuous
    /// (under a gravity error the arm sags from the held posture, and a reference starting at
    /// the measured one would drop the P-term in one period).
    pub(super) fn pd_move_from(
        &mut self,
        start: &[f64],
        target: &[f64],
        total: f64,
        settle: f64,
        noise: f64,
        limit: u64,
    ) -> Result<()> {
        let n = target.len();
        let (mut q_t, mut v_t) = (vec![0.0; n], vec![0.0; n]);
        for k in 0..((total + settle) / self.dt).round() as u64 {
            if self.steps >= limit {
                break;
            }
            for i in 0..n {
                (q_t[i], v_t[i]) = min_jerk(start[i], target[i], k as f64 * self.dt, total);
            }
            let prev = self.prev.clone();
            let scale = self.cfg.babble.gain_scale;
            pd_command(self.learner, &prev, &q_t, &v_t, scale, &mut self.u)?;
            // None while holding the target, so the arm comes to rest there (the static
            // gravity model's samples).
            if noise > 0.0 && (k as f64) * self.dt < total {
                let kp = &self.learner.config().nominal.kp;
                let tau = self.cfg.babble.correlation_time;
                let a = if tau > 0.0 {
                    (-self.dt / tau).exp()
                } else {
                    0.0
                };
                let b = (1.0 - a * a).sqrt();
                for ((u, k), z) in self.u.iter_mut().zip(kp).zip(&mut self.babble_noise) {
                    let e: f64 = StandardNormal.sample(&mut self.rng);
                    *z = a * *z + b * e;
                    *u += noise * k * *z;
                }
            }
            self.step()?;
        }
        Ok(())
    }
}

/// Minimum-jerk interpolation from `a` to `b` over `total` seconds: position and velocity at
/// time `t`.
pub(crate) fn min_jerk(a: f64, b: f64, t: f64, total: f64) -> (f64, f64) {
    let s = (t / total).clamp(0.0, 1.0);
    let p = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
    let v = 30.0 * s * s * (1.0 - s) * (1.0 - s) / total;
    (a + (b - a) * p, if t < total { (b - a) * v } else { 0.0 })
}

/// The PD command of babbling and of returning home: `ĝ(q) + s (K_P (q_d − q) + K_D (q̇_d − q̇))`.
pub(crate) fn pd_command(
    learner: &mut Learner,
    meas: &Measurement,
    q_target: &[f64],
    v_target: &[f64],
    scale: f64,
    u: &mut [f64],
) -> Result<()> {
    let n = u.len();
    // u0 without its PD pull to rest = ĝ: evaluate the nominal and add the pull back.
    learner.nominal(meas.q.as_slice(), meas.qd.as_slice(), u)?;
    let nom = &learner.config().nominal;
    for i in 0..n {
        let g = u[i] + nom.kd[i] * meas.qd[i] + nom.kp[i] * (meas.q[i] - nom.q_rest[i]);
        u[i] = g + scale
            * (nom.kp[i] * (q_target[i] - meas.q[i]) + nom.kd[i] * (v_target[i] - meas.qd[i]));
    }
    Ok(())
}

/// A uniform draw in `[lo, hi)`, or `lo` if the interval is empty.
fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    if hi > lo {
        rng.random_range(lo..hi)
    } else {
        lo
    }
}

#[cfg(test)]
mod tests {
    use super::min_jerk;

    /// The move starts and ends at rest at its ends, passes the midpoint at half time, and its
    /// velocity is the derivative of its position.
    #[test]
    fn minimum_jerk_moves_start_and_end_at_rest() {
        let (a, b, total) = (0.3, -0.5, 1.2);
        assert_eq!(min_jerk(a, b, 0.0, total), (a, 0.0));
        assert_eq!(min_jerk(a, b, total, total), (b, 0.0));
        assert_eq!(min_jerk(a, b, 5.0, total), (b, 0.0));
        assert!((min_jerk(a, b, total / 2.0, total).0 - (a + b) / 2.0).abs() < 1e-15);
        for k in 1..100 {
            let t = total * k as f64 / 100.0;
            let h = 1e-6;
            let fd = (min_jerk(a, b, t + h, total).0 - min_jerk(a, b, t - h, total).0) / (2.0 * h);
            assert!((fd - min_jerk(a, b, t, total).1).abs() < 1e-6);
        }
    }
}
