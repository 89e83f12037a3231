//! What the training driver tells the re-adaptation (`docs/learner.md`, "Re-adaptation"):
//! the disturbance observer's slow estimate ([`Learner::observe_offset`]), and the rollback of a
//! learner whose re-adaptation broke its command ([`Learner::restore`],
//! [`Learner::cap_adaptation`]; `train/rollback.rs`).

use super::Learner;
use crate::error::{LearnError, Result};

impl Learner {
    /// The training driver's disturbance observer's slow estimate `‖d̄‖` (m/s²,
    /// [`crate::Dob::offset`]; 0 when it stops): while the learner re-adapts and
    /// `adaptation.offset_floor > 0`, `(‖d̄‖ / offset_floor)²` joins the error ratio of the next
    /// checks (the larger of it and the fields' ratio counts). A non-finite value counts as 0.
    pub fn observe_offset(&mut self, offset: f64) {
        let a = &self.cfg.adaptation;
        let on = a.enabled && a.offset_floor > 0.0 && offset.is_finite();
        self.adapt.offset_ratio = if on {
            (offset / a.offset_floor).powi(2)
        } else {
            0.0
        };
    }

    /// Caps the re-adaptation's strength at `cap` (clamped to [0, 1]; NaN leaves it as it
    /// is), from the next check of the prediction error on (`adaptation.rollback_damping`).
    pub fn cap_adaptation(&mut self, cap: f64) {
        if !cap.is_nan() {
            self.adapt.cap = cap.clamp(0.0, 1.0);
            self.adapt.strength = self.adapt.strength.min(self.adapt.cap);
        }
    }

    /// Goes back to `checkpoint` (a clone of this learner taken earlier): its models, its
    /// controllers, its load correction and its re-adaptation's level, strength and whether
    /// it had detected a change — and its config and flags, which the training driver leaves
    /// as they were. Kept from this learner: the counters ([`Self::stats`], whose sample count
    /// is the learner's clock), the re-adaptation's peak level and counts (they count what
    /// happened on the robot) and the preallocated scratch buffers.
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] if `checkpoint` is for other dimensions; nothing changes.
    pub fn restore(&mut self, checkpoint: &Learner) -> Result<()> {
        if checkpoint.dims() != self.dims() || checkpoint.dt != self.dt {
            return Err(LearnError::InvalidConfig(format!(
                "a checkpoint for {:?} joints and task at dt {} cannot restore a learner for {:?} \
                 at {}",
                checkpoint.dims(),
                checkpoint.dt,
                self.dims(),
                self.dt
            )));
        }
        let (stats, signal) = (self.stats, self.adapt);
        let ws = std::mem::replace(&mut self.ws, checkpoint.ws.clone());
        self.clone_from(checkpoint);
        self.ws = ws;
        self.stats = stats;
        self.adapt.peak_level = signal.peak_level.max(self.adapt.peak_level);
        self.adapt.checks = signal.checks;
        self.adapt.adapting_steps = signal.adapting_steps;
        Ok(())
    }
}
