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
        // From the arm's velocity after a braked episode (`move_v0`), else from rest; the
        // velocity capped so that the quintic's overshoot stays 0.05 rad inside the limits.
        let v0 = self.move_v0.take().map(|mut v0| {
            for (i, v) in v0.iter_mut().enumerate() {
                let (lo, hi) = (self.q_min[i] + 0.05, self.q_max[i] - 0.05);
                let reach = QUINTIC_OVERSHOOT * total;
                let up = ((hi - start[i].max(target[i])) / reach).max(0.0);
                let down = ((start[i].min(target[i]) - lo) / reach).max(0.0);
                *v = v.clamp(-down, up);
            }
            v0
        });
        for k in 0..((total + settle) / self.dt).round() as u64 {
            if self.steps >= limit {
                break;
            }
            let t = k as f64 * self.dt;
            for i in 0..n {
                (q_t[i], v_t[i]) = match &v0 {
                    Some(v0) => quintic_from(start[i], v0[i], target[i], t, total),
                    None => min_jerk(start[i], target[i], t, total),
                };
            }
            let scale = self.cfg.babble.gain_scale;
            pd_command(self.learner, &self.prev, &q_t, &v_t, scale, &mut self.u)?;
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

/// The largest value of [`quintic_from`]'s `h` on `[0, 1]` (at `s = 1/3`): the move overshoots
/// its ends by at most this times `|v0| T`.
pub(crate) const QUINTIC_OVERSHOOT: f64 = 16.0 / 81.0;

/// The quintic from `a` (rad) at velocity `v0` (rad/s; acceleration 0) to `b` at rest after
/// `total` seconds: position and velocity at time `t` (s; held at `b` after `total`). The
/// minimum-jerk move plus `v0 T h(s)`, `h(s) = s − 6s³ + 8s⁴ − 3s⁵ = s (1 − s)³ (1 + 3s) ≥ 0`
/// (`h(0) = h(1) = 0`, `h'(0) = 1`, `h'(1) = h''(0) = h''(1) = 0`).
pub(crate) fn quintic_from(a: f64, v0: f64, b: f64, t: f64, total: f64) -> (f64, f64) {
    let (q, v) = min_jerk(a, b, t, total);
    if t >= total {
        return (q, v);
    }
    let s = (t / total).clamp(0.0, 1.0);
    let (s2, s3) = (s * s, s * s * s);
    let h = s - 6.0 * s3 + 8.0 * s3 * s - 3.0 * s3 * s2;
    let dh = 1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s2 * s2;
    (q + v0 * total * h, v + v0 * dh)
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
    use super::{min_jerk, quintic_from, QUINTIC_OVERSHOOT};

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

    /// The quintic from a velocity: its ends, its velocity as the derivative of its position,
    /// zero acceleration at both ends, and the minimum-jerk move when the velocity is 0.
    #[test]
    fn the_quintic_starts_at_the_velocity_and_ends_at_rest() {
        let (a, v0, b, total) = (0.3, -1.7, -0.4, 0.8);
        assert_eq!(quintic_from(a, v0, b, 0.0, total), (a, v0));
        let (q, v) = quintic_from(a, v0, b, total, total);
        assert!((q - b).abs() < 1e-15 && v == 0.0, "end {q} {v}");
        let h = 1e-6;
        for k in 1..80 {
            let t = total * k as f64 / 80.0;
            let (qm, qp) = (
                quintic_from(a, v0, b, t - h, total).0,
                quintic_from(a, v0, b, t + h, total).0,
            );
            let v = quintic_from(a, v0, b, t, total).1;
            assert!((v - (qp - qm) / (2.0 * h)).abs() < 1e-6, "t {t}: {v}");
            assert_eq!(quintic_from(a, 0.0, b, t, total), min_jerk(a, b, t, total));
        }
        for t in [0.0, total] {
            let acc = |t: f64| {
                let (vm, vp) = (
                    quintic_from(a, v0, b, t - h, total).1,
                    quintic_from(a, v0, b, t + h, total).1,
                );
                (vp - vm) / (2.0 * h)
            };
            let one_sided = if t == 0.0 { acc(h) } else { acc(t - h) };
            assert!(one_sided.abs() < 1e-3, "acceleration {one_sided} at {t}");
        }
        // Its overshoot beyond the ends is at most `QUINTIC_OVERSHOOT |v0| T`, and reaches it
        // when the ends coincide.
        for (a, v0, b) in [
            (0.2, 3.0, 0.2),
            (0.2, -3.0, 0.2),
            (0.0, 2.0, -0.5),
            (0.0, -2.0, 0.7),
        ] {
            let qs: Vec<f64> = (0..=4000)
                .map(|k| quintic_from(a, v0, b, total * k as f64 / 4000.0, total).0)
                .collect();
            let (hi, lo) = qs
                .iter()
                .fold((f64::MIN, f64::MAX), |(h, l), &q| (h.max(q), l.min(q)));
            let bound = QUINTIC_OVERSHOOT * v0.abs() * total;
            let over = if v0 > 0.0 {
                hi - a.max(b)
            } else {
                a.min(b) - lo
            };
            assert!(
                over <= bound + 1e-12,
                "{a} {v0} {b}: overshoot {over} above {bound}"
            );
            if a == b {
                assert!(
                    over > bound - 1e-6,
                    "{a} {v0} {b}: overshoot {over} below {bound}"
                );
            }
        }
    }
}
