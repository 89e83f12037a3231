//! The external weights alone (a receptive field's activations `a`), decayed as the online
//! statistics are: the effective sample size that `RwrConfig::min_ess_share` compares the
//! reward weighting's with, and whether the statistics have forgotten at all.

use serde::{Deserialize, Serialize};

/// `Σ a`, `Σ a²` of the samples seen, each scaled by every forgetting since it arrived, and
/// whether any forgetting happened since the last [`External::clear`].
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct External {
    sum: f64,
    sum2: f64,
    forgotten: bool,
}

impl External {
    /// Multiplies every weight seen by `f` in (0, 1) (so `Σ a²` by `f²`) and marks the
    /// statistics as forgetting; other factors change nothing.
    pub fn forget(&mut self, f: f64) {
        if f > 0.0 && f < 1.0 {
            self.sum *= f;
            self.sum2 *= f * f;
            self.forgotten = true;
        }
    }

    /// Adds one sample's external weight `a ≥ 0`.
    pub fn add(&mut self, a: f64) {
        self.sum += a;
        self.sum2 += a * a;
    }

    /// `(Σa)² / Σa²`; 0 when empty.
    pub fn ess(&self) -> f64 {
        crate::weights::ess_of(self.sum, self.sum2)
    }

    /// The reference of the share floor: [`Self::ess`] once the statistics have forgotten,
    /// 0 (no floor) before — without forgetting the old samples anchor eq. 28.
    pub fn floor_reference(&self) -> f64 {
        if self.forgotten {
            self.ess()
        } else {
            0.0
        }
    }

    /// Empty, not forgotten.
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}
