//! The return home between on-policy episodes: a minimum-jerk PD move home, then a hold there
//! for 1 s, then with integral action until the arm is at rest at home (or the hold's time is
//! up).
//!
//! The joint gains of an imported arm are `K_P = m_i ω²` with `m_i` the smallest inertia joint
//! `i` can move (`osrl_control::profile`): a heavy mode of several joints (the Panda's shoulder
//! and upper-arm rotations) then has a low, weakly damped frequency, and the learned gravity
//! model's error `Δĝ` leaves a static offset `Δĝ / K_P` of several centiradians. The integral term
//! removes that offset whatever `Δĝ` is, so the settle test does not depend on how well `ĝ` has
//! been learned; the hold ends as soon as the arm is settled.

use super::babble::pd_command;
use super::Trainer;
use crate::error::Result;
use osrl_dynamics::Robot;

impl<R: Robot + ?Sized> Trainer<'_, R> {
    /// Whether the arm is not at rest at home (`home_tolerance` rad, rad/s).
    pub(super) fn away_from_home(&self) -> bool {
        let off = self
            .prev
            .q
            .iter()
            .zip(&self.home)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let tol = self.cfg.home_tolerance;
        off > tol || self.prev.qd.amax() > tol
    }

    /// A PD move home (2 s), then holding home with integral action until the arm is settled
    /// (at least 1 s, at most `home_hold_seconds`); learned from if configured. Returns whether
    /// the arm settled.
    pub(super) fn return_home(&mut self) -> Result<bool> {
        self.learning = self.cfg.learn_on_policy && self.cfg.learn_returning_home;
        let (home, limit) = (self.home.clone(), self.total_steps);
        let braked = self
            .progress
            .last_episode
            .is_some_and(|e| e.braked || e.aborted);
        self.begin_fade(if braked {
            self.cfg.brake_switch_seconds
        } else {
            self.cfg.switch_seconds
        });
        if braked && self.cfg.brake_return_from_velocity {
            self.move_v0 = Some(self.prev.qd.as_slice().to_vec());
        }
        let held = self.posture_holds(limit)?;
        let start = held.unwrap_or_else(|| self.prev.q.as_slice().to_vec());
        self.pd_move_from(&start, &home, 2.0, 0.0, 0.0, limit)?;
        self.hold_home(limit)
    }

    /// The hold's command at home, `ĝ + s (K_P e + K_D ė)` at the last measurement, into `u`
    /// (the command a fade then starts from).
    pub(super) fn hold_command(&mut self) -> Result<()> {
        let (prev, zero) = (self.prev.clone(), vec![0.0; self.home.len()]);
        let scale = self.cfg.babble.gain_scale;
        pd_command(self.learner, &prev, &self.home, &zero, scale, &mut self.u)
    }

    /// Holds home under `ĝ + s (K_P e + K_D ė)` for 1 s; if the arm has not settled then, under
    /// `ĝ + s (K_P e + K_I ∫e + K_D ė)` with `K_I = K_P / home_integral_seconds` (the integral's
    /// torque bounded by half the torque limit) until it has, or `home_hold_seconds` have passed,
    /// or the step count reaches `limit`.
    fn hold_home(&mut self, limit: u64) -> Result<bool> {
        let n = self.home.len();
        let (min_k, max_k) = (
            (1.0 / self.dt).round() as u64,
            (self.cfg.home_hold_seconds / self.dt).round() as u64,
        );
        let ti = self.cfg.home_integral_seconds;
        self.integral.iter_mut().for_each(|v| *v = 0.0);
        let zero = vec![0.0; n];
        let mut k = 0;
        while self.steps < limit && k < max_k.max(min_k) {
            if k >= min_k && !self.away_from_home() {
                return Ok(true);
            }
            let scale = self.cfg.babble.gain_scale;
            pd_command(
                self.learner,
                &self.prev,
                &self.home,
                &zero,
                scale,
                &mut self.u,
            )?;
            let cfg = self.learner.config();
            let (kp, lim) = (&cfg.nominal.kp, &cfg.guards.torque_limits);
            // The first second is the plain PD hold (arms that settle in it are held as
            // without integral action); the integral acts only on an arm that did not.
            if k >= min_k && ti > 0.0 {
                for i in 0..n {
                    self.integral[i] += (self.home[i] - self.prev.q[i]) * self.dt;
                    let ki = scale * kp[i] / ti;
                    let bound = 0.5 * lim[i] / ki;
                    self.integral[i] = self.integral[i].clamp(-bound, bound);
                    self.u[i] += ki * self.integral[i];
                }
            }
            self.step()?;
            k += 1;
        }
        Ok(!self.away_from_home())
    }
}
