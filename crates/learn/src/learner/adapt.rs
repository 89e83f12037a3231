//! Re-adaptation to a changed robot (`docs/learner.md`, "Re-adaptation"): every
//! `adaptation.check_every` learning steps, each active field's local dynamics predict the
//! measured `ẍ` before they learn it; the activation-weighted squared error over the fields' own
//! mean squared residual is the error ratio, whose running level drives the strength `a ∈ [0, 1]`.
//! While `a > 0`, each active field forgets its dynamics and its controller's statistics faster
//! (factor `λ^(a·w)` per sample, `w` its activation), re-solves its dynamics at every M-step,
//! weights new samples by a cost shrunk by `1 − a` and may move its controller further per
//! M-step (trust region × `1 + a (s − 1)`). When the level falls back, `a` is released over
//! `release_seconds`; a continuing learner's controllers keep forgetting at strength
//! `adaptation.controller_floor` after a detection. Fields the arm does not visit forget
//! nothing. Until a change has been detected, the training driver's disturbance observer feeds
//! the level too, and the driver may roll the learner back (`readapt.rs`).

use crate::config::AdaptationConfig;
use serde::Serialize;

/// The re-adaptation's state: the running level of the error ratio and the strength it gives.
/// It is not saved with the learner: [`crate::Learner::reset_adaptation`] starts it afresh (the
/// fields' own residuals, which are saved, are its reference).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AdaptationSignal {
    /// Running level of the error ratio (about 1 where the fields predict as well as they fit).
    pub level: f64,
    /// Strength of the re-adaptation in [0, 1]: 0 up to `on_ratio`, 1 from `full_ratio`.
    pub strength: f64,
    /// Largest level since the last reset.
    pub peak_level: f64,
    /// Checks of the prediction error since the last reset.
    pub checks: u64,
    /// Learning steps taken with a strength above 0 since the last reset.
    pub adapting_steps: u64,
    /// Whether this learner's models have re-adapted (a strength above 0) since the last
    /// reset: the load correction then keeps learning (`load_floor`). A rollback restores it
    /// with the models; the counters above keep counting the run.
    pub detected: bool,
    /// Upper bound on the strength (1 unless the driver lowered it after a rollback,
    /// `adaptation.rollback_damping`).
    pub cap: f64,
    /// The training driver's disturbance observer, `(‖d̄‖ / offset_floor)²` with `d̄` its slow
    /// estimate, while an episode runs (0: none).
    pub offset_ratio: f64,
    /// Whether the signal was started for a learner that continues (`Learner::reset_adaptation`:
    /// `osrl adapt`, E8) rather than for one in its first training: only then do the
    /// controllers keep forgetting at `controller_floor` after a detection. A learner in its
    /// first training reads its own learning as a change (`docs/decisions.md`, D46), and
    /// forgetting from then on cost planar3's `--change-at` runs their tracking (D47).
    pub continuation: bool,
}

impl Default for AdaptationSignal {
    fn default() -> Self {
        Self {
            level: 0.0,
            strength: 0.0,
            peak_level: 0.0,
            checks: 0,
            adapting_steps: 0,
            detected: false,
            cap: 1.0,
            offset_ratio: 0.0,
            continuation: false,
        }
    }
}

/// The error ratio of one check is capped at this, so one wild sample moves the level by a
/// bounded amount.
const MAX_RATIO: f64 = 100.0;

impl AdaptationSignal {
    /// Folds one check's error ratio — the larger of the fields' `se / sv` and, until a change
    /// has been detected, the observer's [`Self::offset_ratio`] — into the level (`dt_check`: seconds of learning
    /// since the last check) and updates the strength.
    pub(crate) fn observe(&mut self, cfg: &AdaptationConfig, se: f64, sv: f64, dt_check: f64) {
        let fields = (sv > 0.0 && se.is_finite()).then(|| se / sv);
        // The observer detects; once the models have re-adapted, the fields' ratio governs.
        let offset = (self.offset_ratio > 0.0 && !self.detected).then_some(self.offset_ratio);
        let Some(ratio) = fields.into_iter().chain(offset).reduce(f64::max) else {
            return;
        };
        let ratio = ratio.min(MAX_RATIO);
        let alpha = (dt_check / cfg.time_constant).min(1.0);
        self.level += alpha * (ratio - self.level);
        self.peak_level = self.peak_level.max(self.level);
        self.checks += 1;
        let target =
            ((self.level - cfg.on_ratio) / (cfg.full_ratio - cfg.on_ratio)).clamp(0.0, 1.0);
        let release = dt_check / cfg.release_seconds;
        let cap = self.cap.min(cfg.max_strength);
        self.strength = target.max(self.strength - release).clamp(0.0, cap);
    }

    /// The extra forgetting factors `(dynamics, controller)` for a field with activation `w`.
    /// The controllers forget at least at `controller_floor` once a change has been detected.
    pub(crate) fn decay(&self, cfg: &AdaptationConfig, w: f64) -> (f64, f64) {
        let e = self.strength * w;
        let ec = self.controller_strength(cfg) * w;
        (
            cfg.dynamics_forgetting.powf(e),
            cfg.controller_forgetting.powf(ec),
        )
    }

    /// The strength at which the controllers forget: the strength, at least `controller_floor`
    /// once a change has been detected by a continuing learner.
    pub(crate) fn controller_strength(&self, cfg: &AdaptationConfig) -> f64 {
        if self.detected && self.continuation {
            self.strength.max(cfg.controller_floor)
        } else {
            self.strength
        }
    }

    /// The cost a sample of cost `r` is weighted with: `(1 − a) r`. A change of the robot
    /// changes the costs of the new samples; with `τ` fitted to the old, small costs, RWR would
    /// give them no weight, so while re-adapting the samples count by their activation (the
    /// hindsight target is already the minimum-norm one).
    pub(crate) fn cost(&self, r: f64) -> f64 {
        r * (1.0 - self.strength)
    }

    /// Whether the learner re-adapts: a change detected since the last reset, or a strength
    /// above 0.
    pub fn readapting(&self) -> bool {
        self.detected || self.strength > 0.0
    }

    /// The factor on the RWR trust region.
    pub(crate) fn trust_scale(&self, cfg: &AdaptationConfig) -> f64 {
        1.0 + self.strength * (cfg.trust_scale - 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::AdaptationSignal;
    use crate::config::AdaptationConfig;

    /// The strength after `checks` checks of a large error ratio (the level far above
    /// `full_ratio`).
    fn strength_after_a_change(cfg: &AdaptationConfig, cap: f64) -> f64 {
        let mut s = AdaptationSignal {
            cap,
            ..AdaptationSignal::default()
        };
        for _ in 0..200 {
            s.observe(cfg, 1e3, 1.0, 0.05);
        }
        s.strength
    }

    /// A large error gives full strength; the rollback's cap and `max_strength` each bound it.
    #[test]
    fn the_strength_is_capped() {
        let cfg = AdaptationConfig::default();
        assert_eq!(strength_after_a_change(&cfg, 1.0), 1.0);
        assert_eq!(strength_after_a_change(&cfg, 0.25), 0.25);
        let half = AdaptationConfig {
            max_strength: 0.5,
            ..AdaptationConfig::default()
        };
        assert_eq!(strength_after_a_change(&half, 1.0), 0.5);
        assert_eq!(strength_after_a_change(&half, 0.25), 0.25);
    }

    /// Until a change has been detected, the observer's ratio drives the level on its own (no
    /// field's ratio) and with the fields' the larger counts; after, the fields' alone.
    #[test]
    fn the_offset_ratio_joins_the_level() {
        let cfg = AdaptationConfig::default();
        let level =
            |offset_ratio: f64, se: f64, sv: f64| level_after(&cfg, offset_ratio, se, sv, false);
        assert!((level(20.0, 0.0, 0.0) - 20.0).abs() < 1e-9);
        assert!((level(20.0, 2.0, 1.0) - 20.0).abs() < 1e-9);
        assert!((level(0.5, 2.0, 1.0) - 2.0).abs() < 1e-9);
        assert_eq!(level(0.0, 0.0, 0.0), 0.0);
        assert!((level_after(&cfg, 20.0, 2.0, 1.0, true) - 2.0).abs() < 1e-9);
    }

    /// A continuing learner's controllers forget at `controller_floor` once a change has been
    /// detected and the strength has fallen below it; the local dynamics follow the strength
    /// alone; nothing forgets before a detection, nor in a learner's first training.
    #[test]
    fn the_controllers_forget_at_their_floor_after_a_detection() {
        let cfg = AdaptationConfig {
            controller_floor: 0.3,
            ..AdaptationConfig::default()
        };
        let mut s = AdaptationSignal {
            continuation: true,
            ..AdaptationSignal::default()
        };
        assert_eq!(s.decay(&cfg, 0.5), (1.0, 1.0));
        s.detected = true;
        // A learner in its first training does not keep forgetting.
        let first = AdaptationSignal {
            continuation: false,
            ..s
        };
        assert_eq!(first.decay(&cfg, 0.5), (1.0, 1.0));
        let (fd, fc) = s.decay(&cfg, 0.5);
        assert_eq!(fd, 1.0);
        assert_eq!(fc, cfg.controller_forgetting.powf(0.15));
        assert!(fc < 1.0);
        s.strength = 0.8;
        let (fd, fc) = s.decay(&cfg, 0.5);
        assert_eq!(fd, cfg.dynamics_forgetting.powf(0.4));
        assert_eq!(fc, cfg.controller_forgetting.powf(0.4));
        // A floor of 0 leaves the factors to the strength.
        s.strength = 0.0;
        let off = AdaptationConfig {
            controller_floor: 0.0,
            ..AdaptationConfig::default()
        };
        assert_eq!(s.decay(&off, 0.5), (1.0, 1.0));
    }

    /// The level after many checks of the ratios given.
    fn level_after(
        cfg: &AdaptationConfig,
        offset_ratio: f64,
        se: f64,
        sv: f64,
        detected: bool,
    ) -> f64 {
        let mut s = AdaptationSignal {
            offset_ratio,
            detected,
            ..AdaptationSignal::default()
        };
        for _ in 0..500 {
            s.observe(cfg, se, sv, 0.05);
        }
        s.level
    }
}
