//! The rollback of a re-adaptation that broke the learned command (`docs/learner.md`,
//! "Re-adaptation"; `docs/decisions.md`, D35): while a trained learner re-adapts (a
//! continuation with `adaptation.enabled`: `osrl adapt`, E8), the driver keeps a copy of it from
//! the end of the last on-policy episode that completed (at first: from the start of the
//! on-policy phase). A run that babbles first (`osrl train --change-at`) never rolls back: its
//! early episodes fail while it learns, and a copy from the babbling would undo that. After
//! `adaptation.rollback_after` episodes in a row that braked or aborted, it restores that copy
//! (the learner's counters kept) and caps the re-adaptation's strength at
//! `adaptation.rollback_damping` times its cap before, so the learning that broke the command
//! does not repeat itself at the same strength.

use super::Trainer;
use crate::error::Result;
use crate::Learner;
use osrl_dynamics::Robot;

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

impl<R: Robot + ?Sized> Trainer<'_, R> {
    /// At the start of the on-policy phase: the first checkpoint, if this run continues a
    /// trained learner that re-adapts, and rollbacks are on.
    pub(super) fn rollback_start(&mut self) {
        let ad = &self.learner.config().adaptation;
        let on = self.continuation && ad.enabled && ad.rollback_after > 0;
        self.rollback = Rollback {
            checkpoint: on.then(|| self.learner.clone()),
            cap: self.learner.adaptation().cap,
            ..Rollback::default()
        };
    }

    /// After an episode (`failed`: braked or aborted): a new checkpoint, or a rollback to the
    /// last one; returns whether it rolled back.
    ///
    /// # Errors
    /// None in practice (the checkpoint is a copy of the same learner).
    pub(super) fn rollback_after_episode(&mut self, failed: bool) -> Result<bool> {
        let ad = &self.learner.config().adaptation;
        let (after, damping) = (ad.rollback_after, ad.rollback_damping);
        let rb = &mut self.rollback;
        let Some(checkpoint) = rb.checkpoint.as_mut() else {
            return Ok(false);
        };
        if !failed {
            rb.failed_in_row = 0;
            checkpoint.clone_from(&*self.learner);
            return Ok(false);
        }
        rb.failed_in_row += 1;
        if rb.failed_in_row < after {
            return Ok(false);
        }
        rb.failed_in_row = 0;
        rb.count += 1;
        rb.cap *= damping;
        self.learner.restore(checkpoint)?;
        self.learner.cap_adaptation(rb.cap);
        Ok(true)
    }
}
