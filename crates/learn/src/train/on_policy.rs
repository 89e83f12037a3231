//! Phase 2, on-policy learning: episodes along the task path from home with the learned
//! controller and exploration noise, each stopped when the task error exceeds `reset_error`
//! (counted as aborted), the arm brought home in between.

use super::curriculum::EpisodePath;
use super::observer::{EpisodeOutcome, EpisodeRecord, EpisodeReport, Phase};
use super::rollback::Rollback;
use super::Trainer;
use crate::dob::observed_reference;
use crate::error::Result;
use osrl_control::task_error;
use osrl_dynamics::Robot;

impl<R: Robot + ?Sized> Trainer<'_, R> {
    /// On-policy learning until the run's time is up. `ĝ` is frozen unless configured otherwise.
    pub(super) fn on_policy(&mut self) -> Result<()> {
        self.progress.phase = Phase::OnPolicy;
        self.clipped_before = self.learner.stats().clipped;
        self.learning = self.cfg.learn_on_policy;
        let gravity_on = self.learner.config().experimental.gravity_on_policy;
        self.learner.freeze_gravity(!gravity_on);
        // A continuation (no babbling before it, e.g. `osrl adapt`) has sent nothing yet: the
        // first episode's fade starts from zero torque unless the hold at home comes first,
        // from the hold's own command (`hold_before_continuation`).
        let continuation = self.steps == 0;
        self.continuation = continuation;
        self.learner
            .freeze_static_gravity(continuation && self.cfg.freeze_static_in_continuation);
        let mut hold_first = continuation && self.cfg.hold_before_continuation;
        if hold_first {
            self.hold_command()?;
        }
        self.rollback = Rollback::start(self.learner, continuation);
        while !self.done() {
            let away = std::mem::take(&mut hold_first) || self.away_from_home();
            if away && !self.return_home()? {
                // Not settled within the hold: the episode starts from where the arm is
                // (counted), rather than returning home again and again.
                self.unsettled_starts += 1;
            }
            if self.done() {
                break;
            }
            self.episode()?;
            self.episode_ended();
        }
        Ok(())
    }

    /// One episode along the path from its start at the curriculum's stage: commands with
    /// exploration, learning from each transition, braked when the task error passes
    /// `brake_error`; the curriculum moves on by its outcome.
    fn episode(&mut self) -> Result<()> {
        self.learning = self.cfg.learn_on_policy;
        self.progress.episodes += 1;
        self.next_path()?;
        let stage = self.curriculum.current();
        let (cfg, rng) = (self.cfg, &mut self.rng);
        let path = EpisodePath::new(
            &self.episode_path,
            stage,
            cfg.episode_seconds,
            &cfg.curriculum,
            rng,
        );
        // The fade from the PD hold takes the switch; the learner's own limiter starts afresh.
        self.learner.start_episode(None)?;
        self.dob.reset();
        // A continuation's controller is trained: its first episode switches as any other.
        let first = self.progress.episodes == 1 && !self.continuation;
        self.begin_fade(if first {
            cfg.first_switch_seconds
        } else {
            cfg.switch_seconds
        });
        let (start_minute, stage_index) = (self.minutes(), self.curriculum.stage);
        self.postures_episode_start();
        let report = self.drive_path(&path, stage)?;
        let outcome = match (report.aborted, report.braked, self.jumped) {
            (true, _, _) => EpisodeOutcome::Aborted,
            (_, true, true) => EpisodeOutcome::BrakedOnStep,
            (_, true, false) => EpisodeOutcome::BrakedOnError,
            _ => EpisodeOutcome::Completed,
        };
        let failed = report.aborted || report.braked;
        let rolled_back = self.rollback.after_episode(self.learner, failed)?;
        self.episode_log.push(EpisodeRecord {
            start_minute,
            stage: stage_index,
            seconds: report.seconds,
            rms_error_mm: report.rms_error * 1e3,
            outcome,
            jump_joint: self.jump_joint.take().filter(|_| report.braked),
            rolled_back,
        });
        let cc = &cfg.curriculum;
        self.curriculum
            .after_episode(failed, report.rms_error, cc.advance_error);
        self.progress.stage = self.curriculum.stage;
        self.progress.last_episode = Some(report);
        Ok(())
    }

    /// Tracks `path` to its end (or the run's); stops early when the task error passes
    /// `brake_error` or a command would jump by more than `brake_step` (braked: that command is
    /// not sent, and the return home takes over within `brake_switch_seconds`), or when the
    /// error passes `reset_error` (aborted).
    fn drive_path(&mut self, path: &EpisodePath, stage: [f64; 2]) -> Result<EpisodeReport> {
        let cc = &self.cfg.curriculum;
        let mut xdd_ref = vec![0.0; self.axes.len()];
        let (mut e2, mut count, mut aborted, mut braked) = (0.0, 0u64, false, false);
        (self.jump_guard, self.jumped, self.jump_joint) = (true, false, None);
        while (count as f64) < (path.seconds / self.dt).round() && !self.done() {
            let t = count as f64 * self.dt;
            let e = self.track(path, t, &mut xdd_ref)?;
            e2 += e * e;
            count += 1;
            if e > self.cfg.reset_error {
                self.progress.aborted_episodes += 1;
                aborted = true;
                break;
            }
            if e > cc.brake_error || self.jumped {
                self.progress.braked_episodes += 1;
                self.progress.braked_on_step += u64::from(self.jumped);
                braked = true;
                break;
            }
            self.postures_record(count);
        }
        self.jump_guard = false;
        // The observer stops with the episode: its estimate no longer says anything.
        self.learner.observe_offset(0.0);
        Ok(EpisodeReport {
            seconds: count as f64 * self.dt,
            aborted,
            braked,
            rms_error: (e2 / count.max(1) as f64).sqrt(),
            stage,
        })
    }

    /// One control period on `path` at episode time `t`: eq. 2's reference, the learned command
    /// with exploration, the step; returns the task error after it (m).
    fn track(&mut self, path: &EpisodePath, t: f64, xdd_ref: &mut [f64]) -> Result<f64> {
        let target = path.sample(&self.episode_path, t);
        let prev = &self.prev;
        // The observer learns from the response to the learned command alone (not to a fade's
        // blend or a command the limits changed).
        let learn = !self.sent_modified;
        let (gains, axes) = (&self.cfg.gains, self.axes);
        observed_reference(gains, &target, axes, prev, &mut self.dob, learn, xdd_ref);
        if self.continuation {
            // A trained learner's observer tells a change from its own noise (D35); a learner
            // that babbled first misses much of the path for a while as it learns.
            self.learner.observe_offset(self.dob.offset());
        }
        let rng = self.cfg.explore.then_some(&mut self.rng);
        let gain = path.exploration_gain(t, self.cfg.quiet_holds, self.cfg.quiet_hold_gain);
        self.learner.set_exploration_gain(gain);
        let (q, qd) = (prev.q.as_slice(), prev.qd.as_slice());
        let limits_before = self.learner.stats();
        self.learner.command(q, qd, xdd_ref, rng, &mut self.u)?;
        let s = self.learner.stats();
        let limited =
            s.clipped != limits_before.clipped || s.rate_limited != limits_before.rate_limited;
        self.step()?;
        self.sent_modified |= limited;
        let after = path.sample(&self.episode_path, t + self.dt);
        Ok(task_error(&after, self.axes, self.prev.x.as_slice()))
    }
}
