//! Phase 2, on-policy learning: episodes along the task path from home with the learned
//! controller and exploration noise, each stopped when the task error exceeds `reset_error`
//! (counted as aborted), the arm brought home in between.

use super::observer::Phase;
use super::Trainer;
use crate::error::Result;
use crate::eval::max_abs_diff;
use osrl_control::{reference_acceleration, task_error};
use osrl_dynamics::Robot;

impl<R: Robot + ?Sized> Trainer<'_, R> {
    /// On-policy learning until the run's time is up. `ĝ` is frozen unless configured otherwise.
    pub(super) fn on_policy(&mut self) -> Result<()> {
        self.progress.phase = Phase::OnPolicy;
        self.learning = self.cfg.learn_on_policy;
        let gravity_on = self.learner.config().experimental.gravity_on_policy;
        self.learner.freeze_gravity(!gravity_on);
        while !self.done() {
            if self.away_from_home() {
                self.return_home()?;
                continue;
            }
            self.episode()?;
            self.episode_ended();
        }
        Ok(())
    }

    /// Whether the arm is not at rest at home (1 cm·rad, 0.01 rad/s).
    fn away_from_home(&self) -> bool {
        let off = self
            .prev
            .q
            .iter()
            .zip(&self.home)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        off > 0.01 || self.prev.qd.amax() > 0.01
    }

    /// A PD move home (2 s) and 1 s of settling there, learned from if configured.
    fn return_home(&mut self) -> Result<()> {
        self.learning = self.cfg.learn_on_policy && self.cfg.learn_returning_home;
        let (home, limit) = (self.home.clone(), self.total_steps);
        self.pd_move(&home, 2.0, 1.0, 0.0, limit)
    }

    /// One episode along the path from its start: commands with exploration, learning from each
    /// transition, stopped (aborted) when the task error exceeds `reset_error`.
    fn episode(&mut self) -> Result<()> {
        self.learning = self.cfg.learn_on_policy;
        self.progress.episodes += 1;
        let m = self.axes.len();
        let mut xdd_ref = vec![0.0; m];
        let mut last_u: Option<Vec<f64>> = None;
        let k_ep = (self.cfg.episode_seconds / self.dt).round() as u64;
        for k in 0..k_ep {
            if self.done() {
                break;
            }
            let t = k as f64 * self.dt;
            let prev = self.prev.clone();
            let target = self.traj.sample(t);
            let (x, xd) = (prev.x.as_slice(), prev.xd.as_slice());
            reference_acceleration(&self.cfg.gains, &target, self.axes, x, xd, &mut xdd_ref);
            let rng = self.cfg.explore.then_some(&mut self.rng);
            let (q, qd) = (prev.q.as_slice(), prev.qd.as_slice());
            self.learner.command(q, qd, &xdd_ref, rng, &mut self.u)?;
            match &mut last_u {
                Some(last) => {
                    self.max_step = self.max_step.max(max_abs_diff(last, &self.u));
                    last.copy_from_slice(&self.u);
                }
                None => last_u = Some(self.u.clone()),
            }
            self.step()?;
            if self.task_error(t + self.dt) > self.cfg.reset_error {
                self.progress.aborted_episodes += 1;
                break;
            }
        }
        Ok(())
    }

    /// `‖x − x_d(t)‖` (m) of the last measurement.
    fn task_error(&self, t: f64) -> f64 {
        task_error(&self.traj.sample(t), self.axes, self.prev.x.as_slice())
    }
}
