//! Settings of the re-adaptation to a changed robot (`docs/learner.md`, "Re-adaptation"): how
//! the learner notices that its local dynamics no longer predict the measured accelerations, and
//! how much faster it forgets and learns while they do.

use crate::error::{LearnError, Result};
use serde::{Deserialize, Serialize};

/// Re-adaptation to a changed robot (a payload, other masses, other friction).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AdaptationConfig {
    /// Whether the learner watches its prediction error and re-adapts. Default false: the
    /// training runs of E1–E7 stay as they were; `osrl adapt` and `osrl train --change` switch it
    /// on.
    pub enabled: bool,
    /// Check the local dynamics' prediction error at every this many learning steps (≥ 1).
    /// Default 4: the check costs about one `θᵀGθ` per active field.
    pub check_every: usize,
    /// Time constant of the running level of the error ratio (s of learning, > 0). Default 0.5:
    /// a few path segments, so one bad sample does not trigger it and a change shows within a
    /// second.
    pub time_constant: f64,
    /// The level (the measured `‖ẍ − Θᵀφ_d‖²` over the fields' own mean squared residual) at
    /// which re-adaptation starts (> 1). Default 4: on an unchanged robot the level stays near
    /// 1 (`docs/decisions.md`, D-adapt).
    pub on_ratio: f64,
    /// The level at which re-adaptation is at full strength (> `on_ratio`). Default 16.
    pub full_ratio: f64,
    /// Floor on a field's mean squared residual (m/s² RMS, > 0) with the local dynamics on
    /// levels (`dynamics.regression = "level"`), so a field fitted to noise-free data does not
    /// make every error look large. Default 0.02.
    pub residual_floor: f64,
    /// The same floor with the local dynamics on differences (`"difference"`, the default
    /// regression; m/s³ RMS, > 0). Default 1: with 0.02 the first episode's start made an
    /// unchanged sarcos7 re-adapt (`docs/decisions.md`, D26).
    pub residual_floor_difference: f64,
    /// Forgetting factor per sample of the local dynamics at full strength and activation 1, in
    /// (0, 1]. Default 0.995: a memory of about 200 samples (0.4 s at 500 Hz).
    pub dynamics_forgetting: f64,
    /// Forgetting factor per sample of the local controllers' statistics at full strength and
    /// activation 1, in (0, 1]. Default 0.999: about 1000 samples, enough to keep the
    /// controllers' confidence.
    pub controller_forgetting: f64,
    /// After the level falls back, the strength falls by at most 1 per this many seconds of
    /// learning (> 0): the re-adaptation settles back gradually instead of stopping as soon as
    /// the fields' residuals have absorbed the new data. Default 20.
    pub release_seconds: f64,
    /// Whether the static gravity model stops learning while re-adapting. Default false: on
    /// planar3 with a 0.5 kg payload, pausing it left the tracking at 57 mm after 3 minutes
    /// instead of 33 mm (`docs/decisions.md`, D-adapt).
    pub pause_static_gravity: bool,
    /// Factor on the RWR trust region at full strength (≥ 1). Default 4: the controllers may move
    /// four times as far per M-step while they re-adapt.
    pub trust_scale: f64,
    /// Whether the nominal behaviour `u0` learns a load correction while re-adapting (one
    /// offset per receptive field, `learner/load.rs`), so the change is absorbed by `u0` instead
    /// of every local controller. Default true (`docs/decisions.md`, D-adapt).
    pub load_correction: bool,
    /// Time constant of the load correction's offsets at full strength and activation 1 (s of
    /// learning, > 0). Default 1: the measured torque error `ε` is noisy (exploration, the
    /// measured `ẍ`), and a payload shows within a few passes of a field.
    pub load_time_constant: f64,
    /// Whether the forward model (the partition) stops learning while the re-adaptation is on
    /// (`enabled`): no field is added, moved or reshaped by the changed robot's data. Default
    /// false.
    pub freeze_partition: bool,
    /// Least strength at which the load correction keeps learning once a change has been
    /// detected (in [0, 1]; a rollback to a checkpoint from before the detection undoes it).
    /// Default 1: it keeps converging after the local dynamics fit again (0: it learns at the
    /// re-adaptation's strength and stops with it; D33, D34; D35 for the rollback).
    pub load_floor: f64,
    /// Least strength at which the local controllers' statistics keep forgetting
    /// (`controller_forgetting`) once a continuing learner (`Learner::reset_adaptation`: `osrl
    /// adapt`, E8) has detected a change, until its next reset (in [0, 1]; 0: only while the
    /// strength is above 0; no effect in a learner's first training, `osrl train --change-at`).
    /// Default 0.1: a memory of about 10,000 samples (20 s at 500 Hz) at activation 1.
    /// Why: the load correction keeps learning after the level has fallen (`load_floor`), and
    /// with it the controllers' residual targets `u − u0 − c` move; statistics that never forget
    /// keep the targets of the correction as it was (`docs/decisions.md`, D47).
    pub controller_floor: f64,
    /// What the error ratio compares (see [`AdaptationSource`]). Default `dynamics`.
    pub signal: AdaptationSource,
    /// Floor on a local controller's mean squared residual for the `command` signal, in N·m
    /// RMS (positive), so a controller fitted to nearly noise-free targets does not make every
    /// error look large. Default 0.05.
    pub command_floor: f64,
    /// Time constant of the task-space disturbance observer (s, ≥ 0; 0: off; `src/dob.rs`)
    /// while re-adapting (`enabled`). Default 0.02: ten control periods at 500 Hz, so a change
    /// shows in the tracking for a fraction of a second rather than until the learning has
    /// absorbed it (`docs/decisions.md`, D34).
    pub observer_seconds: f64,
    /// Bound on the observer's estimate (m/s², Euclidean norm, > 0). Default 5: a bound keeps a
    /// badly wrong model from winding the observer up; the periods spent at it are counted
    /// (`observer_saturated`; the choice between 5 and 10: D34).
    pub observer_max: f64,
    /// Whether the observer also runs when `enabled` is false (the training runs of E1–E7).
    /// Default false: the learned controller of the paper's experiments is the learned command
    /// alone.
    pub observer_always: bool,
    /// After this many on-policy episodes in a row that braked or aborted while a trained
    /// learner re-adapts (a run without babbling: `osrl adapt`, E8), the learner goes back to
    /// its state after the last episode that completed (or at the start of the on-policy
    /// phase), its counters kept; counted (`rollbacks`). 0: never. Default 3: a learner
    /// whose learning has broken its command keeps braking at the command-jump guard, while
    /// the controller it had still tracks (`docs/decisions.md`, D35).
    pub rollback_after: u32,
    /// After each rollback the re-adaptation's strength is capped at this times the cap before
    /// it (in [0, 1]; the cap starts at 1), so the learning that broke the command does not
    /// repeat itself at the same strength. Default 0.5.
    pub rollback_damping: f64,
    /// Upper bound on the re-adaptation's strength (in (0, 1]). Default 1: the strength follows
    /// the level alone; lower values soften every part of the response at once.
    pub max_strength: f64,
    /// The disturbance observer's slow estimate `‖d̄‖` (`d̂` low-passed over 0.5 s; m/s²) at
    /// which its ratio `(‖d̄‖ / offset_floor)²` is 1 (≥ 0; 0: the observer does not feed the
    /// level). The ratio joins the local dynamics' error ratio while an episode of a trained
    /// learner runs (a continuation: `osrl adapt`, E8; not after babbling): a payload
    /// is an offset of `ẍ` that the difference form of the local dynamics does not see and that
    /// the observer cancels within a few `T`, so a change made during tracking could go
    /// undetected. Default 1: on the unchanged arms `‖d̄‖` stays below about 1.4 (planar3) and
    /// 0.7 (sarcos7), so the ratio stays below `on_ratio` (D35).
    pub offset_floor: f64,
    /// While re-adapting, the command's null-space correction (`gravity.null_correction`) is
    /// on, learned from the holds at path postures of the run (`[train.posture_holds]`), so a
    /// controller trained without it learns one for the changed robot. Default false.
    pub null_correction: bool,
    /// With the re-adaptation enabled, the null-space correction's global part
    /// (`gravity.null_scale`, its settings there) is on: while a change is re-adapted the holds
    /// teach one scale `k` of `ĝ`, and `a k ĝ(q)` joins the correction everywhere while the load
    /// correction keeps `1 − a` of its null-space part, `a` the share from the fit's `R²`.
    /// Needs `gravity.null_correction`. Default true.
    /// Why: heavier links change the gravity torques in proportion to `ĝ` at every posture,
    /// where the holds' model knows only the held ones (sarcos7's heavier links, D45).
    pub null_scale: bool,
}

/// Which prediction error the re-adaptation's level is made of (`docs/learner.md`,
/// "Re-adaptation").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AdaptationSource {
    /// The local dynamics' prediction of their regression target (`ẍ`, or `Δẍ/Δt` in the
    /// difference form) over their own fit residual. In the difference form a change that is
    /// mostly an offset of `ẍ` (a payload's gravity) cancels.
    #[default]
    Dynamics,
    /// The local controllers' prediction of their hindsight target (`u − u0 − c` for the
    /// measured `ẍ`, N·m) over their own reward-weighted fit residual: a level in torque, so a
    /// payload's gravity shows, and it falls once the load correction `c` holds it.
    Command,
}

impl Default for AdaptationConfig {
    fn default() -> Self {
        Self {
            enabled: false,
            check_every: 4,
            time_constant: 0.5,
            on_ratio: 4.0,
            full_ratio: 16.0,
            residual_floor: 0.02,
            residual_floor_difference: 1.0,
            dynamics_forgetting: 0.995,
            controller_forgetting: 0.999,
            release_seconds: 20.0,
            pause_static_gravity: false,
            trust_scale: 4.0,
            load_correction: true,
            load_time_constant: 1.0,
            freeze_partition: false,
            load_floor: 1.0,
            controller_floor: 0.1,
            signal: AdaptationSource::Dynamics,
            command_floor: 0.05,
            observer_seconds: 0.02,
            observer_max: 5.0,
            observer_always: false,
            rollback_after: 3,
            rollback_damping: 0.5,
            max_strength: 1.0,
            offset_floor: 1.0,
            null_correction: false,
            null_scale: true,
        }
    }
}

impl AdaptationConfig {
    /// Whether every field is the default (the config then serialises without it).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// Checks every field's range.
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<()> {
        let finite = |x: f64, ok: bool| ok && x.is_finite();
        let unit = |x: f64| x > 0.0 && x <= 1.0;
        let closed = |x: f64| (0.0..=1.0).contains(&x);
        let (on, full) = (self.on_ratio, self.full_ratio);
        // (field, value, accepted, whether it is)
        let checks = [
            (
                "check_every",
                self.check_every as f64,
                "≥ 1",
                self.check_every >= 1,
            ),
            (
                "time_constant",
                self.time_constant,
                "> 0 s",
                finite(self.time_constant, self.time_constant > 0.0),
            ),
            ("on_ratio", on, "> 1", finite(on, on > 1.0)),
            ("full_ratio", full, "> on_ratio", finite(full, full > on)),
            (
                "residual_floor",
                self.residual_floor,
                "> 0",
                finite(self.residual_floor, self.residual_floor > 0.0),
            ),
            (
                "residual_floor_difference",
                self.residual_floor_difference,
                "> 0",
                finite(
                    self.residual_floor_difference,
                    self.residual_floor_difference > 0.0,
                ),
            ),
            (
                "release_seconds",
                self.release_seconds,
                "> 0 s",
                finite(self.release_seconds, self.release_seconds > 0.0),
            ),
            (
                "dynamics_forgetting",
                self.dynamics_forgetting,
                "in (0, 1]",
                unit(self.dynamics_forgetting),
            ),
            (
                "controller_forgetting",
                self.controller_forgetting,
                "in (0, 1]",
                unit(self.controller_forgetting),
            ),
            (
                "load_time_constant",
                self.load_time_constant,
                "> 0 s",
                finite(self.load_time_constant, self.load_time_constant > 0.0),
            ),
            (
                "trust_scale",
                self.trust_scale,
                "≥ 1",
                finite(self.trust_scale, self.trust_scale >= 1.0),
            ),
            (
                "load_floor",
                self.load_floor,
                "in [0, 1]",
                closed(self.load_floor),
            ),
            (
                "controller_floor",
                self.controller_floor,
                "in [0, 1]",
                closed(self.controller_floor),
            ),
            (
                "command_floor",
                self.command_floor,
                "> 0",
                finite(self.command_floor, self.command_floor > 0.0),
            ),
            (
                "observer_seconds",
                self.observer_seconds,
                "≥ 0 s",
                finite(self.observer_seconds, self.observer_seconds >= 0.0),
            ),
            (
                "observer_max",
                self.observer_max,
                "> 0",
                finite(self.observer_max, self.observer_max > 0.0),
            ),
            (
                "rollback_damping",
                self.rollback_damping,
                "in [0, 1]",
                closed(self.rollback_damping),
            ),
            (
                "max_strength",
                self.max_strength,
                "in (0, 1]",
                unit(self.max_strength),
            ),
            (
                "offset_floor",
                self.offset_floor,
                "≥ 0",
                finite(self.offset_floor, self.offset_floor >= 0.0),
            ),
        ];
        match checks.iter().find(|c| !c.3) {
            Some((what, value, accepted, _)) => Err(LearnError::InvalidConfig(format!(
                "adaptation.{what} = {value}: accepted {accepted} (finite)"
            ))),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::AdaptationConfig;

    /// `load_floor` and `controller_floor` are strengths: 0 and 1 pass, outside [0, 1] and NaN
    /// are refused by name, value and accepted range.
    #[test]
    fn the_strength_floors_are_checked() {
        type Set = fn(&mut AdaptationConfig, f64);
        let floors: [(&str, Set); 2] = [
            ("load_floor", |c, v| c.load_floor = v),
            ("controller_floor", |c, v| c.controller_floor = v),
        ];
        for (name, set) in floors {
            for ok in [0.0, 0.3, 1.0] {
                let mut c = AdaptationConfig::default();
                set(&mut c, ok);
                assert!(c.validate().is_ok(), "{name} {ok}");
            }
            for bad in [-0.1, 1.5, f64::NAN] {
                let mut c = AdaptationConfig::default();
                set(&mut c, bad);
                let e = c.validate().unwrap_err().to_string();
                // The field, the value given and what is accepted.
                let value = format!("{name} = {bad}");
                assert!(e.contains(&value) && e.contains("in [0, 1]"), "{e}");
            }
        }
    }

    /// The observer's time constant may be 0 (off) but not negative or non-finite, its bound
    /// must be positive and finite; each is refused by name.
    #[test]
    fn the_observer_settings_are_checked() {
        let off = AdaptationConfig {
            observer_seconds: 0.0,
            ..AdaptationConfig::default()
        };
        assert!(off.validate().is_ok());
        for bad in [-0.01, f64::NAN, f64::INFINITY] {
            let c = AdaptationConfig {
                observer_seconds: bad,
                ..AdaptationConfig::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("observer_seconds"), "{e}");
        }
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let c = AdaptationConfig {
                observer_max: bad,
                ..AdaptationConfig::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("observer_max"), "{e}");
        }
    }

    /// The rollback's damping is in [0, 1] and the strength's bound in (0, 1]; outside, or NaN,
    /// each is refused by name.
    #[test]
    fn the_rollback_settings_are_checked() {
        for bad in [-0.1, 1.5, f64::NAN] {
            let c = AdaptationConfig {
                rollback_damping: bad,
                ..AdaptationConfig::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("rollback_damping"), "{e}");
        }
        for bad in [0.0, -0.5, 1.01, f64::NAN] {
            let c = AdaptationConfig {
                max_strength: bad,
                ..AdaptationConfig::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("max_strength"), "{e}");
        }
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            let c = AdaptationConfig {
                offset_floor: bad,
                ..AdaptationConfig::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("offset_floor"), "{e}");
        }
        let ok = AdaptationConfig {
            offset_floor: 0.0,
            rollback_after: 0,
            rollback_damping: 0.0,
            max_strength: 0.25,
            ..AdaptationConfig::default()
        };
        assert!(ok.validate().is_ok());
    }

    /// The two floors of the error ratio are positive and finite, and refused by name
    /// otherwise.
    #[test]
    fn the_floors_are_checked() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let c = AdaptationConfig {
                residual_floor_difference: bad,
                ..AdaptationConfig::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("residual_floor_difference"), "{e}");
            let c = AdaptationConfig {
                command_floor: bad,
                ..AdaptationConfig::default()
            };
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("command_floor"), "{e}");
        }
        assert!(AdaptationConfig::default().validate().is_ok());
    }
}
