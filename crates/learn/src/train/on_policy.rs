//! Phase 2, on-policy learning: episodes along the task path from home with the learned
//! controller and exploration noise, each stopped when the task error exceeds `reset_error`
//! (counted as aborted), the arm brought home in between.

use super::curriculum::EpisodePath;
use super::observer::{EpisodeReport, Phase};
use super::Trainer;
use crate::error::Result;
use osrl_control::{reference_acceleration, task_error};
use osrl_dynamics::Robot;

impl<R: Robot + ?Sized> Trainer<'_, R> {
    /// On-policy learning until the run's time is up. `ĝ` is frozen unless configured otherwise.
    pub(super) fn on_policy(&mut self) -> Result<()> {
        self.progress.phase = Phase::OnPolicy;
        self.clipped_before = self.learner.stats().clipped;
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
        self.begin_fade(self.cfg.switch_seconds);
        self.pd_move(&home, 2.0, 1.0, 0.0, limit)
    }

    /// One episode along the path from its start at the curriculum's stage: commands with
    /// exploration, learning from each transition, stopped (aborted) when the task error exceeds
    /// `reset_error`; the curriculum moves on by its outcome.
    fn episode(&mut self) -> Result<()> {
        self.learning = self.cfg.learn_on_policy;
        self.progress.episodes += 1;
        let cc = &self.cfg.curriculum;
        let stage = self.curriculum.current();
        let mut path = EpisodePath::new(
            self.traj,
            stage,
            self.cfg.episode_seconds,
            cc,
            &mut self.rng,
        );
        let mut xdd_ref = vec![0.0; self.axes.len()];
        // The fade from the PD hold takes the switch; the learner's own limiter starts afresh.
        self.learner.start_episode(None);
        let first = self.progress.episodes == 1;
        let c = &self.cfg;
        self.begin_fade(if first {
            c.first_switch_seconds
        } else {
            c.switch_seconds
        });
        let (mut e2, mut count, mut aborted, mut braked) = (0.0, 0u64, false, false);
        let mut k = 0u64;
        while (k as f64) < (path.seconds / self.dt).round() && !self.done() {
            let t = k as f64 * self.dt;
            k += 1;
            let prev = self.prev.clone();
            let target = path.sample(self.traj, t);
            let (x, xd) = (prev.x.as_slice(), prev.xd.as_slice());
            reference_acceleration(&self.cfg.gains, &target, self.axes, x, xd, &mut xdd_ref);
            let rng = self.cfg.explore.then_some(&mut self.rng);
            let (q, qd) = (prev.q.as_slice(), prev.qd.as_slice());
            self.learner.command(q, qd, &xdd_ref, rng, &mut self.u)?;
            self.step()?;
            let e = task_error(
                &path.sample(self.traj, t + self.dt),
                self.axes,
                self.prev.x.as_slice(),
            );
            e2 += e * e;
            count += 1;
            if e > self.cfg.reset_error {
                self.progress.aborted_episodes += 1;
                aborted = true;
                break;
            }
            if e > cc.brake_error && !braked {
                path.brake(t + self.dt, cc);
                self.progress.braked_episodes += 1;
                braked = true;
            }
        }
        let rms = (e2 / count.max(1) as f64).sqrt();
        self.curriculum
            .after_episode(aborted || braked, rms, cc.advance_error);
        self.progress.stage = self.curriculum.stage;
        self.progress.last_episode = Some(EpisodeReport {
            seconds: count as f64 * self.dt,
            aborted,
            braked,
            rms_error: rms,
            stage,
        });
        Ok(())
    }
}
