//! The holds at path postures (`TrainConfig::posture_holds`): their configuration and the pool of
//! recorded postures. The driver's part is `postures.rs`; kept apart so that neither the train
//! config nor the trainer's state depends on the driver.

use crate::error::{LearnError, Result};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// Holds at postures of the episodes on the way home (the static gravity model's samples).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PostureHolds {
    /// Postures visited per return home (0: off). Default 3: with the learner's null-space
    /// correction (`gravity.null_correction`) they are what it learns from (D36); about 4 s per
    /// return home.
    pub count: usize,
    /// Postures visited per return home while the learner re-adapts (a change detected or a
    /// strength above 0); none while the option is off (`count = 0`). Default 10: the
    /// null-space correction learns a changed gravity from these holds only, and a run with a
    /// change has few returns home (one per episode of up to a minute).
    pub readapting_count: usize,
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
    /// When a move after a hold starts its reference at the posture held instead of the
    /// measured one. Default `readapting`: while the learner re-adapts to a changed robot
    /// (`ĝ` wrong), the arm sags from a held posture and a reference at the measured posture
    /// drops the PD's P-term in one period; without a change the held reference measured worse
    /// (D37).
    pub held_reference: HeldReference,
    /// Each move after a hold starts with a fade from the hold's last command to the PD's over
    /// this long (s; 0: none). Default 0. Why: the arm sags from a held posture under `ĝ`'s
    /// error, and a reference that starts at the measured posture drops the PD's P-term in one
    /// period (D37): sarcos7's largest command steps in training (0.75–1.1 N·m, at rest).
    pub handover_seconds: f64,
}

/// When the move after a hold at a path posture starts its reference at the held posture
/// ([`PostureHolds::held_reference`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HeldReference {
    /// Always at the measured posture.
    Never,
    /// At the held posture while the learner re-adapts (a change detected or a strength above
    /// 0, [`crate::AdaptationSignal`]).
    Readapting,
    /// Always at the held posture.
    Always,
}

impl Default for PostureHolds {
    fn default() -> Self {
        Self {
            count: 3,
            readapting_count: 10,
            move_seconds: 0.8,
            hold_seconds: 0.6,
            record_every: 1.0,
            jitter: 0.0,
            pool: 64,
            static_only: true,
            held_reference: HeldReference::Readapting,
            handover_seconds: 0.0,
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
        let nonneg = |x: f64| x >= 0.0 && x.is_finite();
        // (field, its value, what is accepted, whether it is)
        let bad = [
            (
                "move_seconds",
                self.move_seconds,
                "> 0 s",
                pos(self.move_seconds),
            ),
            (
                "hold_seconds",
                self.hold_seconds,
                "≥ 0 s",
                nonneg(self.hold_seconds),
            ),
            (
                "record_every",
                self.record_every,
                "> 0 s",
                pos(self.record_every),
            ),
            ("jitter", self.jitter, "≥ 0 rad", nonneg(self.jitter)),
            ("pool", self.pool as f64, "≥ 1", self.pool >= 1),
            (
                "handover_seconds",
                self.handover_seconds,
                "≥ 0 s",
                nonneg(self.handover_seconds),
            ),
        ]
        .into_iter()
        .find(|c| !c.3);
        match bad {
            Some((what, value, accepted, _)) => Err(LearnError::InvalidConfig(format!(
                "posture_holds.{what} = {value}: accepted {accepted} (finite)"
            ))),
            None => Ok(()),
        }
    }
}

/// The recorded postures (most recent last) and the episode time of the next record.
#[derive(Debug, Default)]
pub(super) struct PosturePool {
    pub(super) postures: VecDeque<Vec<f64>>,
    pub(super) next_record: u64,
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
        // The message names the field, its value and what is accepted.
        let e = PostureHolds {
            hold_seconds: -1.0,
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("posture_holds.hold_seconds = -1: accepted ≥ 0 s"),
            "{e}"
        );
    }
}
