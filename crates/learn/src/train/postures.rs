//! Holds at path postures (`TrainConfig::posture_holds`, off by default): the static gravity
//! model's still samples where the task path goes, not only where the babbling went.
//!
//! The babbling holds random targets around home (sarcos7: ±0.2 rad per joint, about 150 holds
//! in 4 minutes), a sparse cover of 7-D joint space; the figure-8's postures reach 0.29 rad from
//! home, between and beyond those holds, and `û0`'s error there is most of sarcos7's command error
//! (`docs/decisions.md`, D23 "What limits it now"). The on-policy stops of the path clock give
//! still samples along the path, but the exploration shakes the arm in them (`M q̈` inside the
//! gate). Here the driver records the measured postures of its episodes (model-free: the arm's
//! own `q`) and, on the way home after an episode, moves to a few of them under the noise-free
//! PD with `ĝ` and holds each until the arm rests, as the babbling does: `u = g(q)` exactly there.

use super::Trainer;
use crate::error::{LearnError, Result};
use osrl_dynamics::Robot;
use rand::RngExt;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// Holds at postures of the episodes on the way home (the static gravity model's samples).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PostureHolds {
    /// Postures visited per return home (0: off). Default 0 (`docs/decisions.md`, D-nmse25).
    pub count: usize,
    /// Minimum-jerk move to each posture (s). Default 0.8: the babbling's shortest moves are
    /// 0.6 s, and the postures lie within a few tenths of a radian of each other.
    pub move_seconds: f64,
    /// Hold at each posture without noise (s). Default 0.6: the babbling's 0.5 s plus time
    /// to come to rest after a move from anywhere on the path.
    pub hold_seconds: f64,
    /// An episode's measured posture is recorded every this many seconds of its time (s).
    /// Default 1: the figure-8's period is 4 s at full speed.
    pub record_every: f64,
    /// Each hold's target is the drawn posture plus a uniform offset within ± this per joint
    /// (rad; inside the joint limits by 0.05 rad). Default 0: the holds at exactly the recorded
    /// postures. A new field of the static model that sees one posture only has undetermined
    /// slopes (D8); the offsets spread its samples.
    pub jitter: f64,
    /// The most recent recorded postures kept to draw from. Default 64: the last episode or two
    /// at the curriculum's current stage.
    pub pool: usize,
    /// The moves and holds teach the static gravity model only (true) or everything, as the
    /// return home does (`learn_returning_home`). Default true: noise-free PD data carry no
    /// excitation for `Â` and the local controllers.
    pub static_only: bool,
}

impl Default for PostureHolds {
    fn default() -> Self {
        Self {
            count: 0,
            move_seconds: 0.8,
            hold_seconds: 0.6,
            record_every: 1.0,
            jitter: 0.0,
            pool: 64,
            static_only: true,
        }
    }
}

impl PostureHolds {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] naming the field out of range.
    pub fn validate(&self) -> Result<()> {
        let pos = |x: f64| x > 0.0 && x.is_finite();
        let bad = [
            ("move_seconds", pos(self.move_seconds)),
            (
                "hold_seconds",
                self.hold_seconds >= 0.0 && self.hold_seconds.is_finite(),
            ),
            ("record_every", pos(self.record_every)),
            ("jitter", self.jitter >= 0.0 && self.jitter.is_finite()),
            ("pool", self.pool >= 1),
        ]
        .into_iter()
        .find(|(_, ok)| !ok);
        match bad {
            Some((what, _)) => Err(LearnError::InvalidConfig(format!(
                "posture_holds.{what} is out of range: {self:?}"
            ))),
            None => Ok(()),
        }
    }
}

/// The recorded postures (most recent last) and the episode time of the next record.
#[derive(Debug, Default)]
pub(super) struct PosturePool {
    postures: VecDeque<Vec<f64>>,
    next_record: u64,
}

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

    /// Moves to `count` recorded postures (drawn uniformly, with replacement) and holds each,
    /// under the noise-free PD with `ĝ`; the static gravity model learns (or everything, as
    /// configured). Nothing if the option is off or nothing is recorded yet.
    pub(super) fn posture_holds(&mut self, limit: u64) -> Result<()> {
        let ph = self.cfg.posture_holds.clone();
        if ph.count == 0 || self.postures.postures.is_empty() {
            return Ok(());
        }
        let (learning, static_only) = (self.learning, self.static_only);
        if ph.static_only {
            self.static_only = self.learning;
            self.learning = false;
        }
        for _ in 0..ph.count {
            let k = self.rng.random_range(0..self.postures.postures.len());
            let mut target = self.postures.postures[k].clone();
            if ph.jitter > 0.0 {
                for (i, t) in target.iter_mut().enumerate() {
                    let d = self.rng.random_range(-ph.jitter..ph.jitter);
                    let (lo, hi) = (self.q_min[i] + 0.05, self.q_max[i] - 0.05);
                    *t = if hi > lo { (*t + d).clamp(lo, hi) } else { *t };
                }
            }
            self.pd_move(&target, ph.move_seconds, ph.hold_seconds, 0.0, limit)?;
        }
        (self.learning, self.static_only) = (learning, static_only);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::PostureHolds;

    /// The defaults are valid and each range check refuses its field.
    #[test]
    fn posture_holds_validate_their_ranges() {
        assert!(PostureHolds::default().validate().is_ok());
        let bad = [
            PostureHolds {
                move_seconds: 0.0,
                ..Default::default()
            },
            PostureHolds {
                hold_seconds: -1.0,
                ..Default::default()
            },
            PostureHolds {
                record_every: f64::NAN,
                ..Default::default()
            },
            PostureHolds {
                pool: 0,
                ..Default::default()
            },
        ];
        for b in bad {
            assert!(b.validate().is_err(), "{b:?}");
        }
    }
}
