//! Settings of a training run: the babbling phase and the on-policy phase.

use crate::error::{LearnError, Result};
use osrl_control::TaskGains;
use serde::{Deserialize, Serialize};

/// Motor babbling: random point-to-point joint movements (minimum jerk) under PD control with
/// the learned gravity compensation, with torque noise.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BabbleConfig {
    /// Simulated minutes of babbling before on-policy learning. Default 4: enough data for the
    /// gravity model and the local dynamics near the path.
    pub minutes: f64,
    /// Targets are drawn uniformly within ± this of the home posture (rad), inside the joint
    /// limits. Default `None`: `min(0.4, 1.4/n)` for `n` joints, so the babbling data stay dense
    /// near the path as the joint space grows.
    pub spread: Option<f64>,
    /// Duration of one move (s), drawn uniformly in this range. Default [0.6, 1.5].
    pub move_time: [f64; 2],
    /// Holding time at each target (s), without noise, so the arm comes to rest there (the still
    /// samples of the static gravity model). Default 0.5.
    pub settle: f64,
    /// Scale of the robot's PD gains while babbling (at most [`MAX_BABBLE_GAIN_SCALE`]). Default
    /// 3: stiff enough to follow the moves with the untrained gravity model.
    pub gain_scale: f64,
    /// White Gaussian torque noise while babbling, as the PD error (rad, at most π) it equals:
    /// joint `j` gets standard deviation `noise · K_Pq,j` (N·m). It makes the commands vary independently
    /// of the state, so the local dynamics `Â = ∂ẍ/∂u` are identifiable. Default 0.02.
    pub noise: f64,
    /// Correlation time of that noise (s; an Ornstein–Uhlenbeck process per joint; 0: white).
    /// Default 0.05: smooth enough for the torque-rate limit, fast enough to decorrelate the
    /// commands from the state.
    pub correlation_time: f64,
}

impl Default for BabbleConfig {
    fn default() -> Self {
        Self {
            minutes: 4.0,
            spread: None,
            move_time: [0.6, 1.5],
            settle: 0.5,
            gain_scale: 3.0,
            noise: 0.02,
            correlation_time: 0.05,
        }
    }
}

impl BabbleConfig {
    /// The spread of the babbling targets for `n` joints (rad): the set value or the default
    /// `min(0.4, 1.4/n)`.
    pub fn spread_for(&self, n: usize) -> f64 {
        self.spread
            .unwrap_or_else(|| (1.4 / n.max(1) as f64).min(0.4))
    }
}

/// Longest on-policy episode (s): an hour. An episode's path is built ahead, and one that long
/// would not return home for the rest of most runs.
pub const MAX_EPISODE_SECONDS: f64 = 3600.0;

/// Largest `babble.gain_scale`: a hundred times the data sheet's PD gains is stiffer than any
/// joint servo runs stably at these control rates; beyond it babbling only saturates.
pub const MAX_BABBLE_GAIN_SCALE: f64 = 100.0;

/// Settings of a training run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrainConfig {
    /// Simulated minutes of training in all, babbling included. Default 30.
    pub minutes: f64,
    pub babble: BabbleConfig,
    /// Task-space gains of the reference dynamics (eq. 2).
    pub gains: TaskGains,
    /// On-policy episodes run the path for this long (s), then stop and hold (see
    /// `curriculum`), unless the error grows too large; at most [`MAX_EPISODE_SECONDS`].
    /// Default 40.
    pub episode_seconds: f64,
    /// An episode stops when the task error exceeds this (m); the arm returns home. Default 0.05.
    pub reset_error: f64,
    /// Evaluate every this many simulated training minutes (0: only at the end). Default 2.
    pub eval_every_minutes: f64,
    /// Learn from every k-th transition (≥ 1; 1 = all). Default 1.
    pub learn_every: usize,
    /// Learn during the on-policy phase (false: babbling only, for diagnostics). Default true.
    pub learn_on_policy: bool,
    /// Learn from the returns home between on-policy episodes. Default true: they are on-policy
    /// data near the path start.
    pub learn_returning_home: bool,
    /// Exploration noise during the on-policy phase. Default true.
    pub explore: bool,
    /// Which holds of the path clock are quiet: there the exploration's amplitude follows the
    /// clock's rate (faded out by its half cosine as it stops, 0 while it holds), so the static
    /// gravity model gets still samples of an arm that the noise does not shake
    /// (`docs/decisions.md`, D20). Default `none`: quiet holds lower sarcos7's `u0` error 2–3×
    /// but cost the local dynamics and controllers their excitation at rest (planar3 loses).
    pub quiet_holds: super::QuietHolds,
    /// The exploration's gain in a quiet hold, in [0, 1]. Default 0.
    pub quiet_hold_gain: f64,
    /// When the driver switches between its PD commands and the learned controller (an
    /// episode's start and end), the sent command fades from the last one to the new source's
    /// over this long (s), instead of jumping. Default 0.25.
    pub switch_seconds: f64,
    /// The same for the first on-policy episode after the babbling (s): the learned controller,
    /// trained on babbling data only, takes over from the PD hold slowly while it learns from
    /// its first on-policy samples. Default 5. A continuation (no babbling, `osrl adapt`)
    /// switches its first episode in `switch_seconds`: its controller is trained, and over 5 s
    /// the arm stayed at home under the hold's fixed torque while the path moved away.
    pub first_switch_seconds: f64,
    /// The same after an episode braked or aborted on its task error (s): short, so the PD
    /// return home takes over before the error grows. Default 0.05.
    pub brake_switch_seconds: f64,
    /// After an episode braked or aborted, the first move of the return home (to a path
    /// posture or home) starts its reference at the arm's measured velocity: a quintic from
    /// `(q, q̇, 0)` to `(target, 0, 0)`, instead of the minimum-jerk move from rest. Default
    /// true. Why: the arm is still moving when an episode brakes, and a reference at rest
    /// makes the PD's damping `K_D q̇` brake it within a few periods, with the largest command
    /// steps of a sarcos7 run (D44).
    pub brake_return_from_velocity: bool,
    /// Largest change of a joint's command from one control period to the next in the
    /// on-policy phase (N·m per period; episodes, their fades and the returns home), applied
    /// after the braking step's check (`curriculum.brake_step` still sees the command before
    /// it) and counted in `rate_limited`. `None` (default): only the torque-rate limit
    /// (`docs/decisions.md`, D24).
    #[serde(default)]
    pub command_step_limit: Option<f64>,
    /// A continuation (no babbling before the on-policy phase, as in `osrl adapt`) starts with
    /// the hold at home under PD with `ĝ`, from the hold's own command; false: the first
    /// episode's fade (`first_switch_seconds`) starts from zero torque, the arm sagging under
    /// gravity until the learned command has taken over. Default true: with the static gravity
    /// model frozen while re-adapting (`adaptation.freeze_static_gravity`) it keeps sarcos7 on
    /// a loaded arm's path (`docs/decisions.md`, D-adapt). A run that babbles first is
    /// unaffected.
    pub hold_before_continuation: bool,
    /// A continuation keeps the static gravity model frozen (it learns nothing from the
    /// still samples of the holds and stops). Default true: on sarcos7 with a 0.5 kg payload
    /// its learning from the loaded arm's holds at home broke the controller within 1.8 s of
    /// `osrl adapt` and every seed diverged (`docs/decisions.md`, D-adapt). A run that babbles
    /// first is unaffected.
    pub freeze_static_in_continuation: bool,
    /// The arm is at home when every joint is within this of the home posture (rad or m) and
    /// moves slower than this (rad/s or m/s); an on-policy episode starts only there. Default
    /// 0.01.
    pub home_tolerance: f64,
    /// Integral time of the hold at home between episodes (s; `K_I = K_P / this`; 0: no
    /// integral action): removes the static offset that the learned gravity model's error
    /// leaves under the joint PD gains. Default 1: well below the stability bound of the
    /// weakly damped modes of arms with inertia-scaled gains.
    pub home_integral_seconds: f64,
    /// The hold at home ends when the arm is settled, after at least 1 s and at most this (s);
    /// an episode that starts unsettled is counted (`unsettled_starts`). Default 5.
    pub home_hold_seconds: f64,
    /// The curriculum and the path clock of the on-policy episodes.
    pub curriculum: super::CurriculumConfig,
    /// Holds at recorded path postures on the way home, for the static gravity model
    /// ([`super::PostureHolds`]). Default off.
    pub posture_holds: super::PostureHolds,
    /// Seed of the exploration and babbling noise. Default 0.
    pub seed: u64,
}

impl Default for TrainConfig {
    fn default() -> Self {
        Self {
            minutes: 30.0,
            babble: BabbleConfig::default(),
            gains: TaskGains::default(),
            episode_seconds: 40.0,
            reset_error: 0.05,
            eval_every_minutes: 2.0,
            learn_every: 1,
            learn_on_policy: true,
            learn_returning_home: true,
            explore: true,
            quiet_holds: super::QuietHolds::None,
            quiet_hold_gain: 0.0,
            switch_seconds: 0.25,
            first_switch_seconds: 5.0,
            brake_switch_seconds: 0.05,
            brake_return_from_velocity: true,
            command_step_limit: None,
            hold_before_continuation: true,
            freeze_static_in_continuation: true,
            home_tolerance: 0.01,
            home_integral_seconds: 1.0,
            home_hold_seconds: 5.0,
            curriculum: super::CurriculumConfig::default(),
            posture_holds: super::PostureHolds::default(),
            seed: 0,
        }
    }
}

impl TrainConfig {
    /// Checks every field's range.
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<()> {
        let b = &self.babble;
        let finite_pos = |x: f64| x > 0.0 && x.is_finite();
        let finite_nonneg = |x: f64| x >= 0.0 && x.is_finite();
        let v = |x: &dyn std::fmt::Debug| format!("{x:?}");
        let (pos, nonneg) = ("> 0, finite", "≥ 0, finite");
        // (setting, its value, what is accepted, whether it is)
        let checks = [
            (
                "minutes",
                v(&self.minutes),
                nonneg,
                finite_nonneg(self.minutes),
            ),
            (
                "babble.minutes",
                v(&b.minutes),
                nonneg,
                finite_nonneg(b.minutes),
            ),
            (
                "babble.spread",
                v(&b.spread),
                "unset or > 0, finite",
                b.spread.is_none_or(finite_pos),
            ),
            (
                "babble.move_time",
                v(&b.move_time),
                "[lo, hi] with 0 < lo ≤ hi, finite",
                b.move_time[0] > 0.0
                    && b.move_time[0] <= b.move_time[1]
                    && b.move_time[1].is_finite(),
            ),
            (
                "babble.gain_scale",
                v(&b.gain_scale),
                "> 0 and at most 100",
                finite_pos(b.gain_scale) && b.gain_scale <= MAX_BABBLE_GAIN_SCALE,
            ),
            (
                "babble.noise",
                v(&b.noise),
                "in [0, π] (rad of PD error)",
                (0.0..=std::f64::consts::PI).contains(&b.noise),
            ),
            (
                "babble.settle",
                v(&b.settle),
                nonneg,
                finite_nonneg(b.settle),
            ),
            (
                "babble.correlation_time",
                v(&b.correlation_time),
                nonneg,
                finite_nonneg(b.correlation_time),
            ),
            (
                "episode_seconds",
                v(&self.episode_seconds),
                "> 0 and at most 3600 (s)",
                finite_pos(self.episode_seconds) && self.episode_seconds <= MAX_EPISODE_SECONDS,
            ),
            (
                "reset_error",
                v(&self.reset_error),
                "> 0",
                self.reset_error > 0.0,
            ),
            (
                "eval_every_minutes",
                v(&self.eval_every_minutes),
                nonneg,
                finite_nonneg(self.eval_every_minutes),
            ),
            (
                "learn_every",
                v(&self.learn_every),
                "≥ 1",
                self.learn_every >= 1,
            ),
            (
                "home_tolerance",
                v(&self.home_tolerance),
                pos,
                finite_pos(self.home_tolerance),
            ),
            (
                "home_integral_seconds",
                v(&self.home_integral_seconds),
                nonneg,
                finite_nonneg(self.home_integral_seconds),
            ),
            (
                "home_hold_seconds",
                v(&self.home_hold_seconds),
                pos,
                finite_pos(self.home_hold_seconds),
            ),
            (
                "switch_seconds",
                v(&self.switch_seconds),
                nonneg,
                finite_nonneg(self.switch_seconds),
            ),
            (
                "first_switch_seconds",
                v(&self.first_switch_seconds),
                nonneg,
                finite_nonneg(self.first_switch_seconds),
            ),
            (
                "brake_switch_seconds",
                v(&self.brake_switch_seconds),
                nonneg,
                finite_nonneg(self.brake_switch_seconds),
            ),
            (
                "command_step_limit",
                v(&self.command_step_limit),
                "unset or > 0, finite",
                self.command_step_limit.is_none_or(finite_pos),
            ),
            (
                "quiet_hold_gain",
                v(&self.quiet_hold_gain),
                "in [0, 1]",
                (0.0..=1.0).contains(&self.quiet_hold_gain),
            ),
        ];
        match checks.iter().find(|c| !c.3) {
            Some((what, value, accepted, _)) => Err(LearnError::InvalidConfig(format!(
                "training setting {what} = {value}: accepted {accepted}"
            ))),
            None => {
                self.curriculum.validate()?;
                self.posture_holds.validate()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    /// A training setting out of range is refused with its name, value and accepted range.
    #[test]
    fn a_training_setting_out_of_range_is_named_with_its_value() {
        use super::TrainConfig;
        let refused = |cfg: &TrainConfig| cfg.validate().unwrap_err().to_string();
        for (cfg, want) in [
            (
                TrainConfig {
                    quiet_hold_gain: 1.5,
                    ..Default::default()
                },
                "quiet_hold_gain = 1.5: accepted in [0, 1]",
            ),
            (
                TrainConfig {
                    command_step_limit: Some(-0.1),
                    ..Default::default()
                },
                "command_step_limit = Some(-0.1)",
            ),
            // Episodes and stops whose path, built ahead, took gigabytes and never finished.
            (
                TrainConfig {
                    episode_seconds: 1e9,
                    ..Default::default()
                },
                "episode_seconds = 1000000000.0: accepted > 0 and at most 3600",
            ),
        ] {
            let e = refused(&cfg);
            assert!(e.contains(want), "{e}");
        }
        let mut cfg = TrainConfig::default();
        cfg.curriculum.stop_every = 1e-6;
        let e = refused(&cfg);
        assert!(e.contains("curriculum.stop_every = 0.000001"), "{e}");
        cfg.curriculum.stop_every = 0.0;
        cfg.curriculum.hold_seconds = 1e300;
        assert!(refused(&cfg).contains("hold_seconds"));
        cfg.curriculum.hold_seconds = 0.0;
        cfg.episode_seconds = super::MAX_EPISODE_SECONDS;
        cfg.validate().unwrap();
    }
}
