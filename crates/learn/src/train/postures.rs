//! Holds at path postures (`TrainConfig::posture_holds`, 3 per return home by default): still
//! samples of gravity where the task path goes, not only where the babbling went, for the
//! null-space correction (or the static gravity model).
//!
//! The babbling holds random targets around home (sarcos7: ±0.2 rad per joint, about 150 holds
//! in 4 minutes), a sparse cover of 7-D joint space; the figure-8's postures reach 0.29 rad from
//! home, between and beyond those holds, and `û0`'s error there is most of sarcos7's command error
//! (`docs/decisions.md`, D23 "What limits it now"). The on-policy stops of the path clock give
//! still samples along the path, but the exploration shakes the arm in them (`M q̈` inside the
//! gate). Here the driver records the measured postures of its episodes (model-free: the arm's
//! own `q`) and, on the way home after an episode, moves to a few of them under the noise-free
//! PD with `ĝ` and holds each until the arm rests, as the babbling does: `u = g(q)` exactly there.
//! While the learner re-adapts, a move after a hold starts its reference at the posture held
//! (`held_reference`): the arm sags from it under the gravity error, and a reference at the
//! measured posture would drop the P-term that carries the error in one period.

use super::{HeldReference, Trainer};
use crate::error::Result;
use osrl_dynamics::Robot;
use rand::RngExt;

impl<R: Robot + ?Sized> Trainer<'_, R> {
    /// At the start of an episode: the first record comes one `record_every` into it.
    pub(super) fn postures_episode_start(&mut self) {
        let every = self.record_steps();
        self.postures.next_record = every;
    }

    /// Records the measured posture if the option is on and the `count`-th step of the episode
    /// is due.
    pub(super) fn postures_record(&mut self, count: u64) {
        let ph = &self.cfg.posture_holds;
        if ph.count == 0 || count < self.postures.next_record {
            return;
        }
        self.postures.next_record += self.record_steps();
        if self.postures.postures.len() >= ph.pool {
            self.postures.postures.pop_front();
        }
        self.postures
            .postures
            .push_back(self.prev.q.as_slice().to_vec());
    }

    fn record_steps(&self) -> u64 {
        ((self.cfg.posture_holds.record_every / self.dt).round() as u64).max(1)
    }

    /// Whether a move after a hold starts its reference at the held posture
    /// (`posture_holds.held_reference`).
    fn held_reference(&self) -> bool {
        match self.cfg.posture_holds.held_reference {
            HeldReference::Never => false,
            HeldReference::Always => true,
            HeldReference::Readapting => self.learner.adaptation().readapting(),
        }
    }

    /// Moves to `count` recorded postures (drawn uniformly, with replacement) and holds each,
    /// under the noise-free PD with `ĝ`; the null-space correction or the static gravity model
    /// learns (or everything, as configured). Returns the last posture held if the move after
    /// it is to start its reference there ([`HeldReference`]); each move after the first does
    /// then too. `None` also if the option is off or nothing is recorded yet.
    pub(super) fn posture_holds(&mut self, limit: u64) -> Result<Option<Vec<f64>>> {
        let ph = self.cfg.posture_holds.clone();
        if ph.count == 0 || self.postures.postures.is_empty() {
            return Ok(None);
        }
        let mut held: Option<Vec<f64>> = None;
        let (learning, static_only) = (self.learning, self.static_only);
        if ph.static_only {
            self.static_only = self.learning;
            self.learning = false;
        }
        let count = if self.learner.adaptation().readapting() {
            ph.readapting_count
        } else {
            ph.count
        };
        for _ in 0..count {
            let k = self.rng.random_range(0..self.postures.postures.len());
            let mut target = self.postures.postures[k].clone();
            if ph.jitter > 0.0 {
                for (i, t) in target.iter_mut().enumerate() {
                    let d = self.rng.random_range(-ph.jitter..ph.jitter);
                    let (lo, hi) = (self.q_min[i] + 0.05, self.q_max[i] - 0.05);
                    *t = if hi > lo { (*t + d).clamp(lo, hi) } else { *t };
                }
            }
            let start = held
                .take()
                .unwrap_or_else(|| self.prev.q.as_slice().to_vec());
            let (m, h) = (ph.move_seconds, ph.hold_seconds);
            self.pd_move_from(&start, &target, m, h, 0.0, limit)?;
            self.learner.end_hold()?;
            held = self.held_reference().then_some(target);
            if ph.handover_seconds > 0.0 {
                self.begin_fade(ph.handover_seconds);
            }
        }
        (self.learning, self.static_only) = (learning, static_only);
        Ok(held)
    }
}
