//! The rollback of a re-adaptation that broke the learned command (`docs/learner.md`,
//! "Re-adaptation"; `docs/decisions.md`, D35): while a trained learner re-adapts (a
//! continuation with `adaptation.enabled`: `osrl adapt`, E8), the driver keeps a copy of it from
//! the end of the last on-policy episode that completed (at first: from the start of the
//! on-policy phase). A run that babbles first (`osrl train --change-at`) never rolls back: its
//! early episodes fail while it learns, and a copy from the babbling would undo that.
//! After `adaptation.rollback_after` episodes in a row that braked or aborted, it restores that
//! copy (the learner's counters kept) and caps the re-adaptation's strength at
//! `adaptation.rollback_damping` times its cap before, so the learning that broke the command
//! does not repeat itself at the same strength.

use crate::error::Result;
use crate::Learner;

/// The driver's rollback state.
#[derive(Default)]
pub(super) struct Rollback {
    /// The learner after the last completed episode (`None`: rollback off).
    checkpoint: Option<Learner>,
    /// Episodes that braked or aborted since the last completed one (or the last rollback).
    failed_in_row: u32,
    /// Rollbacks made, and the strength cap they left.
    pub(super) count: u64,
    cap: f64,
}

impl Rollback {
    /// At the start of the on-policy phase: the first checkpoint, if `continuation` (the run
    /// did not babble) and `learner` re-adapts with rollbacks on.
    pub(super) fn start(learner: &Learner, continuation: bool) -> Self {
        let ad = &learner.config().adaptation;
        let on = continuation && ad.enabled && ad.rollback_after > 0;
        Self {
            checkpoint: on.then(|| learner.clone()),
            cap: learner.adaptation().cap,
            ..Self::default()
        }
    }

    /// After an episode (`failed`: braked or aborted): a new checkpoint of `learner`, or a
    /// rollback of it to the last one; returns whether it rolled back.
    ///
    /// # Errors
    /// None in practice (the checkpoint is a copy of the same learner).
    pub(super) fn after_episode(&mut self, learner: &mut Learner, failed: bool) -> Result<bool> {
        let ad = &learner.config().adaptation;
        let (after, damping) = (ad.rollback_after, ad.rollback_damping);
        let Some(checkpoint) = self.checkpoint.as_mut() else {
            return Ok(false);
        };
        if !failed {
            self.failed_in_row = 0;
            checkpoint.clone_from(learner);
            return Ok(false);
        }
        self.failed_in_row += 1;
        if self.failed_in_row < after {
            return Ok(false);
        }
        self.failed_in_row = 0;
        self.count += 1;
        self.cap *= damping;
        learner.restore(checkpoint)?;
        learner.cap_adaptation(self.cap);
        Ok(true)
    }
}
